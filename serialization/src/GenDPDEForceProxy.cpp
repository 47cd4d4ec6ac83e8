/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
#include "GenDPDEForceProxy.h"
#include "GenDPDEForce.h"
#include "ParticleTypesXml.h"
#include "gendpde/GenDPDEEquationsOfState.h"
#include "internal/StrictXml.h"
#include "openmm/OpenMMException.h"
#include "openmm/serialization/SerializationNode.h"
#include <memory>
#include "internal/MessageText.h"
#include <vector>

using namespace GenDPDEPlugin;
using namespace OpenMM;

namespace {
// Version 2: particle types and per-type Tait parameters. Version 3: the local equations of state (the default law
// and per-type entries, docs/theory.md section 11). Versions 1 and 2 are still read (every type Tait).
const int currentVersion = 4;

void serializeLaw(SerializationNode& node, GenDPDEForce::EquationOfState law, const std::vector<double>& parameters) {
    node.setIntProperty("law", (int) law);
    for (const double p : parameters)
        node.createChildNode("Parameter").setDoubleProperty("value", p);
}

const char* owner = "GenDPDEForce";
/** What a law's number may be, for messages: "an integer naming a law (0 Tait, 1 TaitThermalExpansion, ...)". */
std::string lawNames() {
    std::string list;
    for (int law = 0; law < EquationsOfState::numLaws; law++)
        list += (law == 0 ? "" : ", ") + std::to_string(law) + " " + EquationsOfState::laws[law].name;
    return "an integer naming a law (" + list + ")";
}

/** A law's number (the setter checks that it names a law, and its parameters against the table). */
GenDPDEForce::EquationOfState lawOf(const SerializationNode& node) {
    return (GenDPDEForce::EquationOfState) StrictXml::integer(node, owner, "law", lawNames());
}

std::vector<double> lawParameters(const SerializationNode& node) {
    std::vector<double> parameters;
    for (const SerializationNode& p : node.getChildren()) {
        StrictXml::requireOnly(p, owner, currentVersion, {"value"}, {});
        parameters.push_back(StrictXml::number(p, owner, "value"));
    }
    return parameters;
}
}

GenDPDEForceProxy::GenDPDEForceProxy() : SerializationProxy("GenDPDEForce") {}

void GenDPDEForceProxy::serialize(const void* object, SerializationNode& node) const {
    node.setIntProperty("version", currentVersion);
    const GenDPDEForce& force = *reinterpret_cast<const GenDPDEForce*>(object);
    node.setStringProperty("name", force.getName());
    node.setIntProperty("forceGroup", force.getForceGroup());
    node.setDoubleProperty("cutoff", force.getCutoffDistance());
    node.setIntProperty("method", (int) force.getNonbondedMethod());
    node.setIntProperty("estimator", (int) force.getDensityEstimator());
    node.setDoubleProperty("cutoffScaling", force.getCutoffScaling());
    double n0, pi0, bulkModulus, exponent;
    force.getTaitParameters(n0, pi0, bulkModulus, exponent);
    node.setDoubleProperty("n0", n0);
    node.setDoubleProperty("pi0", pi0);
    node.setDoubleProperty("bulkModulus", bulkModulus);
    node.setDoubleProperty("gammaT", exponent);
    node.setDoubleProperty("backgroundPressure", force.getBackgroundPressure());
    serializeParticleTypes(node, force.getParticleTypes());
    SerializationNode& typeParameters = node.createChildNode("TypeParameters");
    for (int index = 0; index < force.getNumTypeParameters(); index++) {
        int type;
        force.getTypeParameters(index, type, n0, pi0, bulkModulus, exponent);
        typeParameters.createChildNode("Type")
                .setIntProperty("type", type)
                .setDoubleProperty("n0", n0)
                .setDoubleProperty("pi0", pi0)
                .setDoubleProperty("bulkModulus", bulkModulus)
                .setDoubleProperty("gammaT", exponent);
    }
    GenDPDEForce::EquationOfState law;
    std::vector<double> parameters;
    force.getEquationOfState(law, parameters);
    serializeLaw(node.createChildNode("EquationOfState"), law, parameters);
    SerializationNode& typeLaws = node.createChildNode("TypeEquationsOfState");
    for (int index = 0; index < force.getNumTypeEquationsOfState(); index++) {
        int type;
        force.getTypeEquationOfState(index, type, law, parameters);
        SerializationNode& entry = typeLaws.createChildNode("Type");
        entry.setIntProperty("type", type);
        serializeLaw(entry, law, parameters);
    }
}

