/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
/* GenDPDEForce on the device (docs/theory.md sections 2-4), over a neighbour list with a skin:
 *   checkList         the error flags cleared; the list marked for a rebuild if any particle has moved more than
 *                     half the skin since it was built (or the host asks);
 *   (the grid)        (only when marked: the kernels of gendpdeCells.cc return at once otherwise) the cell grid at
 *                     the list's build positions, kept until the next build;
 *   buildList         (only when marked) each particle's neighbours closer than R + skin, from that grid, by
 *                     original index; or buildSharedList, from the cells of the integrator's sweep order when the
 *                     force shares its build (a run of steps of a GenDPDEIntegrator with the same pair range), whose
 *                     check (checkSweepBuild, gendpdeSweep.cc) then takes checkList's place;
 *   computeDensities  n0_i = sum_j w(r_ij) (and the first moments g_i for estimators that read them), then the
 *                     particle's state: V_i, pi_i, f(n_i) (energy), pi_i dV_i/dn0_i and q_i = 2 pi_i dV_i/dG_i g_i,
 *   computeForces     F_i = sum_j [pi_i V'_i + pi_j V'_j] w'(r_ij) e_ij + H(d_ij)(q_i - q_j),
 *   computeVirials    (observables only) each particle's half of sum_j r_ij . F_ij and of sum_j F_ij r_ij^T.
 * One thread per particle in the order of the cell grid of the last build, each gathering over its listed
 * neighbours at the current positions (posq; or, for a particle with more neighbours than the list holds, over the
 * particles of the 27 cells around its build cell, which hold every particle within 1.1 R of its build position, so
 * every one closer than R now: no particle has moved more than 0.05 R; visited by original index too);
 * every pair is computed by both its particles, so no thread writes another particle's sums. A particle's sums run
 * over its neighbours closer than R by original index whichever way they are found: the results do not depend on the
 * list's history (when it was rebuilt), so a run continued from a checkpoint repeats the uninterrupted one bit for
 * bit. Per-particle values and list rows are stored by slot (posq's index). Everything in `real` precision; every
 * formula from the physics core (GenDPDEPhysicsCore.h, GENDPDE_REAL = real), the V-B tables
 * (Physics::VolumeVBPolynomials, VolumeVBQuadrature) from the host's arrays, converted to `real`. The argument order
 * of each kernel is the enum of the same name in CommonGenDPDEForceKernel.cpp. */

/**
 * errors[0] = errors[1] = none (INT_MAX) before each density pass; rebuild[0] = 1 if forceRebuild or if some
 * particle has moved more than maxDrift since the list was built (buildPosition, by slot).
 */
KERNEL void checkList(GLOBAL const real4* RESTRICT posq, GLOBAL const real4* RESTRICT buildPosition, real maxDrift,
                      int forceRebuild, GLOBAL int* RESTRICT rebuild, GLOBAL int* RESTRICT errors) {
    if (GLOBAL_ID == 0) {
        errors[0] = errors[1] = 0x7FFFFFFF;
        if (forceRebuild)
            rebuild[0] = 1;
    }
    if (forceRebuild)
        return;
    for (int s = GLOBAL_ID; s < NUM_ATOMS; s += GLOBAL_SIZE) {
        const real3 d = trimTo3(posq[s]) - trimTo3(buildPosition[s]);
        if (!(dot(d, d) <= maxDrift*maxDrift))
            rebuild[0] = 1;
    }
}

/** Whether the list is being rebuilt (rebuild[0] set); if so, the build's counters restarted (errors[3], errors[4]) and
 *  the builds counted (errors[5]). */
inline DEVICE bool startListBuild(GLOBAL const int* RESTRICT rebuild, GLOBAL int* RESTRICT errors) {
    if (rebuild[0] == 0)
        return false;
    if (GLOBAL_ID == 0) {
        errors[3] = errors[4] = 0;
        errors[5]++;
    }
    return true;
}

/** One particle's row counted: the largest row (errors[2]), the entries (errors[3]) and those closer than R (4). */
inline DEVICE void countListRow(int count, int inRange, GLOBAL int* RESTRICT errors) {
    ATOMIC_MAX(&errors[2], count);
    ATOMIC_ADD(&errors[3], count);
    ATOMIC_ADD(&errors[4], inRange);
}

