/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
#include "GenDPDEForce.h"
#include "TestPlugins.h"
#include "TestUtilities.h"
#include "OpenMM.h"
#include "openmm/serialization/XmlSerializer.h"
#include <cmath>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>

using namespace GenDPDEPlugin;
using namespace OpenMM;

/** Every property survives a round trip; checks are made on the deserialized copy. */
void testSerialization() {
    GenDPDEForce force(1.234);
    force.setNonbondedMethod(GenDPDEForce::CutoffNonPeriodic);
    force.setDensityEstimator(GenDPDEForce::VA);
    force.setCutoffScaling(1.41);
    force.setTaitParameters(4.5, 47.25, 67.5, 6.5);
    force.setBackgroundPressure(123.25);
    force.setForceGroup(5);
    force.setName("argon");
    std::stringstream buffer;
    XmlSerializer::serialize<GenDPDEForce>(&force, "Force", buffer);
    GenDPDEForce* copy = XmlSerializer::deserialize<GenDPDEForce>(buffer);
    ASSERT_EQUAL(force.getCutoffDistance(), copy->getCutoffDistance());
    ASSERT_EQUAL(force.getNonbondedMethod(), copy->getNonbondedMethod());
    ASSERT_EQUAL(force.getDensityEstimator(), copy->getDensityEstimator());
    ASSERT_EQUAL(force.getCutoffScaling(), copy->getCutoffScaling());
    ASSERT_EQUAL(force.getReferenceDensity(), copy->getReferenceDensity());
    ASSERT_EQUAL(force.getReferencePressure(), copy->getReferencePressure());
    ASSERT_EQUAL(force.getBulkModulus(), copy->getBulkModulus());
    ASSERT_EQUAL(force.getTaitExponent(), copy->getTaitExponent());
    ASSERT_EQUAL(force.getBackgroundPressure(), copy->getBackgroundPressure());
    ASSERT_EQUAL(force.getForceGroup(), copy->getForceGroup());
    ASSERT_EQUAL(force.getName(), copy->getName());
    delete copy;
}

/** Particle types (non-consecutive, negative) and per-type Tait parameters survive a round trip. */
void testTypesRoundTrip() {
    GenDPDEForce force(1.0);
    force.setParticleType(3, 42);
    force.setParticleType(0, -7);
    force.setParticleType(10, 42);
    force.addTypeParameters(42, 3.5, -1.25, 80.0, 7.0);
    force.addTypeParameters(-7, 5.5, 2.5, 60.0, 4.5);
    std::stringstream buffer;
    XmlSerializer::serialize<GenDPDEForce>(&force, "Force", buffer);
    std::unique_ptr<GenDPDEForce> copy(XmlSerializer::deserialize<GenDPDEForce>(buffer));
    ASSERT(copy->getParticleTypes() == force.getParticleTypes());
    ASSERT_EQUAL(0, copy->getParticleType(5));
    ASSERT_EQUAL(2, copy->getNumTypeParameters());
    for (int index = 0; index < 2; index++) {
        int type1, type2;
        double a1[4], a2[4];
        force.getTypeParameters(index, type1, a1[0], a1[1], a1[2], a1[3]);
        copy->getTypeParameters(index, type2, a2[0], a2[1], a2[2], a2[3]);
        ASSERT_EQUAL(type1, type2);
        for (int k = 0; k < 4; k++)
            ASSERT_EQUAL(a1[k], a2[k]);
    }
}

/** A version-1 file (written before particle types) is still read: no types, its own Tait parameters. */
void testVersion1() {
    std::stringstream v1(
            "<?xml version=\"1.0\" ?>\n<Force bulkModulus=\"67.5\" cutoff=\"1.234\" cutoffScaling=\"1.41\" "
            "estimator=\"0\" forceGroup=\"5\" gammaT=\"6.5\" method=\"0\" n0=\"4.5\" name=\"argon\" "
            "pi0=\"47.25\" type=\"GenDPDEForce\" version=\"1\"/>\n");
    std::unique_ptr<GenDPDEForce> force(XmlSerializer::deserialize<GenDPDEForce>(v1));
    ASSERT_EQUAL(1.234, force->getCutoffDistance());
    ASSERT_EQUAL(GenDPDEForce::VA, force->getDensityEstimator());
    ASSERT_EQUAL(4.5, force->getReferenceDensity());
    ASSERT_EQUAL(47.25, force->getReferencePressure());
    ASSERT(force->getParticleTypes().empty());
    ASSERT_EQUAL(0, force->getNumTypeParameters());
}

