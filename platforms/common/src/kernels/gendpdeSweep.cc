/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
/* The Shardlow sweep of GenDPDEIntegrator on the device, in the sequence of GenDPDESweepOrder (docs/theory.md
 * section 6), with parallel work inside each block:
 *
 *   orderBlocks   every block in one launch: the particles of the block's region (the up to 3x3x3 cells its
 *                 pairs can touch) staged in local memory by original index (each one's rank found by binary search
 *                 in the other cells, whose particles are listed by index); each particle's partners in the block,
 *                 sought only in the region cells that can pair with it, in (i, j) order, the lists of each four
 *                 consecutive first particles interleaved (the host's sequence); then each pair's level, one more
 *                 than the levels of the latest earlier pairs of its two particles, and the pairs grouped by level
 *                 into the block's slab (sequence position kept).
 *   sweepBlocks   one launch per colour: the region's velocities and internal energies staged in local memory, the
 *                 levels one after another, the pairs of a level at the same time.
 *
 * The pairs of a level share no particle, and every pair comes after all the earlier pairs of its particles, so each
 * particle sees its updates in the order of the sequence with the same inputs: the result is the sequential sweep's
 * to the last bit. A block whose region holds more than SWEEP_MAX_PARTICLES particles, or more pairs than its slab
 * (pairCapacity), is swept by one thread that streams its pairs in sequence from the cell grid (any size; slower).
 *
 * A work group sweeps SWEEP_BLOCKS_PER_GROUP blocks at once, SWEEP_BLOCK_THREADS threads each (OpenMM launches a
 * bounded number of work groups, so that is how many blocks run together); every barrier is the whole group's, so
 * the blocks of a group go through their levels together. Pairs of a block are stored as (i << 16) | j in region
 * ranks (position in the region's list, by original index). Defines: SWEEP_BLOCKS_PER_GROUP, SWEEP_BLOCK_THREADS,
 * SWEEP_MAX_PARTICLES, the STATUS_* words (CommonGenDPDEStatus.h); after gendpdeCells.cc, gendpdeRandom.cc and the
 * sweep's pair step (GenDPDESweepPair.h), with the physics core in `mixed`. */

#define SWEEP_GROUP_SIZE (SWEEP_BLOCKS_PER_GROUP*SWEEP_BLOCK_THREADS)

/** The cells of a block's region along one direction: 2 b + 0, 1, 2, without repeats (periodic grids of 1 or 2
 *  cells) and inside the grid (open boundaries). Returns their number; along[l] the cell at offset l. */
inline DEVICE int regionAxis(int b, int n, int* along) {
#ifdef USE_PERIODIC
    const int count = (n >= 3 ? 3 : n);
#else
    const int count = min(3, n - 2*b);
#endif
    for (int l = 0; l < count; l++) {
        int c = 2*b + l;
#ifdef USE_PERIODIC
        if (c >= n)
            c -= n;
#endif
        along[l] = c;
    }
    return count;
}

/** A region cell's offsets (l_x, l_y, l_z), 2 bits each. */
inline DEVICE int offsetCode(int lx, int ly, int lz) {
    return lx | (ly << 2) | (lz << 4);
}

/**
 * Whether particles in region cells of these offsets can form a pair of this block: along each direction the two
 * cells are the same or adjacent (offsets differ by at most one) and the lower one, the pair's home, is in the block
 * (offset 0 or 1).
 */
inline DEVICE bool pairOfBlock(int codeI, int codeJ) {
    for (int shift = 0; shift < 6; shift += 2) {
        const int a = (codeI >> shift) & 3, b = (codeJ >> shift) & 3;
        if (a - b > 1 || b - a > 1 || (a == 2 && b == 2))
            return false;
    }
    return true;
}

/** The colour of a sweep rank (ranks run colour by colour), and the rank's first in that colour (*first). */
inline DEVICE int rankColour(int rank, int4 blocks, int* first) {
    int start = 0;
    for (int colour = 0; colour < 8; colour++) {
        const int px = colour & 1, py = (colour >> 1) & 1, pz = colour >> 2;
        const int count = ((blocks.x + 1 - px)/2)*((blocks.y + 1 - py)/2)*((blocks.z + 1 - pz)/2);
        if (rank < start + count) {
            *first = start;
            return colour;
        }
        start += count;
    }
    *first = start;
    return 8;
}

