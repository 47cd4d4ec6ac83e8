#include "GenDPDEIntegrator.h"
#include "TestUtilities.h"
#include "OpenMM.h"
#include "openmm/serialization/XmlSerializer.h"
#include <sstream>

using namespace GenDPDEPlugin;
using namespace OpenMM;

/** Every parameter survives a round trip; checks are made on the deserialized copy. */
void testSerialization() {
    GenDPDEIntegrator integrator(0.0123, 1644.8, 2999.1, 0.104);
    integrator.setConstraintTolerance(1e-6);
    integrator.setIntegrationForceGroups(5);
    integrator.setCutoffDistance(1.0375);
    integrator.setRandomNumberSeed(-17);
    integrator.setMode(GenDPDEIntegrator::Isothermal);
    integrator.setTemperature(125.7);
    integrator.setParticleTemperatures({120.0, 125.5, 131.25});
    std::stringstream buffer;
    XmlSerializer::serialize<Integrator>(&integrator, "Integrator", buffer);
    GenDPDEIntegrator* copy = dynamic_cast<GenDPDEIntegrator*>(XmlSerializer::deserialize<Integrator>(buffer));
    ASSERT(copy != nullptr);
    ASSERT_EQUAL(integrator.getStepSize(), copy->getStepSize());
    ASSERT_EQUAL(integrator.getConstraintTolerance(), copy->getConstraintTolerance());
    ASSERT_EQUAL(integrator.getIntegrationForceGroups(), copy->getIntegrationForceGroups());
    ASSERT_EQUAL(integrator.getFriction(), copy->getFriction());
    ASSERT_EQUAL(integrator.getHeatConduction(), copy->getHeatConduction());
    ASSERT_EQUAL(integrator.getHeatCapacity(), copy->getHeatCapacity());
    ASSERT_EQUAL(integrator.getCutoffDistance(), copy->getCutoffDistance());
    ASSERT_EQUAL(integrator.getRandomNumberSeed(), copy->getRandomNumberSeed());
    ASSERT_EQUAL(integrator.getMode(), copy->getMode());
    ASSERT_EQUAL(integrator.getTemperature(), copy->getTemperature());
    ASSERT(integrator.getParticleTemperatures() == copy->getParticleTemperatures());
    delete copy;
}

int main() {
    return runTestProgram([]() {
        testSerialization();
    });
}
