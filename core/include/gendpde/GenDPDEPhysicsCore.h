/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
#ifndef GENDPDE_PHYSICS_CORE_H_
#define GENDPDE_PHYSICS_CORE_H_

/* -------------------------------------------------------------------------- *
 * The physics core of GenDPDE (docs/theory.md sections 2-7): every formula   *
 * the platforms evaluate, written once in the common subset of C++ and of    *
 * OpenMM's Common kernel dialect (OpenCL C, CUDA): plain functions of        *
 * scalars, results through pointers, no std::, no references, no includes.   *
 * A platform kernel is loops and data movement around these functions.       *
 *                                                                            *
 * GenDPDEPhysics.h includes it for the host platforms (GENDPDE_REAL double,  *
 * inside namespace GenDPDEPlugin::Physics); the GPU platforms embed this     *
 * file in their device programs (CommonGenDPDEKernelSources::physicsCore:    *
 * GENDPDE_REAL real for the force, mixed for the integrator). The includer   *
 * defines GENDPDE_REAL, GENDPDE_ISFINITE(x), GENDPDE_FREXP(x, e), the V-B     *
 * table sizes                                                                *
 * GENDPDE_VB_FIRST_OCTAVE, GENDPDE_VB_LAST_OCTAVE, GENDPDE_VB_QUADRATURE_PAIRS *
 * (VolumeVBTables.h), and on the device GENDPDE_CORE (inline DEVICE) and     *
 * GENDPDE_GLOBAL (GLOBAL).                                                   *
 *                                                                            *
 * With GENDPDE_CORE_ARITHMETIC_ONLY defined, only the functions written with *
 * +, -, * and / alone are compiled (the density weight and its derivative,   *
 * the pair force scale, the central pair force), so that GENDPDE_REAL may be *
 * a vector type: the CPU platform's AVX2 gathers (RowGatherAvx2.cpp) include *
 * the core that way with __m256d, four pairs per call.                       *
 *                                                                            *
 * A new density estimator is a new constant below, a branch in               *
 * gendpdeParticleVolume (and gendpdeEstimatorNeedsMoments if it reads the    *
 * moments), its enum value in GenDPDEForce.h and its brute-force oracle in   *
 * tests/BruteForceGenDPDE.h: every platform then runs it.                    *
 * A new equation of state is a GENDPDE_EOS_* constant and a branch of        *
 * gendpdeLocalEquationOfState (gendpdeLawDependsOnTemperature and            *
 * gendpdeLawDensityLimit if they apply), its entry in the table of           *
 * GenDPDEEquationsOfState.h and its oracle in the tests.                     *
 * -------------------------------------------------------------------------- */

#ifndef GENDPDE_REAL
#error "GenDPDEPhysicsCore.h needs its precision GENDPDE_REAL: include GenDPDEPhysicsCoreDouble.h on the host"
#endif
#ifndef GENDPDE_CORE
#define GENDPDE_CORE inline
#endif
#ifndef GENDPDE_GLOBAL
#define GENDPDE_GLOBAL
#endif
/* The precision of the internal energies eps_i the integrator keeps (the device's "mixed"; the host's double). */
#ifndef GENDPDE_ENERGY
#define GENDPDE_ENERGY GENDPDE_REAL
#endif

/* The density estimators, as GenDPDEForce::DensityEstimator numbers them (GenDPDEPhysics.h checks that they agree). */
#define GENDPDE_ESTIMATOR_VA 0   /* traditional, V = 1/n0 */
#define GENDPDE_ESTIMATOR_VB 1   /* partition of unity */
#define GENDPDE_ESTIMATOR_VC 2   /* V-B with the surface correction of the first moment */

/* What gendpdeParticleState finds about a particle (every platform reports these with the same words). */
#define GENDPDE_PARTICLE_VALID 0
#define GENDPDE_PARTICLE_NO_NEIGHBOR 1   /* V-A and n0 = 0: the volume 1/n0 is undefined */
#define GENDPDE_PARTICLE_OVERFLOW 2      /* the equation of state is not finite at the particle's density */
#define GENDPDE_PARTICLE_OUTSIDE_DOMAIN 3 /* the density is outside the equation of state's domain (0 < n < 1/b) */
#define GENDPDE_PARTICLE_TEMPERATURE_JUMP                                                                              \
    4 /* one step's motion changed its temperature by more than a factor
                                               GENDPDE_STEP_TEMPERATURE_FACTOR (section 11): not integrated */
/* The number of statuses: the GPU platforms flag an invalid particle i as GENDPDE_PARTICLE_STATUSES i + status. */
#define GENDPDE_PARTICLE_STATUSES 8

/* The largest factor by which the conservative motion of one step may change a particle's temperature (section 11):
 * the drift of a stable run changes it by ~1% (0.6% in bulk liquid argon, 4% at a V-C slab's free surface, measured),
 * so a particle whose temperature doubles or halves in one step is no longer being integrated. Its logarithm: */
#define GENDPDE_STEP_TEMPERATURE_FACTOR 2
#define GENDPDE_LOG_STEP_TEMPERATURE_FACTOR 0.69314718055994531

/* ---- Weights (sections 2, 5; V-C's moment weight: docs/interfaces.md) ------------------------------------------- */

/** The density weight w(r) = valueScale (1 - r/R)^2 for r < R (the caller tests r < R), valueScale = 15/(2 pi R^3). */
GENDPDE_CORE GENDPDE_REAL gendpdeDensityWeight(GENDPDE_REAL r, GENDPDE_REAL inverseCutoff, GENDPDE_REAL valueScale) {
    const GENDPDE_REAL x = 1 - r * inverseCutoff;
    return valueScale * x * x;
}

/** w'(r) = derivativeScale (1 - r/R) for r < R, derivativeScale = -15/(pi R^4). */
GENDPDE_CORE GENDPDE_REAL gendpdeDensityWeightDerivative(GENDPDE_REAL r, GENDPDE_REAL inverseCutoff,
                                                         GENDPDE_REAL derivativeScale) {
    return derivativeScale * (1 - r * inverseCutoff);
}

#ifndef GENDPDE_CORE_ARITHMETIC_ONLY

/** The scales of w and w' for cutoff R: 15/(2 pi R^3) (1/length^3) and -15/(pi R^4) (1/length^4). */
GENDPDE_CORE void gendpdeDensityWeightScales(GENDPDE_REAL cutoff, GENDPDE_REAL* valueScale,
                                             GENDPDE_REAL* derivativeScale) {
    const GENDPDE_REAL pi = (GENDPDE_REAL) 3.14159265358979323846;
    *valueScale = 15 / (2 * pi * cutoff * cutoff * cutoff);
    *derivativeScale = -15 / (pi * cutoff * cutoff * cutoff * cutoff);
}

