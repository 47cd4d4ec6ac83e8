/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
/* The Shardlow sweep of GenDPDEIntegrator on the device, in the order of GenDPDESweepDefinition.h (docs/theory.md
 * section 6): made once per build from the candidate pairs (closer than candidateRange(R) at the build's positions)
 * and kept while no particle has moved more than half the skin from its build position and the box is the same.
 *
 * Every step (three launches, two of them stages in ticket order: see "Stages in one launch" below):
 *   prepareSweepBuild  the check: each particle's slot by original index (atom reordering moves slots, not the
 *                    order), and the step's build flags: build when the host asks (first step, new box, build
 *                    positions given) or when some particle is farther than sqrt(rebuildDisplacement2(R)) from its
 *                    build position (nearest image: OpenMM may wrap positions between builds); capture the step's
 *                    positions as the build's unless the host gave them. Then, at a build only, in the same launch,
 *                    the cells of the build positions (>= candidateRange(R) wide), particles by original index inside
 *                    a cell, kept until the next build (with open boundaries the host reads the flags and the build's
 *                    bounding box, findSweepBounds, first, and the cells take a launch of their own).
 *   orderBlocks      at a build only (other steps it returns at once, on the device, from the flags):
 *                    every block in one launch: the particles of the block's region (the up to 3x3x3 cells its pairs
 *                    can touch) staged in local memory by original index; each particle's candidates in the block in
 *                    (i, j) order; each pair's level by SweepDefinition::assignLevels's greedy rule (the smallest
 *                    level that no earlier pair of either particle has, in (i, j) order); the pairs grouped by level,
 *                    (i, j) order within a level, into the block's slab.
 *   sweepBlocks      the 8 colours in one launch (a colour's blocks after every block of the colours before it):
 *                    each block's velocities and internal energies staged in local memory, the levels one after
 *                    another, the pairs of a level at the same time, each updated only if it is closer than R at the
 *                    step's positions.
 *
 * The pairs of a level share no particle, so running them at the same time gives the sequence's result to the last
 * bit. A block whose region holds more than SWEEP_MAX_PARTICLES particles, or more candidates than its slab
 * (pairCapacity), is swept by one thread that finds its candidates and their levels again from the build's cells at
 * every step (any size; slower), with the levels kept per particle in levelMasks (blocks of one colour share no
 * particle). More than 32 SWEEP_LEVEL_WORDS levels in a block stop the run (HALT_LEVELS).
 *
 * A work group sweeps SWEEP_BLOCKS_PER_GROUP blocks at once, SWEEP_BLOCK_THREADS threads each (OpenMM launches a
 * bounded number of work groups, so that is how many blocks run together); every barrier is the whole group's, so
 * the blocks of a group go through their levels together. Pairs of a block are stored as (i << 16) | j in region
 * ranks (position in the region's list, by original index). Build flags: flags[2 p] build, flags[2 p + 1] capture,
 * for the step's parity p (each step's check clears the next step's pair). Defines: SWEEP_BLOCKS_PER_GROUP,
 * SWEEP_BLOCK_THREADS, SWEEP_MAX_PARTICLES, SWEEP_LEVEL_WORDS, the STATUS_* words (CommonGenDPDEStatus.h); after
 * gendpdeCells.cc, gendpdeRandom.cc, gendpdeStatus.cc and the sweep's pair step (GenDPDESweepPair.h), with the physics
 * core in `mixed`. */

#define SWEEP_GROUP_SIZE (SWEEP_BLOCKS_PER_GROUP*SWEEP_BLOCK_THREADS)

/* Stages in one launch. A launch whose units must run stage by stage (each stage's units after every unit of the
 * stages before it: the check and the cells of a build; the sweep's colours) hands its units out in ticket order: a
 * work group takes the next ticket, waits until the units of the earlier stages are done, runs its unit, counts it
 * done, and takes another ticket until none is left. A group waits only for units whose tickets were taken before its
 * own, by groups already running, so the launch needs no more groups to be resident at once than the device holds
 * (no deadlock whatever the number of groups or their schedule), and the result is that of one launch per stage.
 * schedule[4] (ints, 0 0 0 NO_VALUE between launches; the last group to leave resets them): the next ticket, the
 * units done, the groups that have left, and the first stage of this launch that stopped the run. A value the whole
 * group needs is read by every thread where it can be (the build flags, final once the check is done; the stop words,
 * read so that every thread agrees: awaitStage); only the ticket goes through local memory. */
#ifdef __OPENCL_VERSION__
#define DEVICE_FENCE mem_fence(CLK_GLOBAL_MEM_FENCE)
#else
#define DEVICE_FENCE __threadfence()
#endif

/** The group's next ticket (every thread of the group gets it). ticket: a local int. */
inline DEVICE int takeTicket(GLOBAL int* RESTRICT schedule, LOCAL_ARG int* ticket) {
    if (LOCAL_ID == 0)
        *ticket = ATOMIC_ADD(&schedule[0], 1);
    SYNC_THREADS;
    return *ticket;
}

/** Wait (the whole group) until `before` units of this launch are done, and see their writes. */
inline DEVICE void awaitUnits(GLOBAL int* RESTRICT schedule, int before) {
    if (LOCAL_ID == 0)
        while (((volatile GLOBAL int*) schedule)[1] < before)
            ;
    DEVICE_FENCE;
    SYNC_THREADS;
    DEVICE_FENCE;
}