/** The block of a sweep rank: colour by colour (its parity), block index order within a colour (blockRanks()). */
inline DEVICE int3 blockOfRank(int rank, int4 blocks) {
    int first;
    const int colour = rankColour(rank, blocks, &first);
    const int px = colour & 1, py = (colour >> 1) & 1, pz = colour >> 2;
    const int mx = (blocks.x + 1 - px)/2, my = (blocks.y + 1 - py)/2;
    const int t = rank - first;
    return make_int3(px + 2*(t%mx), py + 2*((t/mx)%my), pz + 2*(t/(mx*my)));
}

/**
 * The partners of particle i (region rank) in its block: the later particles of the region cells that can hold a pair
 * of the block with it, closer than the cutoff. Returns their number; their ranks go to partners[n].x, in the order
 * found, unless partners is null.
 */
inline DEVICE int blockPartners(int i, int numParticles, LOCAL_ARG const int* regionStart,
        LOCAL_ARG const int* regionCode, LOCAL_ARG const int* rankInRegion, LOCAL_ARG const int* codeOf,
        LOCAL_ARG const mixed4* positionOf, mixed4 boxA, mixed4 boxB, mixed4 boxC, mixed cutoff2,
        GLOBAL int2* partners) {
    const mixed3 ri = trimTo3(positionOf[i]);
    const int codeI = codeOf[i];
    int count = 0;
    for (int c = 0; c < 27 && regionStart[c] < numParticles; c++) {
        if (!pairOfBlock(codeI, regionCode[c]))
            continue;
        for (int k = regionStart[c]; k < regionStart[c + 1]; k++) {
            const int j = rankInRegion[k];
            if (j > i) {
                const mixed3 d = mixedPairDelta(ri, trimTo3(positionOf[j]), boxA, boxB, boxC);
                if (dot(d, d) < cutoff2) {
                    if (partners != 0)
                        partners[count].x = j;
                    count++;
                }
            }
        }
    }
    return count;
}

/**
 * Each block's sweep order, SWEEP_BLOCKS_PER_GROUP blocks per work group: header[rank] = (particles in the region,
 * pairs, levels, 1 if the block must be streamed), blockAtoms/blockSlots[rank SWEEP_MAX_PARTICLES + k] the region's
 * particles by original index, levelStart[rank (pairCapacity + 1) + l] the first entry of level l in
 * blockPairs[rank pairCapacity + ...] = ((i << 16) | j, sequence position). pairScratch holds the sequence while the
 * levels are found.
 */