/**
 * V-C's moment weight over the distance, phi(r)/r = (1/R)(1 - r/R)^2 for r < R (1/length), with
 * phi(r) = (r/R)(1 - r/R)^2: the first moment of a neighbourhood is g_i = sum_j phi(r_ij) e_ij = sum_j (phi/r) d_ij.
 */
GENDPDE_CORE GENDPDE_REAL gendpdeMomentWeightOverDistance(GENDPDE_REAL r, GENDPDE_REAL inverseCutoff) {
    const GENDPDE_REAL y = 1 - r * inverseCutoff;
    return inverseCutoff * y * y;
}

/** phi'(r) = (1/R)(1 - r/R)(1 - 3 r/R) for r < R (1/length). */
GENDPDE_CORE GENDPDE_REAL gendpdeMomentWeightDerivative(GENDPDE_REAL r, GENDPDE_REAL inverseCutoff) {
    const GENDPDE_REAL x = r * inverseCutoff;
    return inverseCutoff * (1 - x) * (1 - 3 * x);
}

/** The weight of the random forces and heat flux, omega_R(r) = 1 - r/R for r < R (section 5). */
GENDPDE_CORE GENDPDE_REAL gendpdeRandomWeight(GENDPDE_REAL r, GENDPDE_REAL cutoff) {
    return 1 - r / cutoff;
}

/* ---- Volume estimators (section 3; V-C: section 3 and docs/interfaces.md) ---------------------------------------- */

/** Whether an estimator reads the first moments g_i of the neighbourhoods (V-C). */
GENDPDE_CORE int gendpdeEstimatorNeedsMoments(int estimator) {
    return estimator == GENDPDE_ESTIMATOR_VC;
}

/**
 * The constants of the estimators for cutoff R and reduced range Rt = R/f_cut, computed once per parameter set:
 * k = kPerDensity n0 with kPerDensity = (2 pi/15) Rt^3; V_B = volumeScale I(k) with volumeScale = 4 pi Rt^3 (length^3);
 * dV_B/dn0 = derivativeScale J(k) with derivativeScale = -(8 pi^2/15) Rt^6 (length^6); V-C's momentScale = c^2 with
 * c = 30/(pi R^3) and densitySoftening = eps^2 with eps = 3/(4 pi R^3) (both 1/length^6).
 */
GENDPDE_CORE void gendpdeEstimatorConstants(GENDPDE_REAL cutoff, GENDPDE_REAL reducedRange, GENDPDE_REAL* kPerDensity,
                                            GENDPDE_REAL* volumeScale, GENDPDE_REAL* derivativeScale,
                                            GENDPDE_REAL* momentScale, GENDPDE_REAL* densitySoftening) {
    const GENDPDE_REAL pi = (GENDPDE_REAL) 3.14159265358979323846;
    const GENDPDE_REAL rt3 = reducedRange * reducedRange * reducedRange, r3 = cutoff * cutoff * cutoff;
    *kPerDensity = (2 * pi / 15) * rt3;
    *volumeScale = 4 * pi * rt3;
    *derivativeScale = -(8 * pi * pi / 15) * rt3 * rt3;
    const GENDPDE_REAL c = 30 / (pi * r3), eps = 3 / (4 * pi * r3);
    *momentScale = c * c;
    *densitySoftening = eps * eps;
}

/**
 * The V-B integrals I(k), J(k) below the polynomial range, 0 < k < 1/16: the closed forms, with ln((k+1)/k) as
 * log1p(k) - log(k) so that no intermediate overflows for subnormal k.
 */
GENDPDE_CORE void gendpdeVolumeIntegralsClosedForm(GENDPDE_REAL k, GENDPDE_REAL* I, GENDPDE_REAL* J) {
    const GENDPDE_REAL s = sqrt(k);
    const GENDPDE_REAL arctangent = atan(1 / s);
    const GENDPDE_REAL logarithm = log1p(k) - log(k);
    *I = (GENDPDE_REAL) 1 / 3 - k - (1 - k) * s * arctangent + k * logarithm;
    *J = (GENDPDE_REAL) 1.5 - logarithm + (1 - 3 * k) / (2 * s) * arctangent;
}

/**
 * The V-B integrals above the polynomial range, k >= 16: Gauss-Legendre quadrature of the integrands in mirror pairs
 * of nodes y, 1 - y (squares nodeSquared, mirrorNodeSquared; one coefficient per pair; VolumeVBTables.h).
 */
GENDPDE_CORE void gendpdeVolumeIntegralsQuadrature(GENDPDE_REAL k, GENDPDE_GLOBAL const GENDPDE_REAL* nodeSquared,
                                                   GENDPDE_GLOBAL const GENDPDE_REAL* mirrorNodeSquared,
                                                   GENDPDE_GLOBAL const GENDPDE_REAL* coefficient, GENDPDE_REAL* I,
                                                   GENDPDE_REAL* J) {
    GENDPDE_REAL sumI = 0, sumJ = 0;
    for (int m = 0; m < GENDPDE_VB_QUADRATURE_PAIRS; m++) {
        const GENDPDE_REAL a = 1 / (nodeSquared[m] + k);
        const GENDPDE_REAL b = 1 / (mirrorNodeSquared[m] + k);
        sumI += coefficient[m] * (a + b);
        sumJ += coefficient[m] * (a * a + b * b);
    }
    *I = sumI;
    *J = sumJ;
}

/**
 * The two polynomials of degree 13 of one V-B piece at t, I's and J's, by Estrin's scheme (pairs with t, then t^2,
 * t^4, t^8: a dependency chain 4 steps deep instead of 13), in lockstep so that a compiler can run the two as the
 * lanes of one vector; c holds {c_p of I, c_p of J} for p = 0 ... 13.
 */
