/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
#ifndef GENDPDE_PARAMETER_CHECKS_H_
#define GENDPDE_PARAMETER_CHECKS_H_

/* Validation of user input. Every message names the class, the parameter, the rejected value with its units and
 * what is allowed, e.g. "GenDPDEForce: cutoffScaling = 0.5 is not allowed; it must be finite and >= 1". */

#include "openmm/OpenMMException.h"
#include <cmath>
#include "internal/MessageText.h"
#include "gendpde/ParameterRanges.h"
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
