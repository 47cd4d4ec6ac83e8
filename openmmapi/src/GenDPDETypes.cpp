/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
#include "internal/GenDPDETypes.h"
#include "gendpde/GenDPDEEquationsOfState.h"
#include "internal/ParameterChecks.h"
#include "openmm/OpenMMException.h"
#include <algorithm>
#include <set>

using namespace GenDPDEPlugin;
using namespace OpenMM;

ParticleTypeIndex::ParticleTypeIndex(const std::map<int, int>& particleTypes, int numParticles,
                                     const std::string& owner) : owner(owner) {
    if (!particleTypes.empty() && particleTypes.rbegin()->first >= numParticles)
        throw OpenMMException(owner + ": setParticleType() was given particle "
                              + std::to_string(particleTypes.rbegin()->first) + ", but the System has "
                              + std::to_string(numParticles) + " particles");
    std::set<int> distinct;
    if ((int) particleTypes.size() < numParticles)
        distinct.insert(0);   // some particle was never given a type
    for (const auto& entry : particleTypes)
        distinct.insert(entry.second);
    types.assign(distinct.begin(), distinct.end());
    particleTypeIndex.assign(numParticles, indexOf(0));
    for (const auto& entry : particleTypes)
        particleTypeIndex[entry.first] = indexOf(entry.second);
}

int ParticleTypeIndex::indexOf(int type) const {
    const auto found = std::lower_bound(types.begin(), types.end(), type);
    return (found != types.end() && *found == type) ? (int) (found - types.begin()) : -1;
}

int ParticleTypeIndex::requireIndexOf(int type, const std::string& entry) const {
    const int index = indexOf(type);
    if (index < 0) {
        std::string known;
        for (int t : types)
            known += (known.empty() ? "" : ", ") + std::to_string(t);
        throw OpenMMException(owner + ": " + entry + " names type " + std::to_string(type)
                              + ", which no particle "
                                "has (the particles' types are "
                              + known
                              + "); set the particle types with "
                                "setParticleType() or remove the entry");
    }
    return index;
}

void GenDPDEPlugin::setParticleTypeIn(std::map<int, int>& particleTypes, const std::string& owner, int index,
                                      int type) {
    if (index < 0)
        ParameterChecks::reject(owner, "particle index in setParticleType", index, "", ">= 0");
    particleTypes[index] = type;
}

int GenDPDEPlugin::particleTypeIn(const std::map<int, int>& particleTypes, int index) {
    const auto found = particleTypes.find(index);
    return found == particleTypes.end() ? 0 : found->second;
}

std::vector<TaitParameters> GenDPDEPlugin::taitParametersByType(const GenDPDEForce& force,
                                                                const ParticleTypeIndex& types) {
    TaitParameters defaults;
    force.getTaitParameters(defaults.referenceDensity, defaults.referencePressure, defaults.bulkModulus,
                            defaults.exponent);
    std::vector<TaitParameters> table(types.getNumTypes(), defaults);
    for (int entry = 0; entry < force.getNumTypeParameters(); entry++) {
        int type;
        TaitParameters p;
        force.getTypeParameters(entry, type, p.referenceDensity, p.referencePressure, p.bulkModulus, p.exponent);
        table[types.requireIndexOf(type, "type parameters " + std::to_string(entry))] = p;
    }
    return table;
}

const char* GenDPDEPlugin::equationOfStateName(GenDPDEForce::EquationOfState law) {
    return EquationsOfState::laws[law].name;
}

std::vector<Physics::LocalEquationOfState> GenDPDEPlugin::equationsOfStateByType(const GenDPDEForce& force,
                                                                                 const ParticleTypeIndex& types) {
    std::vector<GenDPDEForce::EquationOfState> law(types.getNumTypes());
    std::vector<std::vector<double>> parameters(types.getNumTypes());
    for (int t = 0; t < types.getNumTypes(); t++)
        force.getEquationOfState(law[t], parameters[t]);
    for (int entry = 0; entry < force.getNumTypeEquationsOfState(); entry++) {
        int type;
        GenDPDEForce::EquationOfState entryLaw;
        std::vector<double> entryParameters;
        force.getTypeEquationOfState(entry, type, entryLaw, entryParameters);
        const int t = types.requireIndexOf(type, "type equation of state " + std::to_string(entry));
        law[t] = entryLaw;
        parameters[t] = entryParameters;
    }
    const std::vector<TaitParameters> tait = taitParametersByType(force, types);
    std::vector<Physics::LocalEquationOfState> table;
    for (int t = 0; t < types.getNumTypes(); t++)
        table.push_back(packEquationOfState(law[t], parameters[t], tait[t], force.getBackgroundPressure()));
    return table;
}