/** A System holding the force round-trips through XmlSerializer, and the copy computes the same energy. */
void testSystemRoundTrip() {
    System system;
    system.setDefaultPeriodicBoxVectors(Vec3(3, 0, 0), Vec3(0, 3, 0), Vec3(0, 0, 3));
    std::vector<Vec3> positions;
    for (int i = 0; i < 64; i++) {
        system.addParticle(200.0);
        positions.push_back(Vec3(0.75 * (i % 4) + 0.01 * i, 0.75 * ((i / 4) % 4), 0.75 * (i / 16) - 0.02 * (i % 3)));
    }
    GenDPDEForce* force = new GenDPDEForce(1.0);
    force->setCutoffScaling(1.3);
    system.addForce(force);
    std::stringstream buffer;
    XmlSerializer::serialize<System>(&system, "System", buffer);
    System* copy = XmlSerializer::deserialize<System>(buffer);
    ASSERT(dynamic_cast<GenDPDEForce*>(&copy->getForce(0)) != nullptr);
    Platform& platform = Platform::getPlatformByName("Reference");
    VerletIntegrator integrator1(0.001), integrator2(0.001);
    Context original(system, integrator1, platform), restored(*copy, integrator2, platform);
    original.setPositions(positions);
    restored.setPositions(positions);
    ASSERT_EQUAL(original.getState(State::Energy).getPotentialEnergy(),
                 restored.getState(State::Energy).getPotentialEnergy());
    delete copy;
}

/** A file from a newer version is refused with a clear message. */
void testFutureVersion() {
    GenDPDEForce force(1.0);
    std::stringstream buffer;
    XmlSerializer::serialize<GenDPDEForce>(&force, "Force", buffer);
    std::string xml = buffer.str();
    size_t position = xml.find("version=\"4\"");
    ASSERT(position != std::string::npos);
    xml.replace(position, 11, "version=\"99\"");
    std::stringstream future(xml);
    assertThrowsMentioning([&]() { delete XmlSerializer::deserialize<GenDPDEForce>(future); }, {"version 99"});
}

/** The local equations of state (docs/theory.md section 11), the default and per type, survive a round trip. */
void testEquationsOfStateRoundTrip() {
    GenDPDEForce force(1.0);
    force.setParticleType(1, 4);
    force.setParticleType(2, 9);
    force.setEquationOfState(GenDPDEForce::TaitThermalExpansion, {0.125, 300.5});
    force.addTypeEquationOfState(4, GenDPDEForce::VanDerWaals, {0.75, 0.0625, 0.0083});
    force.addTypeEquationOfState(9, GenDPDEForce::Tait, {});
    std::stringstream buffer;
    XmlSerializer::serialize<GenDPDEForce>(&force, "Force", buffer);
    std::unique_ptr<GenDPDEForce> copy(XmlSerializer::deserialize<GenDPDEForce>(buffer));
    GenDPDEForce::EquationOfState law;
    std::vector<double> parameters;
    copy->getEquationOfState(law, parameters);
    ASSERT_EQUAL(GenDPDEForce::TaitThermalExpansion, law);
    ASSERT(parameters == std::vector<double>({0.125, 300.5}));
    ASSERT_EQUAL(2, copy->getNumTypeEquationsOfState());
    int type;
    copy->getTypeEquationOfState(0, type, law, parameters);
    ASSERT_EQUAL(4, type);
    ASSERT_EQUAL(GenDPDEForce::VanDerWaals, law);
    ASSERT(parameters == std::vector<double>({0.75, 0.0625, 0.0083}));
    copy->getTypeEquationOfState(1, type, law, parameters);
    ASSERT_EQUAL(9, type);
    ASSERT_EQUAL(GenDPDEForce::Tait, law);
    ASSERT(parameters.empty());
    ASSERT(copy->dependsOnTemperature());
}

/** The XML of this force with the first occurrence of `from` replaced by `to` (which must be there). */
std::string edited(const GenDPDEForce& force, const std::string& from, const std::string& to) {
    std::stringstream buffer;
    XmlSerializer::serialize<GenDPDEForce>(&force, "Force", buffer);
    std::string xml = buffer.str();
    const size_t position = xml.find(from);
    if (position == std::string::npos)
        throw std::runtime_error("the XML holds no " + from + ":\n" + xml);
    return xml.replace(position, from.size(), to);
}