KERNEL void orderBlocks(int4 cells, int4 blocks, GLOBAL const int* RESTRICT cellStart,
        GLOBAL const int* RESTRICT sortedAtom, GLOBAL const int* RESTRICT sortedSlot, GLOBAL const real4* RESTRICT posq,
        GLOBAL const real4* RESTRICT posqCorrection, mixed4 boxA, mixed4 boxB, mixed4 boxC, mixed cutoff,
        int pairCapacity, GLOBAL int* RESTRICT status, GLOBAL int4* RESTRICT header, GLOBAL int* RESTRICT blockAtoms,
        GLOBAL int* RESTRICT blockSlots, GLOBAL int2* RESTRICT pairScratch, GLOBAL int2* RESTRICT blockPairs,
        GLOBAL int* RESTRICT levelStart) {
    LOCAL int regionCells[27*SWEEP_BLOCKS_PER_GROUP], regionCodes[27*SWEEP_BLOCKS_PER_GROUP];
    LOCAL int regionStarts[28*SWEEP_BLOCKS_PER_GROUP], sharedValues[4*SWEEP_BLOCKS_PER_GROUP];
    LOCAL int firstPairs[SWEEP_MAX_PARTICLES*SWEEP_BLOCKS_PER_GROUP], codes[SWEEP_MAX_PARTICLES*SWEEP_BLOCKS_PER_GROUP];
    LOCAL mixed4 positions[SWEEP_MAX_PARTICLES*SWEEP_BLOCKS_PER_GROUP];
    // Per particle (by rank): its pair count, run, first pair and code (the level of its latest pair at the end); the
    // rank of each particle in region order; the particle of each run.
    LOCAL int pairCounts[SWEEP_MAX_PARTICLES*SWEEP_BLOCKS_PER_GROUP], ranks[SWEEP_MAX_PARTICLES*SWEEP_BLOCKS_PER_GROUP];
    LOCAL int runs[SWEEP_MAX_PARTICLES*SWEEP_BLOCKS_PER_GROUP];
    LOCAL int runParticles[SWEEP_MAX_PARTICLES*SWEEP_BLOCKS_PER_GROUP];
    if (status[STATUS_HALTED] != 0)
        return;
    const int sub = LOCAL_ID/SWEEP_BLOCK_THREADS, lane = LOCAL_ID%SWEEP_BLOCK_THREADS;
    LOCAL_ARG int* regionCell = regionCells + 27*sub;
    LOCAL_ARG int* regionCode = regionCodes + 27*sub;
    LOCAL_ARG int* regionStart = regionStarts + 28*sub;
    LOCAL_ARG int* shared = sharedValues + 4*sub;   // particles, pairs, runs
    LOCAL_ARG int* firstPair = firstPairs + SWEEP_MAX_PARTICLES*sub;
    LOCAL_ARG int* codeOf = codes + SWEEP_MAX_PARTICLES*sub;
    LOCAL_ARG mixed4* positionOf = positions + SWEEP_MAX_PARTICLES*sub;
    LOCAL_ARG int* pairCount = pairCounts + SWEEP_MAX_PARTICLES*sub;
    LOCAL_ARG int* rankInRegion = ranks + SWEEP_MAX_PARTICLES*sub;
    LOCAL_ARG int* runOf = runs + SWEEP_MAX_PARTICLES*sub;
    LOCAL_ARG int* runParticle = runParticles + SWEEP_MAX_PARTICLES*sub;
    const mixed cutoff2 = cutoff*cutoff;
    for (int base = GROUP_ID*SWEEP_BLOCKS_PER_GROUP; base < blocks.w; base += NUM_GROUPS*SWEEP_BLOCKS_PER_GROUP) {
        // Every thread passes every barrier; a block with nothing (left) to do runs its loops zero times.
        const int rank = base + sub;
        const bool active = (rank < blocks.w);
        GLOBAL int2* scratch = pairScratch + (size_t) rank*pairCapacity;
        GLOBAL int2* pairs = blockPairs + (size_t) rank*pairCapacity;
        GLOBAL int* levels = levelStart + (size_t) rank*(pairCapacity + 1);
        if (active && lane == 0) {
            const int3 block = blockOfRank(rank, blocks);
            int alongX[3], alongY[3], alongZ[3];
            const int nx = regionAxis(block.x, cells.x, alongX), ny = regionAxis(block.y, cells.y, alongY);
            const int nz = regionAxis(block.z, cells.z, alongZ);
            int count = 0, total = 0;
            for (int lz = 0; lz < nz; lz++)
                for (int ly = 0; ly < ny; ly++)
                    for (int lx = 0; lx < nx; lx++) {
                        const int cell = (alongZ[lz]*cells.y + alongY[ly])*cells.x + alongX[lx];
                        regionCell[count] = cell;
                        regionCode[count] = offsetCode(lx, ly, lz);
                        regionStart[count++] = total;
                        total += cellStart[cell + 1] - cellStart[cell];
                    }
            for (int c = count; c < 28; c++)
                regionStart[c] = total;
            shared[0] = total;
            ATOMIC_MAX(&status[STATUS_MOST_PARTICLES], total);
            header[rank] = make_int4(total, 0, 0, total > SWEEP_MAX_PARTICLES ? 1 : 0);   // final below if ordered
            if (total > SWEEP_MAX_PARTICLES)
                ATOMIC_ADD(&status[STATUS_STREAMED], 1);
        }
        SYNC_THREADS;
        const int numParticles = (active && shared[0] <= SWEEP_MAX_PARTICLES ? shared[0] : 0);
        // Stage the region's particles, each at its rank by original index: its place in its own cell (cells list
        // their particles by index) plus, in every other cell of the region, the particles of smaller index.
        for (int k = lane; k < numParticles; k += SWEEP_BLOCK_THREADS) {
            int r = 0;
            while (regionStart[r + 1] <= k)
                r++;
            const int m = cellStart[regionCell[r]] + k - regionStart[r], atom = sortedAtom[m], slot = sortedSlot[m];
            int position = k - regionStart[r];
            for (int c = 0; c < 27 && regionStart[c] < numParticles; c++) {
                if (c == r)
                    continue;
                int low = cellStart[regionCell[c]], high = low + regionStart[c + 1] - regionStart[c];
                const int first = low;
                while (low < high) {   // the first particle of cell c with a larger index
                    const int middle = (low + high)/2;
                    if (sortedAtom[middle] < atom)
                        low = middle + 1;
                    else
                        high = middle;
                }
                position += low - first;
            }
            codeOf[position] = regionCode[r];
            const mixed3 position3 = loadMixedPosition(posq, posqCorrection, slot);
            positionOf[position] = make_mixed4(position3.x, position3.y, position3.z, 0);
            blockAtoms[(size_t) rank*SWEEP_MAX_PARTICLES + position] = atom;
            blockSlots[(size_t) rank*SWEEP_MAX_PARTICLES + position] = slot;
            rankInRegion[k] = position;
        }
        SYNC_THREADS;
        // Each particle's pairs with later particles of the block, counted.
        for (int i = lane; i < numParticles; i += SWEEP_BLOCK_THREADS)
            pairCount[i] = blockPartners(i, numParticles, regionStart, regionCode, rankInRegion, codeOf, positionOf,
                                         boxA, boxB, boxC, cutoff2, 0);
        SYNC_THREADS;
        // First pair of each particle's list; runs (particles with pairs) in order.
        if (numParticles > 0 && lane == 0) {
            int total = 0, numRuns = 0;
            for (int i = 0; i < numParticles; i++) {
                firstPair[i] = total;
                total += pairCount[i];
                if (pairCount[i] > 0) {
                    runOf[i] = numRuns;
                    runParticle[numRuns++] = i;
                }
            }
            shared[1] = total;
            shared[2] = numRuns;
            ATOMIC_MAX(&status[STATUS_MOST_PAIRS], total);
            if (total > pairCapacity) {
                header[rank] = make_int4(numParticles, total, 0, 1);
                ATOMIC_ADD(&status[STATUS_STREAMED], 1);
            }
        }
        SYNC_THREADS;
        const bool ordered = (numParticles > 0 && shared[1] <= pairCapacity);
        const int numPairs = (ordered ? shared[1] : 0), numRuns = (ordered ? shared[2] : 0);
        const int listed = (ordered ? numParticles : 0);
        // Each particle's partners in (i, j) order, in pairs[] (free until the levels): listed, then sorted by j.
        for (int i = lane; i < listed; i += SWEEP_BLOCK_THREADS) {
            if (pairCount[i] == 0)
                continue;
            GLOBAL int2* partners = pairs + firstPair[i];
            const int n = blockPartners(i, numParticles, regionStart, regionCode, rankInRegion, codeOf, positionOf,
                                        boxA, boxB, boxC, cutoff2, partners);
            for (int m = 1; m < n; m++) {   // insertion sort: a few dozen partners
                const int j = partners[m].x;
                int q = m - 1;
                while (q >= 0 && partners[q].x > j) {
                    partners[q + 1].x = partners[q].x;
                    q--;
                }
                partners[q + 1].x = j;
            }
        }
        SYNC_THREADS;
        // The sequence: pair k of run r in group g (runs 4g .. 4g + 3) comes after the pairs of rank < k of the
        // group's runs and the pairs of rank k of the group's earlier runs (GenDPDESweepOrder's interleaveRuns).
        for (int i = lane; i < listed; i += SWEEP_BLOCK_THREADS) {
            if (pairCount[i] == 0)
                continue;
            const int run = runOf[i], firstRun = run - (run & 3), endRun = min(firstRun + 4, numRuns);
            const int groupStart = firstPair[runParticle[firstRun]];
            for (int k = 0; k < pairCount[i]; k++) {
                int position = groupStart;
                for (int q = firstRun; q < endRun; q++) {
                    const int length = pairCount[runParticle[q]];
                    position += min(length, k) + (q < run && length > k ? 1 : 0);
                }
                scratch[position] = make_int2((i << 16) | pairs[firstPair[i] + k].x, 0);
            }
        }
        SYNC_THREADS;
        if (ordered)
            for (int l = lane; l <= numPairs; l += SWEEP_BLOCK_THREADS)
                levels[l] = 0;
        for (int i = lane; i < listed; i += SWEEP_BLOCK_THREADS)
            codeOf[i] = 0;   // now: one more than the level of the particle's latest pair
        SYNC_THREADS;
        // Levels, counted per level, then the pairs grouped by level (in sequence order within a level).
        if (ordered && lane == 0) {
            int numLevels = 0;
            for (int n = 0; n < numPairs; n++) {
                const int pair = scratch[n].x, i = pair >> 16, j = pair & 0xFFFF;
                const int level = max(codeOf[i], codeOf[j]);
                codeOf[i] = codeOf[j] = level + 1;
                scratch[n].y = level;
                levels[level + 1]++;
                numLevels = max(numLevels, level + 1);
            }
            for (int l = 0; l < numLevels; l++)
                levels[l + 1] += levels[l];
            for (int n = 0; n < numPairs; n++) {
                const int2 entry = scratch[n];
                pairs[levels[entry.y]++] = make_int2(entry.x, n);
            }
            for (int l = numLevels; l > 0; l--)
                levels[l] = levels[l - 1];
            levels[0] = 0;
            header[rank] = make_int4(numParticles, numPairs, numLevels, 0);
        }
        SYNC_THREADS;
    }
}

