/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
#ifndef GENDPDE_KERNELS_H_
#define GENDPDE_KERNELS_H_

#include "GenDPDEForce.h"
#include "GenDPDEIntegrator.h"
#include "internal/GenDPDEIntegratorUtilities.h"
#include "openmm/KernelImpl.h"
#include "openmm/OpenMMException.h"
#include "openmm/Platform.h"
#include "openmm/System.h"
#include "openmm/internal/ContextImpl.h"
#include <map>
#include <string>
#include <vector>

namespace OpenMM {
class ComputeArray;
}

namespace GenDPDEPlugin {

class CommonGenDPDEForceChecks;   // platforms/common/src/CommonGenDPDEForceChecks.h
class NeighborList;               // platforms/reference/src/NeighborList.h
struct CommonGenDPDEThermalArrays;   // platforms/common/src/CommonGenDPDEThermalArrays.h

/** Per-particle observables of a GenDPDEForce at one configuration (OpenMM units). */
struct GenDPDEObservables {
    std::vector<double> primitiveDensities;   // n0_i (nm^-3)
    std::vector<double> densities;            // n_i = 1/V_i (nm^-3)
    std::vector<double> volumes;              // V_i (nm^3)
    std::vector<double> pressures;            // pi_i (kJ/mol/nm^3)
    double virial = 0.0;                      // W = sum_{i<j} r_ij . F_ij (kJ/mol)
    /** W_i,ab = sum_j (1/2) F_ij,a r_ij,b per particle, row-major (9 per particle, kJ/mol); only if asked for. */
    std::vector<double> particleVirials;
};

/**
 * What a force kernel lends the integrator kernel of the same platform: the force's checks on the device (the Common
 * platforms), which a run of steps may defer; its neighbour list on the host, whose candidates a sweep order built at
 * the same positions may take. An integrator kernel gets null for what it cannot use, so any force kernel can meet any
 * integrator kernel.
 */
class GenDPDEPairSource {
public:
    virtual ~GenDPDEPairSource() {}
    /** The force's checks on the device, which an integrator kernel of the Common platforms may defer, or null. */
    virtual CommonGenDPDEForceChecks* getDeviceChecks() { return nullptr; }
    /**
     * The force's neighbour list on the host platforms (Reference, CPU), or null: a sweep order built at the positions
     * the list was last built at may take its candidates instead of searching them again.
     */
    virtual const NeighborList* getHostNeighborList() const { return nullptr; }
};

/**
 * The particles' thermal state as the integrator kernel holds it, read by the force kernel of the same platform when
 * some particle's equation of state depends on temperature (docs/theory.md section 11; host platforms). Valid until
 * the integrator's state next changes.
 */
struct GenDPDEThermalState {
    bool isothermal; // Isothermal mode: every particle at temperature
    double temperature; // the bath temperature T (K)
    const double* internalEnergies; // eps_i = C_V theta_i (kJ/mol) at the densities where sigma was densityEntropies
    const double* densityEntropies; // sigma(n_i) of those densities (kJ/(mol K)), or null if not known (positions or
            // energies set since): then eps_i belongs to the current positions
    const int* particleClass; // the class of each particle (IntegratorTypeTables)
    const double* classHeatCapacity; // C_V of each class (kJ/(mol K))
    bool checkStep; // an evaluation of a step: a particle whose temperature the step's motion
            // changed by more than GENDPDE_STEP_TEMPERATURE_FACTOR is an error
};

/** The kernel that evaluates a GenDPDEForce. */
class CalcGenDPDEForceKernel : public OpenMM::KernelImpl {
public:
    static std::string Name() { return "CalcGenDPDEForce"; }
    CalcGenDPDEForceKernel(std::string name, const OpenMM::Platform& platform) : OpenMM::KernelImpl(name, platform) {}
    /** Prepare the kernel for a Context holding this System and force. */
    virtual void initialize(const OpenMM::System& system, const GenDPDEForce& force) = 0;
    /** Add the forces to the Context's force array and return the energy (kJ/mol). */
    virtual double execute(OpenMM::ContextImpl& context, bool includeForces, bool includeEnergy) = 0;
    /** Copy the parameters that updateParametersInContext() may change. */
    virtual void copyParametersToContext(OpenMM::ContextImpl& context, const GenDPDEForce& force) = 0;
    /**
     * The observables at the Context's current positions; the per-particle virial tensors only if particleVirials
     * (they cost a pass of their own, which no step pays).
     */
    virtual const GenDPDEObservables& getObservables(OpenMM::ContextImpl& context, bool particleVirials) = 0;
    /**
     * The pairs of the last evaluation, for an integrator kernel of the same platform (valid until the next
     * evaluation), or null if this kernel lends none.
     */
    virtual GenDPDEPairSource* getPairSource() { return nullptr; }
    /**
     * A force whose laws depend on temperature (docs/theory.md section 11): give the integrator kernel of the same
     * platform each particle's C_V theta_i and sigma(n_i) at the positions of the last evaluation, to keep as its
     * state (IntegrateGenDPDEStepKernel::keepThermalState, or its device counterpart). Returns false if this kernel's
     * laws do not depend on temperature.
     */
    virtual bool giveThermalState(class IntegrateGenDPDEStepKernel& integratorKernel) { return false; }
};

/** The kernel that advances a GenDPDEIntegrator by one step and owns the internal energies. */
class IntegrateGenDPDEStepKernel : public OpenMM::KernelImpl {
public:
    static std::string Name() { return "IntegrateGenDPDEStep"; }
    IntegrateGenDPDEStepKernel(std::string name, const OpenMM::Platform& platform) :
            OpenMM::KernelImpl(name, platform) {}
    /**
     * Prepare the kernel for a Context.
     *
     * @param cutoff            the range of the pair interactions (nm); 0 if unknown (then no pair sweep may run)
     * @param seed              the random number seed actually used
     * @param internalEnergies  the initial eps_i (kJ/mol), one per particle
     * @param particleTypes     the particles' types (particle -> type, others 0), the integrator's or the
     *                          GenDPDEForce's (GenDPDEIntegratorUtilities::particleTypes), checked already
     */
    virtual void initialize(OpenMM::ContextImpl& context, const GenDPDEIntegrator& integrator, double cutoff, int seed,
                            const std::vector<double>& internalEnergies, const std::map<int, int>& particleTypes) = 0;
    /**
     * One step. The forces of the integration groups at the current positions have just been computed.
     *
     * @param terms        what the step contains (GenDPDEIntegratorUtilities::stepTerms)
     * @param pairSource   what a GenDPDEForce with the pair range as its cutoff lends this kernel
     *                     (GenDPDEIntegratorUtilities::findPairSource; its device checks), or null
     */
    virtual void execute(OpenMM::ContextImpl& context, const GenDPDEIntegrator& integrator,
                         const GenDPDEStepTerms& terms, GenDPDEPairSource* pairSource) = 0;
    /**
     * Before a run of steps (GenDPDEIntegrator::step(n)) with these terms and pair source (see execute()): a kernel
     * may then defer its checks to finishSteps(), so that a step need not wait for the device.
     */
    virtual void beginSteps(OpenMM::ContextImpl& context, const GenDPDEIntegrator& integrator,
                            const GenDPDEStepTerms& terms, GenDPDEPairSource* pairSource) {}
    /**
     * After a run of steps, or when it was interrupted: throws the first failure of the run (naming the particle and
     * the step; the Context is left at that step, in the state of before it), if any.
     */
    virtual void finishSteps(OpenMM::ContextImpl& context, const GenDPDEIntegrator& integrator) {}
    /** Whether the internal energies were ever set (all zero means never: docs/integrator.md). */
    virtual bool hasInternalEnergies() const {
        const std::vector<double>& energies = getInternalEnergies();
        return !energies.empty() && energies[0] != 0.0;
    }
    /** The kinetic energy with on-step velocities v + (dt/2) F/m (kJ/mol). */
    virtual double computeKineticEnergy(OpenMM::ContextImpl& context, const GenDPDEIntegrator& integrator) = 0;
    /** eps_i (kJ/mol), at the densities of the last keepThermalState() if a law depends on temperature. */
    virtual const std::vector<double>& getInternalEnergies() const = 0;
    /** Set eps_i (kJ/mol) as belonging to the current positions (forgets the sigma_i of keepThermalState()). */
    virtual void setInternalEnergies(const std::vector<double>& internalEnergies) = 0;
    /**
     * The thermal state a host platform's force kernel whose laws depend on temperature reads (docs/theory.md section
     * 11); the GPU platforms hold it on the device instead (getDeviceThermalState) and throw here.
     */
    virtual GenDPDEThermalState getThermalState(const GenDPDEIntegrator& integrator) {
        throw OpenMM::OpenMMException("GenDPDEIntegrator: the " + getPlatform().getName()
                                      + " platform holds the "
                                        "particles' thermal state on the device, not on the host");
    }
    /**
     * Keep the particles' thermal state found by a force evaluation at the current positions: eps_i = thermalEnergies
     * (C_V theta_i, kJ/mol) and the sigma(n_i) they belong to (kJ/(mol K)).
     */
    virtual void keepThermalState(const std::vector<double>& thermalEnergies,
                                  const std::vector<double>& densityEntropies) {}
    /** Forget the sigma_i of keepThermalState(): eps_i now belongs to the current positions (they were set). */
    virtual void forgetDensityEntropies() {}
    /**
     * The GPU platforms' counterpart of getThermalState(): the device arrays of the thermal state (null on the host
     * platforms). The force kernel of the same platform reads them.
     */
    virtual CommonGenDPDEThermalArrays* getDeviceThermalState(const GenDPDEIntegrator& integrator) { return nullptr; }
    /** The GPU platforms' counterpart of keepThermalState(): device arrays by original index (mixed precision). */
    virtual void keepDeviceThermalState(OpenMM::ComputeArray& thermalEnergies, OpenMM::ComputeArray& densityEntropies) {
    }
    virtual int getSeed() const = 0;
    virtual void setSeed(int seed) = 0;
    /**
     * The positions (nm, by particle index) and periodic box vectors (nm) at which the sweep's order was last built
     * (docs/theory.md section 6), for a checkpoint: false if no order is built.
     */
    virtual bool getSweepBuild(std::vector<OpenMM::Vec3>& positions, OpenMM::Vec3 box[3]) const { return false; }
    /**
     * Make the next step build the sweep's order from these positions (nm, by particle index) and box vectors (nm)
     * instead of its own, then apply the rule of rebuilds against them as usual: a run continued from a checkpoint
     * follows the order of the uninterrupted run. Forgets the current order.
     */
    virtual void setSweepBuild(const std::vector<OpenMM::Vec3>& positions, const OpenMM::Vec3 box[3]) {}
    /** Forget the sweep's order: the next step builds it at its own positions (a State was set). */
    virtual void forgetSweepOrder() {}
};

} // namespace GenDPDEPlugin

#endif /*GENDPDE_KERNELS_H_*/
