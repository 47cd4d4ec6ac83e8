/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
#include "internal/GenDPDEForceImpl.h"
#include "GenDPDEIntegrator.h"
#include "internal/BoxGeometry.h"
#include "gendpde/GenDPDEEquationsOfState.h"
#include "internal/GenDPDETypes.h"
#include "openmm/OpenMMException.h"
#include "openmm/internal/ContextImpl.h"
#include "internal/MessageText.h"

using namespace GenDPDEPlugin;
using namespace OpenMM;

GenDPDEForceImpl::GenDPDEForceImpl(const GenDPDEForce& owner) : owner(owner) {}

namespace {
/** The volume of the Context's periodic box (nm^3). */
double boxVolume(ContextImpl& context) {
    Vec3 a, b, c;
    context.getPeriodicBoxVectors(a, b, c);
    return a[0] * b[1] * c[2];
}

/** Whether a law depends on temperature (the physics core's gendpdeLawDependsOnTemperature). */
bool lawDependsOnTemperature(GenDPDEForce::EquationOfState law) {
    return Physics::gendpdeLawDependsOnTemperature(EquationsOfState::laws[law].coreId) != 0;
}

/** Which law makes the force depend on temperature, for messages: "the equation of state of type 2 (...)". */
std::string describeTemperatureDependence(const GenDPDEForce& force) {
    GenDPDEForce::EquationOfState law;
    std::vector<double> parameters;
    force.getEquationOfState(law, parameters);
    if (lawDependsOnTemperature(law))
        return std::string("the equation of state of the types without an entry (") + equationOfStateName(law) + ")";
    for (int entry = 0; entry < force.getNumTypeEquationsOfState(); entry++) {
        int type;
        force.getTypeEquationOfState(entry, type, law, parameters);
        if (lawDependsOnTemperature(law))
            return "the equation of state of type " + std::to_string(type) + " (" + equationOfStateName(law) + ")";
    }
    return "no equation of state";
}
} // namespace

void GenDPDEForceImpl::initialize(ContextImpl& context) {
    const System& system = context.getSystem();
    if (owner.usesPeriodicBoundaryConditions()) {
        Vec3 box[3];
        system.getDefaultPeriodicBoxVectors(box[0], box[1], box[2]);
        BoxGeometry::checkCutoffAgainstBox("GenDPDEForce", owner.getCutoffDistance(), box);
    }
    if (owner.dependsOnTemperature() && dynamic_cast<GenDPDEIntegrator*>(&context.getIntegrator()) == nullptr)
        throw OpenMMException("GenDPDEForce: " + describeTemperatureDependence(owner)
                              + " depends on temperature and "
                                "needs a GenDPDEIntegrator, which holds the particles' temperatures; the Context's "
                                "integrator is another");
    checkBackgroundPressure();
    dependsOnTemperature = owner.dependsOnTemperature();
    backgroundPressure = owner.getBackgroundPressure();
    kernel = context.getPlatform().createKernel(CalcGenDPDEForceKernel::Name(), context);
    kernel.getAs<CalcGenDPDEForceKernel>().initialize(system, owner);
}

double GenDPDEForceImpl::calcForcesAndEnergy(ContextImpl& context, bool includeForces, bool includeEnergy, int groups) {
    if ((groups & (1 << owner.getForceGroup())) == 0)
        return 0.0;
    numEvaluations++;
    double energy = kernel.getAs<CalcGenDPDEForceKernel>().execute(context, includeForces, includeEnergy);
    if (includeEnergy && backgroundPressure != 0)
        energy += Physics::gendpdeBackgroundEnergy(backgroundPressure, boxVolume(context));
    return energy;
}

double GenDPDEForceImpl::backgroundVirial(ContextImpl& context) const {
    return backgroundPressure == 0 ? 0.0 : Physics::gendpdeBackgroundVirial(backgroundPressure, boxVolume(context));
}

void GenDPDEForceImpl::checkBackgroundPressure() const {
    if (owner.getBackgroundPressure() != 0 && !owner.usesPeriodicBoundaryConditions()) {
        MessageText message;
        message << "GenDPDEForce: background pressure p_b = " << owner.getBackgroundPressure() << " kJ/mol/nm^3 "
                << "needs periodic boundaries (its energy is p_b V_box); the nonbonded method is CutoffNonPeriodic: "
                << "set p_b = 0 or use CutoffPeriodic";
        throw OpenMMException(message.str());
    }
}

std::vector<std::string> GenDPDEForceImpl::getKernelNames() {
    return {CalcGenDPDEForceKernel::Name()};
}

void GenDPDEForceImpl::updateParametersInContext(ContextImpl& context) {
    if (owner.dependsOnTemperature() != dependsOnTemperature)
        throw OpenMMException("GenDPDEForce: updateParametersInContext() cannot change whether an equation of state "
                              "depends on temperature; call Context.reinitialize() (or create a new Context) after "
                              "changing it");
    checkBackgroundPressure();
    kernel.getAs<CalcGenDPDEForceKernel>().copyParametersToContext(context, owner);
    backgroundPressure = owner.getBackgroundPressure();
    numParameterUpdates++;
    context.systemChanged();   // (a GenDPDEIntegrator applies its rule for the particles' thermal state)
}

const GenDPDEObservables& GenDPDEForceImpl::getObservables(ContextImpl& context, bool particleVirials) {
    return kernel.getAs<CalcGenDPDEForceKernel>().getObservables(context, particleVirials);
}

GenDPDEPairSource* GenDPDEForceImpl::getPairSource() {
    return kernel.getAs<CalcGenDPDEForceKernel>().getPairSource();
}

bool GenDPDEForceImpl::giveThermalState(IntegrateGenDPDEStepKernel& integratorKernel) {
    return kernel.getAs<CalcGenDPDEForceKernel>().giveThermalState(integratorKernel);
}