/** What every pair update of a step shares (GenDPDEPairSweep.h's PairSweepParameters, on the device). */
typedef struct {
    mixed cutoff, stepSize, sqrtStepSize, boltzmann;
    int dissipation, conduction, internalEnergies, numClasses;
    unsigned int seed, stepLow, stepHigh;
} SweepConstants;

/**
 * One pair update of the sweep on copies of the two particles' velocities (inverse mass in w, as velm) and internal
 * energies: the core's pair step (GenDPDESweepPair.h), as on the host and in LAMMPS, with the pair's stream keyed on
 * (i, j). i < j original indices, d = r_i - r_j. Returns whether an internal energy is now <= 0 (Isoenergetic mode).
 * typeI, typeJ: the particles' classes (GenDPDETypes.h); pairTable[c_i numClasses + c_j] = (friction, heat
 * conduction, alpha = sqrt(2 k_B kappa), sigma of the Isothermal bath), heatCapacityTable[c] = C_V of class c.
 */
inline DEVICE bool pairUpdate(int i, int j, mixed3 d, int typeI, int typeJ, mixed4* vi, mixed4* vj, mixed* ei,
        mixed* ej, SweepConstants c, GLOBAL const mixed4* RESTRICT pairTable,
        GLOBAL const mixed* RESTRICT heatCapacityTable, GLOBAL const randomReal* RESTRICT zigguratX,
        GLOBAL const randomReal* RESTRICT zigguratF, GLOBAL const randomReal* RESTRICT zigguratRatio) {
    const mixed4 pairParameters = pairTable[typeI*c.numClasses + typeJ];
    GenDPDEPairRandom random;
    initPairStream(&random.stream, c.seed, c.stepLow, c.stepHigh, (unsigned int) i, (unsigned int) j);
    random.zigguratX = zigguratX;
    random.zigguratF = zigguratF;
    random.zigguratRatio = zigguratRatio;
    return gendpdeSweepPair(c.dissipation, c.conduction, c.internalEnergies, d.x, d.y, d.z, sqrt(dot(d, d)),
            c.cutoff, vi->w, vj->w, (mixed*) vi, (mixed*) vj, ei, ej, heatCapacityTable[typeI],
            heatCapacityTable[typeJ], pairParameters.x, pairParameters.y, pairParameters.z, pairParameters.w,
            c.boltzmann, c.stepSize, c.sqrtStepSize, &random) != 0;
}