GENDPDE_CORE void gendpdeEstrin13Pair(GENDPDE_GLOBAL const GENDPDE_REAL* c, GENDPDE_REAL t, GENDPDE_REAL* I,
                                      GENDPDE_REAL* J) {
    const GENDPDE_REAL t2 = t * t, t4 = t2 * t2, t8 = t4 * t4;
    // Written out, I's and J's operations side by side: the pairs of adjacent coefficients are the two lanes.
    const GENDPDE_REAL aI0 = c[0] + c[2] * t, aJ0 = c[1] + c[3] * t;
    const GENDPDE_REAL aI1 = c[4] + c[6] * t, aJ1 = c[5] + c[7] * t;
    const GENDPDE_REAL aI2 = c[8] + c[10] * t, aJ2 = c[9] + c[11] * t;
    const GENDPDE_REAL aI3 = c[12] + c[14] * t, aJ3 = c[13] + c[15] * t;
    const GENDPDE_REAL aI4 = c[16] + c[18] * t, aJ4 = c[17] + c[19] * t;
    const GENDPDE_REAL aI5 = c[20] + c[22] * t, aJ5 = c[21] + c[23] * t;
    const GENDPDE_REAL aI6 = c[24] + c[26] * t, aJ6 = c[25] + c[27] * t;
    const GENDPDE_REAL bI0 = aI0 + aI1 * t2, bJ0 = aJ0 + aJ1 * t2;
    const GENDPDE_REAL bI1 = aI2 + aI3 * t2, bJ1 = aJ2 + aJ3 * t2;
    const GENDPDE_REAL bI2 = aI4 + aI5 * t2, bJ2 = aJ4 + aJ5 * t2;
    const GENDPDE_REAL dI = bI2 + aI6 * t4, dJ = bJ2 + aJ6 * t4;
    *I = (bI0 + bI1 * t4) + dI * t8;
    *J = (bJ0 + bJ1 * t4) + dJ * t8;
}

/**
 * The V-B integrals I(k) = int_0^1 y^2 (1-y)^2/(y^2 + k) dy and J(k) = -dI/dk at k > 0, each accurate to a few ulp
 * (checked against 40-digit quadrature in the tests), in three branches:
 *  - 1/16 <= k < 16, the range of liquids: piecewise polynomials of degree 13, 4 pieces per octave of k, generated
 *    at 60 digits (VolumeVBTables.h; polynomials[((octave - first) 4 + piece) 28 + 2 p + {0, 1}] is c_p of {I, J}).
 *    With k = m 2^octave, m in [1, 2), the top two bits of m pick the piece and t = 8 (m - 1) - (2 piece + 1) in
 *    [-1, 1) is exact: no division, no transcendental function.
 *  - k < 1/16: the closed forms (they lose digits to cancellation as k grows).
 *  - k >= 16: 24-point Gauss-Legendre quadrature of the positive integrands (no cancellation).
 * At k = 0 (an isolated particle) I = 1/3 and J diverges; callers handle it (gendpdeParticleVolume).
 */
GENDPDE_CORE void gendpdeVolumeIntegralsVB(GENDPDE_REAL k, GENDPDE_GLOBAL const GENDPDE_REAL* polynomials,
                                           GENDPDE_GLOBAL const GENDPDE_REAL* nodeSquared,
                                           GENDPDE_GLOBAL const GENDPDE_REAL* mirrorNodeSquared,
                                           GENDPDE_GLOBAL const GENDPDE_REAL* quadratureCoefficient, GENDPDE_REAL* I,
                                           GENDPDE_REAL* J) {
    int exponent;
    const GENDPDE_REAL fraction = GENDPDE_FREXP(k, &exponent); // k = fraction 2^exponent, fraction in [1/2, 1)
    const int octave = exponent - 1;
    if (octave >= GENDPDE_VB_FIRST_OCTAVE && octave <= GENDPDE_VB_LAST_OCTAVE) {
        const GENDPDE_REAL m = 2 * fraction;
        const int piece = (int) ((m - 1) * 4);
        const GENDPDE_REAL t = 8 * (m - 1) - (2 * piece + 1);
        gendpdeEstrin13Pair(polynomials + ((octave - GENDPDE_VB_FIRST_OCTAVE) * 4 + piece) * 28, t, I, J);
    } else if (k < 1)
        gendpdeVolumeIntegralsClosedForm(k, I, J);
    else
        gendpdeVolumeIntegralsQuadrature(k, nodeSquared, mirrorNodeSquared, quadratureCoefficient, I, J);
}

/**
 * The surface factor of V-C (docs/interfaces.md): V = V_B (1 + alpha x^2/(1 + x^2)) with x = max(0, a^2 - t)/w,
 * alpha = 3, threshold t = 0.4, width w = 0.3, where a^2 measures how one-sided a particle's neighbourhood is
 * (1 at a flat free surface). *factor receives 1 + alpha x^2/(1 + x^2), *slope its derivative with respect to a^2
 * (both continuous at the threshold, where the factor is 1 and its slope 0).
 */
GENDPDE_CORE void gendpdeSurfaceFactor(GENDPDE_REAL a2, GENDPDE_REAL* factor, GENDPDE_REAL* slope) {
    const GENDPDE_REAL alpha = 3, threshold = (GENDPDE_REAL) 0.4, inverseWidth = 1 / (GENDPDE_REAL) 0.3;
    if (!(a2 > threshold)) {
        *factor = 1;
        *slope = 0;
        return;
    }
    const GENDPDE_REAL x = (a2 - threshold) * inverseWidth, denominator = 1 / (1 + x * x);
    *factor = 1 + alpha * x * x * denominator;
    *slope = alpha * 2 * x * denominator * denominator * inverseWidth;
}

/**
 * A particle's volume V (length^3) and its derivatives dV/dn0 at fixed G (length^6) and dV/dG at fixed n0 (length^3,
 * zero unless the estimator reads the moments), from its primitive density n0 >= 0 and, for V-C, the squared first
 * moment G = |g|^2 of its neighbourhood (dimensionless; ignored by the others), with the constants of
 * gendpdeEstimatorConstants and the V-B tables (gendpdeVolumeIntegralsVB):
 *  - V-A: V = 1/n0, dV/dn0 = -1/n0^2. Returns GENDPDE_PARTICLE_NO_NEIGHBOR at n0 = 0 (then V is infinite).
 *  - V-B: V = volumeScale I(k), dV/dn0 = derivativeScale J(k), k = kPerDensity n0; at n0 = 0 (no neighbour in range)
 *    V = volumeScale/3 exactly and dV/dn0, which diverges like n0^(-1/2), is returned as 0: it only ever multiplies
 *    w' of a pair in range, and a particle with such a pair has n0 > 0.
 *  - V-C: V = V_B (1 + alpha x^2/(1 + x^2)) (gendpdeSurfaceFactor) of a^2 = c^2 G/(n0^2 + eps^2), so
 *    dV/dn0 = V_B' factor - V_B slope 2 a^2 n0/(n0^2 + eps^2) and dV/dG = V_B slope c^2/(n0^2 + eps^2).
 * Returns GENDPDE_PARTICLE_VALID otherwise.
 */
