/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
#include "internal/GenDPDEIntegratorUtilities.h"
#include "GenDPDEForce.h"
#include "internal/GenDPDEForceImpl.h"
#include "GenDPDEKernels.h"
#include "openmm/OpenMMException.h"
#include <algorithm>
#include <cmath>
#include <limits>
#include "internal/MessageText.h"

using namespace GenDPDEPlugin;
using namespace OpenMM;

GenDPDEStepTerms GenDPDEIntegratorUtilities::stepTerms(const GenDPDEIntegrator& integrator, double pairRange) {
    const GenDPDEIntegrator::Mode mode = integrator.getMode();
    GenDPDEStepTerms terms;
    terms.internalEnergies = (mode == GenDPDEIntegrator::Isoenergetic);
    // A term runs if any pair of types has it (the integrator's default, or an addTypePair entry).
    double friction = integrator.getFriction(), heatConduction = integrator.getHeatConduction();
    for (int entry = 0; entry < integrator.getNumTypePairs(); entry++) {
        int type1, type2;
        double entryFriction, entryHeatConduction;
        integrator.getTypePairParameters(entry, type1, type2, entryFriction, entryHeatConduction);
        friction = std::max(friction, entryFriction);
        heatConduction = std::max(heatConduction, entryHeatConduction);
    }
    terms.dissipation = (mode != GenDPDEIntegrator::Conservative && friction > 0.0);
    terms.conduction = (terms.internalEnergies && heatConduction > 0.0);
    terms.pairSweep = terms.dissipation || terms.conduction;
    terms.maxDisplacement = pairRange > 0.0 ? pairRange : std::numeric_limits<double>::infinity();
    return terms;
}

double GenDPDEIntegratorUtilities::pairRange(const System& system, const GenDPDEIntegrator& integrator) {
    double range = integrator.getCutoffDistance();
    if (range != 0.0)
        return range;
    for (int i = 0; i < system.getNumForces(); i++) {
        const GenDPDEForce* force = dynamic_cast<const GenDPDEForce*>(&system.getForce(i));
        if (force == nullptr)
            continue;
        if (range != 0.0 && range != force->getCutoffDistance())
            throw OpenMMException("GenDPDEIntegrator: the System has GenDPDEForces with different cutoffs; "
                                  "call setCutoffDistance() to choose the range of the pair terms");
        range = force->getCutoffDistance();
    }
    return range;
}

GenDPDEPairSource* GenDPDEIntegratorUtilities::findPairSource(ContextImpl& context, const GenDPDEIntegrator& integrator,
                                                              double pairRange) {
    const bool periodic = context.getSystem().usesPeriodicBoundaryConditions();
    for (ForceImpl* impl : context.getForceImpls()) {
        GenDPDEForceImpl* forceImpl = dynamic_cast<GenDPDEForceImpl*>(impl);
        if (forceImpl == nullptr)
            continue;
        const GenDPDEForce& force = forceImpl->getOwner();
        if (force.getCutoffDistance() == pairRange && force.usesPeriodicBoundaryConditions() == periodic
            && (integrator.getIntegrationForceGroups() & (1 << force.getForceGroup())) != 0)
            return forceImpl->getPairSource();
    }
    return nullptr;
}

int GenDPDEIntegratorUtilities::checkThermalForces(const System& system, const GenDPDEIntegrator& integrator) {
    int found = -1;
    for (int i = 0; i < system.getNumForces(); i++) {
        const GenDPDEForce* force = dynamic_cast<const GenDPDEForce*>(&system.getForce(i));
        if (force == nullptr || !force->dependsOnTemperature())
            continue;
        if (found >= 0)
            throw OpenMMException("GenDPDEIntegrator: forces " + std::to_string(found) + " and " + std::to_string(i)
                                  + " of the System are GenDPDEForces whose equations of state depend on temperature; "
                                    "at most one may (the particles have one temperature each)");
        found = i;
        if ((integrator.getIntegrationForceGroups() & (1 << force->getForceGroup())) == 0)
            throw OpenMMException("GenDPDEIntegrator: the GenDPDEForce (force " + std::to_string(i)
                                  + " of the System) "
                                    "has an equation of state that depends on temperature, and its force group "
                                  + std::to_string(force->getForceGroup())
                                  + " is not among the integration force "
                                    "groups; the integrator updates the temperatures from its evaluations");
    }
    return found;
}

IntegrateGenDPDEStepKernel& GenDPDEIntegratorUtilities::thermalStateHolder(ContextImpl& context,
                                                                           const GenDPDEIntegrator*& integrator) {
    integrator = dynamic_cast<const GenDPDEIntegrator*>(&context.getIntegrator());
    if (integrator == nullptr)
        throw OpenMMException("GenDPDEForce: an equation of state that depends on temperature needs a "
                              "GenDPDEIntegrator, which holds the particles' temperatures");
    IntegrateGenDPDEStepKernel& kernel = integrator->boundKernel();
    const bool isothermal = (integrator->getMode() == GenDPDEIntegrator::Isothermal);
    if (isothermal && !(integrator->getTemperature() > 0.0))
        throw OpenMMException(
                "GenDPDEForce: an equation of state that depends on temperature, with the "
                "GenDPDEIntegrator in Isothermal mode, needs the bath temperature; call setTemperature()");
    if (!isothermal && !kernel.hasInternalEnergies())
        throw OpenMMException(
                "GenDPDEForce: an equation of state that depends on temperature needs the particles' "
                "temperatures; call the GenDPDEIntegrator's setTemperature() before creating the Context, "
                "or setParticleTemperatures(), setInternalEnergies() or "
                "setInternalEnergiesToTemperature()");
    return kernel;
}

