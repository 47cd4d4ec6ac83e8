/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
#ifndef GENDPDE_PHYSICS_CORE_DOUBLE_H_
#define GENDPDE_PHYSICS_CORE_DOUBLE_H_

/* The physics core (GenDPDEPhysicsCore.h) and the sweep's pair step (GenDPDESweepPair.h, with CounterRandom's pair
 * streams) compiled in double precision on the host, with the V-B tables they read, in namespace
 * GenDPDEPlugin::Physics: what GenDPDEPhysics.h (the OpenMM platforms, the bindings, the tests) and the LAMMPS
 * package (lammps/src/gendpde_core.h) both include. No OpenMM header. */

#include "gendpde/CounterRandom.h"
#include "gendpde/VolumeVBTables.h"
#include <cmath>
#include <cstdint>
#include <cstring>

namespace GenDPDEPlugin {
namespace Physics {

/**
 * frexp(x, exponent) for a positive double from its bits, inline (glibc's frexp is a library call, and the V-B
 * integrals take one per particle): x = fraction 2^exponent with fraction in [1/2, 1), exactly as frexp gives them.
 * Zero, subnormal and non-finite x go to std::frexp.
 */
inline double frexpOfPositive(double x, int* exponent) {
    std::uint64_t bits;
    std::memcpy(&bits, &x, sizeof(bits));
    const int biased = (int) ((bits >> 52) & 0x7ff);
    if (biased == 0 || biased == 0x7ff)
        return std::frexp(x, exponent);
    *exponent = biased - 1022;
    bits = (bits & ~(0x7ffull << 52)) | (1022ull << 52);
    double fraction;
    std::memcpy(&fraction, &bits, sizeof(fraction));
    return fraction;
}

// The core in double precision, with the sizes of the V-B tables it reads.
#define GENDPDE_REAL double
#define GENDPDE_ISFINITE(x) std::isfinite(x)
#define GENDPDE_FREXP(x, exponent) frexpOfPositive(x, exponent)
#define GENDPDE_VB_FIRST_OCTAVE (VolumeVBPolynomials::firstOctave)
#define GENDPDE_VB_LAST_OCTAVE (VolumeVBPolynomials::lastOctave)
#define GENDPDE_VB_QUADRATURE_PAIRS (VolumeVBQuadrature::numPairs)
#include "gendpde/GenDPDEPhysicsCore.h"
#define GENDPDE_PAIR_STREAM CounterRandom::PairStream
#define GENDPDE_PAIR_NORMAL(stream) ((stream)->normal())
#include "gendpde/GenDPDESweepPair.h"
#undef GENDPDE_PAIR_STREAM
#undef GENDPDE_PAIR_NORMAL
#undef GENDPDE_REAL
#undef GENDPDE_ISFINITE
#undef GENDPDE_FREXP
#undef GENDPDE_VB_FIRST_OCTAVE
#undef GENDPDE_VB_LAST_OCTAVE
#undef GENDPDE_VB_QUADRATURE_PAIRS

/** The V-B polynomial coefficients as the core reads them (gendpdeVolumeIntegralsVB). */
inline const double* volumePolynomials() {
    return &VolumeVBPolynomials::coefficients[0][0][0];
}

} // namespace Physics
} // namespace GenDPDEPlugin

#endif /*GENDPDE_PHYSICS_CORE_DOUBLE_H_*/
