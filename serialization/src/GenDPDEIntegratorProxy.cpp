#include "GenDPDEIntegratorProxy.h"
#include "GenDPDEIntegrator.h"
#include "openmm/OpenMMException.h"
#include "openmm/serialization/SerializationNode.h"
#include <memory>

using namespace GenDPDEPlugin;
using namespace OpenMM;

namespace {
const int currentVersion = 1;
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
    // The initial particle temperatures configured before a Context existed: a parameter of the integrator. The
    // live state of a bound integrator (its Context's internal energies) travels in checkpoints and States only.
    SerializationNode& temperatures = node.createChildNode("ParticleTemperatures");
    for (double t : integrator.initialTemperatures)
        temperatures.createChildNode("Particle").setDoubleProperty("t", t);
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
    std::vector<double> temperatures;
    for (const SerializationNode& particle : node.getChildNode("ParticleTemperatures").getChildren())
        temperatures.push_back(particle.getDoubleProperty("t"));
    if (!temperatures.empty())
        integrator->setParticleTemperatures(temperatures);
    return integrator.release();
}