void* GenDPDEForceProxy::deserialize(const SerializationNode& node) const {
    using namespace StrictXml;
    const int version = integer(node, owner, "version");
    if (version < 1 || version > currentVersion) {
        MessageText message;
        message << "GenDPDEForce: cannot read serialization version " << version << "; this build reads versions 1 to "
                << currentVersion;
        throw OpenMMException(message.str());
    }
    // Every value is read whole (StrictXml), the node may hold only what its version defines, and the setters
    // validate every value: a corrupted file is refused, never read in part.
    std::vector<std::string> children;
    if (version >= 2)
        children.insert(children.end(), {"ParticleTypes", "TypeParameters"});
    if (version >= 3)
        children.insert(children.end(), {"EquationOfState", "TypeEquationsOfState"});
    std::vector<std::string> properties = {"version",       "name", "forceGroup", "cutoff",      "method", "estimator",
                                           "cutoffScaling", "n0",   "pi0",        "bulkModulus", "gammaT"};
    if (version >= 4)
        properties.push_back("backgroundPressure");
    requireOnly(node, owner, version, properties, children);
    std::unique_ptr<GenDPDEForce> force(new GenDPDEForce(number(node, owner, "cutoff")));
    if (node.hasProperty("name"))
        force->setName(node.getStringProperty("name"));
    force->setForceGroup(node.hasProperty("forceGroup") ? integer(node, owner, "forceGroup") : 0);
    force->setNonbondedMethod((GenDPDEForce::NonbondedMethod) integer(node, owner, "method"));
    force->setDensityEstimator((GenDPDEForce::DensityEstimator) integer(node, owner, "estimator"));
    force->setCutoffScaling(number(node, owner, "cutoffScaling"));
    force->setTaitParameters(number(node, owner, "n0"), number(node, owner, "pi0"), number(node, owner, "bulkModulus"),
                             number(node, owner, "gammaT"));
    if (version >= 4)
        force->setBackgroundPressure(number(node, owner, "backgroundPressure"));
    if (version >= 2) {
        deserializeParticleTypes(node, *force, owner, version);
        const SerializationNode& typeParameters = child(node, owner, "TypeParameters");
        requireOnly(typeParameters, owner, version, {}, {"Type"});
        for (const SerializationNode& type : typeParameters.getChildren()) {
            requireOnly(type, owner, version, {"type", "n0", "pi0", "bulkModulus", "gammaT"}, {});
            force->addTypeParameters(integer(type, owner, "type"), number(type, owner, "n0"),
                                     number(type, owner, "pi0"), number(type, owner, "bulkModulus"),
                                     number(type, owner, "gammaT"));
        }
    }
    if (version >= 3) {
        const SerializationNode& law = child(node, owner, "EquationOfState");
        requireOnly(law, owner, version, {"law"}, {"Parameter"});
        force->setEquationOfState(lawOf(law), lawParameters(law));
        const SerializationNode& typeLaws = child(node, owner, "TypeEquationsOfState");
        requireOnly(typeLaws, owner, version, {}, {"Type"});
        for (const SerializationNode& type : typeLaws.getChildren()) {
            requireOnly(type, owner, version, {"type", "law"}, {"Parameter"});
            force->addTypeEquationOfState(integer(type, owner, "type"), lawOf(type), lawParameters(type));
        }
    }
    return force.release();
}
