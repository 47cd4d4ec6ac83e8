/* GenDPDEForce on the device (docs/theory.md sections 2-4), in passes over the cell grid of gendpdeCells.cc, one
 * thread per particle in cell order, each gathering over its neighbours (every pair is computed by both particles, so
 * no thread writes another particle's sums: no atomics, and a fixed summation order):
 *   computeDensities  n0_i = sum_j w(r_ij) (and the first moments g_i for estimators that read them), then the
 *                     particle's state: V_i, pi_i, f(n_i) (energy), pi_i dV_i/dn0_i and q_i = 2 pi_i dV_i/dG_i g_i,
 *   computeForces     F_i = sum_j [pi_i V'_i + pi_j V'_j] w'(r_ij) e_ij + H(d_ij)(q_i - q_j) (fixed point),
 *   computeVirials    (observables only) each particle's half of sum_j r_ij . F_ij and of sum_j F_ij r_ij^T.
 * Everything in `real` precision; every formula from the physics core (GenDPDEPhysicsCore.h, GENDPDE_REAL = real),
 * the V-B tables (Physics::VolumeVBPolynomials, VolumeVBQuadrature) from the host's arrays, converted to `real`.
 * The argument order of each kernel is the enum of the same name in CommonGenDPDEForceKernel.cpp. */

/** errors[0] = errors[1] = none (INT_MAX), on the device, before each density pass. */
KERNEL void resetErrors(GLOBAL int* RESTRICT errors) {
    if (GLOBAL_ID == 0)
        errors[0] = errors[1] = 0x7FFFFFFF;
}

/**
 * Pass 1, then each particle's state. model = (cutoff, 1/cutoff, weight value scale, weight derivative scale),
 * taitTable[t] = (reference density, reference pressure, bulk modulus, exponent) and taitPower[t] (gamma - 1 if
 * an integer, else -1) for particle type t = atomType[original index], volumeConstants = (k per density, volume
 * scale, derivative scale, 0) and momentConstants = (c^2, eps^2, 0, 0) of gendpdeEstimatorConstants, estimator one of
 * GENDPDE_ESTIMATOR_*; polynomials and quadrature the V-B tables (quadrature: squared nodes, mirrored squared nodes,
 * coefficients, GENDPDE_VB_QUADRATURE_PAIRS each). momentForce[k] receives q (estimators that read moments).
 * errors[0] gets the smallest original index of a particle whose position is not finite, errors[1] the smallest
 * 4 i + status over the particles whose state is invalid (GENDPDE_PARTICLE_NO_NEIGHBOR, GENDPDE_PARTICLE_OVERFLOW).
 */
