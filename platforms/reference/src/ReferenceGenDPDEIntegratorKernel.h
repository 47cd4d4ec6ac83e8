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
 * pair sweep at fixed positions, half kick, drift. The sweep's order (GenDPDESweepOrder) is made when the definition's
 * rule asks (a particle moved more than 0.05 R from its position at the last build, or a new box) from the candidates
 * within 1.1 R: a GenDPDEForce's list's if that list was built at the same positions (the same candidates), else a
 * list of the integrator's own; it is kept until the next build.
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
    bool getSweepBuild(std::vector<OpenMM::Vec3>& positions, OpenMM::Vec3 box[3]) const override;
    void setSweepBuild(const std::vector<OpenMM::Vec3>& positions, const OpenMM::Vec3 box[3]) override;
    void forgetSweepOrder() override;

protected:
    // The stages of a step (execute() is the one home of their sequence); a parallel platform overrides them.
    /** The threads each stage may use (1; the CPU platform's "Threads"). */
    virtual int numThreads(OpenMM::ContextImpl& context) const { return 1; }
    /**
     * Throw, naming the particle and the step, before anything changes, if a force is not finite or a particle
     * would move farther than maxDisplacement (nm) in this step (a blown-up simulation).
     */
    virtual void checkStepIsStable(OpenMM::ContextImpl& context, double stepSize, double maxDisplacement);
    /**
     * The step's first half kick, applied as the velocities are copied into the sweep's layout, then the pair updates
     * in the order of GenDPDESweepOrder (Isoenergetic or Isothermal), then the results copied back: the colours one
     * after another, the blocks of a colour at the same time on numThreads(context) threads (they share no
     * particle), each block's pairs in order by one thread. If an internal energy would become <= 0, throw, naming
     * the first failing pair's particle in the sequence: nothing has been copied back, so the velocities and internal
     * energies are those before the step.
     */
    void sweep(OpenMM::ContextImpl& context, std::vector<OpenMM::Vec3>& velocities, const GenDPDEIntegrator& integrator,
               const GenDPDEStepTerms& terms, GenDPDEPairSource* pairSource);
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
    /**
     * Make the sweep's order again (sweepOrder and orderedPairs) if the definition's rule asks for it at the current
     * positions (after a build at the positions of setSweepBuild(), if any), from the candidates of the pair source's
     * host list if it was built at exactly these positions and box, else of our own list.
     */
    void updateSweepOrder(OpenMM::ContextImpl& context, GenDPDEPairSource* pairSource, int numThreads);
    /** Whether the rule asks for a build at these positions and box: none yet, a new box, or a particle moved. */
    bool orderIsStale(const std::vector<OpenMM::Vec3>& positions, const OpenMM::Vec3 box[3], int numThreads) const;
    /**
     * Make sweepOrder and orderedPairs at these positions (nm) and box from the candidates of list (built at exactly
     * these positions and box) or, if null, of our own list built now.
     */
    void buildSweepOrder(const std::vector<OpenMM::Vec3>& positions, const OpenMM::Vec3 box[3],
                         const NeighborList* list, int numThreads);
    /**
     * Copy what the sweep reads into layout (the order's cell order), the velocities given the step's first half
     * kick (the context's forces, half of the integrator's step) on the way, and point parameters at the copied
     * classes. The sweep then works on layout's arrays (the positions too); layout.scatter() copies its results back.
     */
    void gatherSweepState(OpenMM::ContextImpl& context, const GenDPDEIntegrator& integrator,
                          PairSweepParameters& parameters, int numThreads);
    /**
     * The sweep's failure at position failed of orderedPairs (the sweep's state still in layout, nothing copied back):
     * throw, naming the particle and the step.
     */
    [[noreturn]] void failSweep(int failed, long long step);
    double cutoff = 0.0;
    int seed = 0;
    std::unique_ptr<IntegratorTypeTables> typeTables;   // the particle types given to initialize(), and the tables
    std::vector<double> inverseMasses, internalEnergies;
    GenDPDESweepOrder sweepOrder;
    std::vector<SweepPair> orderedPairs;   // the candidates in sweep order, with their slots in layout
    bool orderBuilt = false;
    std::vector<OpenMM::Vec3> buildPositions;   // the positions (nm) and box of the order's build
    OpenMM::Vec3 buildBox[3];
    PeriodicBox sweepBox;   // the box of the order's build (periodic only), for the sweep's nearest images
    std::vector<OpenMM::Vec3> pendingBuildPositions;   // setSweepBuild(): the next order's build, if not empty
    OpenMM::Vec3 pendingBuildBox[3];
    std::vector<int> blockFailure;   // per block of the running colour: position of the failing pair, or -1
    SweepLayout layout;   // the sweep's particle data in sweepOrder's cell order, during a sweep
    std::vector<double> sweepNoise;   // the noise amplitudes of the step's pair updates (PairSweepParameters)
    // docs/theory.md section 11: sigma(n_i) at the densities internalEnergies belong to, if known.
    std::vector<double> densityEntropies;
    bool densityEntropiesKnown = false;
    std::unique_ptr<NeighborList> neighborList;   // the sweep's own candidates (null without pair terms)
};

} // namespace GenDPDEPlugin

#endif /*REFERENCE_GENDPDE_INTEGRATOR_KERNEL_H_*/