GENDPDE_CORE int gendpdeParticleVolume(int estimator, GENDPDE_REAL n0, GENDPDE_REAL G, GENDPDE_REAL kPerDensity,
                                       GENDPDE_REAL volumeScale, GENDPDE_REAL derivativeScale, GENDPDE_REAL momentScale,
                                       GENDPDE_REAL densitySoftening, GENDPDE_GLOBAL const GENDPDE_REAL* polynomials,
                                       GENDPDE_GLOBAL const GENDPDE_REAL* nodeSquared,
                                       GENDPDE_GLOBAL const GENDPDE_REAL* mirrorNodeSquared,
                                       GENDPDE_GLOBAL const GENDPDE_REAL* quadratureCoefficient, GENDPDE_REAL* volume,
                                       GENDPDE_REAL* derivative, GENDPDE_REAL* momentDerivative) {
    *momentDerivative = 0;
    if (estimator == GENDPDE_ESTIMATOR_VA) {
        const GENDPDE_REAL v = 1 / n0;
        *volume = v;
        *derivative = -v * v;
        return n0 == 0 ? GENDPDE_PARTICLE_NO_NEIGHBOR : GENDPDE_PARTICLE_VALID;
    }
    if (n0 == 0) {
        *volume = volumeScale * ((GENDPDE_REAL) 1 / 3);
        *derivative = 0;
    } else {
        GENDPDE_REAL I, J;
        gendpdeVolumeIntegralsVB(kPerDensity * n0, polynomials, nodeSquared, mirrorNodeSquared, quadratureCoefficient,
                                 &I, &J);
        *volume = volumeScale * I;
        *derivative = derivativeScale * J;
    }
    if (estimator == GENDPDE_ESTIMATOR_VC) {
        const GENDPDE_REAL inverse = 1 / (n0 * n0 + densitySoftening);
        const GENDPDE_REAL a2 = momentScale * G * inverse;
        GENDPDE_REAL factor, slope; // the factor and its derivative with respect to a^2
        gendpdeSurfaceFactor(a2, &factor, &slope);
        if (slope != 0) {
            const GENDPDE_REAL v = *volume;
            *derivative = *derivative * factor - v * slope * 2 * a2 * n0 * inverse;
            *momentDerivative = v * slope * momentScale * inverse;
            *volume = v * factor;
        }
    }
    return GENDPDE_PARTICLE_VALID;
}

/* ---- Equation of state and the particle's state (section 4) ----------------------------------------------------- */

/** x^p for an integer p >= 0, by binary powering (exact to a few ulp, several times cheaper than pow). */
GENDPDE_CORE GENDPDE_REAL gendpdeIntegerPower(GENDPDE_REAL x, int p) {
    GENDPDE_REAL result = 1;
    while (p > 0) {
        if (p & 1)
            result *= x;
        x *= x;
        p >>= 1;
    }
    return result;
}

/** The integerPower of gendpdeTait for exponent gamma_T: gamma_T - 1 when gamma_T is an integer in [2, 33], else -1. */
GENDPDE_CORE int gendpdeTaitIntegerPower(GENDPDE_REAL exponent) {
    return (exponent == floor(exponent) && exponent >= 2 && exponent <= 33) ? (int) exponent - 1 : -1;
}

/**
 * The Tait equation of state and the free energy per particle at density n (section 4):
 *   pi(n) = pi0 + B_T [ (n/n0)^gamma_T - 1 ],   f(n) = (B_T - pi0)/n + B_T/((gamma_T - 1) n0) (n/n0)^(gamma_T - 1).
 * integerPower is gamma_T - 1 when gamma_T is an integer in [2, 33] (then by multiplications), else -1 (pow).
 */
GENDPDE_CORE void gendpdeTait(GENDPDE_REAL density, GENDPDE_REAL referenceDensity, GENDPDE_REAL referencePressure,
                              GENDPDE_REAL bulkModulus, GENDPDE_REAL exponent, int integerPower, GENDPDE_REAL* pressure,
                              GENDPDE_REAL* freeEnergy) {
    const GENDPDE_REAL x = density / referenceDensity;
    const GENDPDE_REAL xPowGammaMinusOne =
            (integerPower >= 0 ? gendpdeIntegerPower(x, integerPower) : pow(x, exponent - 1));
    *pressure = referencePressure + bulkModulus * (xPowGammaMinusOne * x - 1);
    *freeEnergy = (bulkModulus - referencePressure) / density
            + bulkModulus / ((exponent - 1) * referenceDensity) * xPowGammaMinusOne;
}

/* ---- Temperature-dependent equations of state (section 11) ----------------------------------------------------- */

/* The local equations of state of the form f(theta, n) = e(n) - theta sigma(n) + C theta (1 - ln(theta/theta0)). */
#define GENDPDE_EOS_TAIT 0 /* sigma = 0: today's Tait law, pi(n) */
#define GENDPDE_EOS_TAIT_THERMAL 1 /* pi = pi_Tait(n) + beta (theta - theta0) */
#define GENDPDE_EOS_VAN_DER_WAALS 2 /* pi = k theta n/(1 - b n) - a n^2 */

/**
 * The density-dependent parts of a free energy per particle
 *   f(theta, n) = e(n) - theta sigma(n) + C theta (1 - ln(theta/theta0))
 * whose heat capacity C (energy/temperature, per particle) does not depend on theta or n (section 11). Then
 *   u = e(n) + C theta,   s = sigma(n) + C ln(theta/theta0),   pi = n^2 df/dn = pressureAtZero + theta thermalPressure,
 * with pressureAtZero = n^2 e'(n) and thermalPressure = -n^2 sigma'(n) = (dpi/dtheta) at fixed n (pressure/
 * temperature). Results through pointers: e (energy), sigma (energy/temperature, up to a constant), pressureAtZero,
 * thermalPressure. The parameters p[] by law (pressure energy/length^3, density 1/length^3), in the order that
 * GenDPDEEquationsOfState.h packs them (a law that extends Tait: n0, pi0, B_T, gamma_T, then its own; any other: its
 * own, then p_b):
 *   GENDPDE_EOS_TAIT:          p0..p3 = n0, pi0, B_T, gamma_T (gendpdeTait); e = f_Tait, sigma = 0;
 *   GENDPDE_EOS_TAIT_THERMAL:  p0..p5 = n0, pi0, B_T, gamma_T, beta, theta0; e = f_Tait(n) + beta theta0/n,
 *                              sigma = beta/n, so pi = pi_Tait(n) + beta (theta - theta0) and alpha = kappa_T0 beta at
 *                              (n0, theta0);
 *   GENDPDE_EOS_VAN_DER_WAALS: p0..p3 = a (energy length^3), b (length^3), k (energy/temperature), p_b (the
 *                              background pressure, energy/length^3); e = -a n - p_b/n, sigma = k ln(1/(b n) - 1),
 *                              defined for 0 < n < 1/b.
 * (The Tait laws take the background pressure p_b in pi0: pi0 + p_b adds p_b to pi and -p_b/n to e.)
 * integerPower as for gendpdeTait (Tait laws only). Returns GENDPDE_PARTICLE_VALID, GENDPDE_PARTICLE_OUTSIDE_DOMAIN
 * (van der Waals: n <= 0 or b n >= 1) or GENDPDE_PARTICLE_OVERFLOW (a result not finite).
 */
