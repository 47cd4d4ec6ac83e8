/* GenDPDEForce on the device (docs/theory.md sections 2-4), in two passes over the cell grid of gendpdeCells.cc, one
 * thread per particle in cell order, each gathering over its neighbours (every pair is computed by both particles, so
 * no thread writes another particle's sums: no atomics, and a fixed summation order):
 *   computeDensities  n0_i = sum_j w(r_ij), then V_i, pi_i, pi_i dV_i/dn0_i and f(n_i) (energy),
 *   computeForces     F_i = sum_j [pi_i V'_i + pi_j V'_j] w'(r_ij) e_ij (fixed point), and the virial.
 * Everything in `real` precision; the formulas from GenDPDEPhysicsCore.h (GENDPDE_REAL = real), the V-B tables
 * (Physics::VolumeVBPolynomials, VolumeVBQuadrature) from the host's arrays, converted to `real`. */

/** errors[0] = errors[1] = none (INT_MAX), on the device, before each density pass. */
KERNEL void resetErrors(GLOBAL int* RESTRICT errors) {
    if (GLOBAL_ID == 0)
        errors[0] = errors[1] = 0x7FFFFFFF;
}

/**
 * The V-B integrals (I, J) of Physics::volumeIntegralsVB at k > 0, with the same three branches: the piece of the
 * polynomial table from frexp (the host reads the same bits of k), the closed forms and the quadrature from the
 * shared core (GenDPDEPhysicsCore.h).
 */
inline DEVICE real2 volumeIntegralsVB(real k, GLOBAL const real2* RESTRICT coefficients,
                                      GLOBAL const real* RESTRICT quadrature) {
    int exponent;
    const real fraction = frexp(k, &exponent);   // k = fraction 2^exponent, fraction in [1/2, 1)
    const int octave = exponent - 1;
    if (octave >= VB_FIRST_OCTAVE && octave <= VB_LAST_OCTAVE) {
        // The piece from the top two bits of the mantissa m = 2 fraction in [1, 2); t in [-1, 1), exact.
        const real m = 2*fraction;
        const int piece = (int) ((m - 1)*4);
        const real t = 8*(m - 1) - (2*piece + 1);
        GLOBAL const real2* c = &coefficients[((octave - VB_FIRST_OCTAVE)*4 + piece)*14];
        // Estrin's scheme, as Physics::VolumeVBPolynomials::estrin13, for I (.x) and J (.y).
        const real t2 = t*t, t4 = t2*t2, t8 = t4*t4;
        real aI[7], aJ[7];
        for (int q = 0; q < 7; q++) {
            aI[q] = c[2*q].x + c[2*q + 1].x*t;
            aJ[q] = c[2*q].y + c[2*q + 1].y*t;
        }
        const real I = ((aI[0] + aI[1]*t2) + (aI[2] + aI[3]*t2)*t4) + ((aI[4] + aI[5]*t2) + aI[6]*t4)*t8;
        const real J = ((aJ[0] + aJ[1]*t2) + (aJ[2] + aJ[3]*t2)*t4) + ((aJ[4] + aJ[5]*t2) + aJ[6]*t4)*t8;
        return make_real2(I, J);
    }
    real I, J;
    if (k < 1)
        gendpdeVolumeIntegralsClosedForm(k, &I, &J);
    else
        gendpdeVolumeIntegralsQuadrature(k, quadrature, &quadrature[VB_QUADRATURE_PAIRS],
                                         &quadrature[2*VB_QUADRATURE_PAIRS], VB_QUADRATURE_PAIRS, &I, &J);
    return make_real2(I, J);
}

/**
 * Pass 1, then each particle's state. model = (cutoff, 1/cutoff, weight value scale, weight derivative scale),
 * taitTable[t] = (reference density, reference pressure, bulk modulus, exponent) and taitPower[t] (gamma - 1 if
 * an integer, else -1) for particle type t = atomType[original index] (one type until types exist: the tables are
 * laid out for them), vb = (k per density, volume scale,
 * derivative scale, 0), estimator 0 = V-A, 1 = V-B, 2 = V-C; for V-C, vc = (c^2, eps^2, 0, 0) of
 * Physics::VolumeEstimatorVC, and momentForce[k] receives q = 2 pi dV/dG g (g the first moment of the neighbourhood,
 * G = |g|^2). errors[0] gets the smallest original index of a particle whose
 * position is not finite, errors[1] the smallest 4 i + status over the particles whose state is invalid (1: no
 * neighbour under V-A, 2: the equation of state overflows).
 */