/** The cells of a streamed block's region: each with its offsets' code and the end of its particles. */
typedef struct {
    int cell[27], code[27], end[27];
    int count;
} StreamRegion;

/**
 * The next particle, by original index, under the cursors next[c] of the region cells c accepted by mask: its sorted
 * index (the cursor moves past it), or -1 if none; *which receives its cell.
 */
inline DEVICE int nextOfRegion(const StreamRegion* region, int* next, unsigned int mask,
                               GLOBAL const int* RESTRICT sortedAtom, int* which) {
    int best = -1, bestAtom = 0x7FFFFFFF;
    for (int c = 0; c < region->count; c++)
        if (((mask >> c) & 1) && next[c] < region->end[c] && sortedAtom[next[c]] < bestAtom) {
            bestAtom = sortedAtom[next[c]];
            best = c;
        }
    *which = best;
    return best < 0 ? -1 : next[best]++;
}

/** A run of a streamed block: particle i's pairs with later particles of the block, one at a time. */
typedef struct {
    int next[27];            // a cursor per region cell
    unsigned int mask;       // the region cells whose particles can pair with i in this block
    int i, slotI, j, slotJ;  // original indices and slots; j < 0 once the run is exhausted
    mixed3 ri, d;            // r_i, and r_i - r_j of the current pair
} StreamRun;

/** Advance a run to its next pair (j = -1 if none). */
inline DEVICE void nextPartner(const StreamRegion* region, StreamRun* run, GLOBAL const int* RESTRICT sortedAtom,
        GLOBAL const int* RESTRICT sortedSlot, GLOBAL const real4* RESTRICT posq,
        GLOBAL const real4* RESTRICT posqCorrection, mixed4 boxA, mixed4 boxB, mixed4 boxC, mixed cutoff2) {
    int which;
    run->j = -1;
    for (int m = nextOfRegion(region, run->next, run->mask, sortedAtom, &which); m >= 0;
             m = nextOfRegion(region, run->next, run->mask, sortedAtom, &which)) {
        if (sortedAtom[m] <= run->i)
            continue;
        const mixed3 d = mixedPairDelta(run->ri, loadMixedPosition(posq, posqCorrection, sortedSlot[m]), boxA, boxB,
                                        boxC);
        if (dot(d, d) < cutoff2) {
            run->j = sortedAtom[m];
            run->slotJ = sortedSlot[m];
            run->d = d;
            return;
        }
    }
}

