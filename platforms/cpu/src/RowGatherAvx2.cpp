/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
#include "RowGatherAvx2.h"
#include <cstdlib>
#include <cstring>
#include <immintrin.h>

using namespace GenDPDEPlugin;
using OpenMM::Vec3;

namespace {

#define GENDPDE_AVX2 __attribute__((target("avx2")))

/**
 * The physics core's pair arithmetic (GenDPDEPhysicsCore.h, GENDPDE_CORE_ARITHMETIC_ONLY) on four pairs at once:
 * with GCC's vector extensions +, -, * and / of __m256d are the lanes' IEEE operations, in the order the scalar
 * core writes them, and a scalar operand (the 1 of 1 - r/R) is broadcast. Each lane therefore has the scalar core's
 * bits (no contraction: compiled for AVX2 without FMA, and -ffp-contract=off).
 */
namespace Lanes4 {
#define GENDPDE_REAL __m256d
#define GENDPDE_CORE GENDPDE_AVX2 inline
#define GENDPDE_CORE_ARITHMETIC_ONLY
#include "gendpde/GenDPDEPhysicsCore.h"
#undef GENDPDE_REAL
#undef GENDPDE_CORE
#undef GENDPDE_CORE_ARITHMETIC_ONLY
} // namespace Lanes4

/** Four pairs (s, t_k) of one row: displacement r_s - r_t (nearest image), r^2 and r, as the scalar kernel. */
struct Lanes {
    __m256d dx, dy, dz, r2, r;
};

/** The neighbors' rows of entries m .. m + count - 1 (count <= 4); unused lanes point at s itself. */
GENDPDE_AVX2 inline __m128i laneRows(const int* neighbors, int m, int count, int s) {
    if (count == 4)
        return _mm_loadu_si128(reinterpret_cast<const __m128i*>(neighbors + m));
    int rows[4] = {s, s, s, s};
    std::memcpy(rows, neighbors + m, sizeof(int) * count);
    return _mm_loadu_si128(reinterpret_cast<const __m128i*>(rows));
}

/** x - L round(x/L) with round(v) = (v + 1.5 2^52) - 1.5 2^52, as PeriodicBox::nearestImageRectangular. */
GENDPDE_AVX2 inline __m256d nearestImage(__m256d x, double length, double inverseLength) {
    const __m256d shifter = _mm256_set1_pd(6755399441055744.0);
    const __m256d rounded =
            _mm256_sub_pd(_mm256_add_pd(_mm256_mul_pd(x, _mm256_set1_pd(inverseLength)), shifter), shifter);
    return _mm256_sub_pd(x, _mm256_mul_pd(_mm256_set1_pd(length), rounded));
}

GENDPDE_AVX2 inline Lanes pairLanes(const RowGatherAvx2::Rows& rows, int s, __m128i neighbors) {
    // Four unaligned loads of (x, y, z, next x) and a 4x4 transpose; the positions carry one padding Vec3.
    alignas(16) int t[4];
    _mm_store_si128(reinterpret_cast<__m128i*>(t), neighbors);
    const double* base = reinterpret_cast<const double*>(rows.position);   // Vec3 is double[3]
    const __m256d p0 = _mm256_loadu_pd(base + 3 * t[0]), p1 = _mm256_loadu_pd(base + 3 * t[1]);
    const __m256d p2 = _mm256_loadu_pd(base + 3 * t[2]), p3 = _mm256_loadu_pd(base + 3 * t[3]);
    const __m256d low01 = _mm256_unpacklo_pd(p0, p1), high01 = _mm256_unpackhi_pd(p0, p1);   // x0 x1 z0 z1, y0 y1 ..
    const __m256d low23 = _mm256_unpacklo_pd(p2, p3), high23 = _mm256_unpackhi_pd(p2, p3);
    const __m256d x = _mm256_permute2f128_pd(low01, low23, 0x20), z = _mm256_permute2f128_pd(low01, low23, 0x31);
    const __m256d y = _mm256_permute2f128_pd(high01, high23, 0x20);
    Lanes lanes;
    lanes.dx = _mm256_sub_pd(_mm256_set1_pd(rows.position[s][0]), x);
    lanes.dy = _mm256_sub_pd(_mm256_set1_pd(rows.position[s][1]), y);
    lanes.dz = _mm256_sub_pd(_mm256_set1_pd(rows.position[s][2]), z);
    if (rows.periodic) {
        lanes.dx = nearestImage(lanes.dx, rows.boxLength[0], rows.inverseBoxLength[0]);
        lanes.dy = nearestImage(lanes.dy, rows.boxLength[1], rows.inverseBoxLength[1]);
        lanes.dz = nearestImage(lanes.dz, rows.boxLength[2], rows.inverseBoxLength[2]);
    }
    // Vec3::dot: (x x + y y) + z z.
    lanes.r2 = _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(lanes.dx, lanes.dx), _mm256_mul_pd(lanes.dy, lanes.dy)),
                             _mm256_mul_pd(lanes.dz, lanes.dz));
    lanes.r = _mm256_sqrt_pd(lanes.r2);
    return lanes;
}