/**
 * Wait until `before` units of this launch are done (those of the earlier stages); then whether the run has stopped
 * before this stage: in an earlier launch, or in an earlier stage of this one (a stop in this stage, by another unit,
 * does not count, as with one launch per stage). Each thread reads the words itself, and all get the same answer: a
 * stop in this stage writes its stage before the status word (stopInStage), so a thread that sees that stop's status
 * word sees its stage too.
 */
inline DEVICE bool awaitStage(GLOBAL int* RESTRICT schedule, int before, int stage, GLOBAL int* RESTRICT status) {
    awaitUnits(schedule, before);
    const int halted = ((volatile GLOBAL int*) status)[STATUS_HALTED];
    DEVICE_FENCE;
    const int stopStage = ((volatile GLOBAL int*) schedule)[3];
    return halted != 0 && (stopStage == NO_VALUE || stopStage < stage);
}

/** This unit stops the run in this stage (before the status word says so: awaitStage reads them the other way). */
inline DEVICE void stopInStage(GLOBAL int* RESTRICT schedule, int stage, GLOBAL int* RESTRICT status, int reason,
                               int stepIndex) {
    ATOMIC_MIN(&schedule[3], stage);
    DEVICE_FENCE;
    haltRun(status, reason, stepIndex);
}

/** The group's unit is done: its writes, then the count. */
inline DEVICE void finishUnit(GLOBAL int* RESTRICT schedule) {
    DEVICE_FENCE;
    SYNC_THREADS;
    if (LOCAL_ID == 0)
        ATOMIC_ADD(&schedule[1], 1);
}

/** The group leaves the launch (no ticket left); the last to leave resets the schedule for the next launch. */
inline DEVICE void leaveLaunch(GLOBAL int* RESTRICT schedule) {
    if (LOCAL_ID == 0 && ATOMIC_ADD(&schedule[2], 1) == (int) NUM_GROUPS - 1) {
        schedule[0] = 0;
        schedule[1] = 0;
        schedule[2] = 0;
        schedule[3] = NO_VALUE;
    }
}

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

/** The number of blocks of a colour (its parity along x, y, z in bits 0, 1, 2). */
inline DEVICE int colourBlocks(int colour, int4 blocks) {
    const int px = colour & 1, py = (colour >> 1) & 1, pz = colour >> 2;
    return ((blocks.x + 1 - px)/2)*((blocks.y + 1 - py)/2)*((blocks.z + 1 - pz)/2);
}

