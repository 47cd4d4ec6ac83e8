/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
#ifndef GENDPDE_ROW_GATHER_AVX2_H_
#define GENDPDE_ROW_GATHER_AVX2_H_

#include "openmm/Vec3.h"

namespace GenDPDEPlugin {

/**
 * The row gathers of the CPU force kernel (CpuGenDPDEForceKernel.cpp) four pairs at a time with AVX2, for open and
 * rectangular periodic boxes and the estimators that read no moments: the physics core's gendpdeDensityWeight,
 * gendpdeDensityWeightDerivative, gendpdePairForceScale and gendpdeCentralPairForce compiled with __m256d operands
 * (GENDPDE_CORE_ARITHMETIC_ONLY), with the masks of the scalar kernel's range tests in place of its branches. Each
 * lane performs the scalar kernel's IEEE operations in the same order (no fused multiply-add: these functions are
 * compiled for AVX2 without FMA, and the build forbids contractions, -ffp-contract=off), and the lanes are added to
 * the particle's sums one after another in row order, so the results are the scalar kernel's, hence Reference's, to
 * the last bit (platforms/cpu/tests/TestCpuGenDPDEEqualsReference.cpp runs both kernels).
 */
namespace RowGatherAvx2 {

/** Whether this processor runs AVX2 (checked once), and the GENDPDE_CPU_VECTOR environment variable is not "0". */
bool enabled();

/** What the gathers read: row positions, rows (CellOrderedCandidates), box and the pair arithmetic's constants. */
struct Rows {
    const OpenMM::Vec3* position;   // row order, wrapped if periodic (nm)
    const int* rowStart;
    const int* upperStart;
    const int* neighbors;
    bool periodic;                  // rectangular box if true
    double boxLength[3], inverseBoxLength[3];
    double cutoff, cutoff2, inverseCutoff;
    double valueScale, derivativeScale;   // of Physics::DensityWeight
};

/** n0 of rows [begin, end) (nm^-3) into density[s]. */
void densities(const Rows& rows, int begin, int end, double* density);

/**
 * The force on rows [begin, end): force[s] starts at its value on entry and gains the row's terms in order;
 * virial[s] = sum over the upper part of the row of (scale r) r (kJ/mol). coefficient: pi dV/dn0 per row.
 */
void forces(const Rows& rows, const double* coefficient, int begin, int end, OpenMM::Vec3* force, double* virial);

} // namespace RowGatherAvx2
} // namespace GenDPDEPlugin

#endif /*GENDPDE_ROW_GATHER_AVX2_H_*/
