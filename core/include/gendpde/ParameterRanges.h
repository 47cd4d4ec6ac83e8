/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
#ifndef GENDPDE_PARAMETER_RANGES_H_
#define GENDPDE_PARAMETER_RANGES_H_

/* The allowed ranges of the parameters (ParameterChecks.h checks values against them), with no dependencies: the
 * table of the equations of state (GenDPDEEquationsOfState.h) holds them, and the LAMMPS package reads that table. */

namespace GenDPDEPlugin {
namespace ParameterChecks {

/** A closed interval [minimum, maximum] of allowed values, with units for messages. */
struct Range {
    double minimum, maximum;
    const char* units;
};

/**
 * The allowed ranges of the parameters (OpenMM units), documented in docs/force.md and docs/integrator.md. They are
 * generous around any physical use (a particle of 1 pm to 10 um, temperatures far outside what a fluid can have) and
 * keep every intermediate of the arithmetic finite and normal in double precision: e.g. the density weight scales
 * like R^-3 and its derivative like R^-4, the pair temperatures use eps_i eps_j (eps_i + eps_j) with eps = C_V T.
 */
namespace Ranges {
constexpr Range cutoff{1e-3, 1e4, "nm"};
constexpr Range cutoffScaling{1.0, 100.0, ""};
constexpr Range referenceDensity{1e-12, 1e12, "nm^-3"};
constexpr Range referencePressure{-1e12, 1e12, "kJ/mol/nm^3"};
constexpr Range bulkModulus{1e-12, 1e12, "kJ/mol/nm^3"};
constexpr Range backgroundPressure{0.0, 1e12, "kJ/mol/nm^3"};
constexpr Range taitExponent{1.0, 100.0, ""};          // gamma_T > 1 (the minimum is excluded)
constexpr Range stepSize{0.0, 1e3, "ps"};            // dt > 0 (the minimum is excluded)
constexpr Range friction{0.0, 1e12, "amu/ps"};
constexpr Range heatConduction{0.0, 1e12, "kJ K/(mol ps)"};
constexpr Range heatCapacity{1e-20, 1e20, "kJ/(mol K)"};
constexpr Range temperature{1e-50, 1e50, "K"};
constexpr Range internalEnergy{1e-100, 1e100, "kJ/mol"};   // eps_i set, or read from checkpoints and States
constexpr Range mass{0.0, 1e12, "amu"};
// (The parameters of the equations of state have their ranges in GenDPDEEquationsOfState.h.)
} // namespace Ranges

} // namespace ParameterChecks
} // namespace GenDPDEPlugin

#endif /*GENDPDE_PARAMETER_RANGES_H_*/