GENDPDE_CORE int gendpdeLocalEquationOfState(int law, GENDPDE_REAL density, GENDPDE_GLOBAL const GENDPDE_REAL* p,
                                             int integerPower, GENDPDE_REAL* energy, GENDPDE_REAL* entropy,
                                             GENDPDE_REAL* pressureAtZero, GENDPDE_REAL* thermalPressure) {
    if (law == GENDPDE_EOS_VAN_DER_WAALS) {
        const GENDPDE_REAL excluded = p[1] * density;
        if (!(density > 0 && excluded < 1)) {
            *energy = *entropy = *pressureAtZero = *thermalPressure = 0;
            return GENDPDE_PARTICLE_OUTSIDE_DOMAIN;
        }
        *energy = -p[0] * density - p[3] / density;
        *entropy = p[2] * log((1 - excluded) / excluded);
        *pressureAtZero = -p[0] * density * density + p[3];
        *thermalPressure = p[2] * density / (1 - excluded);
    } else {
        gendpdeTait(density, p[0], p[1], p[2], p[3], integerPower, pressureAtZero, energy);
        if (law == GENDPDE_EOS_TAIT_THERMAL) {
            *energy += p[4] * p[5] / density;
            *pressureAtZero -= p[4] * p[5];
            *entropy = p[4] / density;
            *thermalPressure = p[4];
        } else
            *entropy = *thermalPressure = 0;
    }
    if (!(GENDPDE_ISFINITE(*energy) && GENDPDE_ISFINITE(*entropy) && GENDPDE_ISFINITE(*pressureAtZero)
          && GENDPDE_ISFINITE(*thermalPressure)))
        return GENDPDE_PARTICLE_OVERFLOW;
    return GENDPDE_PARTICLE_VALID;
}

/** Whether a law depends on temperature (sigma or pi_theta not identically 0): its particles have a thermal state. */
GENDPDE_CORE int gendpdeLawDependsOnTemperature(int law) {
    return law != GENDPDE_EOS_TAIT;
}

/** The largest density of a law's domain (GENDPDE_PARTICLE_OUTSIDE_DOMAIN beyond it), or 0 if it has none. */
GENDPDE_CORE GENDPDE_REAL gendpdeLawDensityLimit(int law, GENDPDE_GLOBAL const GENDPDE_REAL* p) {
    return law == GENDPDE_EOS_VAN_DER_WAALS ? 1 / p[1] : 0;
}

/**
 * The thermal energy C theta a particle has after a change of its density at fixed entropy (section 11): with
 * s = sigma(n) + C ln(theta/theta0) fixed, C theta' = C theta exp(-(sigma(n') - sigma(n))/C). thermalEnergy is
 * C theta (energy), entropyChange sigma(n') - sigma(n) (energy/temperature), heatCapacity C. Exact for any change.
 */
GENDPDE_CORE GENDPDE_REAL gendpdeIsentropicThermalEnergy(GENDPDE_REAL thermalEnergy, GENDPDE_REAL entropyChange,
                                                         GENDPDE_REAL heatCapacity) {
    return thermalEnergy * exp(-entropyChange / heatCapacity);
}

/**
 * Everything a particle contributes to the force, whatever its law (sections 4 and 11): from its primitive density
 * n0, squared moment G (V-C), the estimator's constants and tables (gendpdeParticleVolume), its type's law and
 * parameters p[] (gendpdeLocalEquationOfState) and, for a law that depends on temperature
 * (gendpdeLawDependsOnTemperature), its thermal state: its volume V, pressure pi (energy/length^3), its term of U
 * (*energy), the force coefficient pi dV/dn0 (energy length^3; 0 for an isolated particle, which has no pair to use
 * it) and V-C's moment force scale 2 pi dV/dG (energy; q_i = momentForceScale g_i enters the pair forces,
 * gendpdeMomentPairForce).
 *  - A law that does not depend on temperature (Tait): pi = pressureAtZero, the particle contributes e(n) to U, its
 *    thermal state is not read, and *thermalEnergy receives storedEnergy as it is (0 where there is none).
 *  - isothermal != 0 (the Isothermal mode): theta = temperature; the particle contributes f(T, n) up to a constant,
 *    e(n) - T sigma(n), to U, and *thermalEnergy receives C T;
 *  - otherwise the particle's entropy is fixed between the integrator's updates of its thermal state: it had the
 *    thermal energy storedEnergy = C theta at a density where sigma was storedEntropy, so now
 *    C theta = storedEnergy gendpdeIsentropicThermalEnergy(1, sigma(n) - storedEntropy, C) (*thermalEnergy, in the
 *    precision of the stored energies, GENDPDE_ENERGY, so that keeping it loses nothing and an unmoved particle keeps
 *    its bits), and it contributes e(n) + (C theta - storedEnergy) to U: K + U + sum_i storedEnergy_i is then
 *    K + sum_i u_i(s_i, n_i), whose gradient at fixed entropies is the force. entropyKnown = 0 (the positions or
 *    energies were just set) takes storedEntropy = sigma(n): theta = storedEnergy/C. With checkStep != 0 (an
 *    evaluation of a step, storedEntropy of the previous step's positions) a change of theta by more than a factor
 *    GENDPDE_STEP_TEMPERATURE_FACTOR, |sigma(n) - storedEntropy| > C ln 2, is GENDPDE_PARTICLE_TEMPERATURE_JUMP.
 * A law that depends on temperature has pi = pressureAtZero + theta thermalPressure. *densityEntropy receives sigma(n)
 * (energy/temperature; 0 for a law that does not depend on temperature). Returns GENDPDE_PARTICLE_VALID or why the
 * state is invalid (GENDPDE_PARTICLE_NO_NEIGHBOR, _OUTSIDE_DOMAIN, _OVERFLOW, _TEMPERATURE_JUMP): then the evaluation
 * must stop and say so.
 */
