/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
#ifndef GENDPDE_CORE_TEST_H_
#define GENDPDE_CORE_TEST_H_

/* Assertions for the core's tests, which include nothing but the core and the standard library (no OpenMM): a
 * failed check throws std::runtime_error naming the expression, the values and the line. */

#include <cmath>
#include <functional>
#include <iostream>
#include <sstream>
#include <stdexcept>
#include <string>

namespace GenDPDECoreTest {

/** Throw with the condition's text and where it is, unless it holds. */
inline void check(bool condition, const char* text, const char* file, int line) {
    if (!condition)
        throw std::runtime_error(std::string(file) + ":" + std::to_string(line) + ": " + text + " does not hold");
}

/** Throw with both values unless expected == found. */
template <class A, class B>
void checkEqual(const A& expected, const B& found, const char* text, const char* file, int line) {
    if (!(expected == found)) {
        std::ostringstream message;
        message.precision(17);
        message << file << ":" << line << ": " << text << ": expected " << expected << ", found " << found;
        throw std::runtime_error(message.str());
    }
}

/** Throw unless |expected - found| <= tolerance. */
inline void checkClose(double expected, double found, double tolerance, const std::string& what) {
    if (!(std::fabs(expected - found) <= tolerance)) {
        std::ostringstream message;
        message.precision(17);
        message << what << ": expected " << expected << ", found " << found << " (difference "
                << std::fabs(expected - found) << " > tolerance " << tolerance << ")";
        throw std::runtime_error(message.str());
    }
}

/** Run the tests: "Done" and 0, or the first failure and 1. */
inline int run(const std::function<void()>& tests) {
    try {
        tests();
    } catch (const std::exception& e) {
        std::cout << "FAILED: " << e.what() << std::endl;
        return 1;
    }
    std::cout << "Done" << std::endl;
    return 0;
}

} // namespace GenDPDECoreTest

#define CORE_ASSERT(condition) GenDPDECoreTest::check((condition), #condition, __FILE__, __LINE__)
#define CORE_ASSERT_EQUAL(expected, found)                                                                             \
    GenDPDECoreTest::checkEqual((expected), (found), #expected " == " #found, __FILE__, __LINE__)

#endif /*GENDPDE_CORE_TEST_H_*/
