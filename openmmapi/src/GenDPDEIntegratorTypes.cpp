/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
/* GenDPDEIntegrator's particle types (docs/integrator.md, "Parameters"): a particle's type, each type's heat capacity and
 * each pair of types' friction and heat conduction, with their checks against the bound Context's types. */

#include "GenDPDEIntegrator.h"
#include "internal/GenDPDETypes.h"
#include "internal/ParameterChecks.h"
#include "openmm/OpenMMException.h"
#include <algorithm>
#include <map>
#include <string>
#include <vector>

using namespace GenDPDEPlugin;
using namespace OpenMM;
using namespace ParameterChecks;

namespace {
const char* integratorName = "GenDPDEIntegrator";
} // namespace

void GenDPDEIntegrator::setParticleType(int index, int type) {
    setParticleTypeIn(particleTypes, integratorName, index, type);
    typesChangedWhileBound = (context != nullptr);
}

void GenDPDEIntegrator::requireBoundTypes() {
    if (!typesChangedWhileBound)
        return;
    // The first particle whose type now differs from the one it runs with (the integrator's or the force's).
    for (const auto& entry : particleTypes) {
        const int running = particleTypeIn(contextParticleTypes, entry.first);
        if (entry.second != running)
            throw OpenMMException(
                    "GenDPDEIntegrator: the type of particle " + std::to_string(entry.first) + " was changed to "
                    + std::to_string(entry.second)
                    + " after the Context was created (it runs "
                      "with type "
                    + std::to_string(running)
                    + "); particle types are read when the Context is "
                      "created: call Context.reinitialize(preserveState=True) to apply them, or set them back");
    }
    typesChangedWhileBound = false; // every change gave a particle the type it runs with
}

void GenDPDEIntegrator::requireContextType(const std::string& entry, int type) const {
    if (context == nullptr || std::binary_search(contextTypes.begin(), contextTypes.end(), type))
        return;
    std::string known;
    for (int t : contextTypes)
        known += (known.empty() ? "" : ", ") + std::to_string(t);
    throw OpenMMException(entry + ": no particle of the Context has type " + std::to_string(type) + " (its types are "
                          + known
                          + "), so the entry could never take effect; particle types are read when the "
                            "Context is created: set them, call Context.reinitialize(preserveState=True), then add "
                            "the entry");
}

int GenDPDEIntegrator::getParticleType(int index) const {
    return particleTypeIn(particleTypes, index);
}

const std::map<int, int>& GenDPDEIntegrator::getParticleTypes() const {
    return particleTypes;
}

void GenDPDEIntegrator::checkTypeHeatCapacity(int index, int type, double heatCapacity) const {
    const std::string entry = std::string(integratorName) + " type heat capacity " + std::to_string(index) + " (type "
            + std::to_string(type) + ")";
    requireInRange(entry, "heat capacity", heatCapacity, Ranges::heatCapacity);
    requireContextType(entry, type);
    for (int other = 0; other < (int) typeHeatCapacities.size(); other++)
        if (other != index && typeHeatCapacities[other].type == type)
            throw OpenMMException(entry + ": type " + std::to_string(type) + " already has a heat capacity (entry "
                                  + std::to_string(other) + "); change that entry with setTypeHeatCapacity()");
}

int GenDPDEIntegrator::addTypeHeatCapacity(int type, double heatCapacity) {
    checkTypeHeatCapacity(typeHeatCapacities.size(), type, heatCapacity);
    typeHeatCapacities.push_back({type, heatCapacity});
    applyThermalRule(ThermalEvent::ParametersChanged);
    return typeHeatCapacities.size() - 1;
}

int GenDPDEIntegrator::getNumTypeHeatCapacities() const {
    return typeHeatCapacities.size();
}

void GenDPDEIntegrator::getTypeHeatCapacity(int index, int& type, double& heatCapacity) const {
    requireIndex(integratorName, "type heat capacity index", index, typeHeatCapacities.size());
    type = typeHeatCapacities[index].type;
    heatCapacity = typeHeatCapacities[index].heatCapacity;
}

void GenDPDEIntegrator::setTypeHeatCapacity(int index, int type, double heatCapacity) {
    requireIndex(integratorName, "type heat capacity index", index, typeHeatCapacities.size());
    checkTypeHeatCapacity(index, type, heatCapacity);
    typeHeatCapacities[index] = {type, heatCapacity};
    applyThermalRule(ThermalEvent::ParametersChanged);
}

void GenDPDEIntegrator::checkTypePair(int index, int type1, int type2, double friction, double heatConduction) const {
    const std::string entry = std::string(integratorName) + " type pair " + std::to_string(index) + " (types "
            + std::to_string(type1) + ", " + std::to_string(type2) + ")";
    requireInRange(entry, "friction", friction, Ranges::friction);
    requireInRange(entry, "heat conduction", heatConduction, Ranges::heatConduction);
    requireContextType(entry, type1);
    requireContextType(entry, type2);
    for (int other = 0; other < (int) typePairs.size(); other++) {
        const TypePair& p = typePairs[other];
        if (other != index && ((p.type1 == type1 && p.type2 == type2) || (p.type1 == type2 && p.type2 == type1)))
            throw OpenMMException(entry + ": this pair of types already has parameters (entry " + std::to_string(other)
                                  + "); change that entry with setTypePairParameters()");
    }
}

int GenDPDEIntegrator::addTypePair(int type1, int type2, double friction, double heatConduction) {
    checkTypePair(typePairs.size(), type1, type2, friction, heatConduction);
    typePairs.push_back({type1, type2, friction, heatConduction});
    return typePairs.size() - 1;
}

int GenDPDEIntegrator::getNumTypePairs() const {
    return typePairs.size();
}

void GenDPDEIntegrator::getTypePairParameters(int index, int& type1, int& type2, double& friction,
                                              double& heatConduction) const {
    requireIndex(integratorName, "type pair index", index, typePairs.size());
    const TypePair& p = typePairs[index];
    type1 = p.type1;
    type2 = p.type2;
    friction = p.friction;
    heatConduction = p.heatConduction;
}

void GenDPDEIntegrator::setTypePairParameters(int index, int type1, int type2, double friction, double heatConduction) {
    requireIndex(integratorName, "type pair index", index, typePairs.size());
    checkTypePair(index, type1, type2, friction, heatConduction);
    typePairs[index] = {type1, type2, friction, heatConduction};
}

std::vector<double> GenDPDEIntegrator::particleHeatCapacities(const System& system,
                                                              const std::map<int, int>& typeOfParticle) const {
    const ParticleTypeIndex types(typeOfParticle, system.getNumParticles(), integratorName);
    return GenDPDEPlugin::particleHeatCapacities(typePairTable(*this, types), types);
}