/**
 * The list, when marked for a rebuild: the neighbours (slots) of the particle in slot s closer than listRange, by
 * original index, are neighbours[s capacity + n], n < min(listCount[s], capacity); buildPosition[s] its position.
 * listCount[s] counts them all (more than capacity: the passes use the cells for that particle), and errors[2] keeps
 * the largest count seen, so that the host can make room. Counters: errors[3] the entries of the list, errors[4] the
 * neighbours closer than R among them (each pair twice), errors[5] the number of builds.
 */
KERNEL void buildList(int4 cells, GLOBAL const int* RESTRICT cellStart, GLOBAL const int* RESTRICT sortedCell,
        GLOBAL const int* RESTRICT sortedSlot, GLOBAL const real4* RESTRICT sortedPos,
        GLOBAL const int* RESTRICT atomIndex, real4 boxA, real4 boxB, real4 boxC, real cutoff, real listRange,
        int capacity, GLOBAL const int* RESTRICT rebuild, GLOBAL real4* RESTRICT buildPosition,
        GLOBAL int* RESTRICT listCount,
        GLOBAL int* RESTRICT neighbours, GLOBAL int* RESTRICT errors) {
    if (!startListBuild(rebuild, errors))
        return;
    const real range2 = listRange*listRange, cutoff2 = cutoff*cutoff;
    for (int k = GLOBAL_ID; k < NUM_ATOMS; k += GLOBAL_SIZE) {
        const real4 position = sortedPos[k];
        const real3 ri = trimTo3(position);
        const int3 home = cellCoordinates(sortedCell[k], cells);
        const int s = sortedSlot[k];
        int count = 0, inRange = 0;
        GLOBAL int* list = neighbours + (size_t) s*capacity;
        FOR_EACH_NEIGHBOUR_CELL(home, cells, cx, cy, cz, cell) {
            for (int m = cellStart[cell]; m < cellStart[cell + 1]; m++) {
                const real3 d = pairDelta(ri, trimTo3(sortedPos[m]), boxA, boxB, boxC);
                if (m != k && dot(d, d) < range2) {
                    if (count < capacity)
                        list[count] = sortedSlot[m];
                    count++;
                    inRange += (dot(d, d) < cutoff2 ? 1 : 0);
                }
            }
        }
        // By original index (insertion sort: a few dozen neighbours).
        const int listed = min(count, capacity);
        for (int n = 1; n < listed; n++) {
            const int slot = list[n], atom = atomIndex[slot];
            int m = n - 1;
            while (m >= 0 && atomIndex[list[m]] > atom) {
                list[m + 1] = list[m];
                m--;
            }
            list[m + 1] = slot;
        }
        buildPosition[s] = position;
        listCount[s] = count;
        countListRow(count, inRange, errors);
    }
}

/**
 * The list of a build shared with the integrator's sweep (CommonGenDPDEBuildSource: the same pair range, periodic),
 * when marked: from the sweep's cells at its build positions (cellStart, orderAtom: the particles cell by cell, by
 * original index in a cell; atomCell, orderPosition (mixed), slotOfAtom: by original index), each particle's
 * neighbours closer than listRange at the build positions, by original index, as buildList makes them from the
 * force's own grid; and the order the passes walk (sortedSlot, sortedAtom, sortedCell: the sweep's cell order). The
 * sweep's rule, checked before every evaluation that shares it, keeps every particle within half the skin of its
 * build position, so the list holds every pair closer than R.
 */
