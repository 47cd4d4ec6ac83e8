#ifndef REFERENCE_GENDPDE_INTEGRATOR_KERNEL_H_
#define REFERENCE_GENDPDE_INTEGRATOR_KERNEL_H_

#include "GenDPDEKernels.h"
#include "NeighborList.h"
#include "openmm/Vec3.h"
#include <memory>
#include <vector>

namespace GenDPDEPlugin {

class ReferenceCalcGenDPDEForceKernel;

/**
 * Reference (double precision, single thread) step of GenDPDEIntegrator (docs/theory.md section 5): half kick, pair sweep
 * at fixed positions, half kick, drift. The pairs come from the System's GenDPDEForce when it has just been
 * evaluated at these positions with the same cutoff (no second neighbor search), else from a neighbor list of
 * the integrator's own.
 */
class ReferenceIntegrateGenDPDEStepKernel : public IntegrateGenDPDEStepKernel {
public:
    ReferenceIntegrateGenDPDEStepKernel(std::string name, const OpenMM::Platform& platform) :
            IntegrateGenDPDEStepKernel(name, platform) {
    }
    void initialize(OpenMM::ContextImpl& context, const GenDPDEIntegrator& integrator, double cutoff, int seed,
                    const std::vector<double>& internalEnergies) override;
    void execute(OpenMM::ContextImpl& context, const GenDPDEIntegrator& integrator) override;
    double computeKineticEnergy(OpenMM::ContextImpl& context, const GenDPDEIntegrator& integrator) override;
    const std::vector<double>& getInternalEnergies() const override {
        return internalEnergies;
    }
    void setInternalEnergies(const std::vector<double>& energies) override {
        internalEnergies = energies;
    }
    int getSeed() const override {
        return seed;
    }
    void setSeed(int seed) override {
        this->seed = seed;
    }
private:
    /** The pairs closer than the cutoff at the current positions. */
    PairView currentPairs(OpenMM::ContextImpl& context, const GenDPDEIntegrator& integrator);
    /** docs/theory.md section 5, full GenDPDE: momenta, mechanical heating and conduction; false if some eps <= 0. */
    bool sweepIsoenergetic(PairView pairs, std::vector<OpenMM::Vec3>& velocities, const GenDPDEIntegrator& integrator,
                           long long step, int& failedParticle);
    /** The classic DPD thermostat at the set temperature. */
    void sweepIsothermal(PairView pairs, std::vector<OpenMM::Vec3>& velocities, const GenDPDEIntegrator& integrator,
                         long long step);
    /** The order in which the pairs are updated (indices into the pairs); see the .cpp. */
    const std::vector<int>& sweepOrder(PairView pairs);
    void kick(std::vector<OpenMM::Vec3>& velocities, const std::vector<OpenMM::Vec3>& forces, double timeStep) const;
    double cutoff = 0.0;
    int seed = 0;
    std::vector<double> inverseMasses, internalEnergies;
    std::vector<OpenMM::Vec3> savedVelocities;
    std::vector<int> firstPair, order;
    std::vector<double> savedInternalEnergies;
    // Pairs: shared with the GenDPDEForce kernel if it uses the same cutoff, otherwise our own list.
    struct SharedForce {
        ReferenceCalcGenDPDEForceKernel* kernel;
        int group;
    };
    std::vector<SharedForce> sharedForces;   // GenDPDEForces with the integrator's cutoff and boundaries
    std::unique_ptr<NeighborList> neighborList;
};

} // namespace GenDPDEPlugin

#endif /*REFERENCE_GENDPDE_INTEGRATOR_KERNEL_H_*/