GENDPDE_CORE int gendpdeParticleState(int estimator, GENDPDE_REAL n0, GENDPDE_REAL G, GENDPDE_REAL kPerDensity,
                                      GENDPDE_REAL volumeScale, GENDPDE_REAL derivativeScale, GENDPDE_REAL momentScale,
                                      GENDPDE_REAL densitySoftening, GENDPDE_GLOBAL const GENDPDE_REAL* polynomials,
                                      GENDPDE_GLOBAL const GENDPDE_REAL* nodeSquared,
                                      GENDPDE_GLOBAL const GENDPDE_REAL* mirrorNodeSquared,
                                      GENDPDE_GLOBAL const GENDPDE_REAL* quadratureCoefficient, int law,
                                      GENDPDE_GLOBAL const GENDPDE_REAL* p, int integerPower, int isothermal,
                                      GENDPDE_REAL temperature, GENDPDE_ENERGY storedEnergy, GENDPDE_REAL storedEntropy,
                                      int entropyKnown, int checkStep, GENDPDE_REAL heatCapacity, GENDPDE_REAL* volume,
                                      GENDPDE_REAL* pressure, GENDPDE_REAL* energy, GENDPDE_REAL* forceCoefficient,
                                      GENDPDE_REAL* momentForceScale, GENDPDE_ENERGY* thermalEnergy,
                                      GENDPDE_REAL* densityEntropy) {
    GENDPDE_REAL derivative, momentDerivative;
    int status = gendpdeParticleVolume(estimator, n0, G, kPerDensity, volumeScale, derivativeScale, momentScale,
                                       densitySoftening, polynomials, nodeSquared, mirrorNodeSquared,
                                       quadratureCoefficient, volume, &derivative, &momentDerivative);
    GENDPDE_REAL e, sigma, pressureAtZero, thermalPressure;
    const int lawStatus = gendpdeLocalEquationOfState(law, 1 / (*volume), p, integerPower, &e, &sigma, &pressureAtZero,
                                                      &thermalPressure);
    if (status == GENDPDE_PARTICLE_VALID)
        status = lawStatus;
    const int thermal = gendpdeLawDependsOnTemperature(law);
    GENDPDE_REAL theta = 0;
    if (!thermal) {
        *thermalEnergy = storedEnergy;
        *energy = e;
    } else if (isothermal) {
        theta = temperature;
        *thermalEnergy = heatCapacity * temperature;
        *energy = e - temperature * sigma;
    } else {
        const GENDPDE_REAL entropyChange = entropyKnown ? sigma - storedEntropy : 0;
        if (checkStep && status == GENDPDE_PARTICLE_VALID
            && !(fabs(entropyChange) <= GENDPDE_LOG_STEP_TEMPERATURE_FACTOR * heatCapacity))
            status = GENDPDE_PARTICLE_TEMPERATURE_JUMP;
        *thermalEnergy = storedEnergy * gendpdeIsentropicThermalEnergy(1, entropyChange, heatCapacity);
        theta = (GENDPDE_REAL) (*thermalEnergy / heatCapacity);
        *energy = e + (GENDPDE_REAL) (*thermalEnergy - storedEnergy);
    }
    *densityEntropy = sigma;
    *pressure = (thermal ? pressureAtZero + theta * thermalPressure : pressureAtZero);
    if (thermal && status == GENDPDE_PARTICLE_VALID
        && !(GENDPDE_ISFINITE(*energy) && GENDPDE_ISFINITE(*pressure) && GENDPDE_ISFINITE(*thermalEnergy)))
        status = GENDPDE_PARTICLE_OVERFLOW;
    *forceCoefficient = (n0 > 0 ? (*pressure) * derivative : 0);
    *momentForceScale = 2 * ((*pressure) * momentDerivative);
    return status;
}

#endif /* GENDPDE_CORE_ARITHMETIC_ONLY */

/* ---- Pair forces and virials (section 4) ------------------------------------------------------------------------ */

/**
 * The scale s of the central pair force F_ij = s d_ij (d_ij = r_i - r_j, r = |d_ij| > 0): s = (c_i + c_j) w'(r)/r
 * (1/length: energy/length^2 over length), with coefficientSum = c_i + c_j the particles' force coefficients
 * pi dV/dn0 (energy length^3) and weightDerivative = w'(r) (1/length^4).
 */
GENDPDE_CORE GENDPDE_REAL gendpdePairForceScale(GENDPDE_REAL coefficientSum, GENDPDE_REAL weightDerivative,
                                                GENDPDE_REAL r) {
    return coefficientSum * weightDerivative / r;
}

/**
 * The central pair force F = s d for the scale s of gendpdePairForceScale and d = r_i - r_j (length) of length r:
 * stores F in force[0..2] (energy/length) and returns its virial d . F = s r^2 (energy).
 */
GENDPDE_CORE GENDPDE_REAL gendpdeCentralPairForce(GENDPDE_REAL scale, GENDPDE_REAL dx, GENDPDE_REAL dy, GENDPDE_REAL dz,
                                                  GENDPDE_REAL r, GENDPDE_REAL* force) {
    force[0] = dx * scale;
    force[1] = dy * scale;
    force[2] = dz * scale;
    return scale * r * r;
}

#ifndef GENDPDE_CORE_ARITHMETIC_ONLY

/**
 * V-C's pair force from the moments: H(d) (q_i - q_j) with H = phi'(r) e e^T + (phi(r)/r)(I - e e^T), the gradient of
 * the pair's moment term phi(r) e with respect to d = r_i - r_j, e = d/r the unit vector (ex, ey, ez), r < R, and
 * dq = q_i - q_j (energy). Stores it in force[0..2] (energy/length) and returns its virial d . H dq = r phi' (e . dq).
 */
GENDPDE_CORE GENDPDE_REAL gendpdeMomentPairForce(GENDPDE_REAL ex, GENDPDE_REAL ey, GENDPDE_REAL ez, GENDPDE_REAL r,
                                                 GENDPDE_REAL inverseCutoff, GENDPDE_REAL dqx, GENDPDE_REAL dqy,
                                                 GENDPDE_REAL dqz, GENDPDE_REAL* force) {
    const GENDPDE_REAL along = ex * dqx + ey * dqy + ez * dqz;
    const GENDPDE_REAL phiPrime = gendpdeMomentWeightDerivative(r, inverseCutoff);
    const GENDPDE_REAL phiOverR = gendpdeMomentWeightOverDistance(r, inverseCutoff);
    const GENDPDE_REAL alongScale = phiPrime * along;
    force[0] = ex * alongScale + (dqx - ex * along) * phiOverR;
    force[1] = ey * alongScale + (dqy - ey * along) * phiOverR;
    force[2] = ez * alongScale + (dqz - ez * along) * phiOverR;
    return r * phiPrime * along;
}