KERNEL void computeDensities(int4 cells, GLOBAL const int* RESTRICT cellStart, GLOBAL const int* RESTRICT sortedCell,
        GLOBAL const int* RESTRICT sortedAtom, GLOBAL const real4* RESTRICT sortedPos,
        real4 boxA, real4 boxB, real4 boxC, real4 model, GLOBAL const int* RESTRICT atomType,
        GLOBAL const real4* RESTRICT taitTable, GLOBAL const int* RESTRICT taitPowerTable, real4 volumeConstants,
        real4 momentConstants, int estimator, GLOBAL const real* RESTRICT polynomials,
        GLOBAL const real* RESTRICT quadrature, GLOBAL real* RESTRICT primitiveDensity, GLOBAL real* RESTRICT volume,
        GLOBAL real* RESTRICT pressure, GLOBAL real* RESTRICT forceCoefficient, GLOBAL real4* RESTRICT momentForce,
        GLOBAL mixed* RESTRICT energyBuffer, GLOBAL int* RESTRICT errors) {
    const real cutoff2 = model.x*model.x;
    const int moments = gendpdeEstimatorNeedsMoments(estimator);
    mixed energy = 0;
    for (int k = GLOBAL_ID; k < NUM_ATOMS; k += GLOBAL_SIZE) {
        const real3 ri = trimTo3(sortedPos[k]);
        if (!(isfinite(ri.x) && isfinite(ri.y) && isfinite(ri.z)))
            ATOMIC_MIN(&errors[0], sortedAtom[k]);
        const int3 home = cellCoordinates(sortedCell[k], cells);
        real n0 = 0;
        real3 g = make_real3(0, 0, 0);
        FOR_EACH_NEIGHBOUR_CELL(home, cells, cx, cy, cz, cell) {
            for (int m = cellStart[cell]; m < cellStart[cell + 1]; m++) {
                const real3 d = pairDelta(ri, trimTo3(sortedPos[m]), boxA, boxB, boxC);
                const real r2 = dot(d, d);
                if (m != k && r2 < cutoff2) {
                    const real r = sqrt(r2);
                    n0 += gendpdeDensityWeight(r, model.y, model.z);
                    if (moments && r > 0)
                        g += d*gendpdeMomentWeightOverDistance(r, model.y);
                }
            }
        }
        const int type = atomType[sortedAtom[k]];
        const real4 tait = taitTable[type];
        real v, pi, f, coefficient, momentForceScale;
        const int status = gendpdeParticleState(estimator, n0, dot(g, g), volumeConstants.x, volumeConstants.y,
                volumeConstants.z, momentConstants.x, momentConstants.y, polynomials, quadrature,
                quadrature + GENDPDE_VB_QUADRATURE_PAIRS, quadrature + 2*GENDPDE_VB_QUADRATURE_PAIRS, tait.x, tait.y,
                tait.z, tait.w, taitPowerTable[type], &v, &pi, &f, &coefficient, &momentForceScale);
        if (moments) {
            const real3 q = g*momentForceScale;
            momentForce[k] = make_real4(q.x, q.y, q.z, 0);
        }
        if (status != GENDPDE_PARTICLE_VALID)
            ATOMIC_MIN(&errors[1], 4*sortedAtom[k] + status);
        primitiveDensity[k] = n0;
        volume[k] = v;
        pressure[k] = pi;
        forceCoefficient[k] = coefficient;
        energy += f;
    }
    energyBuffer[GLOBAL_ID] += energy;
}

/**
 * The force on the particle at sorted index k from its neighbour at m, d = r_k - r_m of length 0 < r < R, with their
 * force coefficients ci, cj and moment forces qi, qj (zero unless the estimator reads moments): the central force
 * gendpdePairForceScale d plus V-C's gendpdeMomentPairForce; *virial receives d . F.
 */
inline DEVICE real3 pairForce(real3 d, real r, real ci, real cj, real3 qi, real3 qj, real4 model, real* virial) {
    const real scale = gendpdePairForceScale(ci + cj, gendpdeDensityWeightDerivative(r, model.y, model.w), r);
    real3 force = d*scale;
    *virial = scale*r*r;
    // q vanishes below V-C's threshold, for nearly all of a bulk liquid: nothing to add then.
    if (qi.x != 0 || qi.y != 0 || qi.z != 0 || qj.x != 0 || qj.y != 0 || qj.z != 0) {
        const real3 e = d*(1/r), dq = qi - qj;
        real momentTerm[3];
        *virial += gendpdeMomentPairForce(e.x, e.y, e.z, r, model.y, dq.x, dq.y, dq.z, momentTerm);
        force += make_real3(momentTerm[0], momentTerm[1], momentTerm[2]);
    }
    return force;
}

/**
 * Pass 2: F_i, added to the fixed-point force buffer in slot order. Every pair is computed by both its particles, from
 * exactly opposite displacements (pairDelta), so both get exactly opposite pair forces. In double precision a particle
 * sums them in double and converts once to fixed point (the total force vanishes to double rounding). With float
 * forces each pair force is converted to fixed point (truncation toward zero is odd) and summed as integers: the total
 * force vanishes exactly, where float sums would leave ~1e-7 of every particle's force in it (momentum is what DPD
 * conserves), at the price of 2^-32 kJ/mol/nm of quantisation per pair, far below float rounding.
 */
