/* GenDPDEIntegrator on the device (docs/theory.md sections 5-7): kicks, drift, and the Shardlow sweep in the order
 * of GenDPDESweepOrder (blocks of 2x2x2 cells in 8 colours, one launch per colour, one thread per block, the block's
 * pairs in (i, j) order with the lists of four consecutive first particles interleaved), so that the device applies
 * the pair updates in the sequence of the host platforms, with the pair physics of GenDPDEPhysicsCore.h
 * (GENDPDE_REAL = mixed). Velocities in `mixed` precision (velm, w = 1/m), internal
 * energies in `mixed` precision indexed by original particle index (atom reordering never moves them).
 *
 * status[0]: the smallest original index of a particle whose step would be unstable; status[1]: the number of pairs;
 * status[2]: the sweep position of the first pair after which an internal energy is <= 0; status[3]: pairs found in
 * cells that are not adjacent (none are possible). Each is NO_VALUE (INT_MAX) or 0 until set. The argument order of
 * each kernel is the enum of the same name in CommonGenDPDEIntegratorKernel.cpp. */

#define NO_VALUE 0x7FFFFFFF

KERNEL void resetStatus(GLOBAL int* RESTRICT status) {
    if (GLOBAL_ID == 0) {
        status[0] = NO_VALUE;
        status[1] = 0;
        status[2] = NO_VALUE;
        status[3] = 0;
    }
}

inline DEVICE mixed3 loadForce(GLOBAL const mm_long* RESTRICT forceBuffers, int slot) {
    const mixed scale = 1/(mixed) 0x100000000;
    return make_mixed3(scale*forceBuffers[slot], scale*forceBuffers[slot + PADDED_NUM_ATOMS],
                       scale*forceBuffers[slot + 2*PADDED_NUM_ATOMS]);
}

/** Before anything changes: the forces finite and no particle about to move farther than maxDisplacement. */
KERNEL void checkStep(GLOBAL const mixed4* RESTRICT velm, GLOBAL const mm_long* RESTRICT forceBuffers,
                      GLOBAL const int* RESTRICT atomIndex, mixed stepSize, mixed maxDisplacement,
                      GLOBAL int* RESTRICT status) {
    for (int slot = GLOBAL_ID; slot < NUM_ATOMS; slot += GLOBAL_SIZE) {
        const mixed4 v = velm[slot];
        const mixed3 f = loadForce(forceBuffers, slot);
        const mixed3 displacement = (make_mixed3(v.x, v.y, v.z) + f*(stepSize*v.w))*stepSize;
        if (v.w != 0 && !(dot(displacement, displacement) <= maxDisplacement*maxDisplacement))
            ATOMIC_MIN(&status[0], atomIndex[slot]);
    }
}

/** v += (dt F/m) for every particle of finite mass. */
KERNEL void kick(GLOBAL mixed4* RESTRICT velm, GLOBAL const mm_long* RESTRICT forceBuffers, mixed timeStep) {
    for (int slot = GLOBAL_ID; slot < NUM_ATOMS; slot += GLOBAL_SIZE) {
        mixed4 v = velm[slot];
        if (v.w != 0) {
            const mixed3 f = loadForce(forceBuffers, slot)*(timeStep*v.w);
            v.x += f.x;
            v.y += f.y;
            v.z += f.z;
            velm[slot] = v;
        }
    }
}

/** r += dt v (posq plus its correction in mixed precision). */
KERNEL void drift(GLOBAL real4* RESTRICT posq, GLOBAL real4* RESTRICT posqCorrection,
                  GLOBAL const mixed4* RESTRICT velm, mixed timeStep) {
    for (int slot = GLOBAL_ID; slot < NUM_ATOMS; slot += GLOBAL_SIZE) {
        const mixed4 v = velm[slot];
        if (v.w != 0) {
            mixed3 r = loadMixedPosition(posq, posqCorrection, slot);
            r.x += v.x*timeStep;
            r.y += v.y*timeStep;
            r.z += v.z*timeStep;
            const real4 old = posq[slot];
#ifdef USE_MIXED_PRECISION
            const real4 rounded = make_real4((real) r.x, (real) r.y, (real) r.z, old.w);
            posq[slot] = rounded;
            posqCorrection[slot] = make_real4(r.x - (mixed) rounded.x, r.y - (mixed) rounded.y,
                                              r.z - (mixed) rounded.z, 0);
#else
            posq[slot] = make_real4(r.x, r.y, r.z, old.w);
#endif
        }
    }
}

