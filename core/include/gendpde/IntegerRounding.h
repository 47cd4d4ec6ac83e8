/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
#ifndef GENDPDE_INTEGER_ROUNDING_H_
#define GENDPDE_INTEGER_ROUNDING_H_

/* Rounding to integers without library calls, for the box geometry and the sweep's cells. No dependencies: the
 * LAMMPS package includes it too. */

namespace GenDPDEPlugin {
namespace BoxGeometry {

/** x rounded to the nearest integer (ties to even), branch-free; exact for |x| < 2^51. */
inline double roundToInteger(double x) {
    const double shifter = 6755399441055744.0;   // 1.5 * 2^52: the sum's last bit is the units digit
    return (x + shifter) - shifter;
}

/**
 * The largest integer <= x, exact for |x| < 2^51 (std::floor's value, but +0 for -0). Without SSE4.1, which the
 * Reference platform does not require, std::floor is a library call: three per particle made the wrap of 32,000
 * positions cost 0.6 ms.
 */
inline double floorToInteger(double x) {
    const double rounded = roundToInteger(x);
    return rounded > x ? rounded - 1.0 : rounded;
}

} // namespace BoxGeometry
} // namespace GenDPDEPlugin

#endif /*GENDPDE_INTEGER_ROUNDING_H_*/
