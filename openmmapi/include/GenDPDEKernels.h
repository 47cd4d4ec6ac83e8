#ifndef GENDPDE_KERNELS_H_
#define GENDPDE_KERNELS_H_

#include "GenDPDEForce.h"
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

/**
 * Register this plugin's kernel factories on every platform that can run them and does not have them yet.
 * Called from getKernelNames() of the force and the integrator, i.e. just before a Context chooses its platform,
 * so that platforms loaded after this library (OpenMM's CPU plugin) are covered. Idempotent.
 */
void registerGenDPDEKernelFactories();

} // namespace GenDPDEPlugin

#endif /*GENDPDE_KERNELS_H_*/
