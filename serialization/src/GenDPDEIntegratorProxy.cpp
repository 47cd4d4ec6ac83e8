#include "GenDPDEIntegratorProxy.h"
#include "GenDPDEIntegrator.h"
#include "ParticleTypesXml.h"
#include "openmm/OpenMMException.h"
#include "openmm/serialization/SerializationNode.h"
#include <memory>

using namespace GenDPDEPlugin;
using namespace OpenMM;

namespace {
// Version 2: particle types, per-type heat capacities and type pairs. Version 3: the initial internal energies
// (setInternalEnergies before a Context). Version 4: adiabaticPositionChanges. Versions 1 to 3 are still read.
const int currentVersion = 4;
}

GenDPDEIntegratorProxy::GenDPDEIntegratorProxy() : SerializationProxy("GenDPDEIntegrator") {
}

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
        heatCapacities.createChildNode("Type").setIntProperty("type", type).setDoubleProperty("heatCapacity",
                                                                                            heatCapacity);
    }
    SerializationNode& typePairs = node.createChildNode("TypePairs");
    for (int index = 0; index < integrator.getNumTypePairs(); index++) {
        int type1, type2;
        double friction, heatConduction;
        integrator.getTypePairParameters(index, type1, type2, friction, heatConduction);
        typePairs.createChildNode("Pair").setIntProperty("type1", type1).setIntProperty("type2", type2)
                .setDoubleProperty("friction", friction).setDoubleProperty("heatConduction", heatConduction);
    }
}

void* GenDPDEIntegratorProxy::deserialize(const SerializationNode& node) const {
    int version = node.getIntProperty("version");
    if (version < 1 || version > currentVersion)
        throw OpenMMException("GenDPDEIntegrator: cannot read serialization version " + std::to_string(version)
                              + "; this build reads versions 1 to " + std::to_string(currentVersion));
    // The constructor and setters validate every value.
    std::unique_ptr<GenDPDEIntegrator> integrator(new GenDPDEIntegrator(node.getDoubleProperty("stepSize"),
            node.getDoubleProperty("friction"), node.getDoubleProperty("heatConduction"),
            node.getDoubleProperty("heatCapacity")));
    integrator->setConstraintTolerance(node.getDoubleProperty("constraintTolerance"));
    integrator->setIntegrationForceGroups(node.getIntProperty("integrationForceGroups"));
    integrator->setCutoffDistance(node.getDoubleProperty("cutoff"));
    integrator->setRandomNumberSeed(node.getIntProperty("randomSeed"));
    integrator->setMode((GenDPDEIntegrator::Mode) node.getIntProperty("mode"));
    double temperature = node.getDoubleProperty("temperature");
    if (temperature != 0.0)
        integrator->setTemperature(temperature);
    if (version >= 4)
        integrator->setAdiabaticPositionChanges(node.getBoolProperty("adiabaticPositionChanges"));
    std::vector<double> temperatures;
    for (const SerializationNode& particle : node.getChildNode("ParticleTemperatures").getChildren())
        temperatures.push_back(particle.getDoubleProperty("t"));
    if (!temperatures.empty())
        integrator->setParticleTemperatures(temperatures);
    if (version >= 3) {
        std::vector<double> energies;
        for (const SerializationNode& particle : node.getChildNode("InternalEnergies").getChildren())
            energies.push_back(particle.getDoubleProperty("e"));
        if (!energies.empty())
            integrator->setInternalEnergies(energies);
    }
    if (version >= 2) {
        deserializeParticleTypes(node, *integrator);
        for (const SerializationNode& type : node.getChildNode("TypeHeatCapacities").getChildren())
            integrator->addTypeHeatCapacity(type.getIntProperty("type"), type.getDoubleProperty("heatCapacity"));
        for (const SerializationNode& pair : node.getChildNode("TypePairs").getChildren())
            integrator->addTypePair(pair.getIntProperty("type1"), pair.getIntProperty("type2"),
                                    pair.getDoubleProperty("friction"), pair.getDoubleProperty("heatConduction"));
    }
    return integrator.release();
}
