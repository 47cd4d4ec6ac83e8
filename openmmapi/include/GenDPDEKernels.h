#ifndef GENDPDE_KERNELS_H_
#define GENDPDE_KERNELS_H_

#include "GenDPDEForce.h"
#include "GenDPDEIntegrator.h"
#include "internal/GenDPDEIntegratorUtilities.h"
#include "openmm/KernelImpl.h"
#include "openmm/System.h"
#include "openmm/internal/ContextImpl.h"
#include <string>
#include <vector>

namespace GenDPDEPlugin {

/** Per-particle observables of a GenDPDEForce at one configuration (OpenMM units). */
struct GenDPDEObservables {
    std::vector<double> primitiveDensities;   // n0_i (nm^-3)
    std::vector<double> densities;            // n_i = 1/V_i (nm^-3)
    std::vector<double> volumes;              // V_i (nm^3)
    std::vector<double> pressures;            // pi_i (kJ/mol/nm^3)
    double virial = 0.0;                      // W = sum_{i<j} r_ij . F_ij (kJ/mol)
};

/** The kernel that evaluates a GenDPDEForce. */
class CalcGenDPDEForceKernel : public OpenMM::KernelImpl {
public:
    static std::string Name() {
        return "CalcGenDPDEForce";
    }
    CalcGenDPDEForceKernel(std::string name, const OpenMM::Platform& platform) : OpenMM::KernelImpl(name, platform) {
    }
    /** Prepare the kernel for a Context holding this System and force. */
    virtual void initialize(const OpenMM::System& system, const GenDPDEForce& force) = 0;
    /** Add the forces to the Context's force array and return the energy (kJ/mol). */
    virtual double execute(OpenMM::ContextImpl& context, bool includeForces, bool includeEnergy) = 0;
    /** Copy the parameters that updateParametersInContext() may change. */
    virtual void copyParametersToContext(OpenMM::ContextImpl& context, const GenDPDEForce& force) = 0;
    /** The observables at the Context's current positions. */
    virtual const GenDPDEObservables& getObservables(OpenMM::ContextImpl& context) = 0;
};

/** The kernel that advances a GenDPDEIntegrator by one step and owns the internal energies. */
class IntegrateGenDPDEStepKernel : public OpenMM::KernelImpl {
public:
    static std::string Name() {
        return "IntegrateGenDPDEStep";
    }
    IntegrateGenDPDEStepKernel(std::string name, const OpenMM::Platform& platform) : OpenMM::KernelImpl(name, platform) {
    }
    /**
     * Prepare the kernel for a Context.
     *
     * @param cutoff            the range of the pair interactions (nm); 0 if unknown (then no pair sweep may run)
     * @param seed              the random number seed actually used
     * @param internalEnergies  the initial eps_i (kJ/mol), one per particle
     */
    virtual void initialize(OpenMM::ContextImpl& context, const GenDPDEIntegrator& integrator, double cutoff, int seed,
                            const std::vector<double>& internalEnergies) = 0;
    /**
     * One step. The forces of the integration groups at the current positions have just been computed.
     *
     * @param terms            what the step contains (GenDPDEIntegratorUtilities::stepTerms)
     * @param pairListSource   a GenDPDEForce among those just evaluated whose pairs (cutoff = the pair range) the
     *                         sweep may reuse, or null: then the kernel finds the pairs itself
     */
    virtual void execute(OpenMM::ContextImpl& context, const GenDPDEIntegrator& integrator,
                         const GenDPDEStepTerms& terms, GenDPDEForceImpl* pairListSource) = 0;
    /** The kinetic energy with on-step velocities v + (dt/2) F/m (kJ/mol). */
    virtual double computeKineticEnergy(OpenMM::ContextImpl& context, const GenDPDEIntegrator& integrator) = 0;
    virtual const std::vector<double>& getInternalEnergies() const = 0;
    virtual void setInternalEnergies(const std::vector<double>& internalEnergies) = 0;
    virtual int getSeed() const = 0;
    virtual void setSeed(int seed) = 0;
};

} // namespace GenDPDEPlugin

#endif /*GENDPDE_KERNELS_H_*/