/** The colour of a sweep rank (ranks run colour by colour), and the rank's first in that colour (*first). */
inline DEVICE int rankColour(int rank, int4 blocks, int* first) {
    int start = 0;
    for (int colour = 0; colour < 8; colour++) {
        const int count = colourBlocks(colour, blocks);
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

/** Whether this step builds the order (and the run goes on). */
inline DEVICE bool building(GLOBAL const int* RESTRICT flags, int parity, GLOBAL const int* RESTRICT status) {
    return flags[2*parity] != 0 && status[STATUS_HALTED] == 0;
}

/** The build position of a particle: the step's (stored as the build's) when capturing, else the stored one. */
inline DEVICE mixed3 buildPositionOf(int atom, int capture, GLOBAL const real4* RESTRICT posq,
        GLOBAL const real4* RESTRICT posqCorrection, GLOBAL const int* RESTRICT slotOfAtom,
        GLOBAL const mixed4* RESTRICT buildPosition) {
    return capture ? loadMixedPosition(posq, posqCorrection, slotOfAtom[atom]) : trimTo3(buildPosition[atom]);
}

/** Open boundaries, at a build: the bounding box of the build positions, bounds = (low.xyz, high.xyz); one group. */
KERNEL void findSweepBounds(GLOBAL const int* RESTRICT flags, int parity, GLOBAL const int* RESTRICT status,
        GLOBAL const real4* RESTRICT posq, GLOBAL const real4* RESTRICT posqCorrection,
        GLOBAL const int* RESTRICT slotOfAtom, GLOBAL const mixed4* RESTRICT buildPosition,
        GLOBAL mixed* RESTRICT bounds) {
    LOCAL mixed lowest[3*BOUNDS_GROUP_SIZE];
    LOCAL mixed highest[3*BOUNDS_GROUP_SIZE];
    if (!building(flags, parity, status))
        return;
    const int capture = flags[2*parity + 1];
    mixed3 low = buildPositionOf(0, capture, posq, posqCorrection, slotOfAtom, buildPosition), high = low;
    for (int i = LOCAL_ID; i < NUM_ATOMS; i += LOCAL_SIZE) {
        const mixed3 r = buildPositionOf(i, capture, posq, posqCorrection, slotOfAtom, buildPosition);
        low = make_mixed3(min(low.x, r.x), min(low.y, r.y), min(low.z, r.z));
        high = make_mixed3(max(high.x, r.x), max(high.y, r.y), max(high.z, r.z));
    }
    reduceBounds(low, high, lowest, highest, bounds);
}

/**
 * The first part of a step in one launch of SCAN_GROUP_SIZE-thread groups, its stages in ticket order (above):
 *   0 check   each particle's slot (slotOfAtom[original index]: atom reordering moves slots, not the order) and the
 *             step's build flags (parity p: flags[2 p] build, flags[2 p + 1] capture; the other parity's cleared):
 *             a build when the host asks (hostBuild: from buildPosition, unless a particle is too far from it;
 *             hostCapture: from the step's positions), or, from the step's positions, when some particle is farther
 *             than sqrt(limit2) from buildPosition (nearest image in the step's box: OpenMM may wrap positions
 *             between builds). A GenDPDEForce that shares the build (its neighbour list made from this build's
 *             cells, CommonGenDPDEBuildSource): listRebuild[0] = 1 where the order is built, or if listForced;
 *             forceErrors[0..1] cleared when clearForceErrors (that force's own check, which this one replaces,
 *             cleared them). Otherwise both point at one placeholder.
 * At a build only (a group that finds none due leaves the launch):
 *   1 assign  each particle's build position (the step's, stored, when capturing), its cell in the build's box (the
 *             step's, boxA..C; open boundaries: low, extent) by original index, the number per cell (cellCount zero)
 *   2 scan    the cells' first entries (scanInGroup, one unit; cellCount left zero)
 *   3 fill    each particle listed in its cell, in any order (cellFill zero before)
 *   4 sort    each cell's particles by original index (insertion sort: a cell holds a few); cellFill zero again.
 * The launch runs stages firstStage .. endStage - 1: all five with periodic boundaries; with open boundaries the
 * check, then, at a build, stages 1-4 once the host has the build's bounding box (findSweepBounds). atomUnits and
 * cellUnits: the units of the stages over particles and over cells. Pointers to what the launch writes and reads
 * again are neither const nor restrict (a read-only cache would not see the other groups' writes). PoCL 3.1's barrier
 * pass is fragile around this loop: a helper function for a stage's units made it fail an assertion
 * ("Incoming edges to non-entry block"), and a break or continue past a barrier hung it; run the OpenCL tests after
 * any change to its shape.
 */
KERNEL void prepareSweepBuild(int firstStage, int endStage, int atomUnits, int cellUnits,
        GLOBAL const real4* RESTRICT posq, GLOBAL const real4* RESTRICT posqCorrection,
        GLOBAL const int* RESTRICT atomIndex, GLOBAL mixed4* buildPosition, mixed4 boxA, mixed4 boxB, mixed4 boxC,
        mixed limit2, int parity, int hostBuild, int hostCapture, GLOBAL int* flags, GLOBAL int* slotOfAtom,
        GLOBAL int* status, GLOBAL int* listRebuild, int listForced, GLOBAL int* forceErrors, int clearForceErrors,
        mixed4 low, mixed4 extent, int4 cells, GLOBAL int* atomCell, GLOBAL int* cellCount, GLOBAL int* cellStart,
        GLOBAL int* cellFill, GLOBAL int* sortedAtom, GLOBAL int* schedule) {
    LOCAL int partial[SCAN_GROUP_SIZE];
    LOCAL int groupValues[1];   // the group's ticket
    int numUnits = 0;
    for (int stage = firstStage; stage < endStage; stage++)
        numUnits += (stage == 2 ? 1 : stage == 4 ? cellUnits : atomUnits);
    const int checkUnits = (firstStage == 0 ? atomUnits : 0);
    int ticket = takeTicket(schedule, groupValues);
    while (ticket < numUnits) {
        int stage = firstStage, before = 0;
        for (;; stage++) {
            const int units = (stage == 2 ? 1 : stage == 4 ? cellUnits : atomUnits);
            if (ticket < before + units)
                break;
            before += units;
        }
        const int unit = ticket - before, stride = atomUnits*LOCAL_SIZE;
        // A unit of the cells: only at a build (the check's flags, once every check unit is done, give every group
        // the same answer; a group that finds no build leaves the launch).
        // (Each thread reads the flags itself: they are final once the check is done.)
        int work = 1, capture = 0;
        if (stage > 0) {
            awaitUnits(schedule, checkUnits);
            work = (((volatile GLOBAL int*) flags)[2*parity] != 0 && status[STATUS_HALTED] == 0);
            capture = ((volatile GLOBAL int*) flags)[2*parity + 1];
        }
        if (work) {
            if (stage > 0)
                awaitUnits(schedule, before);
            if (stage == 0) {
                if (unit == 0 && LOCAL_ID == 0) {
                    flags[2*(1 - parity)] = 0;
                    flags[2*(1 - parity) + 1] = 0;
                    if (clearForceErrors)
                        forceErrors[0] = forceErrors[1] = NO_VALUE;
                    if (listForced)
                        listRebuild[0] = 1;
                    if (status[STATUS_HALTED] == 0 && (hostBuild || hostCapture)) {
                        flags[2*parity] = 1;
                        listRebuild[0] = 1;
                        if (hostCapture)
                            flags[2*parity + 1] = 1;
                    }
                }
                if (status[STATUS_HALTED] == 0)
                    for (int s = unit*LOCAL_SIZE + LOCAL_ID; s < NUM_ATOMS; s += stride) {
                        const int atom = atomIndex[s];
                        slotOfAtom[atom] = s;
                        if (!hostCapture) {
                            const mixed3 d = mixedPairDelta(loadMixedPosition(posq, posqCorrection, s),
                                                            trimTo3(buildPosition[atom]), boxA, boxB, boxC);
                            if (dot(d, d) > limit2) {
                                flags[2*parity] = 1;
                                flags[2*parity + 1] = 1;
                                listRebuild[0] = 1;
                            }
                        }
                    }
            } else if (stage == 1) {
                for (int atom = unit*LOCAL_SIZE + LOCAL_ID; atom < NUM_ATOMS; atom += stride) {
                    const mixed3 r = (capture ? loadMixedPosition(posq, posqCorrection, slotOfAtom[atom])
                                              : trimTo3(buildPosition[atom]));
                    if (capture)
                        buildPosition[atom] = make_mixed4(r.x, r.y, r.z, 0);
                    const int cell = cellIndex(cellOfPosition(r, boxA, boxB, boxC, low, extent, cells), cells);
                    atomCell[atom] = cell;
                    ATOMIC_ADD(&cellCount[cell], 1);
                }
            } else if (stage == 2)
                scanInGroup(partial, cellCount, cellStart, cells.w);
            else if (stage == 3)
                for (int atom = unit*LOCAL_SIZE + LOCAL_ID; atom < NUM_ATOMS; atom += stride) {
                    const int cell = atomCell[atom];
                    sortedAtom[cellStart[cell] + ATOMIC_ADD(&cellFill[cell], 1)] = atom;
                }
            else
                for (int cell = unit*LOCAL_SIZE + LOCAL_ID; cell < cells.w; cell += cellUnits*LOCAL_SIZE) {
                    const int begin = cellStart[cell], end = cellStart[cell + 1];
                    cellFill[cell] = 0;
                    for (int k = begin + 1; k < end; k++) {
                        const int atom = sortedAtom[k];
                        int m = k - 1;
                        while (m >= begin && sortedAtom[m] > atom) {
                            sortedAtom[m + 1] = sortedAtom[m];
                            m--;
                        }
                        sortedAtom[m + 1] = atom;
                    }
                }
            finishUnit(schedule);
        }
        ticket = (work ? takeTicket(schedule, groupValues) : numUnits);
    }
    leaveLaunch(schedule);
}

/**
 * name(usedI, usedJ): the greedy level of a pair whose particles have used the levels in masks usedI, usedJ
 * (SWEEP_LEVEL_WORDS words each, in this address space; SweepDefinition::assignLevels): the smallest level in
 * neither, now marked in both; -1 if all are used.
 */
#define GENDPDE_GREEDY_LEVEL(name, space) \
inline DEVICE int name(space unsigned int* usedI, space unsigned int* usedJ) { \
    for (int w = 0; w < SWEEP_LEVEL_WORDS; w++) { \
        const unsigned int free = ~(usedI[w] | usedJ[w]); \
        if (free != 0) { \
            int bit = 0; \
            while (((free >> bit) & 1u) == 0) \
                bit++; \
            usedI[w] |= 1u << bit; \
            usedJ[w] |= 1u << bit; \
            return 32*w + bit; \
        } \
    } \
    return -1; \
}
GENDPDE_GREEDY_LEVEL(greedyLevelLocal, LOCAL_ARG)
GENDPDE_GREEDY_LEVEL(greedyLevelGlobal, GLOBAL)

/**
 * The candidates of particle i (region rank) in its block: the later particles of the region cells that can hold a
 * pair of the block with it, closer than sqrt(range2) at the build positions. Returns their number; their ranks go to
 * partners[n].x, in the order found, unless partners is null.
 */
inline DEVICE int blockPartners(int i, int numParticles, LOCAL_ARG const int* regionStart,
        LOCAL_ARG const int* regionCode, LOCAL_ARG const int* rankInRegion, LOCAL_ARG const int* codeOf,
        LOCAL_ARG const mixed4* positionOf, mixed4 boxA, mixed4 boxB, mixed4 boxC, mixed range2,
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
                if (dot(d, d) < range2) {
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
 * At a build: each block's order, SWEEP_BLOCKS_PER_GROUP blocks per work group, from the build's cells (cellStart,
 * sortedAtom), positions (buildPosition, by original index) and box (boxA..C), for candidates closer than
 * candidateRange: header[rank] = (particles in the region, pairs, levels, 1 if the block must be streamed),
 * blockAtoms[rank SWEEP_MAX_PARTICLES + k] the region's particles by original index, levelStart[rank (pairCapacity +
 * 1) + l] the first entry of level l in blockPairs[rank pairCapacity + ...] = (i << 16) | j. pairScratch holds the
 * pairs in (i, j) order with their levels while they are grouped. Counts the build (status[STATUS_BUILDS]).
 */
KERNEL void orderBlocks(GLOBAL const int* RESTRICT flags, int parity, int stepIndex, int4 cells, int4 blocks,
        GLOBAL const int* RESTRICT cellStart, GLOBAL const int* RESTRICT sortedAtom,
        GLOBAL const mixed4* RESTRICT buildPosition, mixed4 boxA, mixed4 boxB, mixed4 boxC, mixed candidateRange,
        int pairCapacity, GLOBAL int* RESTRICT status, GLOBAL int4* RESTRICT header, GLOBAL int* RESTRICT blockAtoms,
        GLOBAL int2* RESTRICT pairScratch, GLOBAL int* RESTRICT blockPairs, GLOBAL int* RESTRICT levelStart) {
    LOCAL int regionCells[27*SWEEP_BLOCKS_PER_GROUP], regionCodes[27*SWEEP_BLOCKS_PER_GROUP];
    LOCAL int regionStarts[28*SWEEP_BLOCKS_PER_GROUP], sharedValues[4*SWEEP_BLOCKS_PER_GROUP];
    LOCAL int firstPairs[SWEEP_MAX_PARTICLES*SWEEP_BLOCKS_PER_GROUP], codes[SWEEP_MAX_PARTICLES*SWEEP_BLOCKS_PER_GROUP];
    // Per particle (by rank): its position (then, once the pairs are listed, its mask of used levels: SWEEP_LEVEL_WORDS
    // words fit in a mixed4), its pair count, first pair and code; the rank of each particle in region order.
    LOCAL mixed4 positions[SWEEP_MAX_PARTICLES*SWEEP_BLOCKS_PER_GROUP];
    LOCAL int pairCounts[SWEEP_MAX_PARTICLES*SWEEP_BLOCKS_PER_GROUP], ranks[SWEEP_MAX_PARTICLES*SWEEP_BLOCKS_PER_GROUP];
    if (!building(flags, parity, status))
        return;
    if (GLOBAL_ID == 0)
        status[STATUS_BUILDS]++;
    const int sub = LOCAL_ID/SWEEP_BLOCK_THREADS, lane = LOCAL_ID%SWEEP_BLOCK_THREADS;
    LOCAL_ARG int* regionCell = regionCells + 27*sub;
    LOCAL_ARG int* regionCode = regionCodes + 27*sub;
    LOCAL_ARG int* regionStart = regionStarts + 28*sub;
    LOCAL_ARG int* shared = sharedValues + 4*sub;   // particles, pairs
    LOCAL_ARG int* firstPair = firstPairs + SWEEP_MAX_PARTICLES*sub;
    LOCAL_ARG int* codeOf = codes + SWEEP_MAX_PARTICLES*sub;
    LOCAL_ARG mixed4* positionOf = positions + SWEEP_MAX_PARTICLES*sub;
    LOCAL_ARG unsigned int* levelMask = (LOCAL_ARG unsigned int*) (positions + SWEEP_MAX_PARTICLES*sub);
    LOCAL_ARG int* pairCount = pairCounts + SWEEP_MAX_PARTICLES*sub;
    LOCAL_ARG int* rankInRegion = ranks + SWEEP_MAX_PARTICLES*sub;
    const mixed range2 = candidateRange*candidateRange;
    for (int base = GROUP_ID*SWEEP_BLOCKS_PER_GROUP; base < blocks.w; base += NUM_GROUPS*SWEEP_BLOCKS_PER_GROUP) {
        // Every thread passes every barrier; a block with nothing (left) to do runs its loops zero times.
        const int rank = base + sub;
        const bool active = (rank < blocks.w);
        GLOBAL int2* scratch = pairScratch + (size_t) rank*pairCapacity;
        GLOBAL int* pairs = blockPairs + (size_t) rank*pairCapacity;
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
            const int atom = sortedAtom[cellStart[regionCell[r]] + k - regionStart[r]];
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
            positionOf[position] = buildPosition[atom];
            blockAtoms[(size_t) rank*SWEEP_MAX_PARTICLES + position] = atom;
            rankInRegion[k] = position;
        }
        SYNC_THREADS;
        // Each particle's candidates among the later particles of the block, counted.
        for (int i = lane; i < numParticles; i += SWEEP_BLOCK_THREADS)
            pairCount[i] = blockPartners(i, numParticles, regionStart, regionCode, rankInRegion, codeOf, positionOf,
                                         boxA, boxB, boxC, range2, 0);
        SYNC_THREADS;
        // The first pair of each particle's list: the pairs in (i, j) order.
        if (numParticles > 0 && lane == 0) {
            int total = 0;
            for (int i = 0; i < numParticles; i++) {
                firstPair[i] = total;
                total += pairCount[i];
            }
            shared[1] = total;
            ATOMIC_MAX(&status[STATUS_MOST_PAIRS], total);
            if (total > pairCapacity) {
                header[rank] = make_int4(numParticles, total, 0, 1);
                ATOMIC_ADD(&status[STATUS_STREAMED], 1);
            }
        }
        SYNC_THREADS;
        const bool ordered = (numParticles > 0 && shared[1] <= pairCapacity);
        const int numPairs = (ordered ? shared[1] : 0);
        const int listed = (ordered ? numParticles : 0);
        // Each particle's candidates in (i, j) order, in the scratch slab: listed, then sorted by j.
        for (int i = lane; i < listed; i += SWEEP_BLOCK_THREADS) {
            if (pairCount[i] == 0)
                continue;
            GLOBAL int2* partners = scratch + firstPair[i];
            const int n = blockPartners(i, numParticles, regionStart, regionCode, rankInRegion, codeOf, positionOf,
                                        boxA, boxB, boxC, range2, partners);
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
        // The positions are no longer needed: their space holds each particle's mask of used levels.
        for (int k = lane; k < listed*SWEEP_LEVEL_WORDS; k += SWEEP_BLOCK_THREADS)
            levelMask[k] = 0;
        if (ordered)
            for (int l = lane; l <= numPairs; l += SWEEP_BLOCK_THREADS)
                levels[l] = 0;
        SYNC_THREADS;
        // The levels by the greedy rule, in (i, j) order, counted per level; then the pairs grouped by level ((i, j)
        // order within a level).
        if (ordered && lane == 0) {
            int numLevels = 0;
            bool tooMany = false;
            for (int i = 0; i < numParticles && !tooMany; i++)
                for (int n = firstPair[i]; n < firstPair[i] + pairCount[i]; n++) {
                    const int j = scratch[n].x;
                    const int level = greedyLevelLocal(levelMask + i*SWEEP_LEVEL_WORDS, levelMask + j*SWEEP_LEVEL_WORDS);
                    if (level < 0) {   // more levels than the masks hold: the run stops
                        haltRun(status, HALT_LEVELS, stepIndex);
                        tooMany = true;
                        break;
                    }
                    scratch[n] = make_int2((i << 16) | j, level);
                    levels[level + 1]++;
                    numLevels = max(numLevels, level + 1);
                }
            if (tooMany)
                numLevels = 0;
            for (int l = 0; l < numLevels; l++)
                levels[l + 1] += levels[l];
            for (int n = 0; n < numPairs && numLevels > 0; n++) {
                const int2 entry = scratch[n];
                pairs[levels[entry.y]++] = entry.x;
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

/** Particle i's candidates in a streamed block, later particles of the block in index order, one at a time. */
typedef struct {
    int next[27];            // a cursor per region cell
    unsigned int mask;       // the region cells whose particles can pair with i in this block
    int i, j;                // original indices; j < 0 once the run is exhausted
    mixed3 ri;               // i's build position
} StreamRun;

/** Advance a run to its next candidate (j = -1 if none), closer than sqrt(range2) at the build positions. */
inline DEVICE void nextPartner(const StreamRegion* region, StreamRun* run, GLOBAL const int* RESTRICT sortedAtom,
        GLOBAL const mixed4* RESTRICT buildPosition, mixed4 boxA, mixed4 boxB, mixed4 boxC, mixed range2) {
    int which;
    run->j = -1;
    for (int m = nextOfRegion(region, run->next, run->mask, sortedAtom, &which); m >= 0;
             m = nextOfRegion(region, run->next, run->mask, sortedAtom, &which)) {
        const int atom = sortedAtom[m];
        if (atom <= run->i)
            continue;
        const mixed3 d = mixedPairDelta(run->ri, trimTo3(buildPosition[atom]), boxA, boxB, boxC);
        if (dot(d, d) < range2) {
            run->j = atom;
            return;
        }
    }
}

/**
 * The sweep of one block by one thread (for blocks beyond the capacities of orderBlocks; any number of particles and
 * pairs): the candidates found again from the build's cells (cellStart, sortedAtom), positions and box (build*), in
 * (i, j) order, their greedy levels kept per particle in levelMasks (by original index, SWEEP_LEVEL_WORDS words each;
 * no other block of the colour touches these particles); one pass to count the levels, then one pass per level that
 * updates that level's pairs closer than the cutoff at the step's positions. Returns the sequence position of the first
 * pair after which an internal energy is <= 0, with that particle and its energy, or -1; -2 if the block needs more
 * levels than the masks hold.
 */
DEVICE int streamBlock(int3 block, int4 cells, GLOBAL const int* RESTRICT cellStart,
        GLOBAL const int* RESTRICT sortedAtom, GLOBAL const mixed4* RESTRICT buildPosition, mixed4 buildA,
        mixed4 buildB, mixed4 buildC, mixed candidate2, GLOBAL unsigned int* RESTRICT levelMasks,
        GLOBAL const int* RESTRICT slotOfAtom, GLOBAL const real4* RESTRICT posq,
        GLOBAL const real4* RESTRICT posqCorrection, GLOBAL mixed4* RESTRICT velm, GLOBAL mixed* RESTRICT energies,
        mixed4 boxA, mixed4 boxB, mixed4 boxC, GLOBAL const int* RESTRICT atomType, SweepConstants c,
        GLOBAL const mixed4* RESTRICT pairTable, GLOBAL const mixed* RESTRICT heatCapacityTable,
        GLOBAL const randomReal* RESTRICT zigguratX, GLOBAL const randomReal* RESTRICT zigguratF,
        GLOBAL const randomReal* RESTRICT zigguratRatio, int* failedParticle, mixed* failedEnergy) {
    StreamRegion region;
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
                region.end[region.count++] = cellStart[cell + 1];
            }
    const mixed cutoff2 = c.cutoff*c.cutoff;
    int position = 0, numLevels = 0;
    for (int level = -1; level < numLevels; level++) {
        // A pass over the candidates in (i, j) order, from no level used.
        for (int q = 0; q < region.count; q++)
            for (int m = cellStart[region.cell[q]]; m < region.end[q]; m++)
                for (int w = 0; w < SWEEP_LEVEL_WORDS; w++)
                    levelMasks[(size_t) sortedAtom[m]*SWEEP_LEVEL_WORDS + w] = 0;
        int firstNext[27], which;
        for (int q = 0; q < region.count; q++)
            firstNext[q] = cellStart[region.cell[q]];
        for (int m = nextOfRegion(&region, firstNext, 0xFFFFFFFFu, sortedAtom, &which); m >= 0;
                 m = nextOfRegion(&region, firstNext, 0xFFFFFFFFu, sortedAtom, &which)) {
            StreamRun run;
            run.mask = 0;
            for (int q = 0; q < region.count; q++) {
                run.next[q] = cellStart[region.cell[q]];
                if (pairOfBlock(region.code[which], region.code[q]))
                    run.mask |= 1u << q;
            }
            run.i = sortedAtom[m];
            run.ri = trimTo3(buildPosition[run.i]);
            for (nextPartner(&region, &run, sortedAtom, buildPosition, buildA, buildB, buildC, candidate2);
                     run.j >= 0;
                     nextPartner(&region, &run, sortedAtom, buildPosition, buildA, buildB, buildC, candidate2)) {
                const int i = run.i, j = run.j;
                const int pairLevel = greedyLevelGlobal(levelMasks + (size_t) i*SWEEP_LEVEL_WORDS,
                                                        levelMasks + (size_t) j*SWEEP_LEVEL_WORDS);
                if (pairLevel < 0)
                    return -2;
                if (level < 0) {
                    numLevels = max(numLevels, pairLevel + 1);
                    continue;
                }
                if (pairLevel != level)
                    continue;
                const int slotI = slotOfAtom[i], slotJ = slotOfAtom[j];
                const mixed3 d = mixedPairDelta(loadMixedPosition(posq, posqCorrection, slotI),
                                                loadMixedPosition(posq, posqCorrection, slotJ), boxA, boxB, boxC);
                if (!(dot(d, d) < cutoff2)) {
                    position++;
                    continue;
                }
                mixed4 vi = velm[slotI], vj = velm[slotJ];
                mixed ei = 0, ej = 0;
                if (c.internalEnergies) {
                    ei = energies[i];
                    ej = energies[j];
                }
                const bool failed = pairUpdate(i, j, d, atomType[i], atomType[j], &vi, &vj, &ei, &ej, c, pairTable,
                                               heatCapacityTable, zigguratX, zigguratF, zigguratRatio);
                velm[slotI] = vi;
                velm[slotJ] = vj;
                if (c.internalEnergies) {
                    energies[i] = ei;
                    energies[j] = ej;
                }
                if (failed) {
                    *failedParticle = (ei > 0 ? j : i);
                    *failedEnergy = (ei > 0 ? ej : ei);
                    return position;
                }
                position++;
            }
        }
    }
    return -1;
}

/**
 * The colours firstColour .. endColour - 1 of the sweep, in one launch (stages in ticket order, above): a unit is
 * SWEEP_BLOCKS_PER_GROUP blocks of one colour, each swept level by level (orderBlocks) or, when orderBlocks could not
 * hold it, streamed by one thread. Each pair of the order is updated only if it is closer than the cutoff at the
 * step's positions (posq, boxA..C). parameters = (cutoff, dt, sqrt(dt), k_B); terms bit 0: dissipation, bit 1:
 * conduction, bit 2: internal energies. A block after which an internal energy is <= 0 records the first such pair of
 * its sequence (failure[rank] = particle, failureEnergy[rank] = its energy) and stops the run (HALT_SWEEP; FAILED_RANK
 * the smallest failed rank); the colours after it do nothing, and finishStep rolls the step back. The build's cells,
 * positions and box (build*, candidateRange) serve the streamed blocks.
 */
KERNEL void sweepBlocks(int firstColour, int endColour, int4 cells, int4 blocks, GLOBAL const int4* RESTRICT header,
        GLOBAL const int* RESTRICT blockAtoms, GLOBAL const int* RESTRICT levelStart,
        GLOBAL const int* RESTRICT blockPairs, int pairCapacity, GLOBAL const int* RESTRICT cellStart,
        GLOBAL const int* RESTRICT sortedAtom, GLOBAL const mixed4* RESTRICT buildPosition, mixed4 buildA,
        mixed4 buildB, mixed4 buildC, mixed candidateRange, GLOBAL unsigned int* RESTRICT levelMasks,
        GLOBAL const int* RESTRICT slotOfAtom, GLOBAL const real4* RESTRICT posq,
        GLOBAL const real4* RESTRICT posqCorrection, GLOBAL mixed4* RESTRICT velm, GLOBAL mixed* RESTRICT energies,
        mixed4 boxA, mixed4 boxB, mixed4 boxC, mixed4 parameters, GLOBAL const int* RESTRICT atomType,
        GLOBAL const mixed4* RESTRICT pairTable, GLOBAL const mixed* RESTRICT heatCapacityTable, int numClasses,
        int terms, unsigned int seed, unsigned int stepLow, unsigned int stepHigh, int stepIndex,
        GLOBAL const randomReal* RESTRICT zigguratX, GLOBAL const randomReal* RESTRICT zigguratF,
        GLOBAL const randomReal* RESTRICT zigguratRatio, GLOBAL int* RESTRICT status, GLOBAL int* RESTRICT failure,
        GLOBAL mixed* RESTRICT failureEnergy, GLOBAL int* RESTRICT schedule) {
    LOCAL mixed4 velocities[SWEEP_MAX_PARTICLES*SWEEP_BLOCKS_PER_GROUP];
    LOCAL mixed internalEnergies[SWEEP_MAX_PARTICLES*SWEEP_BLOCKS_PER_GROUP];
    LOCAL int types[SWEEP_MAX_PARTICLES*SWEEP_BLOCKS_PER_GROUP], slots[SWEEP_MAX_PARTICLES*SWEEP_BLOCKS_PER_GROUP];
    LOCAL int atoms[SWEEP_MAX_PARTICLES*SWEEP_BLOCKS_PER_GROUP];
    LOCAL int firstFailures[SWEEP_BLOCKS_PER_GROUP], levelCounts[SWEEP_BLOCKS_PER_GROUP];
    LOCAL int groupValues[1];   // the group's ticket
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
    const mixed cutoff2 = c.cutoff*c.cutoff;
    int numUnits = 0;
    for (int colour = firstColour; colour < endColour; colour++)
        numUnits += (colourBlocks(colour, blocks) + SWEEP_BLOCKS_PER_GROUP - 1)/SWEEP_BLOCKS_PER_GROUP;
    for (int ticket = takeTicket(schedule, groupValues); ticket < numUnits;
             ticket = takeTicket(schedule, groupValues)) {
        // The ticket's colour, its first rank and its blocks (as blockOfRank), and the units of the colours before it.
        int colour = firstColour, unitsBefore = 0, firstRank = 0, count = 0;
        for (int k = 0; k < 8; k++) {
            count = colourBlocks(k, blocks);
            if (k >= firstColour) {
                const int units = (count + SWEEP_BLOCKS_PER_GROUP - 1)/SWEEP_BLOCKS_PER_GROUP;
                if (ticket < unitsBefore + units) {
                    colour = k;
                    break;
                }
                unitsBefore += units;
            }
            firstRank += count;
        }
        const bool stopped = awaitStage(schedule, unitsBefore, colour, status);
        // Every thread passes every barrier; a block with nothing (left) to do runs its loops zero times.
        const int base = (ticket - unitsBefore)*SWEEP_BLOCKS_PER_GROUP;
        const int rank = firstRank + base + sub;
        const bool active = (!stopped && base + sub < count);
        const int4 info = (active ? header[rank] : make_int4(0, 0, 0, 0));
        if (info.w != 0 && lane == 0) {
            // Beyond the capacities: one thread streams the block's pairs in sequence.
            int particle;
            mixed energy;
            const int failed = streamBlock(blockOfRank(rank, blocks), cells, cellStart, sortedAtom, buildPosition,
                    buildA, buildB, buildC, candidateRange*candidateRange, levelMasks, slotOfAtom, posq,
                    posqCorrection, velm, energies, boxA, boxB, boxC, atomType, c, pairTable, heatCapacityTable,
                    zigguratX, zigguratF, zigguratRatio, &particle, &energy);
            if (failed == -2)
                stopInStage(schedule, colour, status, HALT_LEVELS, stepIndex);
            else if (failed >= 0) {
                failure[rank] = particle;
                failureEnergy[rank] = energy;
                ATOMIC_MIN(&status[STATUS_FAILED_RANK], rank);
                stopInStage(schedule, colour, status, HALT_SWEEP, stepIndex);
            }
        }
        const int numParticles = (info.w == 0 ? info.x : 0), numLevels = (info.w == 0 ? info.z : 0);
        GLOBAL const int* particleAtom = blockAtoms + (size_t) rank*SWEEP_MAX_PARTICLES;
        for (int k = lane; k < numParticles; k += SWEEP_BLOCK_THREADS) {
            const int atom = particleAtom[k], slot = slotOfAtom[atom];
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
        // The levels in turn; after a failure only the pairs before it in the sequence (the level order, as stored)
        // still matter (a later pair never precedes an earlier one of the same particle), and the first failing pair
        // is the one reported.
        GLOBAL const int* levels = levelStart + (size_t) rank*(pairCapacity + 1);
        GLOBAL const int* pairs = blockPairs + (size_t) rank*pairCapacity;
        int myFailure = NO_VALUE, myParticle = -1;
        mixed myEnergy = 0;
        for (int level = 0; level < groupLevels; level++) {
            const int end = (level < numLevels ? levels[level + 1] : 0);
            for (int n = (level < numLevels ? levels[level] : 0) + lane; n < end; n += SWEEP_BLOCK_THREADS) {
                if (n > firstFailures[sub])
                    continue;
                const int entry = pairs[n], i = entry >> 16, j = entry & 0xFFFF;
                const mixed3 d = mixedPairDelta(loadMixedPosition(posq, posqCorrection, slotOf[i]),
                                                loadMixedPosition(posq, posqCorrection, slotOf[j]), boxA, boxB, boxC);
                if (!(dot(d, d) < cutoff2))
                    continue;   // a candidate beyond the cutoff at this step
                mixed4 vi = velocityOf[i], vj = velocityOf[j];
                mixed ei = energyOf[i], ej = energyOf[j];
                const bool failed = pairUpdate(atomOf[i], atomOf[j], d, typeOf[i], typeOf[j], &vi, &vj, &ei, &ej, c,
                        pairTable, heatCapacityTable, zigguratX, zigguratF, zigguratRatio);
                velocityOf[i] = vi;
                velocityOf[j] = vj;
                energyOf[i] = ei;
                energyOf[j] = ej;
                if (failed && n < myFailure) {
                    myFailure = n;
                    myParticle = (ei > 0 ? atomOf[j] : atomOf[i]);
                    myEnergy = (ei > 0 ? ej : ei);
                    ATOMIC_MIN(&firstFailures[sub], n);
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
            stopInStage(schedule, colour, status, HALT_SWEEP, stepIndex);
        }
        if (active && lane == 0)
            ATOMIC_MAX(&status[STATUS_LEVELS + colour], numLevels);
        finishUnit(schedule);
    }
    leaveLaunch(schedule);
}