KERNEL void buildSharedList(int4 cells, GLOBAL const int* RESTRICT cellStart, GLOBAL const int* RESTRICT orderAtom,
        GLOBAL const int* RESTRICT atomCell, GLOBAL const int* RESTRICT slotOfAtom,
        GLOBAL const mixed4* RESTRICT orderPosition, real4 boxA, real4 boxB, real4 boxC, real cutoff, real listRange,
        int capacity, GLOBAL const int* RESTRICT rebuild, GLOBAL int* RESTRICT sortedSlot,
        GLOBAL int* RESTRICT sortedAtom, GLOBAL int* RESTRICT sortedCell, GLOBAL real4* RESTRICT buildPosition,
        GLOBAL int* RESTRICT listCount, GLOBAL int* RESTRICT neighbours, GLOBAL int* RESTRICT errors) {
    if (!startListBuild(rebuild, errors))
        return;
    const real range2 = listRange*listRange, cutoff2 = cutoff*cutoff;
    for (int k = GLOBAL_ID; k < NUM_ATOMS; k += GLOBAL_SIZE) {
        const int atom = orderAtom[k], s = slotOfAtom[atom], homeCell = atomCell[atom];
        const mixed4 own = orderPosition[atom];
        const real3 ri = make_real3((real) own.x, (real) own.y, (real) own.z);
        const int3 home = cellCoordinates(homeCell, cells);
        int count = 0, inRange = 0;
        GLOBAL int* list = neighbours + (size_t) s*capacity;
        FOR_EACH_NEIGHBOUR_CELL(home, cells, cx, cy, cz, cell) {
            for (int m = cellStart[cell]; m < cellStart[cell + 1]; m++) {
                const int other = orderAtom[m];
                const mixed4 p = orderPosition[other];
                const real3 d = pairDelta(ri, make_real3((real) p.x, (real) p.y, (real) p.z), boxA, boxB, boxC);
                if (m != k && dot(d, d) < range2) {
                    if (count < capacity)
                        list[count] = other; // (original indices while sorting, slots after)
                    count++;
                    inRange += (dot(d, d) < cutoff2 ? 1 : 0);
                }
            }
        }
        const int listed = min(count, capacity);
        for (int n = 1; n < listed; n++) {
            const int value = list[n];
            int m = n - 1;
            while (m >= 0 && list[m] > value) {
                list[m + 1] = list[m];
                m--;
            }
            list[m + 1] = value;
        }
        for (int n = 0; n < listed; n++)
            list[n] = slotOfAtom[list[n]];
        sortedSlot[k] = s;
        sortedAtom[k] = atom;
        sortedCell[k] = homeCell;
        buildPosition[s] = make_real4(ri.x, ri.y, ri.z, 0);
        listCount[s] = count;
        countListRow(count, inRange, errors);
    }
}

/** The density pass's terms of one pair (d = r_i - r_j) closer than the cutoff: w(r) and, with moments, d phi(r)/r. */
inline DEVICE void addDensityTerms(real3 d, real4 model, int moments, real* n0, real3* g) {
    const real r2 = dot(d, d);
    if (!(r2 < model.x*model.x))
        return;
    const real r = sqrt(r2);
    *n0 += gendpdeDensityWeight(r, model.y, model.z);
    if (moments && r > 0)
        *g += d*gendpdeMomentWeightOverDistance(r, model.y);
}

/**
 * The force on particle i from its neighbour j, d = r_i - r_j, with their force coefficients ci, cj and, if moments,
 * moment forces qi, qj: the physics core's gendpdePairForce for 0 < r < R (else zero: beyond the cutoff, or
 * coincident); *virial receives d . F.
 */
inline DEVICE real3 pairForce(real3 d, real ci, real cj, int moments, real3 qi, real3 qj, real4 model, real* virial) {
    const real r2 = dot(d, d);
    *virial = 0;
    if (!(r2 < model.x*model.x && r2 > 0))
        return make_real3(0, 0, 0);
    const real r = sqrt(r2);
    real force[3];
    *virial = gendpdePairForce(d.x, d.y, d.z, r, ci + cj, gendpdeDensityWeightDerivative(r, model.y, model.w),
                               model.y, moments, qi.x, qi.y, qi.z, qj.x, qj.y, qj.z, force);
    return make_real3(force[0], force[1], force[2]);
}

/**
 * The neighbours of one particle (at k in the cell grid's order, slot s) in turn, by original index: its listed ones,
 * or, when its list overflowed, the particles of the 27 cells around its cell (each time the one of smallest index
 * after the last: slow, for a rare particle).
 */
typedef struct {
    int s, n, end, lastAtom, walkCells;
    int3 home;
} NeighbourCursor;

inline DEVICE NeighbourCursor firstNeighbour(int k, int s, GLOBAL const int* RESTRICT listCount, int capacity,
                                             GLOBAL const int* RESTRICT sortedCell, int4 cells) {
    NeighbourCursor c;
    c.s = s;
    c.n = 0;
    const int count = listCount[s];
    c.walkCells = (count > capacity);
    c.end = (c.walkCells ? 0 : count);
    c.lastAtom = -1;
    c.home = (c.walkCells ? cellCoordinates(sortedCell[k], cells) : make_int3(0, 0, 0));
    return c;
}

