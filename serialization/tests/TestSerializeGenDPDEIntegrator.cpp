/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
#include "GenDPDEIntegrator.h"
#include "TestUtilities.h"
#include "OpenMM.h"
#include "openmm/serialization/XmlSerializer.h"
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>

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
    integrator.setAdiabaticPositionChanges(true);
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
    ASSERT(copy->getAdiabaticPositionChanges());
    delete copy;
}

/** Initial internal energies (setInternalEnergies before a Context) survive a round trip exactly, in place of
 *  temperatures; temperatures set after them replace them in the copy too. */
void testInternalEnergiesRoundTrip() {
    GenDPDEIntegrator integrator(0.01, 1000.0, 2000.0, 0.1);
    const std::vector<double> energies = {0.1 / 3.0, 12.5 * (1.0 + 1e-15), 1e-90, 7e90};
    integrator.setInternalEnergies(energies);
    std::stringstream buffer;
    XmlSerializer::serialize<Integrator>(&integrator, "Integrator", buffer);
    ASSERT(buffer.str().find("version=\"4\"") != std::string::npos);
    std::unique_ptr<Integrator> deserialized(XmlSerializer::deserialize<Integrator>(buffer));
    GenDPDEIntegrator* copy = dynamic_cast<GenDPDEIntegrator*>(deserialized.get());
    ASSERT(copy != nullptr);
    ASSERT(copy->getInternalEnergies() == energies);
    integrator.setParticleTemperatures({300.0, 310.0});
    std::stringstream again;
    XmlSerializer::serialize<Integrator>(&integrator, "Integrator", again);
    std::unique_ptr<Integrator> second(XmlSerializer::deserialize<Integrator>(again));
    const std::vector<double> temperatures = dynamic_cast<GenDPDEIntegrator*>(second.get())->getParticleTemperatures();
    ASSERT(temperatures == std::vector<double>({300.0, 310.0}));
}

/** Particle types (non-consecutive, negative), per-type heat capacities and type pairs survive a round trip. */
void testTypesRoundTrip() {
    GenDPDEIntegrator integrator(0.01, 1000.0, 2000.0, 0.1);
    integrator.setParticleType(2, 42);
    integrator.setParticleType(0, -7);
    integrator.addTypeHeatCapacity(42, 0.25);
    integrator.addTypeHeatCapacity(-7, 0.5);
    integrator.addTypePair(42, -7, 123.0, 456.0);
    integrator.addTypePair(42, 42, 0.0, 789.0);
    std::stringstream buffer;
    XmlSerializer::serialize<Integrator>(&integrator, "Integrator", buffer);
    std::unique_ptr<Integrator> deserialized(XmlSerializer::deserialize<Integrator>(buffer));
    GenDPDEIntegrator* copy = dynamic_cast<GenDPDEIntegrator*>(deserialized.get());
    ASSERT(copy != nullptr);
    ASSERT(copy->getParticleTypes() == integrator.getParticleTypes());
    ASSERT_EQUAL(2, copy->getNumTypeHeatCapacities());
    for (int index = 0; index < 2; index++) {
        int type1, type2;
        double c1, c2;
        integrator.getTypeHeatCapacity(index, type1, c1);
        copy->getTypeHeatCapacity(index, type2, c2);
        ASSERT_EQUAL(type1, type2);
        ASSERT_EQUAL(c1, c2);
    }
    ASSERT_EQUAL(2, copy->getNumTypePairs());
    for (int index = 0; index < 2; index++) {
        int a1, b1, a2, b2;
        double f1, k1, f2, k2;
        integrator.getTypePairParameters(index, a1, b1, f1, k1);
        copy->getTypePairParameters(index, a2, b2, f2, k2);
        ASSERT(a1 == a2 && b1 == b2 && f1 == f2 && k1 == k2);
    }
}

/** A version-1 file (written before particle types) is still read. */
void testVersion1() {
    std::stringstream v1("<?xml version=\"1.0\" ?>\n<Integrator constraintTolerance=\"1e-05\" cutoff=\"0\" "
                         "friction=\"1644.8\" heatCapacity=\"0.104\" heatConduction=\"2999.1\" "
                         "integrationForceGroups=\"-1\" mode=\"0\" randomSeed=\"5\" stepSize=\"0.0123\" "
                         "temperature=\"125.7\" type=\"GenDPDEIntegrator\" version=\"1\">"
                         "<ParticleTemperatures/></Integrator>\n");
    std::unique_ptr<Integrator> deserialized(XmlSerializer::deserialize<Integrator>(v1));
    GenDPDEIntegrator* integrator = dynamic_cast<GenDPDEIntegrator*>(deserialized.get());
    ASSERT(integrator != nullptr);
    ASSERT_EQUAL(1644.8, integrator->getFriction());
    ASSERT_EQUAL(0.104, integrator->getHeatCapacity());
    ASSERT(integrator->getParticleTypes().empty());
    ASSERT_EQUAL(0, integrator->getNumTypePairs());
    ASSERT_EQUAL(0, integrator->getNumTypeHeatCapacities());
}

/**
 * Values are read whole and a node holds only what its version defines: an empty value, trailing garbage, a
 * fraction where an integer is, a word for a flag, a version-3 file with adiabaticPositionChanges, and both initial
 * lists at once are refused, naming what is wrong.
 */
void testStrictReading() {
    GenDPDEIntegrator integrator(0.0125, 1644.8, 2999.1, 0.104);
    integrator.setMode(GenDPDEIntegrator::Conservative);
    integrator.setParticleTemperatures({120.0, 125.5});
    integrator.setAdiabaticPositionChanges(true);
    std::stringstream buffer;
    XmlSerializer::serialize<Integrator>(&integrator, "Integrator", buffer);
    const std::string xml = buffer.str();
    auto refused = [&](const std::string& from, const std::string& to, const std::vector<std::string>& words) {
        std::string text = xml;
        const size_t position = text.find(from);
        if (position == std::string::npos)
            throw std::runtime_error("the XML holds no " + from + ":\n" + xml);
        std::stringstream stream(text.replace(position, from.size(), to));
        assertThrowsMentioning([&]() { delete XmlSerializer::deserialize<Integrator>(stream); }, words);
    };
    refused("stepSize=\".0125\"", "stepSize=\"\"", {"GenDPDEIntegrator XML", "stepSize = ''", "not a number"});
    refused("friction=\"1644.8\"", "friction=\"1644.8kg\"", {"friction = '1644.8kg'"});
    refused("mode=\"2\"", "mode=\"1.5\"", {"mode = '1.5'", "not an integer"});
    refused("adiabaticPositionChanges=\"1\"", "adiabaticPositionChanges=\"yes\"",
            {"adiabaticPositionChanges = 'yes'", "0 or 1 (or false or true)"}); // what is read, all of it
    refused("version=\"4\"", "version=\"3\"", {"version 3", "property 'adiabaticPositionChanges'"});
    refused("t=\"120\"", "t=\"120 K\"", {"Particle.t = '120 K'"});
    refused("<InternalEnergies/>", "<InternalEnergies><Particle e=\"1\"/></InternalEnergies>",
            {"both initial temperatures and initial internal energies"});
    std::stringstream good(xml);
    std::unique_ptr<Integrator> copy(XmlSerializer::deserialize<Integrator>(good));
    ASSERT(dynamic_cast<GenDPDEIntegrator&>(*copy).getAdiabaticPositionChanges());
}

int main() {
    return runTestProgram([]() {
        testSerialization();
        testInternalEnergiesRoundTrip();
        testTypesRoundTrip();
        testVersion1();
        testStrictReading();
    });
}
