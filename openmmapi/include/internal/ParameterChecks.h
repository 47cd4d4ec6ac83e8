#ifndef GENDPDE_PARAMETER_CHECKS_H_
#define GENDPDE_PARAMETER_CHECKS_H_

/* Validation of user input. Every message names the class, the parameter, the rejected value with its units and
 * what is allowed, e.g. "GenDPDEForce: cutoffScaling = 0.5 is not allowed; it must be finite and >= 1". */

#include "openmm/OpenMMException.h"
#include <cmath>
#include <sstream>
#include <string>

namespace GenDPDEPlugin {
namespace ParameterChecks {

[[noreturn]] inline void reject(const std::string& owner, const std::string& parameter, double value,
                                const std::string& units, const std::string& allowed) {
    std::ostringstream message;
    message.precision(12);
    message << owner << ": " << parameter << " = " << value << (units.empty() ? "" : " ") << units
            << " is not allowed; it must be " << allowed;
    throw OpenMM::OpenMMException(message.str());
}

inline void requireFinite(const std::string& owner, const std::string& parameter, double value,
                          const std::string& units = "") {
    if (!std::isfinite(value))
        reject(owner, parameter, value, units, "finite");
}

inline void requirePositive(const std::string& owner, const std::string& parameter, double value,
                            const std::string& units = "") {
    if (!std::isfinite(value) || !(value > 0.0))
        reject(owner, parameter, value, units, "finite and > 0");
}

inline void requireNonNegative(const std::string& owner, const std::string& parameter, double value,
                               const std::string& units = "") {
    if (!std::isfinite(value) || !(value >= 0.0))
        reject(owner, parameter, value, units, "finite and >= 0");
}

inline void requireAtLeast(const std::string& owner, const std::string& parameter, double value, double minimum,
                           const std::string& units = "") {
    if (!std::isfinite(value) || !(value >= minimum)) {
        std::ostringstream allowed;
        allowed << "finite and >= " << minimum;
        reject(owner, parameter, value, units, allowed.str());
    }
}

inline void requireGreaterThan(const std::string& owner, const std::string& parameter, double value, double minimum,
                               const std::string& units = "") {
    if (!std::isfinite(value) || !(value > minimum)) {
        std::ostringstream allowed;
        allowed << "finite and > " << minimum;
        reject(owner, parameter, value, units, allowed.str());
    }
}

} // namespace ParameterChecks
} // namespace GenDPDEPlugin

#endif /*GENDPDE_PARAMETER_CHECKS_H_*/
