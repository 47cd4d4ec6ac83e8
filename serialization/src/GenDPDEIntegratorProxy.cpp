/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
#include "GenDPDEIntegratorProxy.h"
#include "GenDPDEIntegrator.h"
#include "ParticleTypesXml.h"
#include "internal/StrictXml.h"
#include "openmm/OpenMMException.h"
#include "openmm/serialization/SerializationNode.h"
#include <memory>

using namespace GenDPDEPlugin;
using namespace OpenMM;

namespace {
// Version 2: particle types, per-type heat capacities and type pairs. Version 3: the initial internal energies
// (setInternalEnergies before a Context). Version 4: adiabaticPositionChanges. Versions 1 to 3 are still read.
const int currentVersion = 4;
const char* owner = "GenDPDEIntegrator";

/** The values of the children (each <Particle> with one property) of a list element. */
std::vector<double> particleValues(const SerializationNode& list, const std::string& property, int version) {
    StrictXml::requireOnly(list, owner, version, {}, {"Particle"});
    std::vector<double> values;
    for (const SerializationNode& particle : list.getChildren()) {
        StrictXml::requireOnly(particle, owner, version, {property}, {});
        values.push_back(StrictXml::number(particle, owner, property));
    }
    return values;
}
}

GenDPDEIntegratorProxy::GenDPDEIntegratorProxy() : SerializationProxy("GenDPDEIntegrator") {}

void GenDPDEIntegratorProxy::serialize(const void* object, SerializationNode& node) const {
    node.setIntProperty("version", currentVersion);
    const GenDPDEIntegrator& integrator = *reinterpret_cast<const GenDPDEIntegrator*>(object);
    node.setDoubleProperty("stepSize", integrator.getStepSize());
    node.setDoubleProperty("constraintTolerance", integrator.getConstraintTolerance());
    node.setIntProperty("integrationForceGroups", integrator.getIntegrationForceGroups());
    node.setDoubleProperty("friction", integrator.getFriction());
    node.setDoubleProperty("heatConduction", integrator.getHeatConduction());
    node.setDoubleProperty("heatCapacity", integrator.getHeatCapacity());
    node.setDoubleProperty("cutoff", integrator.getCutoffDistance());
    node.setIntProperty("randomSeed", integrator.getRandomNumberSeed());
    node.setIntProperty("mode", (int) integrator.getMode());
    node.setDoubleProperty("temperature", integrator.getTemperature());
    node.setBoolProperty("adiabaticPositionChanges", integrator.getAdiabaticPositionChanges());
    // The initial particle temperatures or internal energies configured before a Context existed (at most one list
    // is not empty): a parameter of the integrator. The live state of a bound integrator (its Context's internal
    // energies) travels in checkpoints and States only.
    SerializationNode& temperatures = node.createChildNode("ParticleTemperatures");
    for (double t : integrator.initialTemperatures)
        temperatures.createChildNode("Particle").setDoubleProperty("t", t);
    SerializationNode& energies = node.createChildNode("InternalEnergies");
    for (double e : integrator.initialEnergies)
        energies.createChildNode("Particle").setDoubleProperty("e", e);
    serializeParticleTypes(node, integrator.getParticleTypes());
    SerializationNode& heatCapacities = node.createChildNode("TypeHeatCapacities");
    for (int index = 0; index < integrator.getNumTypeHeatCapacities(); index++) {
        int type;
        double heatCapacity;
        integrator.getTypeHeatCapacity(index, type, heatCapacity);
        heatCapacities.createChildNode("Type")
                .setIntProperty("type", type)
                .setDoubleProperty("heatCapacity", heatCapacity);
    }
    SerializationNode& typePairs = node.createChildNode("TypePairs");
    for (int index = 0; index < integrator.getNumTypePairs(); index++) {
        int type1, type2;
        double friction, heatConduction;
        integrator.getTypePairParameters(index, type1, type2, friction, heatConduction);
        typePairs.createChildNode("Pair")
                .setIntProperty("type1", type1)
                .setIntProperty("type2", type2)
                .setDoubleProperty("friction", friction)
                .setDoubleProperty("heatConduction", heatConduction);
    }
}