/** Each particle's kinetic energy with the on-step velocity v + (dt/2) F/m. */
KERNEL void kineticEnergies(GLOBAL const mixed4* RESTRICT velm, GLOBAL const mm_long* RESTRICT forceBuffers,
                            mixed halfStep, GLOBAL mixed* RESTRICT energy) {
    for (int slot = GLOBAL_ID; slot < NUM_ATOMS; slot += GLOBAL_SIZE) {
        const mixed4 v = velm[slot];
        if (v.w == 0)
            energy[slot] = 0;
        else {
            const mixed3 u = make_mixed3(v.x, v.y, v.z) + loadForce(forceBuffers, slot)*(halfStep*v.w);
            energy[slot] = dot(u, u)/(2*v.w);
        }
    }
}

KERNEL void invertAtomIndex(GLOBAL const int* RESTRICT atomIndex, GLOBAL int* RESTRICT slotOfAtom) {
    for (int slot = GLOBAL_ID; slot < NUM_ATOMS; slot += GLOBAL_SIZE)
        slotOfAtom[atomIndex[slot]] = slot;
}

/**
 * The pairs (i < j, original indices, closer than the cutoff) by block: with fill == 0 count them per block, by the
 * block's rank in the sweep (rankOfBlock), with fill != 0 list them in their block's range (in any order;
 * orderBlockPairs orders them). A pair's block is
 * that of its home cell (along each direction the cell the other follows), as in GenDPDESweepOrder.
 */
KERNEL void findBlockPairs(int4 cells, int4 blocks, GLOBAL const int* RESTRICT cellStart,
        GLOBAL const int* RESTRICT sortedCell, GLOBAL const int* RESTRICT sortedAtom,
        GLOBAL const int* RESTRICT sortedSlot, GLOBAL const real4* RESTRICT posq,
        GLOBAL const real4* RESTRICT posqCorrection, mixed4 boxA, mixed4 boxB, mixed4 boxC, mixed cutoff,
        GLOBAL const int* RESTRICT rankOfBlock, int fill, GLOBAL int* RESTRICT blockCount,
        GLOBAL const int* RESTRICT blockStart, GLOBAL int2* RESTRICT blockPairs, GLOBAL int* RESTRICT status) {
    const mixed cutoff2 = cutoff*cutoff;
    for (int k = GLOBAL_ID; k < NUM_ATOMS; k += GLOBAL_SIZE) {
        const int i = sortedAtom[k];
        const mixed3 ri = loadMixedPosition(posq, posqCorrection, sortedSlot[k]);
        const int3 home = cellCoordinates(sortedCell[k], cells);
        FOR_EACH_NEIGHBOUR_CELL(home, cells, cx, cy, cz, cell) {
            for (int m = cellStart[cell]; m < cellStart[cell + 1]; m++) {
                const int j = sortedAtom[m];
                if (j <= i)
                    continue;
                const mixed3 d = mixedPairDelta(ri, loadMixedPosition(posq, posqCorrection, sortedSlot[m]),
                                                boxA, boxB, boxC);
                if (!(dot(d, d) < cutoff2))
                    continue;
                // The home cell along each direction: the lower one (modulo the grid if periodic).
                int ci[3] = {home.x, home.y, home.z}, cj[3] = {cx, cy, cz}, n[3] = {cells.x, cells.y, cells.z};
                int block[3];
                bool adjacent = true;
                for (int dim = 0; dim < 3; dim++) {
                    int delta = cj[dim] - ci[dim];
#ifdef USE_PERIODIC
                    delta += (delta < -1 ? n[dim] : 0) - (delta > 1 ? n[dim] : 0);
#endif
                    adjacent = adjacent && (delta >= -1 && delta <= 1);
                    block[dim] = (delta == -1 ? cj[dim] : ci[dim]) >> 1;
                }
                if (!adjacent) {
                    ATOMIC_ADD(&status[3], 1);
                    continue;
                }
                const int rank = rankOfBlock[(block[2]*blocks.y + block[1])*blocks.x + block[0]];
                if (fill == 0)
                    ATOMIC_ADD(&blockCount[rank], 1);
                else
                    blockPairs[blockStart[rank] + ATOMIC_ADD(&blockCount[rank], 1)] = make_int2(i, j);
            }
        }
    }
}

