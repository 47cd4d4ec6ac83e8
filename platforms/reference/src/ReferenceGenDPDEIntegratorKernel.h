/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
#ifndef REFERENCE_GENDPDE_INTEGRATOR_KERNEL_H_
#define REFERENCE_GENDPDE_INTEGRATOR_KERNEL_H_

#include "GenDPDEKernels.h"
#include "internal/GenDPDETypes.h"
#include "NeighborList.h"
#include "internal/GenDPDEPairSweep.h"
#include "internal/GenDPDESweepOrder.h"
#include "openmm/Vec3.h"
#include <memory>
#include <vector>

namespace GenDPDEPlugin {

/**
 * Reference (double precision, single thread) step of GenDPDEIntegrator (docs/theory.md sections 5-7): half kick,
 * pair sweep at fixed positions, half kick, drift. The pairs come from the pair source the API found
 * (GenDPDEIntegratorUtilities::findPairSource: a GenDPDEForce evaluated at these positions just before) if it
 * offers them as a host list for this step and range, else from a neighbor list of the integrator's own.
 */
class ReferenceIntegrateGenDPDEStepKernel : public IntegrateGenDPDEStepKernel {
public:
    ReferenceIntegrateGenDPDEStepKernel(std::string name, const OpenMM::Platform& platform) :
            IntegrateGenDPDEStepKernel(name, platform) {}
    void initialize(OpenMM::ContextImpl& context, const GenDPDEIntegrator& integrator, double cutoff, int seed,
                    const std::vector<double>& internalEnergies, const std::map<int, int>& particleTypes) override;
    void execute(OpenMM::ContextImpl& context, const GenDPDEIntegrator& integrator, const GenDPDEStepTerms& terms,
                 GenDPDEPairSource* pairSource) override;
    double computeKineticEnergy(OpenMM::ContextImpl& context, const GenDPDEIntegrator& integrator) override;
    const std::vector<double>& getInternalEnergies() const override { return internalEnergies; }
    void setInternalEnergies(const std::vector<double>& energies) override {
        internalEnergies = energies;
        forgetDensityEntropies();
    }
    GenDPDEThermalState getThermalState(const GenDPDEIntegrator& integrator) override;
    void keepThermalState(const std::vector<double>& thermalEnergies,
                          const std::vector<double>& densityEntropies) override {
        internalEnergies = thermalEnergies;
        this->densityEntropies = densityEntropies;
        densityEntropiesKnown = true;
    }
    void forgetDensityEntropies() override { densityEntropiesKnown = false; }
    int getSeed() const override { return seed; }
    void setSeed(int seed) override { this->seed = seed; }

protected:
    // The stages of a step (execute() is the one home of their sequence); a parallel platform overrides them.
    /**
     * The pairs closer than the cutoff at the current positions: the source's if it lends them as a host list found
     * at this step with this range, else from our own list; on this many threads.
     */
    PairView currentPairs(OpenMM::ContextImpl& context, GenDPDEPairSource* pairSource, int numThreads);
    /** The threads each stage may use (1; the CPU platform's "Threads"). */
    virtual int numThreads(OpenMM::ContextImpl& context) const { return 1; }
    /**
     * Throw, naming the particle and the step, before anything changes, if a force is not finite or a particle
     * would move farther than maxDisplacement (nm) in this step (a blown-up simulation).
     */
    virtual void checkStepIsStable(OpenMM::ContextImpl& context, double stepSize, double maxDisplacement);
    /**
     * The step's first half kick, applied as the velocities are copied into the sweep's layout, then the pair updates
     * in the order of GenDPDESweepOrder (Isoenergetic or Isothermal), then the results copied back. If an internal
     * energy would become <= 0, throw: nothing has been copied back, so the velocities and internal energies are those
     * before the step.
     */
    virtual void sweep(OpenMM::ContextImpl& context, PairView pairs, std::vector<OpenMM::Vec3>& velocities,
                       const GenDPDEIntegrator& integrator, const GenDPDEStepTerms& terms);
    /** v += timeStep F/m for every particle with mass. */
    virtual void kick(OpenMM::ContextImpl& context, std::vector<OpenMM::Vec3>& velocities,
                      const std::vector<OpenMM::Vec3>& forces, double timeStep);
    /** x += timeStep v for every particle with mass. */
    virtual void drift(OpenMM::ContextImpl& context, std::vector<OpenMM::Vec3>& positions,
                       const std::vector<OpenMM::Vec3>& velocities, double timeStep);
    /** The first particle in [begin, end) with a non-finite force or a step longer than maxDisplacement, or -1. */
    int firstUnstableParticle(OpenMM::ContextImpl& context, double stepSize, double maxDisplacement, int begin,
                              int end) const;
    /** The error for particle i found by firstUnstableParticle(), naming it and the step. */
    [[noreturn]] void throwUnstable(OpenMM::ContextImpl& context, int i, double stepSize, double maxDisplacement) const;
    /** Particle i's kinetic energy with on-step velocities (kJ/mol); 0 for a massless particle. */
    double kineticEnergy(int i, const std::vector<OpenMM::Vec3>& velocities, const std::vector<OpenMM::Vec3>& forces,
                         double halfStep) const;
    /** Build sweepOrder for these pairs at the current positions, on this many threads. */
    void buildSweepOrder(OpenMM::ContextImpl& context, PairView pairs, int numThreads);
    /**
     * Copy what the sweep reads into layout (the order's cell order), the velocities given the step's first half
     * kick (the context's forces, half of the integrator's step) on the way, and point parameters at the copied
     * classes. The sweep then works on layout's arrays; layout.scatter() copies its results back. positions (by
     * particle index): the geometry of pairs that do not carry it (PairView::getPositions()), or null.
     */
    void gatherSweepState(OpenMM::ContextImpl& context, const GenDPDEIntegrator& integrator,
                          PairSweepParameters& parameters, int numThreads, const OpenMM::Vec3* positions = nullptr);
    /**
     * The sweep's failure at position failed of the order (the sweep's state still in layout, nothing copied back):
     * throw, naming the particle and the step.
     */
    [[noreturn]] void failSweep(PairView pairs, const std::vector<int>& order, int failed, long long step);
    double cutoff = 0.0;
    int seed = 0;
    std::unique_ptr<IntegratorTypeTables> typeTables;   // the particle types given to initialize(), and the tables
    std::vector<double> inverseMasses, internalEnergies;
    GenDPDESweepOrder sweepOrder;
    SweepLayout layout;   // the sweep's particle data in sweepOrder's cell order, during a sweep
    std::vector<double> sweepNoise;   // the noise amplitudes of the step's pair updates (PairSweepParameters)
    // docs/theory.md section 11: sigma(n_i) at the densities internalEnergies belong to, if known.
    std::vector<double> densityEntropies;
    bool densityEntropiesKnown = false;
    std::unique_ptr<NeighborList> neighborList;   // used when no GenDPDEForce's pairs can be reused
};

} // namespace GenDPDEPlugin

#endif /*REFERENCE_GENDPDE_INTEGRATOR_KERNEL_H_*/