void* GenDPDEIntegratorProxy::deserialize(const SerializationNode& node) const {
    using namespace StrictXml;
    const int version = integer(node, owner, "version");
    if (version < 1 || version > currentVersion)
        throw OpenMMException("GenDPDEIntegrator: cannot read serialization version " + std::to_string(version)
                              + "; this build reads versions 1 to " + std::to_string(currentVersion));
    // Every value is read whole (StrictXml), the node may hold only what its version defines, and the constructor and
    // setters validate every value: a corrupted file is refused, never read in part.
    std::vector<std::string> properties = {
            "version",    "stepSize",       "constraintTolerance", "integrationForceGroups",
            "friction",   "heatConduction", "heatCapacity",        "cutoff",
            "randomSeed", "mode",           "temperature"};
    std::vector<std::string> children = {"ParticleTemperatures"};
    if (version >= 2)
        children.insert(children.end(), {"ParticleTypes", "TypeHeatCapacities", "TypePairs"});
    if (version >= 3)
        children.push_back("InternalEnergies");
    if (version >= 4)
        properties.push_back("adiabaticPositionChanges");
    requireOnly(node, owner, version, properties, children);
    std::unique_ptr<GenDPDEIntegrator> integrator(
            new GenDPDEIntegrator(number(node, owner, "stepSize"), number(node, owner, "friction"),
                                  number(node, owner, "heatConduction"), number(node, owner, "heatCapacity")));
    integrator->setConstraintTolerance(number(node, owner, "constraintTolerance"));
    integrator->setIntegrationForceGroups(integer(node, owner, "integrationForceGroups"));
    integrator->setCutoffDistance(number(node, owner, "cutoff"));
    integrator->setRandomNumberSeed(integer(node, owner, "randomSeed"));
    integrator->setMode((GenDPDEIntegrator::Mode) integer(node, owner, "mode"));
    const double temperature = number(node, owner, "temperature");
    if (temperature != 0.0)
        integrator->setTemperature(temperature);
    if (version >= 4)
        integrator->setAdiabaticPositionChanges(boolean(node, owner, "adiabaticPositionChanges"));
    const std::vector<double> temperatures = particleValues(child(node, owner, "ParticleTemperatures"), "t", version);
    if (!temperatures.empty())
        integrator->setParticleTemperatures(temperatures);
    if (version >= 3) {
        const std::vector<double> energies = particleValues(child(node, owner, "InternalEnergies"), "e", version);
        if (!energies.empty()) {
            if (!temperatures.empty())
                throw OpenMMException("GenDPDEIntegrator XML: both initial temperatures and initial internal energies "
                                      "are given (at most one list may hold values; corrupt)");
            integrator->setInternalEnergies(energies);
        }
    }
    if (version >= 2) {
        deserializeParticleTypes(node, *integrator, owner, version);
        const SerializationNode& heatCapacities = child(node, owner, "TypeHeatCapacities");
        requireOnly(heatCapacities, owner, version, {}, {"Type"});
        for (const SerializationNode& type : heatCapacities.getChildren()) {
            requireOnly(type, owner, version, {"type", "heatCapacity"}, {});
            integrator->addTypeHeatCapacity(integer(type, owner, "type"), number(type, owner, "heatCapacity"));
        }
        const SerializationNode& typePairs = child(node, owner, "TypePairs");
        requireOnly(typePairs, owner, version, {}, {"Pair"});
        for (const SerializationNode& pair : typePairs.getChildren()) {
            requireOnly(pair, owner, version, {"type1", "type2", "friction", "heatConduction"}, {});
            integrator->addTypePair(integer(pair, owner, "type1"), integer(pair, owner, "type2"),
                                    number(pair, owner, "friction"), number(pair, owner, "heatConduction"));
        }
    }
    return integrator.release();
}