/**
 * The sweep of one block by one thread, its pairs streamed in sequence from the cell grid (any number of particles
 * and pairs: for blocks beyond the capacities of orderBlocks). Returns the sequence position of the first pair after
 * which an internal energy is <= 0, with that particle and its energy, or -1.
 */
DEVICE int streamBlock(int3 block, int4 cells, GLOBAL const int* RESTRICT cellStart,
        GLOBAL const int* RESTRICT sortedAtom, GLOBAL const int* RESTRICT sortedSlot, GLOBAL const real4* RESTRICT posq,
        GLOBAL const real4* RESTRICT posqCorrection, GLOBAL mixed4* RESTRICT velm, GLOBAL mixed* RESTRICT energies,
        mixed4 boxA, mixed4 boxB, mixed4 boxC, GLOBAL const int* RESTRICT atomType, SweepConstants c,
        GLOBAL const mixed4* RESTRICT pairTable, GLOBAL const mixed* RESTRICT heatCapacityTable,
        GLOBAL const randomReal* RESTRICT zigguratX, GLOBAL const randomReal* RESTRICT zigguratF,
        GLOBAL const randomReal* RESTRICT zigguratRatio, int* failedParticle, mixed* failedEnergy) {
    StreamRegion region;
    int firstNext[27];
    int alongX[3], alongY[3], alongZ[3];
    const int nx = regionAxis(block.x, cells.x, alongX), ny = regionAxis(block.y, cells.y, alongY);
    const int nz = regionAxis(block.z, cells.z, alongZ);
    region.count = 0;
    for (int lz = 0; lz < nz; lz++)
        for (int ly = 0; ly < ny; ly++)
            for (int lx = 0; lx < nx; lx++) {
                const int cell = (alongZ[lz]*cells.y + alongY[ly])*cells.x + alongX[lx];
                region.cell[region.count] = cell;
                region.code[region.count] = offsetCode(lx, ly, lz);
                region.end[region.count] = cellStart[cell + 1];
                firstNext[region.count++] = cellStart[cell];
            }
    const mixed cutoff2 = c.cutoff*c.cutoff;
    StreamRun runs[4];
    int position = 0, which;
    while (true) {
        // Up to four runs: the next particles in index order that have a pair in this block.
        int numRuns = 0;
        while (numRuns < 4) {
            const int m = nextOfRegion(&region, firstNext, 0xFFFFFFFFu, sortedAtom, &which);
            if (m < 0)
                break;
            StreamRun* run = &runs[numRuns];
            run->mask = 0;
            for (int q = 0; q < region.count; q++) {
                run->next[q] = cellStart[region.cell[q]];
                if (pairOfBlock(region.code[which], region.code[q]))
                    run->mask |= 1u << q;
            }
            run->i = sortedAtom[m];
            run->slotI = sortedSlot[m];
            run->ri = loadMixedPosition(posq, posqCorrection, run->slotI);
            nextPartner(&region, run, sortedAtom, sortedSlot, posq, posqCorrection, boxA, boxB, boxC, cutoff2);
            if (run->j >= 0)
                numRuns++;
        }
        if (numRuns == 0)
            return -1;
        // Interleaved: the next pair of each run in turn.
        bool any = true;
        while (any) {
            any = false;
            for (int r = 0; r < numRuns; r++) {
                StreamRun* run = &runs[r];
                if (run->j < 0)
                    continue;
                any = true;
                mixed4 vi = velm[run->slotI], vj = velm[run->slotJ];
                mixed ei = 0, ej = 0;
                if (c.internalEnergies) {
                    ei = energies[run->i];
                    ej = energies[run->j];
                }
                const bool failed = pairUpdate(run->i, run->j, run->d, atomType[run->i], atomType[run->j], &vi, &vj,
                        &ei, &ej, c, pairTable, heatCapacityTable, zigguratX, zigguratF, zigguratRatio);
                velm[run->slotI] = vi;
                velm[run->slotJ] = vj;
                if (c.internalEnergies) {
                    energies[run->i] = ei;
                    energies[run->j] = ej;
                }
                if (failed) {
                    *failedParticle = (ei > 0 ? run->j : run->i);
                    *failedEnergy = (ei > 0 ? ej : ei);
                    return position;
                }
                position++;
                nextPartner(&region, run, sortedAtom, sortedSlot, posq, posqCorrection, boxA, boxB, boxC, cutoff2);
            }
        }
    }
}