/**
 * Values are read whole and a node holds only what its version defines: an empty value, trailing garbage, a fraction
 * or a word where an integer law is, and a version-2 file with an equation of state are refused, naming what is
 * wrong (OpenMM's reader took "" as 0, "1.0garbage" as 1, "1.5" as 1, "abc" as Tait, and dropped the law).
 */
void testStrictReading() {
    GenDPDEForce force(1.25);
    force.setEquationOfState(GenDPDEForce::TaitThermalExpansion, {0.5, 300.0});
    force.addTypeEquationOfState(3, GenDPDEForce::VanDerWaals, {0.75, 0.0625, 0.0083});
    auto refused = [&](const std::string& from, const std::string& to, const std::vector<std::string>& words) {
        std::stringstream xml(edited(force, from, to));
        assertThrowsMentioning([&]() { delete XmlSerializer::deserialize<GenDPDEForce>(xml); }, words);
    };
    refused("cutoff=\"1.25\"", "cutoff=\"\"", {"GenDPDEForce XML", "cutoff = ''", "not a number"});
    refused("cutoff=\"1.25\"", "cutoff=\"1.25garbage\"", {"cutoff = '1.25garbage'", "not a number"});
    refused("cutoff=\"1.25\"", "cutoff=\" 1.25\"", {"cutoff = ' 1.25'"});
    refused("law=\"1\"", "law=\"1.5\"", {"law = '1.5'", "an integer naming a law"});
    refused("law=\"1\"", "law=\"abc\"", {"law = 'abc'", "0 Tait, 1 TaitThermalExpansion, 2 VanDerWaals"});
    refused("law=\"1\"", "law=\"7\"", {"equation of state = 7"});
    refused("value=\".5\"", "value=\".5x\"", {"Parameter.value = '.5x'"});
    refused("estimator=\"1\"", "estimator=\"1e0\"", {"estimator = '1e0'"});
    refused("version=\"4\"", "version=\"2\"", {"version 2", "does not define"});
    refused("version=\"4\"", "version=\"3\"", {"version 3", "property 'backgroundPressure'", "does not define"});
    refused("version=\"4\"", "version=\"4\" extra=\"1\"", {"property 'extra'", "does not define"});
    refused("backgroundPressure=\"0\"", "backgroundPressure=\"-1\"", {"background pressure p_b", "-1"});
    refused(" n0=", " m0=", {"property 'm0'"});
    // A number in the C locale's form, and the non-finite words OpenMM writes, are read (the setter then judges).
    std::stringstream exponent(edited(force, "cutoff=\"1.25\"", "cutoff=\"125e-2\""));
    std::unique_ptr<GenDPDEForce> copy(XmlSerializer::deserialize<GenDPDEForce>(exponent));
    ASSERT_EQUAL(1.25, copy->getCutoffDistance());
    refused("cutoff=\"1.25\"", "cutoff=\"Infinity\"", {"cutoff", "inf"});
    // An integer as OpenMM writes one (issue 54: "04" read as version 4), -0 read as 0 (it was kept as -0.0 and
    // written back as "-0"), and an element without a name named as such (it was "the <> element has a child <>").
    refused("version=\"4\"", "version=\"04\"", {"version = '04'", "no leading zero"});
    refused("version=\"4\"", "version=\"+4\"", {"version = '+4'"});
    refused("law=\"1\"", "law=\"-0\"", {"law = '-0'"});
    refused("<TypeEquationsOfState>", "<TypeEquationsOfState><></>", {"an element without a name (<>)"});
    std::stringstream negativeZero(edited(force, "backgroundPressure=\"0\"", "backgroundPressure=\"-0\""));
    std::unique_ptr<GenDPDEForce> zero(XmlSerializer::deserialize<GenDPDEForce>(negativeZero));
    ASSERT(!std::signbit(zero->getBackgroundPressure()));
    std::stringstream written;
    XmlSerializer::serialize<GenDPDEForce>(zero.get(), "Force", written);
    ASSERT(written.str().find("backgroundPressure=\"0\"") != std::string::npos);
}

int main() {
    return runTestProgram([]() {
        loadGenDPDEKernels("Reference");
        testSerialization();
        testTypesRoundTrip();
        testEquationsOfStateRoundTrip();
        testVersion1();
        testSystemRoundTrip();
        testFutureVersion();
        testStrictReading();
    });
}
