/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
#ifndef GENDPDE_TEST_UTILITIES_H_
#define GENDPDE_TEST_UTILITIES_H_

/* Assertions for the C++ tests. Every tolerance is explicit at the call site (absolute, or relative to the
 * expected value); none silently switches to an absolute scale of 1 as OpenMM's ASSERT_EQUAL_TOL does. */

#include "CoreTest.h"
#include "openmm/OpenMMException.h"
#include "openmm/internal/AssertionUtilities.h"
#include "openmm/Vec3.h"
#include <cmath>
#include <cstdlib>
#include <functional>
#include <iostream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

/**
 * The precision of the platform under test: "double" on the host platforms; a GPU platform's test driver sets its
 * Precision ("single", "mixed" or "double").
 */
inline std::string& testPrecision() {
    static std::string precision = "double";
    return precision;
}

/** Whether forces are computed in float (a GPU platform in single or mixed precision). */
inline bool floatForces() {
    return testPrecision() != "double";
}

/**
 * A tolerance for double-precision forces, or the one for float forces (single and mixed precision: positions and
 * pair sums in float, 2^-24 = 6e-8 relative per operation; a test that uses the second says why its value).
 */
inline double precisionTolerance(double doubleTolerance, double floatTolerance) {
    return floatForces() ? floatTolerance : doubleTolerance;
}

inline void assertClose(double expected, double found, double tolerance, const std::string& what) {
    GenDPDECoreTest::checkClose(expected, found, tolerance, what);
}

inline void assertRelative(double expected, double found, double relativeTolerance, const std::string& what) {
    assertClose(expected, found, relativeTolerance * std::abs(expected), what);
}

inline void assertVectorClose(const OpenMM::Vec3& expected, const OpenMM::Vec3& found, double tolerance,
                              const std::string& what) {
    for (int k = 0; k < 3; k++)
        assertClose(expected[k], found[k], tolerance, what + " (component " + std::to_string(k) + ")");
}

/** The call must throw an OpenMMException whose message contains every fragment. */
inline void assertThrowsMentioning(const std::function<void()>& call, const std::vector<std::string>& fragments) {
    try {
        call();
    } catch (const OpenMM::OpenMMException& e) {
        std::string message = e.what();
        for (const std::string& fragment : fragments)
            if (message.find(fragment) == std::string::npos)
                throw std::runtime_error("exception message lacks '" + fragment + "': " + message);
        return;
    }
    throw std::runtime_error("expected an OpenMMException mentioning '" + fragments[0] + "', none was thrown");
}

/** Environment variables set for a block of code (developer settings read when a Context is created), then unset. */
class ScopedEnvironment {
public:
    explicit ScopedEnvironment(const std::vector<std::pair<std::string, std::string>>& values) : values(values) {
        for (const auto& value : values)
            setenv(value.first.c_str(), value.second.c_str(), 1);
    }
    ~ScopedEnvironment() {
        for (const auto& value : values)
            unsetenv(value.first.c_str());
    }
    std::string label() const { return describe(values); }
    static std::string describe(const std::vector<std::pair<std::string, std::string>>& values) {
        std::string text;
        for (const auto& value : values)
            text += " " + value.first + "=" + value.second;
        return text.empty() ? " (defaults)" : text;
    }

private:
    std::vector<std::pair<std::string, std::string>> values;
};

/** main() of a test program: run the tests, print "Done" or the failure, return the exit status (as the core's
 *  tests do: core/tests/CoreTest.h). */
inline int runTestProgram(const std::function<void()>& tests) {
    return GenDPDECoreTest::run(tests);
}

#endif /*GENDPDE_TEST_UTILITIES_H_*/