/**
 * One colour of the sweep: the blocks of ranks firstRank .. firstRank + numRanks - 1, SWEEP_BLOCKS_PER_GROUP per work
 * group, each level by level (orderBlocks) or, when orderBlocks could not hold it, streamed by one thread.
 * parameters = (cutoff, dt, sqrt(dt), k_B); terms bit 0: dissipation, bit 1: conduction, bit 2: internal energies.
 * A block after which an internal energy is <= 0 records the first such pair of its sequence (failure[rank] =
 * particle, failureEnergy[rank] = its energy) and stops the run (HALT_SWEEP; FAILED_RANK the smallest failed rank);
 * finishStep then rolls the step back.
 */
KERNEL void sweepBlocks(int firstRank, int numRanks, int4 cells, int4 blocks, GLOBAL const int4* RESTRICT header,
        GLOBAL const int* RESTRICT blockAtoms, GLOBAL const int* RESTRICT blockSlots,
        GLOBAL const int* RESTRICT levelStart, GLOBAL const int2* RESTRICT blockPairs, int pairCapacity,
        GLOBAL const int* RESTRICT cellStart, GLOBAL const int* RESTRICT sortedAtom,
        GLOBAL const int* RESTRICT sortedSlot, GLOBAL const real4* RESTRICT posq,
        GLOBAL const real4* RESTRICT posqCorrection, GLOBAL mixed4* RESTRICT velm, GLOBAL mixed* RESTRICT energies,
        mixed4 boxA, mixed4 boxB, mixed4 boxC, mixed4 parameters, GLOBAL const int* RESTRICT atomType,
        GLOBAL const mixed4* RESTRICT pairTable, GLOBAL const mixed* RESTRICT heatCapacityTable, int numClasses,
        int terms, unsigned int seed, unsigned int stepLow, unsigned int stepHigh, int stepIndex,
        GLOBAL const randomReal* RESTRICT zigguratX, GLOBAL const randomReal* RESTRICT zigguratF,
        GLOBAL const randomReal* RESTRICT zigguratRatio, GLOBAL int* RESTRICT status, GLOBAL int* RESTRICT failure,
        GLOBAL mixed* RESTRICT failureEnergy) {
    LOCAL mixed4 velocities[SWEEP_MAX_PARTICLES*SWEEP_BLOCKS_PER_GROUP];
    LOCAL mixed internalEnergies[SWEEP_MAX_PARTICLES*SWEEP_BLOCKS_PER_GROUP];
    LOCAL int types[SWEEP_MAX_PARTICLES*SWEEP_BLOCKS_PER_GROUP], slots[SWEEP_MAX_PARTICLES*SWEEP_BLOCKS_PER_GROUP];
    LOCAL int atoms[SWEEP_MAX_PARTICLES*SWEEP_BLOCKS_PER_GROUP];
    LOCAL int firstFailures[SWEEP_BLOCKS_PER_GROUP], levelCounts[SWEEP_BLOCKS_PER_GROUP];
    if (status[STATUS_HALTED] != 0)
        return;   // an earlier colour or the step's check stopped the run
    const int sub = LOCAL_ID/SWEEP_BLOCK_THREADS, lane = LOCAL_ID%SWEEP_BLOCK_THREADS;
    LOCAL_ARG mixed4* velocityOf = velocities + SWEEP_MAX_PARTICLES*sub;
    LOCAL_ARG mixed* energyOf = internalEnergies + SWEEP_MAX_PARTICLES*sub;
    LOCAL_ARG int* typeOf = types + SWEEP_MAX_PARTICLES*sub;
    LOCAL_ARG int* slotOf = slots + SWEEP_MAX_PARTICLES*sub;
    LOCAL_ARG int* atomOf = atoms + SWEEP_MAX_PARTICLES*sub;
    SweepConstants c;
    c.cutoff = parameters.x;
    c.stepSize = parameters.y;
    c.sqrtStepSize = parameters.z;
    c.boltzmann = parameters.w;
    c.dissipation = (terms & 1) != 0;
    c.conduction = (terms & 2) != 0;
    c.internalEnergies = (terms & 4) != 0;
    c.numClasses = numClasses;
    c.seed = seed;
    c.stepLow = stepLow;
    c.stepHigh = stepHigh;
    for (int base = GROUP_ID*SWEEP_BLOCKS_PER_GROUP; base < numRanks; base += NUM_GROUPS*SWEEP_BLOCKS_PER_GROUP) {
        // Every thread passes every barrier; a block with nothing (left) to do runs its loops zero times.
        const int rank = firstRank + base + sub;
        const bool active = (base + sub < numRanks);
        const int4 info = (active ? header[rank] : make_int4(0, 0, 0, 0));
        if (info.w != 0 && lane == 0) {
            // Beyond the capacities: one thread streams the block's pairs in sequence.
            int particle;
            mixed energy;
            const int failed = streamBlock(blockOfRank(rank, blocks), cells, cellStart, sortedAtom, sortedSlot, posq,
                    posqCorrection, velm, energies, boxA, boxB, boxC, atomType, c, pairTable, heatCapacityTable,
                    zigguratX, zigguratF, zigguratRatio, &particle, &energy);
            if (failed >= 0) {
                failure[rank] = particle;
                failureEnergy[rank] = energy;
                ATOMIC_MIN(&status[STATUS_FAILED_RANK], rank);
                haltRun(status, HALT_SWEEP, stepIndex);
            }
        }
        const int numParticles = (info.w == 0 ? info.x : 0), numLevels = (info.w == 0 ? info.z : 0);
        GLOBAL const int* particleAtom = blockAtoms + (size_t) rank*SWEEP_MAX_PARTICLES;
        GLOBAL const int* particleSlot = blockSlots + (size_t) rank*SWEEP_MAX_PARTICLES;
        for (int k = lane; k < numParticles; k += SWEEP_BLOCK_THREADS) {
            const int atom = particleAtom[k], slot = particleSlot[k];
            velocityOf[k] = velm[slot];
            energyOf[k] = (c.internalEnergies ? energies[atom] : 0);
            typeOf[k] = atomType[atom];
            slotOf[k] = slot;
            atomOf[k] = atom;
        }
        if (lane == 0) {
            firstFailures[sub] = NO_VALUE;
            levelCounts[sub] = numLevels;
        }
        SYNC_THREADS;
        int groupLevels = 0;
        for (int b = 0; b < SWEEP_BLOCKS_PER_GROUP; b++)
            groupLevels = max(groupLevels, levelCounts[b]);
        // The levels in turn; after a failure only the pairs before it in the sequence still matter (a later pair
        // never precedes an earlier one of the same particle), and the first failing pair is the one reported.
        GLOBAL const int* levels = levelStart + (size_t) rank*(pairCapacity + 1);
        GLOBAL const int2* pairs = blockPairs + (size_t) rank*pairCapacity;
        int myFailure = NO_VALUE, myParticle = -1;
        mixed myEnergy = 0;
        for (int level = 0; level < groupLevels; level++) {
            const int end = (level < numLevels ? levels[level + 1] : 0);
            for (int n = (level < numLevels ? levels[level] : 0) + lane; n < end; n += SWEEP_BLOCK_THREADS) {
                const int2 entry = pairs[n];
                if (entry.y > firstFailures[sub])
                    continue;
                const int i = entry.x >> 16, j = entry.x & 0xFFFF;
                mixed4 vi = velocityOf[i], vj = velocityOf[j];
                mixed ei = energyOf[i], ej = energyOf[j];
                const mixed3 d = mixedPairDelta(loadMixedPosition(posq, posqCorrection, slotOf[i]),
                                                loadMixedPosition(posq, posqCorrection, slotOf[j]), boxA, boxB, boxC);
                const bool failed = pairUpdate(atomOf[i], atomOf[j], d, typeOf[i], typeOf[j], &vi, &vj, &ei, &ej, c,
                        pairTable, heatCapacityTable, zigguratX, zigguratF, zigguratRatio);
                velocityOf[i] = vi;
                velocityOf[j] = vj;
                energyOf[i] = ei;
                energyOf[j] = ej;
                if (failed && entry.y < myFailure) {
                    myFailure = entry.y;
                    myParticle = (ei > 0 ? atomOf[j] : atomOf[i]);
                    myEnergy = (ei > 0 ? ej : ei);
                    ATOMIC_MIN(&firstFailures[sub], entry.y);
                }
            }
            SYNC_THREADS;
        }
        for (int k = lane; k < numParticles; k += SWEEP_BLOCK_THREADS) {
            velm[slotOf[k]] = velocityOf[k];
            if (c.internalEnergies)
                energies[atomOf[k]] = energyOf[k];
        }
        if (myFailure != NO_VALUE && myFailure == firstFailures[sub]) {
            failure[rank] = myParticle;
            failureEnergy[rank] = myEnergy;
            ATOMIC_MIN(&status[STATUS_FAILED_RANK], rank);
            haltRun(status, HALT_SWEEP, stepIndex);
        }
        if (active && lane == 0) {
            int first;
            ATOMIC_MAX(&status[STATUS_LEVELS + rankColour(rank, blocks, &first)], numLevels);
        }
        SYNC_THREADS;
    }
}