inline DEVICE bool pairBefore(int2 a, int2 b) {
    return a.x < b.x || (a.x == b.x && a.y < b.y);
}

/**
 * Each block's pairs in sweep order: sorted by (i, j) (Shell sort in place), then the lists of each four consecutive
 * distinct first particles interleaved into orderedPairs (GenDPDESweepOrder's interleaveRuns).
 */
KERNEL void orderBlockPairs(int numBlocks, GLOBAL const int* RESTRICT blockStart, GLOBAL int2* RESTRICT blockPairs,
                            GLOBAL int2* RESTRICT orderedPairs) {
    for (int b = GLOBAL_ID; b < numBlocks; b += GLOBAL_SIZE) {
        const int begin = blockStart[b], count = blockStart[b + 1] - begin;
        GLOBAL int2* pairs = &blockPairs[begin];
        int gap = 1;
        while (gap < count/3)
            gap = 3*gap + 1;
        for (; gap > 0; gap /= 3)
            for (int k = gap; k < count; k++) {
                const int2 pair = pairs[k];
                int m = k;
                while (m >= gap && pairBefore(pair, pairs[m - gap])) {
                    pairs[m] = pairs[m - gap];
                    m -= gap;
                }
                pairs[m] = pair;
            }
        GLOBAL int2* output = &orderedPairs[begin];
        int next = 0, start = 0;
        while (start < count) {
            int runStart[5], numRuns = 0, end = start;
            while (numRuns < 4 && end < count) {
                runStart[numRuns++] = end;
                const int particle = pairs[end].x;
                while (end < count && pairs[end].x == particle)
                    end++;
            }
            runStart[numRuns] = end;
            int longest = 0;
            for (int r = 0; r < numRuns; r++)
                longest = max(longest, runStart[r + 1] - runStart[r]);
            for (int rank = 0; rank < longest; rank++)
                for (int r = 0; r < numRuns; r++)
                    if (runStart[r] + rank < runStart[r + 1])
                        output[next++] = pairs[runStart[r] + rank];
            start = end;
        }
    }
}

/** Physics::dissipativePairUpdate on velm entries: the impulse of the shared core applied along e. */
inline DEVICE mixed dissipativePairUpdate(mixed3 e, mixed omegaR, mixed friction, mixed noiseAmplitude,
        mixed stepSize, mixed sqrtStepSize, mixed4* vi, mixed4* vj, mixed xi) {
    const mixed inverseMassI = vi->w, inverseMassJ = vj->w;
    const mixed u0 = e.x*(vi->x - vj->x) + e.y*(vi->y - vj->y) + e.z*(vi->z - vj->z);
    mixed kineticChange;
    const mixed impulse = gendpdePairImpulse(u0, omegaR, friction, noiseAmplitude, stepSize, sqrtStepSize,
                                             inverseMassI + inverseMassJ, xi, &kineticChange);
    vi->x += e.x*(impulse*inverseMassI);
    vi->y += e.y*(impulse*inverseMassI);
    vi->z += e.z*(impulse*inverseMassI);
    vj->x -= e.x*(impulse*inverseMassJ);
    vj->y -= e.y*(impulse*inverseMassJ);
    vj->z -= e.z*(impulse*inverseMassJ);
    return kineticChange;
}

/**
 * One colour of the sweep: thread t runs the block of rank firstRank + t, its pairs in order (GenDPDEPairSweep.h).
 * parameters = (cutoff, dt, sqrt(dt), 0); per pair of type indices (GenDPDETypes.h; atomType by original index)
 * pairTable[t_i numTypes + t_j] = (friction, heat conduction, alpha = sqrt(2 k_B kappa), sigma of the Isothermal
 * bath); heatCapacityTable[t] = C_V of type t; terms bit 0: dissipation, bit 1: conduction, bit 2: internal energies.
 */