/** The next neighbour's slot, with *d = ri - r_t; -1 when there is none left. */
inline DEVICE int nextNeighbour(NeighbourCursor* c, real3 ri, real3* d, GLOBAL const int* RESTRICT neighbours,
        int capacity, GLOBAL const real4* RESTRICT posq, int4 cells, GLOBAL const int* RESTRICT cellStart,
        GLOBAL const int* RESTRICT sortedAtom, GLOBAL const int* RESTRICT sortedSlot,
        GLOBAL const real4* RESTRICT sortedPos, real4 boxA, real4 boxB, real4 boxC) {
    if (!c->walkCells) {
        if (c->n == c->end)
            return -1;
        const int t = neighbours[(size_t) c->s*capacity + c->n++];
        *d = pairDelta(ri, trimTo3(posq[t]), boxA, boxB, boxC);
        return t;
    }
    int best = -1, bestAtom = 0x7FFFFFFF;
    FOR_EACH_NEIGHBOUR_CELL(c->home, cells, cx, cy, cz, cell) {
        for (int m = cellStart[cell]; m < cellStart[cell + 1]; m++) {
            const int atom = sortedAtom[m];
            if (atom > c->lastAtom && atom < bestAtom && sortedSlot[m] != c->s) {
                best = m;
                bestAtom = atom;
            }
        }
    }
    if (best < 0)
        return -1;
    c->lastAtom = bestAtom;
    const int slot = sortedSlot[best];
    *d = pairDelta(ri, trimTo3(posq[slot]), boxA, boxB, boxC);
    return slot;
}

/* The arguments every pass takes to walk the neighbours (the list, and the cell grid for overflowed particles). */
#define NEIGHBOUR_ARGUMENTS GLOBAL const int* RESTRICT listCount, GLOBAL const int* RESTRICT neighbours, int capacity, \
        int4 cells, GLOBAL const int* RESTRICT cellStart, GLOBAL const int* RESTRICT sortedCell, \
        GLOBAL const int* RESTRICT sortedAtom, GLOBAL const int* RESTRICT sortedSlot, \
        GLOBAL const real4* RESTRICT sortedPos, GLOBAL const real4* RESTRICT posq, real4 boxA, real4 boxB, real4 boxC
#define NEXT_NEIGHBOUR(cursor, ri, d) nextNeighbour(&cursor, ri, &d, neighbours, capacity, posq, cells, cellStart, \
        sortedAtom, sortedSlot, sortedPos, boxA, boxB, boxC)

/**
 * Pass 1, then each particle's state. model = (cutoff, 1/cutoff, weight value scale, weight derivative scale),
 * lawTable[t] (GENDPDE_EOS_*), lawParameters[LAW_PARAMETER_STRIDE t ...] (the core's parameters of the type's law,
 * GenDPDEEquationsOfState.h: for a Tait law reference density, reference pressure, bulk modulus, exponent) and
 * taitPower[t] (gamma - 1 if an integer, else -1) for particle type t = atomType[original index],
 * volumeConstants = (k per density, volume scale, derivative scale, 0) and momentConstants = (c^2, eps^2, 0, 0) of
 * gendpdeEstimatorConstants, estimator one of GENDPDE_ESTIMATOR_*; polynomials and quadrature the V-B tables (quadrature: squared nodes, mirrored squared nodes,
 * coefficients, GENDPDE_VB_QUADRATURE_PAIRS each). Results by slot; momentForce[s] receives q (estimators that read
 * moments). errors[0] gets the smallest original index of a particle whose position is not finite, errors[1] the
 * smallest GENDPDE_PARTICLE_STATUSES i + status over the particles whose state is invalid (GENDPDE_PARTICLE_*).
 * The list's rebuild mark is cleared.
 * Every particle's state is gendpdeParticleState's. With thermal != 0 (a law depends on temperature, docs/theory.md
 * section 11) a particle whose law does takes its temperature from the integrator (isothermal: every theta =
 * temperature; otherwise storedEnergy eps_i, with storedEntropy sigma_i if entropyKnown, and
 * C_V = classHeatCapacity[particleClass[i]], all by original index; checkStep: a step's evaluation), and every
 * particle writes C_V theta_i and sigma(n_i) by original index to thermalEnergyOut and densityEntropyOut (a particle
 * whose law does not depend on temperature: its eps_i and 0). With thermal = 0 those arrays are not touched.
 */