GenDPDEThermalState GenDPDEIntegratorUtilities::thermalState(ContextImpl& context) {
    const GenDPDEIntegrator* integrator;
    IntegrateGenDPDEStepKernel& kernel = thermalStateHolder(context, integrator);
    return kernel.getThermalState(*integrator);
}

void GenDPDEIntegratorUtilities::keepThermalState(ContextImpl& context, const GenDPDEIntegrator& integrator,
                                                  IntegrateGenDPDEStepKernel& kernel) {
    if (integrator.getMode() == GenDPDEIntegrator::Isothermal) {
        kernel.forgetDensityEntropies();
        return;
    }
    for (ForceImpl* impl : context.getForceImpls()) {
        GenDPDEForceImpl* forceImpl = dynamic_cast<GenDPDEForceImpl*>(impl);
        if (forceImpl != nullptr && forceImpl->giveThermalState(kernel))
            return;   // (at most one such force: checkThermalForces)
    }
}

namespace {

/** Throw, naming the first particle (in index order) whose type differs between two settings of the types. */
void requireSameTypes(const std::map<int, int>& first, const std::string& firstName, const std::map<int, int>& second,
                      const std::string& secondName, int numParticles) {
    auto typeOf = [](const std::map<int, int>& types, int particle) {
        const auto entry = types.find(particle);
        return entry == types.end() ? 0 : entry->second;
    };
    std::vector<int> named;
    for (const auto& entry : first)
        named.push_back(entry.first);
    for (const auto& entry : second)
        named.push_back(entry.first);
    std::sort(named.begin(), named.end());
    for (int particle : named)
        if (particle < numParticles && typeOf(first, particle) != typeOf(second, particle))
            throw OpenMMException(
                    "GenDPDEIntegrator: particle " + std::to_string(particle) + " has type "
                    + std::to_string(typeOf(first, particle)) + " on " + firstName + " but type "
                    + std::to_string(typeOf(second, particle)) + " on " + secondName
                    + ". A particle's type is one "
                      "setting: set the types on the GenDPDEForce (the integrator then takes them), or the same types "
                      "on both (docs/types.md)");
}

} // namespace

std::map<int, int> GenDPDEIntegratorUtilities::particleTypes(const System& system,
                                                             const GenDPDEIntegrator& integrator) {
    const std::map<int, int>* forceTypes = nullptr;
    std::string forceName;
    for (int i = 0; i < system.getNumForces(); i++) {
        const GenDPDEForce* force = dynamic_cast<const GenDPDEForce*>(&system.getForce(i));
        if (force == nullptr || force->getParticleTypes().empty())
            continue;
        const std::string name = "the GenDPDEForce (force " + std::to_string(i) + " of the System)";
        if (forceTypes == nullptr) {
            forceTypes = &force->getParticleTypes();
            forceName = name;
        } else
            requireSameTypes(*forceTypes, forceName, force->getParticleTypes(), name, system.getNumParticles());
    }
    const std::map<int, int>& own = integrator.getParticleTypes();
    if (forceTypes == nullptr)
        return own;
    if (own.empty())
        return *forceTypes;
    requireSameTypes(own, "the GenDPDEIntegrator", *forceTypes, forceName, system.getNumParticles());
    return own;
}

std::string GenDPDEIntegratorUtilities::nonFinitePositionMessage(int particle, const Vec3& position, long long step) {
    MessageText message;
    message << "GenDPDEIntegrator: the position of particle " << particle << " is not finite (" << position[0] << ", "
            << position[1] << ", " << position[2] << ") at step " << step << "; the step was not applied";
    return message.str();
}

std::string GenDPDEIntegratorUtilities::nonFiniteForceMessage(int particle, const Vec3& force, long long step) {
    MessageText message;
    message << "GenDPDEIntegrator: the force on particle " << particle << " is not finite (" << force[0] << ", "
            << force[1] << ", " << force[2] << ") at step " << step << "; the step was not applied";
    return message.str();
}

std::string GenDPDEIntegratorUtilities::unstableStepMessage(int particle, double distance, double maxDisplacement,
                                                            long long step) {
    MessageText message;
    message.precision(6);
    message << "GenDPDEIntegrator: particle " << particle << " would move " << distance << " nm in one step, more "
            << "than the pair range " << maxDisplacement << " nm, at step " << step << ": the simulation has become "
            << "unstable (reduce the step size); the step was not applied";
    return message.str();
}

std::string GenDPDEIntegratorUtilities::nonPositiveEnergyMessage(int particle, double energy, long long step) {
    MessageText message;
    message.precision(6);
    message << "GenDPDEIntegrator: the internal energy of particle " << particle << " would become " << energy
            << " kJ/mol (<= 0) at step " << step << "; the step was not applied. Reduce the step size or increase "
            << "the heat capacity (the relative fluctuations of eps_i scale like sqrt(k_B/C_V))";
    return message.str();
}

std::string GenDPDEIntegratorUtilities::unstableParticleMessage(int particle, const Vec3& velocity, const Vec3& force,
                                                                double inverseMass, double stepSize,
                                                                double maxDisplacement, long long step) {
    if (!(std::isfinite(force[0]) && std::isfinite(force[1]) && std::isfinite(force[2])))
        return nonFiniteForceMessage(particle, force, step);
    const Vec3 displacement = (velocity + force * (stepSize * inverseMass)) * stepSize;
    return unstableStepMessage(particle, std::sqrt(displacement.dot(displacement)), maxDisplacement, step);
}