KERNEL void sweepColour(int firstRank, int numRanks, GLOBAL const int* RESTRICT blockStart,
        GLOBAL const int2* RESTRICT orderedPairs, GLOBAL const int* RESTRICT slotOfAtom,
        GLOBAL const real4* RESTRICT posq, GLOBAL const real4* RESTRICT posqCorrection,
        GLOBAL mixed4* RESTRICT velm, GLOBAL mixed* RESTRICT energies, mixed4 boxA, mixed4 boxB, mixed4 boxC,
        mixed4 parameters, GLOBAL const int* RESTRICT atomType, GLOBAL const mixed4* RESTRICT pairTable,
        GLOBAL const mixed* RESTRICT heatCapacityTable, int numTypes, mixed boltzmann, int terms, unsigned int seed,
        unsigned int stepLow, unsigned int stepHigh, GLOBAL const randomReal* RESTRICT zigguratX,
        GLOBAL const randomReal* RESTRICT zigguratF, GLOBAL const randomReal* RESTRICT zigguratRatio,
        GLOBAL int* RESTRICT status) {
    if (status[2] != NO_VALUE)
        return;   // an earlier colour failed
    const mixed cutoff = parameters.x, stepSize = parameters.y, sqrtStepSize = parameters.z;
    const bool dissipation = (terms & 1) != 0, conduction = (terms & 2) != 0, internalEnergies = (terms & 4) != 0;
    for (int t = GLOBAL_ID; t < numRanks; t += GLOBAL_SIZE) {
        const int b = firstRank + t;
        for (int n = blockStart[b]; n < blockStart[b + 1]; n++) {
            const int2 pair = orderedPairs[n];
            const int si = slotOfAtom[pair.x], sj = slotOfAtom[pair.y];
            mixed4 vi = velm[si], vj = velm[sj];
            const mixed3 d = mixedPairDelta(loadMixedPosition(posq, posqCorrection, si),
                                            loadMixedPosition(posq, posqCorrection, sj), boxA, boxB, boxC);
            const mixed r = sqrt(dot(d, d));
            if (r == 0 || (vi.w == 0 && vj.w == 0))
                continue;
            const mixed omegaR = gendpdeRandomWeight(r, cutoff);
            const mixed3 e = d*(1/r);
            const int typeI = atomType[pair.x], typeJ = atomType[pair.y];
            const mixed4 pairParameters = pairTable[typeI*numTypes + typeJ];
            const mixed friction = pairParameters.x;
            GenDPDEStream random;
            initPairStream(&random, seed, stepLow, stepHigh, (unsigned int) pair.x, (unsigned int) pair.y);
            if (!internalEnergies) {
                dissipativePairUpdate(e, omegaR, friction, pairParameters.w, stepSize, sqrtStepSize, &vi, &vj,
                                      (mixed) randomNormal(&random, zigguratX, zigguratF, zigguratRatio));
                velm[si] = vi;
                velm[sj] = vj;
                continue;
            }
            mixed ei = energies[pair.x], ej = energies[pair.y];
            mixed pairThermalEnergy, inverseTemperatureDifference, frictionFactor;
            gendpdePairTemperatures(ei, ej, heatCapacityTable[typeI], heatCapacityTable[typeJ], boltzmann,
                                    &pairThermalEnergy, &inverseTemperatureDifference, &frictionFactor);
            if (dissipation) {
                const mixed kineticChange = dissipativePairUpdate(e, omegaR, friction*(1 + frictionFactor),
                        sqrt(2*friction*pairThermalEnergy), stepSize, sqrtStepSize, &vi, &vj,
                        (mixed) randomNormal(&random, zigguratX, zigguratF, zigguratRatio));
                ei -= (mixed) 0.5*kineticChange;
                ej -= (mixed) 0.5*kineticChange;
                velm[si] = vi;
                velm[sj] = vj;
            }
            if (conduction) {
                const mixed flow = gendpdeConductiveHeat(omegaR, pairParameters.y, pairParameters.z,
                        inverseTemperatureDifference, stepSize, sqrtStepSize,
                        (mixed) randomNormal(&random, zigguratX, zigguratF, zigguratRatio));
                ei += flow;
                ej -= flow;
            }
            energies[pair.x] = ei;
            energies[pair.y] = ej;
            if (!(ei > 0) || !(ej > 0)) {
                ATOMIC_MIN(&status[2], n);
                break;
            }
        }
    }
}