/**
 * The force on i from j of a pair closer than the cutoff (section 4), as every platform computes it: the central
 * force (gendpdeCentralPairForce) of scale (c_i + c_j) w'(r)/r, plus V-C's moment force H(d) (q_i - q_j)
 * (gendpdeMomentPairForce) where moments != 0 and q_i or q_j is not zero (q vanishes for the particles below V-C's
 * threshold, nearly all of a bulk liquid: their pairs skip it). d = r_i - r_j (length) of length r > 0,
 * coefficientSum = c_i + c_j the force coefficients pi dV/dn0 (energy length^3), weightDerivative = w'(r)
 * (1/length^4; gendpdeDensityWeightDerivative, or 0 for a pair the caller counts as out of range), q_i, q_j the
 * moment forces q = 2 pi (dV/dG) g (energy; read only if moments != 0). Stores F in force[0..2] (energy/length) and
 * returns its virial d . F (energy).
 */
GENDPDE_CORE GENDPDE_REAL gendpdePairForce(GENDPDE_REAL dx, GENDPDE_REAL dy, GENDPDE_REAL dz, GENDPDE_REAL r,
                                           GENDPDE_REAL coefficientSum, GENDPDE_REAL weightDerivative,
                                           GENDPDE_REAL inverseCutoff, int moments, GENDPDE_REAL qix, GENDPDE_REAL qiy,
                                           GENDPDE_REAL qiz, GENDPDE_REAL qjx, GENDPDE_REAL qjy, GENDPDE_REAL qjz,
                                           GENDPDE_REAL* force) {
    GENDPDE_REAL virial =
            gendpdeCentralPairForce(gendpdePairForceScale(coefficientSum, weightDerivative, r), dx, dy, dz, r, force);
    if (moments && !(qix == 0 && qiy == 0 && qiz == 0 && qjx == 0 && qjy == 0 && qjz == 0)) {
        const GENDPDE_REAL inverseDistance = 1 / r;
        GENDPDE_REAL momentForce[3];
        virial += gendpdeMomentPairForce(dx * inverseDistance, dy * inverseDistance, dz * inverseDistance, r,
                                         inverseCutoff, qix - qjx, qiy - qjy, qiz - qjz, momentForce);
        force[0] += momentForce[0];
        force[1] += momentForce[1];
        force[2] += momentForce[2];
    }
    return virial;
}

/**
 * Each particle's virial tensor gets half of each of its pairs': virial[3a + b] += (F_a/2) d_b for the pair force F
 * on i and d = r_i - r_j (energy). The two halves are equal (F and d both change sign), so the particles' tensors
 * add up to the system's W_ab = sum over pairs of F_a d_b = -dU/d(strain_ab).
 */
GENDPDE_CORE void gendpdeAddHalfPairVirial(GENDPDE_REAL fx, GENDPDE_REAL fy, GENDPDE_REAL fz, GENDPDE_REAL dx,
                                           GENDPDE_REAL dy, GENDPDE_REAL dz, GENDPDE_REAL* virial) {
    const GENDPDE_REAL hx = fx / 2, hy = fy / 2, hz = fz / 2;
    virial[0] += hx * dx;
    virial[1] += hx * dy;
    virial[2] += hx * dz;
    virial[3] += hy * dx;
    virial[4] += hy * dy;
    virial[5] += hy * dz;
    virial[6] += hz * dx;
    virial[7] += hz * dy;
    virial[8] += hz * dz;
}

/* ---- The background pressure's box term (section 12) ------------------------------------------------------------ */

/** The box term of the energy, p_b V_box (energy), of a background pressure p_b in a periodic box of volume V_box. */
GENDPDE_CORE GENDPDE_REAL gendpdeBackgroundEnergy(GENDPDE_REAL backgroundPressure, GENDPDE_REAL boxVolume) {
    return backgroundPressure * boxVolume;
}

/**
 * The box term's virial, the trace W_xx + W_yy + W_zz = -3 p_b V_box (energy) of -dU/d(strain): each diagonal element
 * is a third of it, the off-diagonal ones zero. (Engines share it equally among the particles.)
 */
GENDPDE_CORE GENDPDE_REAL gendpdeBackgroundVirial(GENDPDE_REAL backgroundPressure, GENDPDE_REAL boxVolume) {
    return -3 * backgroundPressure * boxVolume;
}

/* ---- The integrator's pair updates (sections 5-7) --------------------------------------------------------------- */

/**
 * What a pair update needs from the internal energies eps_i, eps_j and heat capacities C_i, C_j (sections 5 and 7),
 * with beta = 1/theta = C/eps: k_B Theta_ij with 1/Theta_ij = (beta_i + beta_j)/2, beta_i - beta_j, and the Ito
 * factor of the friction k_B (beta_i^2/C_i + beta_j^2/C_j)/(beta_i + beta_j)^2 = k_B (beta_i/eps_i + beta_j/eps_j)
 * /(beta_i + beta_j)^2. beta = 1/theta stays within the range of the temperatures, so no intermediate overflows for
 * any allowed eps and C_V.
 *
 * Why the Ito factor (derivation: docs/theory.md section 7): Theta_ij depends on eps_i and eps_j, which every random
 * kick changes (mechanical heating), so the noise of the momentum equation is multiplicative. Its equilibrium, the
 * microcanonical density prod_i eps_i^(C_i/k_B) on the energy shell (from which T_kin = <1/theta>^-1 and the Gamma
 * law of eps_i follow), is stationary only if the noise is read post-point (Haenggi-Klimontovich); a pair update
 * draws the noise with the temperatures it starts from (Ito), which needs the drift (1/2) d(b^2)/du, b^2 the variance
 * rate of the relative velocity u. Worked out, that drift is the factor above (k_B/(2 C_V) for equal temperatures):
 * the update uses gamma (1 + frictionFactor) with sigma^2 = 2 gamma k_B Theta_ij. Without it the kinetic temperature
 * exceeds the harmonic-mean temperature by k_B/(2 C_V): 4.0% for liquid argon's C_V = 12.51 k_B, as measured
 * (python/tests/test_integrator_physics.py). In the isothermal limit C_V -> infinity it vanishes.
 */
GENDPDE_CORE void gendpdePairTemperatures(GENDPDE_REAL energyI, GENDPDE_REAL energyJ, GENDPDE_REAL heatCapacityI,
                                          GENDPDE_REAL heatCapacityJ, GENDPDE_REAL boltzmann,
                                          GENDPDE_REAL* pairThermalEnergy, GENDPDE_REAL* inverseTemperatureDifference,
                                          GENDPDE_REAL* frictionFactor) {
    const GENDPDE_REAL betaI = heatCapacityI / energyI, betaJ = heatCapacityJ / energyJ;
    const GENDPDE_REAL inverseSum = 1 / (betaI + betaJ);
    *pairThermalEnergy = 2 * boltzmann * inverseSum;
    *inverseTemperatureDifference = betaI - betaJ;
    *frictionFactor = boltzmann * (betaI / energyI + betaJ / energyJ) * inverseSum * inverseSum;
}