/** All bits set where the pair is listed (r^2 < R^2). */
GENDPDE_AVX2 inline __m256d listedMask(const RowGatherAvx2::Rows& rows, const Lanes& lanes) {
    return _mm256_cmp_pd(lanes.r2, _mm256_set1_pd(rows.cutoff2), _CMP_LT_OQ);
}

/** All bits set where the weight and its derivative are nonzero: listed and r < R. */
GENDPDE_AVX2 inline __m256d inRangeMask(const RowGatherAvx2::Rows& rows, const Lanes& lanes) {
    return _mm256_and_pd(listedMask(rows, lanes), _mm256_cmp_pd(lanes.r, _mm256_set1_pd(rows.cutoff), _CMP_LT_OQ));
}

GENDPDE_AVX2 void densitiesAvx2(const RowGatherAvx2::Rows& rows, int begin, int end, double* density) {
    alignas(32) double weight[4];
    for (int s = begin; s < end; s++) {
        double n0 = 0.0;
        for (int m = rows.rowStart[s]; m < rows.rowStart[s + 1]; m += 4) {
            const int count = rows.rowStart[s + 1] - m < 4 ? rows.rowStart[s + 1] - m : 4;
            const Lanes lanes = pairLanes(rows, s, laneRows(rows.neighbors, m, count, s));
            // w(r), masked.
            const __m256d w = Lanes4::gendpdeDensityWeight(lanes.r, _mm256_set1_pd(rows.inverseCutoff),
                                                           _mm256_set1_pd(rows.valueScale));
            _mm256_store_pd(weight, _mm256_and_pd(inRangeMask(rows, lanes), w));
            for (int k = 0; k < count; k++)
                n0 += weight[k];
        }
        density[s] = n0;
    }
}

GENDPDE_AVX2 void forcesAvx2(const RowGatherAvx2::Rows& rows, const double* coefficient, int begin, int end,
                             Vec3* force, double* virial) {
    alignas(32) double fx[4], fy[4], fz[4], w[4];
    const __m256d inverseCutoff = _mm256_set1_pd(rows.inverseCutoff);
    const __m256d derivativeScale = _mm256_set1_pd(rows.derivativeScale);
    const double* coefficientBase = coefficient;
    for (int s = begin; s < end; s++) {
        Vec3 f = force[s];
        double sum = 0.0;
        const int upper = rows.upperStart[s];
        for (int m = rows.rowStart[s]; m < rows.rowStart[s + 1]; m += 4) {
            const int count = rows.rowStart[s + 1] - m < 4 ? rows.rowStart[s + 1] - m : 4;
            const __m128i neighbors = laneRows(rows.neighbors, m, count, s);
            const Lanes lanes = pairLanes(rows, s, neighbors);
            // scale = ((c_s + c_t) w'(r))/r where in range and r > 0, else 0 (the division by 1 there).
            const __m256d positive = _mm256_cmp_pd(lanes.r, _mm256_setzero_pd(), _CMP_GT_OQ);
            alignas(16) int t[4];
            _mm_store_si128(reinterpret_cast<__m128i*>(t), neighbors);
            const __m256d sumOfCoefficients =
                    _mm256_add_pd(_mm256_set1_pd(coefficient[s]),
                                  _mm256_set_pd(coefficientBase[t[3]], coefficientBase[t[2]], coefficientBase[t[1]],
                                                coefficientBase[t[0]]));
            const __m256d derivative = Lanes4::gendpdeDensityWeightDerivative(lanes.r, inverseCutoff, derivativeScale);
            const __m256d divisor = _mm256_blendv_pd(_mm256_set1_pd(1.0), lanes.r, positive);
            const __m256d scale = _mm256_and_pd(_mm256_and_pd(inRangeMask(rows, lanes), positive),
                                                Lanes4::gendpdePairForceScale(sumOfCoefficients, derivative, divisor));
            __m256d term[3];
            _mm256_store_pd(w, Lanes4::gendpdeCentralPairForce(scale, lanes.dx, lanes.dy, lanes.dz, lanes.r, term));
            _mm256_store_pd(fx, term[0]);
            _mm256_store_pd(fy, term[1]);
            _mm256_store_pd(fz, term[2]);
            for (int k = 0; k < count; k++) {
                f[0] += fx[k];
                f[1] += fy[k];
                f[2] += fz[k];
                if (m + k >= upper)
                    sum += w[k];
            }
        }
        force[s] = f;
        virial[s] = sum;
    }
}

bool detectEnabled() {
    const char* setting = std::getenv("GENDPDE_CPU_VECTOR");
    if (setting != nullptr && std::strcmp(setting, "0") == 0)
        return false;
    __builtin_cpu_init();
    return __builtin_cpu_supports("avx2");
}

} // namespace

bool RowGatherAvx2::enabled() {
    static const bool result = detectEnabled();
    return result;
}

void RowGatherAvx2::densities(const Rows& rows, int begin, int end, double* density) {
    densitiesAvx2(rows, begin, end, density);
}

void RowGatherAvx2::forces(const Rows& rows, const double* coefficient, int begin, int end, Vec3* force,
                           double* virial) {
    forcesAvx2(rows, coefficient, begin, end, force, virial);
}