KERNEL void computeDensities(int4 cells, GLOBAL const int* RESTRICT cellStart, GLOBAL const int* RESTRICT sortedCell,
        GLOBAL const int* RESTRICT sortedAtom, GLOBAL const real4* RESTRICT sortedPos,
        real4 boxA, real4 boxB, real4 boxC, real4 model, GLOBAL const int* RESTRICT atomType,
        GLOBAL const real4* RESTRICT taitTable, GLOBAL const int* RESTRICT taitPowerTable, real4 vb, int estimator,
        GLOBAL const real2* RESTRICT vbCoefficients, GLOBAL const real* RESTRICT vbQuadrature,
        GLOBAL real* RESTRICT primitiveDensity, GLOBAL real* RESTRICT volume, GLOBAL real* RESTRICT pressure,
        GLOBAL real* RESTRICT forceCoefficient, GLOBAL mixed* RESTRICT energyBuffer, GLOBAL int* RESTRICT errors,
        real4 vc, GLOBAL real4* RESTRICT momentForce) {
    const real cutoff2 = model.x*model.x;
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
                    const real x = 1 - r*model.y;
                    n0 += model.z*x*x;
                    if (estimator == 2 && r > 0)
                        g += d*(model.y*x*x);   // phi(r) e = (r/R)(1 - r/R)^2 d/r = d (1/R)(1 - r/R)^2
                }
            }
        }
        // docs/theory.md sections 3-4: the volume, the Tait pressure and free energy, and pi dV/dn0.
        real v, derivative;
        int status = 0;
        if (estimator == 0) {
            if (n0 == 0)
                status = 1;
            v = 1/n0;
            derivative = -v*v;
        }
        else {
            if (n0 == 0) {
                v = vb.y/3;
                derivative = 0;   // diverges, but multiplies no pair: an isolated particle has no pair in range
            }
            else {
                const real2 integrals = volumeIntegralsVB(vb.x*n0, vbCoefficients, vbQuadrature);
                v = vb.y*integrals.x;
                derivative = vb.z*integrals.y;
            }
        }
        // V-C (docs/interfaces.md): V_B times the surface factor of a^2 = c^2 G/(n0^2 + eps^2).
        real momentDerivative = 0;
        if (estimator == 2) {
            const real inverse = 1/(n0*n0 + vc.y);
            const real a2 = vc.x*dot(g, g)*inverse;
            real factor, slope;
            gendpdeSurfaceFactor(a2, &factor, &slope);
            if (slope != 0) {
                derivative = derivative*factor - v*slope*2*a2*n0*inverse;
                momentDerivative = v*slope*vc.x*inverse;
                v *= factor;
            }
        }
        const int type = atomType[sortedAtom[k]];
        const real4 tait = taitTable[type];
        const int taitPower = taitPowerTable[type];
        real pi, f;
        gendpdeTait(1/v, tait.x, tait.y, tait.z, tait.w, taitPower, &pi, &f);
        if (estimator == 2) {
            const real3 q = g*(2*pi*momentDerivative);
            momentForce[k] = make_real4(q.x, q.y, q.z, 0);
        }
        if (status == 0 && !(isfinite(f) && isfinite(pi)))
            status = 2;
        if (status != 0)
            ATOMIC_MIN(&errors[1], 4*sortedAtom[k] + status);
        primitiveDensity[k] = n0;
        volume[k] = v;
        pressure[k] = pi;
        forceCoefficient[k] = (n0 > 0 ? pi*derivative : 0);
        energy += f;
    }
    energyBuffer[GLOBAL_ID] += energy;
}

/**
 * Pass 2: F_i (added to the fixed-point force buffer in slot order) and, if particleVirial is requested, each
 * particle's half of sum_j r_ij . F_ij. Every pair is computed by both its particles, from exactly opposite
 * displacements (pairDelta), so both get exactly opposite pair forces. In double precision a particle sums them in
 * double and converts once to fixed point (the total force vanishes to double rounding). With float forces each pair
 * force is converted to fixed point (truncation toward zero is odd) and summed as integers: the total force vanishes
 * exactly, where float sums would leave ~1e-7 of every particle's force in it (momentum is what DPD conserves), at
 * the price of 2^-32 kJ/mol/nm of quantisation per pair, far below float rounding.
 */
KERNEL void computeForces(int4 cells, GLOBAL const int* RESTRICT cellStart, GLOBAL const int* RESTRICT sortedCell,
        GLOBAL const int* RESTRICT sortedSlot, GLOBAL const real4* RESTRICT sortedPos,
        real4 boxA, real4 boxB, real4 boxC, real4 model, GLOBAL const real* RESTRICT forceCoefficient,
        GLOBAL mm_long* RESTRICT forceBuffers, int includeForces, int includeVirial,
        GLOBAL real* RESTRICT particleVirial, int moments, GLOBAL const real4* RESTRICT momentForce) {
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
        real virial = 0;
        FOR_EACH_NEIGHBOUR_CELL(home, cells, cx, cy, cz, cell) {
            for (int m = cellStart[cell]; m < cellStart[cell + 1]; m++) {
                const real3 d = pairDelta(ri, trimTo3(sortedPos[m]), boxA, boxB, boxC);
                const real r2 = dot(d, d);
                if (r2 < cutoff2 && r2 > 0) {   // coincident particles (and the particle itself): no force
                    const real r = sqrt(r2);
                    const real scale = (ci + forceCoefficient[m])*(model.w*(1 - r*model.y))/r;
                    real3 pairForce = d*scale;
                    virial += scale*r2;
                    const real3 qj = (moments ? trimTo3(momentForce[m]) : make_real3(0, 0, 0));
                    if (qi.x != 0 || qi.y != 0 || qi.z != 0 || qj.x != 0 || qj.y != 0 || qj.z != 0) {
                        // V-C: H(d) (q_i - q_j), H = phi' e e^T + (phi/r)(I - e e^T), phi = (r/R)(1 - r/R)^2;
                        // q vanishes below the threshold, for nearly all of a bulk liquid.
                        const real3 e = d*(1/r), dq = qi - qj;
                        const real x = r*model.y, along = dot(e, dq);
                        const real phiPrime = model.y*(1 - x)*(1 - 3*x), phiOverR = model.y*(1 - x)*(1 - x);
                        pairForce += e*(phiPrime*along) + (dq - e*along)*phiOverR;
                        virial += r*phiPrime*along;
                    }
#ifdef USE_DOUBLE_PRECISION
                    force += pairForce;
#else
                    forceX += realToFixedPoint(pairForce.x);
                    forceY += realToFixedPoint(pairForce.y);
                    forceZ += realToFixedPoint(pairForce.z);
#endif
                }
            }
        }
        if (includeForces) {
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
        if (includeVirial)
            particleVirial[k] = virial/2;
    }
}
