#ifndef REFERENCE_GENDPDE_FORCE_KERNEL_H_
#define REFERENCE_GENDPDE_FORCE_KERNEL_H_

#include "GenDPDEKernels.h"
#include "NeighborList.h"
#include "openmm/Vec3.h"
#include <memory>
#include <vector>

namespace GenDPDEPlugin {

/**
 * Reference (double precision, single thread) evaluation of GenDPDEForce, docs/theory.md sections 2-4:
 * one sweep over the pairs for the primitive densities, one pass over the particles for volumes, pressures and
 * free energies, and one sweep over the pairs for the forces and the virial.
 */
class ReferenceCalcGenDPDEForceKernel : public CalcGenDPDEForceKernel {
public:
    ReferenceCalcGenDPDEForceKernel(std::string name, const OpenMM::Platform& platform) :
            CalcGenDPDEForceKernel(name, platform) {
    }
    void initialize(const OpenMM::System& system, const GenDPDEForce& force) override;
    double execute(OpenMM::ContextImpl& context, bool includeForces, bool includeEnergy) override;
    void copyParametersToContext(OpenMM::ContextImpl& context, const GenDPDEForce& force) override;
    const GenDPDEObservables& getObservables(OpenMM::ContextImpl& context) override;
    /** The neighbor list; its pairs are those of the most recent evaluation. */
    const NeighborList& getNeighborList() const {
        return *neighborList;
    }
private:
    /** Take the parameters that updateParametersInContext() may change; reject changes of the others. */
    void readParameters(const GenDPDEForce& force);
    /** Pair sweep and particle pass: fills the per-particle arrays and returns U = sum_i f(n_i) (kJ/mol). */
    double computeDensitiesAndEnergy(OpenMM::ContextImpl& context);
    /** Pair sweep for F_i (added to *forces unless null); returns the virial W (kJ/mol). */
    double computePairForces(std::vector<OpenMM::Vec3>* forces) const;
    double cutoff, cutoffScaling;
    double referenceDensity, referencePressure, bulkModulus, exponent;
    GenDPDEForce::DensityEstimator estimator;
    bool periodic;
    std::unique_ptr<NeighborList> neighborList;
    // Per particle, at the positions of the last evaluation.
    std::vector<double> primitiveDensity, volume, pressure;
    std::vector<double> forceCoefficient;   // pi_i dV_i/dn0_i (kJ/mol nm^3)
    // Observables and the configuration they belong to.
    GenDPDEObservables observables;
    std::vector<OpenMM::Vec3> observedPositions;
    OpenMM::Vec3 observedBox[3];
    bool observablesValid = false;
};

} // namespace GenDPDEPlugin

#endif /*REFERENCE_GENDPDE_FORCE_KERNEL_H_*/
