/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
#ifndef REFERENCE_GENDPDE_FORCE_KERNEL_H_
#define REFERENCE_GENDPDE_FORCE_KERNEL_H_

#include "GenDPDEKernels.h"
#include "NeighborList.h"
#include "internal/GenDPDEPhysics.h"
#include "internal/GenDPDETypes.h"
#include "openmm/Vec3.h"
#include <memory>
#include <vector>

namespace GenDPDEPlugin {

/**
 * Reference (double precision, single thread) evaluation of GenDPDEForce, docs/theory.md sections 2-4:
 * one sweep over the pairs for the primitive densities (and, for estimators that read them, the first moments), one
 * pass over the particles for their states (the physics core's gendpdeParticleState), and one sweep over the pairs
 * for the forces and the virial.
 */
class ReferenceCalcGenDPDEForceKernel : public CalcGenDPDEForceKernel, public GenDPDEPairSource {
public:
    ReferenceCalcGenDPDEForceKernel(std::string name, const OpenMM::Platform& platform) :
            CalcGenDPDEForceKernel(name, platform) {}
    void initialize(const OpenMM::System& system, const GenDPDEForce& force) override;
    double execute(OpenMM::ContextImpl& context, bool includeForces, bool includeEnergy) override;
    void copyParametersToContext(OpenMM::ContextImpl& context, const GenDPDEForce& force) override;
    const GenDPDEObservables& getObservables(OpenMM::ContextImpl& context, bool particleVirials) override;
    GenDPDEPairSource* getPairSource() override { return this; }
    const NeighborList* getHostNeighborList() const override { return neighborList.get(); }
    bool giveThermalState(IntegrateGenDPDEStepKernel& integratorKernel) override {
        if (dependsOnTemperature)
            integratorKernel.keepThermalState(thermalEnergy, densityEntropy);
        return dependsOnTemperature;
    }

protected:
    /**
     * What the particle pass needs per evaluation: the estimator, the equation of state of each type and, if a law
     * depends on temperature, the particles' thermal state (the Context's GenDPDEIntegrator's).
     */
    struct ParticleModel {
        ParticleModel(const ReferenceCalcGenDPDEForceKernel& kernel, OpenMM::ContextImpl& context);
        /**
         * Particle i's state (type index t, primitive density n0, squared moment G): the physics core's
         * gendpdeParticleState, whatever the law; a law that depends on temperature reads the thermal state, a law
         * that does not (Tait, in a force whose other laws depend on temperature) keeps its eps_i as it is.
         */
        int particleState(int i, int t, double n0, double G, Physics::ParticleState& state) const {
            const Physics::LocalEquationOfState& law = (*laws)[t];
            Physics::ThermalInput input = {false, 0.0, 0.0, 0.0, false, 0.0, false};
            if (thermal.internalEnergies != nullptr)
                input.storedEnergy = thermal.internalEnergies[i];
            if (law.dependsOnTemperature())
                input = {thermal.isothermal,
                         thermal.temperature,
                         thermal.internalEnergies[i],
                         thermal.densityEntropies != nullptr ? thermal.densityEntropies[i] : 0.0,
                         thermal.densityEntropies != nullptr,
                         thermal.classHeatCapacity[thermal.particleClass[i]],
                         thermal.checkStep};
            return Physics::particleState(estimator, law, n0, G, input, state);
        }
        Physics::VolumeEstimator estimator;
        const std::vector<Physics::LocalEquationOfState>* laws;   // by type index
        GenDPDEThermalState thermal;   // if kernel.dependsOnTemperature
    };
    /** Take the parameters that updateParametersInContext() may change; reject changes of the others. */
    void readParameters(const GenDPDEForce& force);
    /** Throw if firstBadParticle >= 0 (a non-finite position) or the cutoff exceeds half the box. */
    void checkConfiguration(OpenMM::ContextImpl& context, int firstBadParticle) const;
    /** The first particle in [begin, end) whose position is not finite, or -1. */
    static int firstNonFinitePosition(const std::vector<OpenMM::Vec3>& positions, int begin, int end);
    /** Whether the estimator needs the first moments of the neighbourhoods (VC). */
    bool usesMoments() const { return Physics::gendpdeEstimatorNeedsMoments(estimator) != 0; }
    /** Store particle i's state in the per-particle arrays. */
    void storeParticle(int i, const Physics::ParticleState& state) {
        volume[i] = state.volume;
        pressure[i] = state.pressure;
        forceCoefficient[i] = state.forceCoefficient;
        if (usesMoments())
            momentForce[i] = moment[i] * state.momentForceScale;
        storeThermalState(i, state);
    }
    /** Store particle i's thermal state (a law that depends on temperature; nothing otherwise). */
    void storeThermalState(int i, const Physics::ParticleState& state) {
        if (dependsOnTemperature) {
            thermalEnergy[i] = state.thermalEnergy;
            densityEntropy[i] = state.densityEntropy;
        }
    }
    /**
     * The error for particle i whose state has this status (Physics, GENDPDE_PARTICLE_*), naming it and the step;
     * volume: its volume (nm^3). The particle's state is stored already (storeParticle()).
     */
    [[noreturn]] void throwParticleError(int status, int i, double volume, OpenMM::ContextImpl& context) const;
    /** Pair sweep and particle pass: fills the per-particle arrays and returns U = sum_i f(n_i) (kJ/mol). */
    virtual double computeDensitiesAndEnergy(OpenMM::ContextImpl& context);
    /**
     * Pair sweep for F_i (added to *forces unless null) and, if particleVirials is not null, each particle's virial
     * tensor (9 per particle, kJ/mol); returns the virial W (kJ/mol).
     */
    virtual double computePairForces(OpenMM::ContextImpl& context, std::vector<OpenMM::Vec3>* forces,
                                     std::vector<double>* particleVirials);
    double cutoff, cutoffScaling;
    std::unique_ptr<ParticleTypeIndex> types;   // the particle types, fixed when the Context is created
    std::vector<Physics::LocalEquationOfState> lawByType;   // by type index
    bool dependsOnTemperature = false;          // some type's law does (docs/theory.md section 11)
    int estimator;                              // GenDPDEForce::DensityEstimator (= GENDPDE_ESTIMATOR_*)
    bool periodic;
    std::unique_ptr<NeighborList> neighborList;
    int numParticles = 0;
    /** Give the per-particle arrays below (primitiveDensity ... forceCoefficient) their size, where a pass fills them. */
    void sizeParticleArrays() {
        for (std::vector<double>* values : {&primitiveDensity, &volume, &pressure, &forceCoefficient})
            values->resize(numParticles);
    }
    // Whether computeDensitiesAndEnergy() runs for getObservables(), which reads the per-particle arrays below (the
    // CPU platform's passes fill them only then).
    bool observablesAsked = false;
    // Per particle, at the positions of the last evaluation that filled them (sizeParticleArrays()).
    std::vector<double> primitiveDensity, volume, pressure;
    std::vector<double> forceCoefficient; // pi_i dV_i/dn0_i (kJ/mol nm^3)
    // Laws that depend on temperature: C_V theta_i (kJ/mol) and sigma(n_i) (kJ/(mol K)); eps_i and 0 for Tait particles.
    std::vector<double> thermalEnergy, densityEntropy;
    std::vector<double> particleVirial; // sum over the pairs (i, j > i) of r_ij . F_ij (kJ/mol)
    std::vector<OpenMM::Vec3> moment; // VC: g_i = sum_j phi(r_ij) e_ij (dimensionless)
    std::vector<OpenMM::Vec3> momentForce; // VC: q_i = 2 pi_i dV_i/dG_i g_i (kJ/mol)
    // Observables and the configuration they belong to.
    GenDPDEObservables observables;
    std::vector<OpenMM::Vec3> observedPositions;
    OpenMM::Vec3 observedBox[3];
    bool observablesValid = false, observedVirials = false;
};

} // namespace GenDPDEPlugin

#endif /*REFERENCE_GENDPDE_FORCE_KERNEL_H_*/