KERNEL void computeDensities(NEIGHBOUR_ARGUMENTS, GLOBAL const int* RESTRICT atomIndex, real4 model,
        GLOBAL const int* RESTRICT atomType, GLOBAL const real* RESTRICT lawParameters,
        GLOBAL const int* RESTRICT taitPowerTable, real4 volumeConstants, real4 momentConstants, int estimator,
        GLOBAL const real* RESTRICT polynomials, GLOBAL const real* RESTRICT quadrature,
        GLOBAL real* RESTRICT primitiveDensity, GLOBAL real* RESTRICT volume, GLOBAL real* RESTRICT pressure,
        GLOBAL real* RESTRICT forceCoefficient, GLOBAL real4* RESTRICT momentForce,
        GLOBAL mixed* RESTRICT energyBuffer, GLOBAL int* RESTRICT rebuild, GLOBAL int* RESTRICT errors,
        int thermal, int isothermal, real temperature, int entropyKnown, int checkStep,
        GLOBAL const int* RESTRICT lawTable, GLOBAL const mixed* RESTRICT storedEnergy,
        GLOBAL const mixed* RESTRICT storedEntropy, GLOBAL const int* RESTRICT particleClass,
        GLOBAL const mixed* RESTRICT classHeatCapacity, GLOBAL mixed* RESTRICT thermalEnergyOut,
        GLOBAL mixed* RESTRICT densityEntropyOut) {
    if (GLOBAL_ID == 0)
        rebuild[0] = 0;
    const int moments = gendpdeEstimatorNeedsMoments(estimator);
    mixed energy = 0;
    for (int k = GLOBAL_ID; k < NUM_ATOMS; k += GLOBAL_SIZE) {
        const int s = sortedSlot[k], atom = atomIndex[s];
        const real3 ri = trimTo3(posq[s]);
        if (!(isfinite(ri.x) && isfinite(ri.y) && isfinite(ri.z)))
            ATOMIC_MIN(&errors[0], atom);
        real n0 = 0;
        real3 g = make_real3(0, 0, 0);
        NeighbourCursor cursor = firstNeighbour(k, s, listCount, capacity, sortedCell, cells);
        real3 d;
        while (NEXT_NEIGHBOUR(cursor, ri, d) >= 0)
            addDensityTerms(d, model, moments, &n0, &g);
        const int type = atomType[atom];
        real v, pi, f, coefficient, momentForceScale;
        mixed thermalEnergy;
        real sigma;
        // docs/theory.md section 11: a law that depends on temperature at theta_i, with eps_i in mixed precision.
        const int status = gendpdeParticleState(estimator, n0, dot(g, g), volumeConstants.x, volumeConstants.y,
                volumeConstants.z, momentConstants.x, momentConstants.y, polynomials, quadrature,
                quadrature + GENDPDE_VB_QUADRATURE_PAIRS, quadrature + 2*GENDPDE_VB_QUADRATURE_PAIRS, lawTable[type],
                lawParameters + LAW_PARAMETER_STRIDE*type, taitPowerTable[type], isothermal, temperature,
                thermal ? storedEnergy[atom] : 0, thermal ? (real) storedEntropy[atom] : 0, entropyKnown, checkStep,
                thermal ? (real) classHeatCapacity[particleClass[atom]] : 1, &v, &pi, &f, &coefficient,
                &momentForceScale, &thermalEnergy, &sigma);
        if (thermal) {
            thermalEnergyOut[atom] = thermalEnergy;
            densityEntropyOut[atom] = sigma;
        }
        if (moments) {
            const real3 q = g*momentForceScale;
            momentForce[s] = make_real4(q.x, q.y, q.z, 0);
        }
        if (status != GENDPDE_PARTICLE_VALID)
            ATOMIC_MIN(&errors[1], GENDPDE_PARTICLE_STATUSES*atom + status);
        primitiveDensity[s] = n0;
        volume[s] = v;
        pressure[s] = pi;
        forceCoefficient[s] = coefficient;
        energy += f;
    }
    energyBuffer[GLOBAL_ID] += energy;
}

