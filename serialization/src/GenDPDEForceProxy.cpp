#include "GenDPDEForceProxy.h"
#include "GenDPDEForce.h"
#include "ParticleTypesXml.h"
#include "openmm/OpenMMException.h"
#include "openmm/serialization/SerializationNode.h"
#include <memory>
#include <sstream>
#include <vector>

using namespace GenDPDEPlugin;
using namespace OpenMM;

namespace {
// Version 2: particle types and per-type Tait parameters. Version 3: the local equations of state (the default law
// and per-type entries, docs/theory.md section 11). Versions 1 and 2 are still read (every type Tait).
const int currentVersion = 3;

void serializeLaw(SerializationNode& node, GenDPDEForce::EquationOfState law, const std::vector<double>& parameters) {
    node.setIntProperty("law", (int) law);
    for (const double p : parameters)
        node.createChildNode("Parameter").setDoubleProperty("value", p);
}

std::vector<double> lawParameters(const SerializationNode& node) {
    std::vector<double> parameters;
    for (const SerializationNode& p : node.getChildren())
        parameters.push_back(p.getDoubleProperty("value"));
    return parameters;
}
}

GenDPDEForceProxy::GenDPDEForceProxy() : SerializationProxy("GenDPDEForce") {
}

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
    serializeParticleTypes(node, force.getParticleTypes());
    SerializationNode& typeParameters = node.createChildNode("TypeParameters");
    for (int index = 0; index < force.getNumTypeParameters(); index++) {
        int type;
        force.getTypeParameters(index, type, n0, pi0, bulkModulus, exponent);
        typeParameters.createChildNode("Type").setIntProperty("type", type).setDoubleProperty("n0", n0)
                .setDoubleProperty("pi0", pi0).setDoubleProperty("bulkModulus", bulkModulus)
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
    int version = node.getIntProperty("version");
    if (version < 1 || version > currentVersion) {
        std::ostringstream message;
        message << "GenDPDEForce: cannot read serialization version " << version << "; this build reads versions 1 to "
                << currentVersion;
        throw OpenMMException(message.str());
    }
    // The setters validate every value, so a corrupted file is rejected with the usual messages.
    std::unique_ptr<GenDPDEForce> force(new GenDPDEForce(node.getDoubleProperty("cutoff")));
    force->setName(node.getStringProperty("name", force->getName()));
    force->setForceGroup(node.getIntProperty("forceGroup", 0));
    force->setNonbondedMethod((GenDPDEForce::NonbondedMethod) node.getIntProperty("method"));
    force->setDensityEstimator((GenDPDEForce::DensityEstimator) node.getIntProperty("estimator"));
    force->setCutoffScaling(node.getDoubleProperty("cutoffScaling"));
    force->setTaitParameters(node.getDoubleProperty("n0"), node.getDoubleProperty("pi0"),
                             node.getDoubleProperty("bulkModulus"), node.getDoubleProperty("gammaT"));
    if (version >= 2) {
        deserializeParticleTypes(node, *force);
        for (const SerializationNode& type : node.getChildNode("TypeParameters").getChildren())
            force->addTypeParameters(type.getIntProperty("type"), type.getDoubleProperty("n0"),
                                     type.getDoubleProperty("pi0"), type.getDoubleProperty("bulkModulus"),
                                     type.getDoubleProperty("gammaT"));
    }
    if (version >= 3) {
        const SerializationNode& law = node.getChildNode("EquationOfState");
        force->setEquationOfState((GenDPDEForce::EquationOfState) law.getIntProperty("law"), lawParameters(law));
        for (const SerializationNode& type : node.getChildNode("TypeEquationsOfState").getChildren())
            force->addTypeEquationOfState(type.getIntProperty("type"),
                                          (GenDPDEForce::EquationOfState) type.getIntProperty("law"),
                                          lawParameters(type));
    }
    return force.release();
}
