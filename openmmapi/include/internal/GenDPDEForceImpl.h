/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
#ifndef GENDPDE_FORCE_IMPL_H_
#define GENDPDE_FORCE_IMPL_H_

#include "GenDPDEForce.h"
#include "GenDPDEKernels.h"
#include "openmm/Kernel.h"
#include "openmm/internal/ForceImpl.h"
#include <map>
#include <string>
#include <vector>

namespace GenDPDEPlugin {

/** The internal implementation of GenDPDEForce inside a Context. */
class GenDPDEForceImpl : public OpenMM::ForceImpl {
public:
    explicit GenDPDEForceImpl(const GenDPDEForce& owner);
    void initialize(OpenMM::ContextImpl& context) override;
    const GenDPDEForce& getOwner() const override { return owner; }
    void updateContextState(OpenMM::ContextImpl& context, bool& forcesInvalid) override {}
    double calcForcesAndEnergy(OpenMM::ContextImpl& context, bool includeForces, bool includeEnergy,
                               int groups) override;
    std::map<std::string, double> getDefaultParameters() override { return {}; }
    std::vector<std::string> getKernelNames() override;
    void updateParametersInContext(OpenMM::ContextImpl& context);
    /** The observables at the Context's positions (the per-particle virial tensors if particleVirials). */
    const GenDPDEObservables& getObservables(OpenMM::ContextImpl& context, bool particleVirials);
    /** The pairs of the kernel's last evaluation, which an integrator kernel may reuse, or null (GenDPDEKernels.h). */
    GenDPDEPairSource* getPairSource();
    /**
     * Give the thermal state of the kernel's last evaluation to an integrator kernel, if the force's laws depend on
     * temperature (CalcGenDPDEForceKernel::giveThermalState); false if they do not.
     */
    bool giveThermalState(IntegrateGenDPDEStepKernel& integratorKernel);
    /** Whether the force's laws depend on temperature (fixed when the Context is created). */
    bool hasThermalLaws() const { return dependsOnTemperature; }
    /**
     * How many times the force has been evaluated in this Context: an evaluation at other positions (a barostat's
     * trial move) replaces the pairs and thermal state the kernel holds, so a GenDPDEIntegrator that keeps the forces
     * of its last evaluation for the next step checks that none came between.
     */
    long long getNumEvaluations() const { return numEvaluations; }
    /**
     * The box term of the background pressure p_b in the virial, -3 p_b V_box (kJ/mol), with p_b as the Context has
     * it (copied at creation and by updateParametersInContext); 0 where p_b = 0.
     */
    double backgroundVirial(OpenMM::ContextImpl& context) const;
    /** How many times updateParametersInContext() has changed the force's parameters in this Context. */
    long long getNumParameterUpdates() const { return numParameterUpdates; }

private:
    const GenDPDEForce& owner;
    OpenMM::Kernel kernel;
    bool dependsOnTemperature = false; // as the Context was created (updateParametersInContext cannot change it)
    double backgroundPressure = 0; // p_b as the Context has it (kJ/mol/nm^3)
    /** p_b > 0 needs periodic boundaries (its energy term is p_b V_box). */
    void checkBackgroundPressure() const;
    long long numEvaluations = 0, numParameterUpdates = 0;
};

} // namespace GenDPDEPlugin

#endif /*GENDPDE_FORCE_IMPL_H_*/