/**
 * Pass 2: F_i, added to the fixed-point force buffer by slot, summed over the neighbours in index order. Every pair
 * is computed by both its particles, from exactly opposite displacements (pairDelta), so both get exactly opposite
 * pair forces. In double precision a particle sums them in double and converts once to fixed point (the total force
 * vanishes to double rounding). With float forces each pair force is converted to fixed point (truncation toward zero
 * is odd) and summed as integers: the total force vanishes exactly, where float sums would leave ~1e-7 of every
 * particle's force in it (momentum is what DPD conserves), at the price of 2^-32 kJ/mol/nm per pair.
 */
KERNEL void computeForces(NEIGHBOUR_ARGUMENTS, real4 model, GLOBAL const real* RESTRICT forceCoefficient,
        int moments, GLOBAL const real4* RESTRICT momentForce, GLOBAL mm_long* RESTRICT forceBuffers) {
    for (int k = GLOBAL_ID; k < NUM_ATOMS; k += GLOBAL_SIZE) {
        const int s = sortedSlot[k];
        const real3 ri = trimTo3(posq[s]);
        const real ci = forceCoefficient[s];
        const real3 qi = (moments ? trimTo3(momentForce[s]) : make_real3(0, 0, 0));
#ifdef USE_DOUBLE_PRECISION
        real3 force = make_real3(0, 0, 0);
#else
        mm_long forceX = 0, forceY = 0, forceZ = 0;
#endif
        NeighbourCursor cursor = firstNeighbour(k, s, listCount, capacity, sortedCell, cells);
        real3 d;
        int t;
        while ((t = NEXT_NEIGHBOUR(cursor, ri, d)) >= 0) {
            real virial;
            const real3 f = pairForce(d, ci, forceCoefficient[t], moments, qi,
                                      (moments ? trimTo3(momentForce[t]) : make_real3(0, 0, 0)), model, &virial);
#ifdef USE_DOUBLE_PRECISION
            force += f;
#else
            forceX += realToFixedPoint(f.x);
            forceY += realToFixedPoint(f.y);
            forceZ += realToFixedPoint(f.z);
#endif
        }
#ifdef USE_DOUBLE_PRECISION
        forceBuffers[s] += realToFixedPoint(force.x);
        forceBuffers[s + PADDED_NUM_ATOMS] += realToFixedPoint(force.y);
        forceBuffers[s + 2*PADDED_NUM_ATOMS] += realToFixedPoint(force.z);
#else
        forceBuffers[s] += forceX;
        forceBuffers[s + PADDED_NUM_ATOMS] += forceY;
        forceBuffers[s + 2*PADDED_NUM_ATOMS] += forceZ;
#endif
    }
}

/**
 * The observables' pass (never run by a step): each particle's half of sum_j d_ij . F_ij into particleVirial[s] and,
 * if tensors, of sum_j F_ij d_ij^T into particleVirialTensor[9 s ... 9 s + 8] (row-major, gendpdeAddHalfPairVirial).
 */
KERNEL void computeVirials(NEIGHBOUR_ARGUMENTS, real4 model, GLOBAL const real* RESTRICT forceCoefficient,
        int moments, GLOBAL const real4* RESTRICT momentForce, int tensors, GLOBAL real* RESTRICT particleVirial,
        GLOBAL real* RESTRICT particleVirialTensor) {
    for (int k = GLOBAL_ID; k < NUM_ATOMS; k += GLOBAL_SIZE) {
        const int s = sortedSlot[k];
        const real3 ri = trimTo3(posq[s]);
        const real ci = forceCoefficient[s];
        const real3 qi = (moments ? trimTo3(momentForce[s]) : make_real3(0, 0, 0));
        real sum = 0;
        real tensor[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
        NeighbourCursor cursor = firstNeighbour(k, s, listCount, capacity, sortedCell, cells);
        real3 d;
        int t;
        while ((t = NEXT_NEIGHBOUR(cursor, ri, d)) >= 0) {
            real virial;
            const real3 f = pairForce(d, ci, forceCoefficient[t], moments, qi,
                                      (moments ? trimTo3(momentForce[t]) : make_real3(0, 0, 0)), model, &virial);
            sum += virial;
            const real r2 = dot(d, d);
            if (tensors && r2 < model.x*model.x && r2 > 0)
                gendpdeAddHalfPairVirial(f.x, f.y, f.z, d.x, d.y, d.z, tensor);
        }
        particleVirial[s] = sum/2;
        if (tensors)
            for (int c = 0; c < 9; c++)
                particleVirialTensor[9*s + c] = tensor[c];
    }
}
