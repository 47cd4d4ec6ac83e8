#ifndef GENDPDE_PARAMETER_CHECKS_H_
#define GENDPDE_PARAMETER_CHECKS_H_

/* Validation of user input. Every message names the class, the parameter, the rejected value with its units and
 * what is allowed, e.g. "GenDPDEForce: cutoffScaling = 0.5 is not allowed; it must be finite and >= 1". */

#include "openmm/OpenMMException.h"
#include <cmath>
#include "internal/MessageText.h"
#include <string>

namespace GenDPDEPlugin {
namespace ParameterChecks {

[[noreturn]] inline void reject(const std::string& owner, const std::string& parameter, double value,
                                const std::string& units, const std::string& allowed) {
    MessageText message;
    message.precision(12);
    message << owner << ": " << parameter << " = " << value << (units.empty() ? "" : " ") << units
            << " is not allowed; it must be " << allowed;
    throw OpenMM::OpenMMException(message.str());
}

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

/** Reject a value outside range (or equal to its minimum if the minimum is excluded). */
inline void requireInRange(const std::string& owner, const std::string& parameter, double value, const Range& range,
                           bool excludeMinimum = false) {
    const bool below = excludeMinimum ? !(value > range.minimum) : !(value >= range.minimum);
    if (!std::isfinite(value) || below || !(value <= range.maximum)) {
        MessageText allowed;
        allowed.precision(12);
        allowed << "finite and in " << (excludeMinimum ? "(" : "[") << range.minimum << ", " << range.maximum << "]"
                << (range.units[0] == '\0' ? "" : " ") << range.units;
        reject(owner, parameter, value, range.units, allowed.str());
    }
}

/** Reject an index outside [0, count) into a list of entries (type parameters, type pairs). */
inline void requireIndex(const std::string& owner, const std::string& parameter, int index, int count) {
    if (index < 0 || index >= count)
        reject(owner, parameter, index, "",
               count == 0 ? std::string("an existing entry, and there are none")
                          : "in [0, " + std::to_string(count - 1) + "]");
}

} // namespace ParameterChecks
} // namespace GenDPDEPlugin

#endif /*GENDPDE_PARAMETER_CHECKS_H_*/