/**
 * The dissipative and random impulse P of one pair along e (section 6), in two stages: an explicit half (half the
 * friction, half the random impulse) and an implicit half solved exactly for the final relative velocity (a
 * Crank-Nicolson step of u = e.(v_i - v_j), whose stationary variance stays exact for any dt). u0 is u before the
 * update, inverseReducedMass 1/m_i + 1/m_j, friction the coefficient of the drift -friction omega_R^2 u,
 * noiseAmplitude the sigma of the random impulse sigma omega_R dW, xi a standard normal variate. P e goes to i and
 * -P e to j; *kineticChange receives the change of the pair's kinetic energy, P (u0 + P (1/m_i + 1/m_j)/2).
 */
GENDPDE_CORE GENDPDE_REAL gendpdePairImpulse(GENDPDE_REAL u0, GENDPDE_REAL omegaR, GENDPDE_REAL friction,
                                             GENDPDE_REAL noiseAmplitude, GENDPDE_REAL stepSize,
                                             GENDPDE_REAL sqrtStepSize, GENDPDE_REAL inverseReducedMass,
                                             GENDPDE_REAL xi, GENDPDE_REAL* kineticChange) {
    const GENDPDE_REAL frictionHalf = (GENDPDE_REAL) 0.5 * friction * omegaR * omegaR * stepSize;
    const GENDPDE_REAL implicitFactor = 1 / (1 + inverseReducedMass * frictionHalf);
    const GENDPDE_REAL randomHalf = (GENDPDE_REAL) 0.5 * noiseAmplitude * omegaR * sqrtStepSize * xi;
    const GENDPDE_REAL explicitHalf = randomHalf - frictionHalf * u0;
    const GENDPDE_REAL u1 = u0 + inverseReducedMass * explicitHalf;
    const GENDPDE_REAL implicitHalf = (randomHalf - frictionHalf * u1) * implicitFactor;
    const GENDPDE_REAL impulse = explicitHalf + implicitHalf;
    *kineticChange = impulse * (u0 + (GENDPDE_REAL) 0.5 * inverseReducedMass * impulse);
    return impulse;
}

/**
 * The heat that flows from j to i in one step (section 5): kappa omega_q (1/theta_i - 1/theta_j) dt
 * + alpha omega_R sqrt(dt) xi_q, with omega_q = omega_R^2 and randomAmplitude alpha = sqrt(2 k_B kappa).
 */
GENDPDE_CORE GENDPDE_REAL gendpdeConductiveHeat(GENDPDE_REAL omegaR, GENDPDE_REAL heatConduction,
                                                GENDPDE_REAL randomAmplitude, GENDPDE_REAL inverseTemperatureDifference,
                                                GENDPDE_REAL stepSize, GENDPDE_REAL sqrtStepSize, GENDPDE_REAL xiQ) {
    return heatConduction * omegaR * omegaR * inverseTemperatureDifference * stepSize
            + randomAmplitude * omegaR * sqrtStepSize * xiQ;
}

/**
 * One pair update of the sweep with internal energies (sections 5-7), at the temperatures theta = eps/C the two
 * particles have when the pair is reached, as every platform performs it:
 *  - dissipation != 0: the impulse of gendpdePairImpulse with the friction gamma (1 + the Ito factor) and the noise
 *    sigma = sqrt(2 gamma k_B Theta_ij); the change of the pair's kinetic energy is taken from the two internal
 *    energies in equal halves;
 *  - conduction != 0: then the heat of gendpdeConductiveHeat flows from j to i.
 * pairThermalEnergy, inverseTemperatureDifference and frictionFactor are gendpdePairTemperatures of the internal
 * energies *energyI, *energyJ before the update (the caller computes them first: their divisions then run while it
 * draws the random variates). u0 = e . (v_i - v_j) before the update (length/time; e the unit vector from j to i),
 * omegaR = omega_R(r), inverseMassI, inverseMassJ (1/mass), friction gamma (mass/time) and heatConduction kappa
 * (energy temperature/time) of the pair's classes, heatNoise alpha = sqrt(2 k_B kappa), xi and xiQ standard normal
 * variates of the impulse and of the heat (each read only where its term runs; a pair's random stream gives xi
 * first). *energyI, *energyJ hold eps_i, eps_j (energy) and receive their new values; *impulse receives P (mass
 * length/time; 0 without dissipation): the caller adds P e/m_i to v_i and -P e/m_j to v_j. Returns nonzero if an
 * internal energy is now <= 0 (or not a number): the sweep stops at this pair.
 */
GENDPDE_CORE int gendpdePairUpdate(int dissipation, int conduction, GENDPDE_REAL pairThermalEnergy,
                                   GENDPDE_REAL inverseTemperatureDifference, GENDPDE_REAL frictionFactor,
                                   GENDPDE_REAL u0, GENDPDE_REAL omegaR, GENDPDE_REAL inverseMassI,
                                   GENDPDE_REAL inverseMassJ, GENDPDE_REAL friction, GENDPDE_REAL heatConduction,
                                   GENDPDE_REAL heatNoise, GENDPDE_REAL stepSize, GENDPDE_REAL sqrtStepSize,
                                   GENDPDE_REAL xi, GENDPDE_REAL xiQ, GENDPDE_REAL* energyI, GENDPDE_REAL* energyJ,
                                   GENDPDE_REAL* impulse) {
    *impulse = 0;
    if (dissipation) {
        GENDPDE_REAL kineticChange;
        *impulse =
                gendpdePairImpulse(u0, omegaR, friction * (1 + frictionFactor), sqrt(2 * friction * pairThermalEnergy),
                                   stepSize, sqrtStepSize, inverseMassI + inverseMassJ, xi, &kineticChange);
        *energyI -= (GENDPDE_REAL) 0.5 * kineticChange;
        *energyJ -= (GENDPDE_REAL) 0.5 * kineticChange;
    }
    if (conduction) {
        const GENDPDE_REAL heat = gendpdeConductiveHeat(omegaR, heatConduction, heatNoise, inverseTemperatureDifference,
                                                        stepSize, sqrtStepSize, xiQ);
        *energyI += heat;
        *energyJ -= heat;
    }
    return !(*energyI > 0) || !(*energyJ > 0);
}

#endif /* GENDPDE_CORE_ARITHMETIC_ONLY */

#endif /*GENDPDE_PHYSICS_CORE_H_*/