Physics::LocalEquationOfState GenDPDEPlugin::packEquationOfState(GenDPDEForce::EquationOfState law,
                                                                 const std::vector<double>& parameters,
                                                                 const TaitParameters& tait,
                                                                 double backgroundPressure) {
    // The given parameters (the Tait four first for a law that extends Tait) packed as the core reads them, with
    // the background pressure (GenDPDEEquationsOfState.h, packCoreParameters: as the LAMMPS package packs them).
    const EquationsOfState::Law& description = EquationsOfState::laws[law];
    std::vector<double> given;
    if (description.extendsTait)
        given = {tait.referenceDensity, tait.referencePressure, tait.bulkModulus, tait.exponent};
    given.insert(given.end(), parameters.begin(), parameters.end());
    Physics::LocalEquationOfState eos;
    eos.law = description.coreId;
    eos.parameter.resize(EquationsOfState::coreStride());
    eos.integerPower =
            EquationsOfState::packCoreParameters(description, given.data(), backgroundPressure, eos.parameter.data());
    return eos;
}

TypePairTable GenDPDEPlugin::typePairTable(const GenDPDEIntegrator& integrator, const ParticleTypeIndex& types) {
    // The classes: 0 for every type without an entry, then one per type named by an entry, in the order named.
    TypePairTable table;
    table.classOfType.assign(types.getNumTypes(), 0);
    std::vector<int> typeOfClass = {-1};
    auto classOf = [&](int type, const std::string& entry) {
        int& assigned = table.classOfType[types.requireIndexOf(type, entry)];
        if (assigned == 0) {
            assigned = typeOfClass.size();
            typeOfClass.push_back(type);
        }
        return assigned;
    };
    for (int entry = 0; entry < integrator.getNumTypeHeatCapacities(); entry++) {
        int type;
        double heatCapacity;
        integrator.getTypeHeatCapacity(entry, type, heatCapacity);
        classOf(type, "type heat capacity " + std::to_string(entry));
    }
    for (int entry = 0; entry < integrator.getNumTypePairs(); entry++) {
        int type1, type2;
        double friction, heatConduction;
        integrator.getTypePairParameters(entry, type1, type2, friction, heatConduction);
        classOf(type1, "type pair " + std::to_string(entry));
        classOf(type2, "type pair " + std::to_string(entry));
    }
    // The values: the integrator's everywhere, then the entries'.
    const int n = table.numClasses = typeOfClass.size();
    table.heatCapacity.assign(n, integrator.getHeatCapacity());
    table.friction.assign(n * n, integrator.getFriction());
    table.heatConduction.assign(n * n, integrator.getHeatConduction());
    for (int entry = 0; entry < integrator.getNumTypeHeatCapacities(); entry++) {
        int type;
        double heatCapacity;
        integrator.getTypeHeatCapacity(entry, type, heatCapacity);
        table.heatCapacity[table.classOf(types.indexOf(type))] = heatCapacity;
    }
    for (int entry = 0; entry < integrator.getNumTypePairs(); entry++) {
        int type1, type2;
        double friction, heatConduction;
        integrator.getTypePairParameters(entry, type1, type2, friction, heatConduction);
        const int a = table.classOf(types.indexOf(type1)), b = table.classOf(types.indexOf(type2));
        table.friction[a * n + b] = table.friction[b * n + a] = friction;
        table.heatConduction[a * n + b] = table.heatConduction[b * n + a] = heatConduction;
    }
    return table;
}

std::vector<double> GenDPDEPlugin::particleHeatCapacities(const TypePairTable& table, const ParticleTypeIndex& types) {
    std::vector<double> result;
    result.reserve(types.getParticleTypeIndices().size());
    for (int t : types.getParticleTypeIndices())
        result.push_back(table.heatCapacity[table.classOf(t)]);
    return result;
}

bool IntegratorTypeTables::update(const GenDPDEIntegrator& integrator) {
    TypePairTable next = typePairTable(integrator, types);
    const bool classesChanged = particleClass.empty() || next.classOfType != table.classOfType;
    table = std::move(next);
    if (classesChanged) {
        particleClass.clear();
        particleClass.reserve(types.getParticleTypeIndices().size());
        for (int t : types.getParticleTypeIndices())
            particleClass.push_back(table.classOf(t));
    }
    return classesChanged;
}
