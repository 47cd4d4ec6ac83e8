/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
#ifndef GENDPDE_EQUATIONS_OF_STATE_H_
#define GENDPDE_EQUATIONS_OF_STATE_H_

/* The one description of the local equations of state (docs/theory.md section 11): for each law its API name, its
 * physics-core id, and its parameters with their names, units and allowed ranges. The checks and messages of
 * GenDPDEForce, the XML serialization, the packing of the parameters for the platforms (equationsOfStateByType) and
 * the Python unit wrapping (through SWIG) all read this table.
 *
 * A new law is: its formula in the physics core (a GENDPDE_EOS_* id and a branch of gendpdeLocalEquationOfState,
 * GenDPDEPhysicsCore.h; gendpdeLawDependsOnTemperature if it does), an entry here, its enum value in GenDPDEForce.h
 * (python/tests/test_tables.py checks through the bindings that every entry's name is the enum value of its place),
 * and its oracle in the tests. Engine-neutral (core/): the LAMMPS package takes its laws' names and parameters from
 * it too. */

#include "gendpde/GenDPDEPhysicsCoreDouble.h"
#include "gendpde/ParameterRanges.h"
#include <cmath>
#include <cstdio>
#include <string>

namespace GenDPDEPlugin {
namespace EquationsOfState {

/** The most parameters a law may take through the API (setEquationOfState); raise it freely. */
constexpr int maxParameters = 8;

/** One parameter of a law as the API takes it. */
struct Parameter {
    const char* name;          // short name, as Python and the documentation spell it ("beta")
    const char* description;   // for messages ("thermal pressure coefficient beta")
    ParameterChecks::Range range;   // allowed values, with the units (OpenMM units) as text ("kJ/mol/nm^3/K"):
                                    // generous, as ParameterChecks::Ranges (their own, or a shared one)
    bool excludeMinimum = false;    // whether range.minimum itself is refused
};

/** A law. */
struct Law {
    const char* name;          // as the API spells it, GenDPDEForce::EquationOfState ("VanDerWaals")
    const char* description;   // for messages about a particle's law ("van der Waals")
    int coreId;                // its GENDPDE_EOS_* number in the physics core
    /**
     * How the core's parameters are made of the API's: a law that extends the Tait law takes the type's Tait
     * parameters n0, pi0 + p_b, B_T, gamma_T, then its own; any other takes its own, then the background pressure
     * p_b (gendpdeLocalEquationOfState).
     */
    bool extendsTait;
    /** Its domain of densities, for messages, if not every n > 0 ("0 < n < 1/b"); "" otherwise. */
    const char* domain;
    int numParameters;
    Parameter parameters[maxParameters];
    /** The number of parameters the physics core reads. */
    constexpr int numCoreParameters() const { return numParameters + (extendsTait ? 4 : 1); }
};

/** Every law, at its GenDPDEForce::EquationOfState number. */
constexpr Law laws[] = {
        {"Tait", "Tait", GENDPDE_EOS_TAIT, true, "", 0, {}},
        {"TaitThermalExpansion",
         "Tait",
         GENDPDE_EOS_TAIT_THERMAL,
         true,
         "",
         2,
         {{"beta", "thermal pressure coefficient beta", {-1e12, 1e12, "kJ/mol/nm^3/K"}},   // (dpi/dtheta)_n
          {"theta0", "reference temperature theta0", ParameterChecks::Ranges::temperature}}},
        {"VanDerWaals",
         "van der Waals",
         GENDPDE_EOS_VAN_DER_WAALS,
         false,
         "0 < n < 1/b",
         3,
         {{"a", "van der Waals attraction a", {0.0, 1e12, "kJ/mol nm^3"}},
          {"b", "van der Waals excluded volume b", {1e-12, 1e12, "nm^3"}},
          {"k", "van der Waals entropy scale k", ParameterChecks::Ranges::heatCapacity}}},
};

/** The number of laws. */
constexpr int numLaws = sizeof(laws) / sizeof(laws[0]);

/** The number of parameters every type has on the platforms (the most any law's core reads). */
constexpr int coreStride() {
    int stride = 0;
    for (const Law& law : laws)
        stride = (law.numCoreParameters() > stride ? law.numCoreParameters() : stride);
    return stride;
}

constexpr bool numberedInOrder() {
    for (int k = 0; k < numLaws; k++)
        if (laws[k].coreId != k || laws[k].numParameters > maxParameters)
            return false;
    return true;
}
static_assert(numberedInOrder(), "each law's core id must be its place in the table");

/** The law numbered law (a GenDPDEForce::EquationOfState value), or nullptr if there is none. */
inline const Law* find(int law) {
    return (law >= 0 && law < numLaws) ? &laws[law] : nullptr;
}

/** The laws for messages: "Tait (0), TaitThermalExpansion (1) or VanDerWaals (2)". */
inline std::string listOfLaws() {
    std::string list;
    for (int k = 0; k < numLaws; k++)
        list += std::string(k == 0 ? "" : (k + 1 == numLaws ? " or " : ", ")) + laws[k].name + " (" + std::to_string(k)
                + ")";
    return list;
}

/** A law's parameters for messages: "van der Waals attraction a, van der Waals excluded volume b, ...". */
inline std::string listOfParameters(const Law& law) {
    std::string list;
    for (int k = 0; k < law.numParameters; k++)
        list += (k == 0 ? "" : ", ") + std::string(law.parameters[k].description);
    return list;
}

/**
 * The four Tait parameters that a law extending Tait takes first, n0, pi0, B_T, gamma_T (GenDPDEForce::
 * setTaitParameters), described as the laws' own parameters are.
 */
constexpr Parameter taitParameters[4] = {
        {"n0", "reference density n0", ParameterChecks::Ranges::referenceDensity},
        {"pi0", "reference pressure pi0", ParameterChecks::Ranges::referencePressure},
        {"B_T", "bulk modulus B_T", ParameterChecks::Ranges::bulkModulus},
        {"gamma_T", "Tait exponent gamma_T", ParameterChecks::Ranges::taitExponent, true},
};

/** The number of parameters a law is given: the four Tait parameters first if it extends Tait, then its own. */
constexpr int numGivenParameters(const Law& law) {
    return (law.extendsTait ? 4 : 0) + law.numParameters;
}

/** The k-th parameter a law is given (numGivenParameters: the Tait four first if it extends Tait). */
inline const Parameter& givenParameter(const Law& law, int k) {
    return law.extendsTait ? (k < 4 ? taitParameters[k] : law.parameters[k - 4]) : law.parameters[k];
}

/**
 * Whether value is allowed for parameter p by the rule that holds in any units (an engine whose units are not
 * OpenMM's, as LAMMPS's): finite, and of the sign its range asks (> 0 where the range starts above 0 or excludes 0,
 * >= 0 where it starts at 0); a dimensionless parameter (no units) must lie in its range itself. rule receives the
 * rule in words ("> 0 and finite", "in (1, 100]").
 */
inline bool allowedInAnyUnits(const Parameter& p, double value, std::string& rule) {
    const ParameterChecks::Range& range = p.range;
    if (range.units[0] == '\0') {
        char text[64];
        std::snprintf(text, sizeof(text), "in %s%g, %g]", p.excludeMinimum ? "(" : "[", range.minimum, range.maximum);
        rule = text;
        return (p.excludeMinimum ? value > range.minimum : value >= range.minimum) && value <= range.maximum;
    }
    const bool finite = std::isfinite(value);
    if (range.minimum > 0.0 || (p.excludeMinimum && range.minimum == 0.0)) {
        rule = "> 0 and finite";
        return finite && value > 0.0;
    }
    if (range.minimum == 0.0) {
        rule = ">= 0 and finite";
        return finite && value >= 0.0;
    }
    rule = "finite";
    return finite;
}

/**
 * The physics core's parameters of a law (gendpdeLocalEquationOfState) from what it is given, given[0 ..
 * numGivenParameters(law)) (the Tait four first if it extends Tait, then its own), and the background pressure p_b,
 * which adds to every law's pressure (and -p_b/n to its free energy): to pi0 of a law that extends Tait, as the last
 * parameter of any other. Writes coreStride() values to core (unused ones 0: every type has the same number, which
 * the platforms upload with one stride). Returns the Tait law's integer power (gendpdeTaitIntegerPower of gamma_T),
 * or -1 for a law that does not extend Tait.
 */
inline int packCoreParameters(const Law& law, const double* given, double backgroundPressure, double* core) {
    int n = 0, integerPower = -1;
    if (law.extendsTait) {
        core[n++] = given[0];
        core[n++] = given[1] + backgroundPressure;
        core[n++] = given[2];
        core[n++] = given[3];
        integerPower = Physics::gendpdeTaitIntegerPower(given[3]);
    }
    for (int k = 0; k < law.numParameters; k++)
        core[n++] = given[(law.extendsTait ? 4 : 0) + k];
    if (!law.extendsTait)
        core[n++] = backgroundPressure;
    while (n < coreStride())
        core[n++] = 0.0;
    return integerPower;
}

} // namespace EquationsOfState
} // namespace GenDPDEPlugin

#endif /*GENDPDE_EQUATIONS_OF_STATE_H_*/
