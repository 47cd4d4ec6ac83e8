/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
/* The tables of the core (core/include/gendpde): what GenDPDEForce's checks and messages, the XML serialization and
 * the packing for the platforms read.
 *  - The equations of state (GenDPDEEquationsOfState.h): every law of the table, with parameters taken from the
 *    table alone, is accepted, round-trips through XML, is refused with a wrong count or a parameter outside its
 *    range in words the table gives, and is packed as the table lays it out.
 *  - The density estimators (GenDPDEDensityEstimators.h): every one is accepted and round-trips, a number past the
 *    table is refused naming them all, and what the table says of each (reads f_cut, needs moments) is what the
 *    physics core does with it. */

#include "GenDPDEForce.h"
#include "TestPlugins.h"
#include "TestUtilities.h"
#include "gendpde/GenDPDEDensityEstimators.h"
#include "gendpde/GenDPDEEquationsOfState.h"
#include "internal/GenDPDEPhysics.h"
#include "internal/GenDPDETypes.h"
#include "openmm/serialization/XmlSerializer.h"
#include <cmath>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

using namespace GenDPDEPlugin;
using namespace OpenMM;
namespace Table = GenDPDEPlugin::EquationsOfState;

namespace {

/** A value the table allows for parameter p, distinct for each k (1.25, 2.25 ... clamped into the range). */
double allowedValue(const Table::Parameter& p, int k) {
    double value = 1.25 + k;
    if (value < p.range.minimum || (p.excludeMinimum && value == p.range.minimum))
        value = (p.range.minimum > 0 ? 2 * p.range.minimum : p.range.minimum + 1);
    if (value > p.range.maximum)
        value = p.range.maximum;
    return value;
}

std::vector<double> allowedParameters(const Table::Law& law) {
    std::vector<double> parameters;
    for (int k = 0; k < law.numParameters; k++)
        parameters.push_back(allowedValue(law.parameters[k], k));
    return parameters;
}

std::string text(double value) {
    std::ostringstream out;
    out.precision(12);
    out << value;
    return out.str();
}

void testEveryLawIsAcceptedAndRoundTrips() {
    ASSERT(Table::numLaws >= 3);
    GenDPDEForce force(1.0);
    for (int law = 0; law < Table::numLaws; law++) {
        const std::vector<double> parameters = allowedParameters(Table::laws[law]);
        force.setEquationOfState((GenDPDEForce::EquationOfState) law, parameters);
        force.addTypeEquationOfState(10 + law, (GenDPDEForce::EquationOfState) law, parameters);
        ASSERT_EQUAL(std::string(Table::laws[law].name), equationOfStateName((GenDPDEForce::EquationOfState) law));
    }
    std::stringstream buffer;
    XmlSerializer::serialize<GenDPDEForce>(&force, "Force", buffer);
    std::unique_ptr<GenDPDEForce> copy(XmlSerializer::deserialize<GenDPDEForce>(buffer));
    ASSERT_EQUAL(Table::numLaws, copy->getNumTypeEquationsOfState());
    for (int law = 0; law < Table::numLaws; law++) {
        int type;
        GenDPDEForce::EquationOfState found;
        std::vector<double> parameters;
        copy->getTypeEquationOfState(law, type, found, parameters);
        ASSERT_EQUAL(10 + law, type);
        ASSERT_EQUAL(law, (int) found);
        ASSERT(parameters == allowedParameters(Table::laws[law]));
    }
}

void testWrongCountsAndRangesAreRefusedInTheTablesWords() {
    GenDPDEForce force(1.0);
    for (int law = 0; law < Table::numLaws; law++) {
        const Table::Law& description = Table::laws[law];
        const auto eos = (GenDPDEForce::EquationOfState) law;
        std::vector<double> parameters = allowedParameters(description);
        parameters.push_back(1.0);
        assertThrowsMentioning([&]() { force.setEquationOfState(eos, parameters); },
                               {description.name, "takes " + std::to_string(description.numParameters) + " parameters",
                                "not " + std::to_string(parameters.size())});
        for (int k = 0; k < description.numParameters; k++) {
            const Table::Parameter& p = description.parameters[k];
            std::vector<double> bad = allowedParameters(description);
            bad[k] = p.range.minimum - std::fabs(p.range.minimum) - 1;   // below the range
            assertThrowsMentioning(
                    [&]() { force.addTypeEquationOfState(3, eos, bad); },
                    {"type equation of state", p.description, text(bad[k]), p.range.units, text(p.range.maximum)});
        }
    }
    ASSERT_EQUAL(0, force.getNumTypeEquationsOfState());   // nothing was added by a refused call
    std::vector<std::string> names;
    for (const Table::Law& law : Table::laws)
        names.push_back(law.name);
    names.push_back("equation of state = " + std::to_string(Table::numLaws));
    assertThrowsMentioning([&]() { force.setEquationOfState((GenDPDEForce::EquationOfState) Table::numLaws, {}); },
                           names);
}

void testPackingFollowsTheTable() {
    const TaitParameters tait = {4.0, 0.5, 20.0, 7.0};
    const double backgroundPressure = 0.25;
    for (int law = 0; law < Table::numLaws; law++) {
        const Table::Law& description = Table::laws[law];
        const std::vector<double> parameters = allowedParameters(description);
        const Physics::LocalEquationOfState eos =
                packEquationOfState((GenDPDEForce::EquationOfState) law, parameters, tait, backgroundPressure);
        ASSERT_EQUAL(description.coreId, eos.law);
        ASSERT_EQUAL((size_t) Table::coreStride(), eos.parameter.size());
        ASSERT(description.numCoreParameters() <= Table::coreStride());
        std::vector<double> expected;
        if (description.extendsTait)
            expected = {4.0, 0.5 + backgroundPressure, 20.0, 7.0};
        expected.insert(expected.end(), parameters.begin(), parameters.end());
        if (!description.extendsTait)
            expected.push_back(backgroundPressure);
        expected.resize(Table::coreStride(), 0.0);
        ASSERT(expected == eos.parameter);
        // The core takes the law: some density gives a valid state.
        double e, sigma, pressureAtZero, thermalPressure;
        const int status = Physics::gendpdeLocalEquationOfState(eos.law, 1e-3, eos.parameter.data(), eos.integerPower,
                                                                &e, &sigma, &pressureAtZero, &thermalPressure);
        ASSERT_EQUAL(GENDPDE_PARTICLE_VALID, status);
    }
}

void testRulesInAnyUnits() {
    // What an engine in other units (LAMMPS) checks of each given parameter: a value GenDPDEForce accepts passes; a
    // non-finite one never does; one below a range that starts at or above 0 does not; a dimensionless parameter
    // (gamma_T) keeps its whole range.
    std::string rule;
    for (const Table::Law& law : Table::laws)
        for (int k = 0; k < Table::numGivenParameters(law); k++) {
            const Table::Parameter& p = Table::givenParameter(law, k);
            ASSERT(Table::allowedInAnyUnits(p, allowedValue(p, k), rule));
            ASSERT(!Table::allowedInAnyUnits(p, std::nan(""), rule));
            ASSERT(!Table::allowedInAnyUnits(p, INFINITY, rule));
            if (p.range.minimum >= 0.0)
                ASSERT(!Table::allowedInAnyUnits(p, -1.0, rule));
        }
    const Table::Parameter& exponent = Table::taitParameters[3];
    ASSERT(!Table::allowedInAnyUnits(exponent, 1.0, rule) && Table::allowedInAnyUnits(exponent, 100.0, rule));
    ASSERT(!Table::allowedInAnyUnits(exponent, 100.5, rule));
    ASSERT_EQUAL(std::string("in (1, 100]"), rule);
    ASSERT(Table::allowedInAnyUnits(Table::taitParameters[1], -5.0, rule)); // pi0 may be negative
    ASSERT_EQUAL(std::string("finite"), rule);
}

void testEveryEstimatorIsAcceptedAndRoundTrips() {
    namespace Estimators = DensityEstimators;
    ASSERT(Estimators::numEstimators >= 3);
    for (int k = 0; k < Estimators::numEstimators; k++) {
        GenDPDEForce force(1.0);
        force.setDensityEstimator((GenDPDEForce::DensityEstimator) k);
        std::stringstream buffer;
        XmlSerializer::serialize<GenDPDEForce>(&force, "Force", buffer);
        std::unique_ptr<GenDPDEForce> copy(XmlSerializer::deserialize<GenDPDEForce>(buffer));
        ASSERT_EQUAL(k, (int) copy->getDensityEstimator());
        ASSERT(Estimators::findByName(Estimators::estimators[k].name) == &Estimators::estimators[k]);
        ASSERT(Estimators::find(k) == &Estimators::estimators[k]);
    }
    std::vector<std::string> names = {"density estimator"};
    for (const Estimators::Estimator& estimator : Estimators::estimators)
        names.push_back(estimator.name);
    GenDPDEForce force(1.0);
    for (int bad : {-1, Estimators::numEstimators}) {
        names.push_back("= " + std::to_string(bad));
        assertThrowsMentioning([&]() { force.setDensityEstimator((GenDPDEForce::DensityEstimator) bad); }, names);
        names.pop_back();
    }
    ASSERT(Estimators::find(-1) == nullptr && Estimators::findByName("V") == nullptr);
    ASSERT(Estimators::findByName("vb") == &Estimators::estimators[GENDPDE_ESTIMATOR_VB]); // LAMMPS's spelling
}

void testEstimatorEntriesSayWhatTheCoreDoes() {
    // At a liquid's primitive density n0 (nm^-3) and a one-sided neighbourhood (G = 4 n0^2, a^2 = 1: a flat free
    // surface): an estimator reads f_cut if its volume changes between f_cut = 1 and 1.5, and the moments if its
    // volume changes with G or its dV/dG is not zero.
    const double cutoff = 1.0, n0 = 6.5, G = 4 * n0 * n0;
    for (const DensityEstimators::Estimator& entry : DensityEstimators::estimators) {
        const Physics::VolumeEstimator plain(entry.coreId, cutoff, cutoff), scaled(entry.coreId, cutoff, cutoff / 1.5);
        const bool readsCutoffScaling = plain(n0).volume != scaled(n0).volume;
        const Physics::ParticleVolumeAndMoment bulk = plain(n0, 0.0), surface = plain(n0, G);
        const bool readsMoments = bulk.volume != surface.volume || surface.momentDerivative != 0.0;
        ASSERT_EQUAL(entry.readsCutoffScaling, readsCutoffScaling);
        ASSERT_EQUAL(entry.needsMoments, readsMoments);
        ASSERT_EQUAL(entry.needsMoments, Physics::gendpdeEstimatorNeedsMoments(entry.coreId) != 0);
        ASSERT(entry.stableStepFactor > 0.0 && entry.stableStepFactor <= 1.0);
    }
}

} // namespace

int main() {
    return runTestProgram([]() {
        loadGenDPDEKernels("Reference");
        testEveryLawIsAcceptedAndRoundTrips();
        testWrongCountsAndRangesAreRefusedInTheTablesWords();
        testPackingFollowsTheTable();
        testRulesInAnyUnits();
        testEveryEstimatorIsAcceptedAndRoundTrips();
        testEstimatorEntriesSayWhatTheCoreDoes();
    });
}