KERNEL void computeForces(int4 cells, GLOBAL const int* RESTRICT cellStart, GLOBAL const int* RESTRICT sortedCell,
        GLOBAL const int* RESTRICT sortedSlot, GLOBAL const real4* RESTRICT sortedPos,
        real4 boxA, real4 boxB, real4 boxC, real4 model, GLOBAL const real* RESTRICT forceCoefficient,
        int moments, GLOBAL const real4* RESTRICT momentForce, GLOBAL mm_long* RESTRICT forceBuffers) {
    const real cutoff2 = model.x*model.x;
    for (int k = GLOBAL_ID; k < NUM_ATOMS; k += GLOBAL_SIZE) {
        const real3 ri = trimTo3(sortedPos[k]);
        const real ci = forceCoefficient[k];
        const real3 qi = (moments ? trimTo3(momentForce[k]) : make_real3(0, 0, 0));
        const int3 home = cellCoordinates(sortedCell[k], cells);
#ifdef USE_DOUBLE_PRECISION
        real3 force = make_real3(0, 0, 0);
#else
        mm_long forceX = 0, forceY = 0, forceZ = 0;
#endif
        FOR_EACH_NEIGHBOUR_CELL(home, cells, cx, cy, cz, cell) {
            for (int m = cellStart[cell]; m < cellStart[cell + 1]; m++) {
                const real3 d = pairDelta(ri, trimTo3(sortedPos[m]), boxA, boxB, boxC);
                const real r2 = dot(d, d);
                if (r2 < cutoff2 && r2 > 0) {   // coincident particles (and the particle itself): no force
                    real virial;
                    const real3 f = pairForce(d, sqrt(r2), ci, forceCoefficient[m], qi,
                                              (moments ? trimTo3(momentForce[m]) : make_real3(0, 0, 0)), model,
                                              &virial);
#ifdef USE_DOUBLE_PRECISION
                    force += f;
#else
                    forceX += realToFixedPoint(f.x);
                    forceY += realToFixedPoint(f.y);
                    forceZ += realToFixedPoint(f.z);
#endif
                }
            }
        }
        const int slot = sortedSlot[k];
#ifdef USE_DOUBLE_PRECISION
        forceBuffers[slot] += realToFixedPoint(force.x);
        forceBuffers[slot + PADDED_NUM_ATOMS] += realToFixedPoint(force.y);
        forceBuffers[slot + 2*PADDED_NUM_ATOMS] += realToFixedPoint(force.z);
#else
        forceBuffers[slot] += forceX;
        forceBuffers[slot + PADDED_NUM_ATOMS] += forceY;
        forceBuffers[slot + 2*PADDED_NUM_ATOMS] += forceZ;
#endif
    }
}

/**
 * The observables' pass (never run by a step): each particle's half of sum_j d_ij . F_ij into particleVirial[k] and,
 * if tensors, of sum_j F_ij d_ij^T into particleVirialTensor[9 k ... 9 k + 8] (row-major, gendpdeAddHalfPairVirial).
 */
KERNEL void computeVirials(int4 cells, GLOBAL const int* RESTRICT cellStart, GLOBAL const int* RESTRICT sortedCell,
        GLOBAL const real4* RESTRICT sortedPos, real4 boxA, real4 boxB, real4 boxC, real4 model,
        GLOBAL const real* RESTRICT forceCoefficient, int moments, GLOBAL const real4* RESTRICT momentForce,
        int tensors, GLOBAL real* RESTRICT particleVirial, GLOBAL real* RESTRICT particleVirialTensor) {
    const real cutoff2 = model.x*model.x;
    for (int k = GLOBAL_ID; k < NUM_ATOMS; k += GLOBAL_SIZE) {
        const real3 ri = trimTo3(sortedPos[k]);
        const real ci = forceCoefficient[k];
        const real3 qi = (moments ? trimTo3(momentForce[k]) : make_real3(0, 0, 0));
        const int3 home = cellCoordinates(sortedCell[k], cells);
        real sum = 0;
        real tensor[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
        FOR_EACH_NEIGHBOUR_CELL(home, cells, cx, cy, cz, cell) {
            for (int m = cellStart[cell]; m < cellStart[cell + 1]; m++) {
                const real3 d = pairDelta(ri, trimTo3(sortedPos[m]), boxA, boxB, boxC);
                const real r2 = dot(d, d);
                if (r2 < cutoff2 && r2 > 0) {
                    real virial;
                    const real3 f = pairForce(d, sqrt(r2), ci, forceCoefficient[m], qi,
                                              (moments ? trimTo3(momentForce[m]) : make_real3(0, 0, 0)), model,
                                              &virial);
                    sum += virial;
                    if (tensors)
                        gendpdeAddHalfPairVirial(f.x, f.y, f.z, d.x, d.y, d.z, tensor);
                }
            }
        }
        particleVirial[k] = sum/2;
        if (tensors)
            for (int c = 0; c < 9; c++)
                particleVirialTensor[9*k + c] = tensor[c];
    }
}
