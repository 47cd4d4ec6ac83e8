/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
#ifdef __OPENCL_VERSION__
#define ATOMIC_MIN(p, v) atomic_min(p, v)
#define ATOMIC_MAX(p, v) atomic_max(p, v)
#define ATOMIC_CAS(p, compare, v) atomic_cmpxchg(p, compare, v)
#else
#define ATOMIC_MIN(p, v) atomicMin(p, v)
#define ATOMIC_MAX(p, v) atomicMax(p, v)
#define ATOMIC_CAS(p, compare, v) atomicCAS(p, compare, v)
#endif

/* The cell grid of GenDPDE's device kernels (CommonGenDPDECellGrid): the cells of GenDPDESweepOrder (docs/theory.md
 * section 6), at least R wide, so that every pair closer than R lies in the same or adjacent cells. The particles are
 * listed cell by cell, by original index inside a cell, so that every loop over neighbours runs in an order that does
 * not depend on atom reordering or on the thread schedule.
 *
 * Defines: NUM_ATOMS, SCAN_GROUP_SIZE, BOUNDS_GROUP_SIZE, and USE_PERIODIC or not; USE_MIXED_PRECISION as OpenMM
 * sets it. The grid, cells = (n_x, n_y, n_z, n_x n_y n_z), is an argument: it changes with the box. A slot, in every
 * device kernel of the plugin, is an atom's position in OpenMM's per-atom arrays (posq, velm, the force buffers),
 * which atom reordering changes; the original index never changes. The argument order of each kernel is the enum of
 * the same name in CommonGenDPDECellGrid.cpp. */

/** The position of the particle in slot `index`, in mixed precision (posq plus its correction when mixed). */
inline DEVICE mixed3 loadMixedPosition(GLOBAL const real4* RESTRICT posq, GLOBAL const real4* RESTRICT posqCorrection,
                                       int index) {
    real4 pos = posq[index];
#ifdef USE_MIXED_PRECISION
    real4 correction = posqCorrection[index];
    return make_mixed3(pos.x + (mixed) correction.x, pos.y + (mixed) correction.y, pos.z + (mixed) correction.z);
#else
    return make_mixed3(pos.x, pos.y, pos.z);
#endif
}

/** The cell (x, y, z) of a position, as GenDPDESweepOrder computes it on the host. */
inline DEVICE int3 cellOfPosition(mixed3 r, mixed4 boxA, mixed4 boxB, mixed4 boxC, mixed4 low, mixed4 extent,
                                  int4 cells) {
    mixed unit[3];
#ifdef USE_PERIODIC
    // Fractional coordinates in the reduced box, wrapped into [0, 1).
    mixed sz = r.z/boxC.z;
    mixed sy = (r.y - sz*boxC.y)/boxB.y;
    mixed sx = (r.x - sz*boxC.x - sy*boxB.x)/boxA.x;
    unit[0] = sx - floor(sx);
    unit[1] = sy - floor(sy);
    unit[2] = sz - floor(sz);
#else
    unit[0] = (extent.x > 0 ? (r.x - low.x)/extent.x : (mixed) 0);
    unit[1] = (extent.y > 0 ? (r.y - low.y)/extent.y : (mixed) 0);
    unit[2] = (extent.z > 0 ? (r.z - low.z)/extent.z : (mixed) 0);
#endif
    int3 cell;
    cell.x = max(0, min(cells.x - 1, (int) (unit[0]*cells.x)));
    cell.y = max(0, min(cells.y - 1, (int) (unit[1]*cells.y)));
    cell.z = max(0, min(cells.z - 1, (int) (unit[2]*cells.z)));
    return cell;
}

inline DEVICE int cellIndex(int3 c, int4 cells) {
    return (c.z*cells.y + c.y)*cells.x + c.x;
}

inline DEVICE int3 cellCoordinates(int index, int4 cells) {
    return make_int3(index%cells.x, (index/cells.x)%cells.y, index/(cells.x*cells.y));
}

/**
 * The work group's bounding box from each thread's (low, high): bounds = (low.xyz, high.xyz). lowest and highest:
 * local scratch of 3 LOCAL_SIZE each.
 */
inline DEVICE void reduceBounds(mixed3 low, mixed3 high, LOCAL_ARG mixed* lowest, LOCAL_ARG mixed* highest,
                                GLOBAL mixed* RESTRICT bounds) {
    lowest[3*LOCAL_ID] = low.x;
    lowest[3*LOCAL_ID + 1] = low.y;
    lowest[3*LOCAL_ID + 2] = low.z;
    highest[3*LOCAL_ID] = high.x;
    highest[3*LOCAL_ID + 1] = high.y;
    highest[3*LOCAL_ID + 2] = high.z;
    SYNC_THREADS;
    if (LOCAL_ID < 3) {
        mixed a = lowest[LOCAL_ID], b = highest[LOCAL_ID];
        for (int t = 1; t < LOCAL_SIZE; t++) {
            a = min(a, lowest[3*t + LOCAL_ID]);
            b = max(b, highest[3*t + LOCAL_ID]);
        }
        bounds[LOCAL_ID] = a;
        bounds[3 + LOCAL_ID] = b;
    }
}

/** The bounding box of the particles (open boundaries): one work group; bounds = (low.xyz, high.xyz). */
KERNEL void findBounds(GLOBAL const real4* RESTRICT posq, GLOBAL const real4* RESTRICT posqCorrection,
                       GLOBAL mixed* RESTRICT bounds) {
    LOCAL mixed lowest[3*BOUNDS_GROUP_SIZE];
    LOCAL mixed highest[3*BOUNDS_GROUP_SIZE];
    mixed3 low = loadMixedPosition(posq, posqCorrection, 0), high = low;
    for (int i = LOCAL_ID; i < NUM_ATOMS; i += LOCAL_SIZE) {
        mixed3 r = loadMixedPosition(posq, posqCorrection, i);
        low = make_mixed3(min(low.x, r.x), min(low.y, r.y), min(low.z, r.z));
        high = make_mixed3(max(high.x, r.x), max(high.y, r.y), max(high.z, r.z));
    }
    reduceBounds(low, high, lowest, highest, bounds);
}

/*
 * The grid's kernels take gate first: they build only when gate[0] != 0 (the neighbour list's rebuild mark, set on the
 * device by checkList, or an array holding 1 where the grid is built at every evaluation), and otherwise return at
 * once, so that the grid of the last list build is kept without the host knowing when that was.
 */

/** Each slot's cell, and the number of particles per cell (cellCount cleared before). */
KERNEL void assignCells(GLOBAL const int* RESTRICT gate, GLOBAL const real4* RESTRICT posq, GLOBAL const real4* RESTRICT posqCorrection,
                        mixed4 boxA, mixed4 boxB, mixed4 boxC, mixed4 low, mixed4 extent, int4 cells,
                        GLOBAL int* RESTRICT slotCell, GLOBAL int* RESTRICT cellCount) {
    if (gate[0] == 0)
        return;
    for (int slot = GLOBAL_ID; slot < NUM_ATOMS; slot += GLOBAL_SIZE) {
        int cell = cellIndex(cellOfPosition(loadMixedPosition(posq, posqCorrection, slot), boxA, boxB, boxC, low,
                                            extent, cells), cells);
        slotCell[slot] = cell;
        ATOMIC_ADD(&cellCount[cell], 1);
    }
}

/**
 * Exclusive prefix sums of counts[0..n) into starts[0..n], in one work group of SCAN_GROUP_SIZE threads (partial:
 * SCAN_GROUP_SIZE ints of local memory): each thread sums a contiguous range, the range totals are scanned, then each
 * range is written. The counts are left zero, ready for the next count. Returns the total (to thread 0).
 */
inline DEVICE int scanInGroup(LOCAL_ARG int* partial, GLOBAL int* RESTRICT counts, GLOBAL int* RESTRICT starts,
                              int n) {
    const int perThread = (n + SCAN_GROUP_SIZE - 1)/SCAN_GROUP_SIZE;
    const int begin = min(n, (int) LOCAL_ID*perThread), end = min(n, begin + perThread);
    int sum = 0;
    for (int i = begin; i < end; i++)
        sum += counts[i];
    partial[LOCAL_ID] = sum;
    SYNC_THREADS;
    if (LOCAL_ID == 0) {
        int total = 0;
        for (int t = 0; t < SCAN_GROUP_SIZE; t++) {
            int value = partial[t];
            partial[t] = total;
            total += value;
        }
        starts[n] = total;
    }
    SYNC_THREADS;
    int running = partial[LOCAL_ID];
    for (int i = begin; i < end; i++) {
        starts[i] = running;
        running += counts[i];
        counts[i] = 0;
    }
    return starts[n];
}

/** scanInGroup's prefix sums, the total also into totalOut[totalIndex]. */
KERNEL void exclusiveScan(GLOBAL const int* RESTRICT gate, GLOBAL int* RESTRICT counts, GLOBAL int* RESTRICT starts,
                          int n, GLOBAL int* RESTRICT totalOut, int totalIndex) {
    LOCAL int partial[SCAN_GROUP_SIZE];
    if (gate[0] == 0)
        return;
    const int total = scanInGroup(partial, counts, starts, n);
    if (LOCAL_ID == 0)
        totalOut[totalIndex] = total;
}

/** List each slot in its cell (in any order; sortCells orders them and clears cellFill again). cellFill zero before. */
KERNEL void fillCells(GLOBAL const int* RESTRICT gate, GLOBAL const int* RESTRICT slotCell, GLOBAL const int* RESTRICT cellStart,
                      GLOBAL int* RESTRICT cellFill, GLOBAL int* RESTRICT sortedSlot) {
    if (gate[0] == 0)
        return;
    for (int slot = GLOBAL_ID; slot < NUM_ATOMS; slot += GLOBAL_SIZE) {
        int cell = slotCell[slot];
        sortedSlot[cellStart[cell] + ATOMIC_ADD(&cellFill[cell], 1)] = slot;
    }
}

/**
 * Order each cell's particles by original index (insertion sort: a cell holds a few particles), and copy their
 * original indices and positions (real precision: the positions of the build, which buildList reads) into cell
 * order; cellFill zero again.
 */
KERNEL void sortCells(GLOBAL const int* RESTRICT gate, int4 cells, GLOBAL const int* RESTRICT cellStart, GLOBAL int* RESTRICT cellFill,
                      GLOBAL int* RESTRICT sortedSlot,
                      GLOBAL const int* RESTRICT atomIndex, GLOBAL int* RESTRICT sortedAtom,
                      GLOBAL int* RESTRICT sortedCell, GLOBAL const real4* RESTRICT posq,
                      GLOBAL real4* RESTRICT sortedPos) {
    if (gate[0] == 0)
        return;
    for (int cell = GLOBAL_ID; cell < cells.w; cell += GLOBAL_SIZE) {
        const int begin = cellStart[cell], end = cellStart[cell + 1];
        cellFill[cell] = 0;
        for (int k = begin + 1; k < end; k++) {
            const int slot = sortedSlot[k], atom = atomIndex[slot];
            int m = k - 1;
            while (m >= begin && atomIndex[sortedSlot[m]] > atom) {
                sortedSlot[m + 1] = sortedSlot[m];
                m--;
            }
            sortedSlot[m + 1] = slot;
        }
        for (int k = begin; k < end; k++) {
            const int slot = sortedSlot[k];
            sortedAtom[k] = atomIndex[slot];
            sortedCell[k] = cell;
            sortedPos[k] = posq[slot];
        }
    }
}

/** The neighbouring cells along one direction: offsets lo..hi (periodic grids of 1 or 2 cells visit each once). */
inline DEVICE int2 neighbourOffsets(int numCells) {
#ifdef USE_PERIODIC
    return make_int2(numCells >= 3 ? -1 : 0, numCells >= 2 ? 1 : 0);
#else
    return make_int2(-1, 1);
#endif
}

/** Cell coordinate c + d along a direction of n cells: wrapped if periodic, -1 if outside an open grid. */
inline DEVICE int shiftCell(int c, int d, int n) {
    c += d;
#ifdef USE_PERIODIC
    return (c < 0 ? c + n : (c >= n ? c - n : c));
#else
    return (c < 0 || c >= n ? -1 : c);
#endif
}

/**
 * for every cell next to `home` (itself included), once each: the statement that follows runs with cx, cy, cz the
 * cell's coordinates and cell its index (periodic grids wrap; open grids skip cells outside).
 */
#define FOR_EACH_NEIGHBOUR_CELL(home, cells, cx, cy, cz, cell) \
    for (int dz_ = neighbourOffsets(cells.z).x; dz_ <= neighbourOffsets(cells.z).y; dz_++) \
    for (int dy_ = neighbourOffsets(cells.y).x; dy_ <= neighbourOffsets(cells.y).y; dy_++) \
    for (int dx_ = neighbourOffsets(cells.x).x; dx_ <= neighbourOffsets(cells.x).y; dx_++) \
    for (int cz = shiftCell(home.z, dz_, cells.z), cy = shiftCell(home.y, dy_, cells.y), \
             cx = shiftCell(home.x, dx_, cells.x), cell = (cz*cells.y + cy)*cells.x + cx, \
             once_ = (cx >= 0 && cy >= 0 && cz >= 0); once_; once_ = 0)

#ifdef USE_PERIODIC
#define GENDPDE_PERIODIC 1
#else
#define GENDPDE_PERIODIC 0
#endif

/**
 * name(r_i, r_j, box) = r_i - r_j for the nearest image (periodic: OpenMM's reduced box, valid for r < half the
 * smallest width), in one precision. The box vectors' w components hold 1/a_x, 1/b_y, 1/c_z
 * (CommonGenDPDECellGrid::setBoxArguments): a multiplication where the host divides, which picks the same image for
 * every pair closer than half the box, the only ones whose image matters. Image shifts round to nearest even (rint),
 * which is odd-symmetric: r_j - r_i gets exactly the opposite vector, so both particles of a pair see the same pair.
 */
#define GENDPDE_NEAREST_IMAGE(name, scalar, vector3, vector4) \
inline DEVICE vector3 name(vector3 ri, vector3 rj, vector4 boxA, vector4 boxB, vector4 boxC) { \
    vector3 d = ri - rj; \
    if (GENDPDE_PERIODIC) { \
        scalar scale = rint(d.z*boxC.w); \
        d.x -= boxC.x*scale; \
        d.y -= boxC.y*scale; \
        d.z -= boxC.z*scale; \
        scale = rint(d.y*boxB.w); \
        d.x -= boxB.x*scale; \
        d.y -= boxB.y*scale; \
        scale = rint(d.x*boxA.w); \
        d.x -= boxA.x*scale; \
    } \
    return d; \
}
GENDPDE_NEAREST_IMAGE(pairDelta, real, real3, real4)            /* the force's positions, `real` */
GENDPDE_NEAREST_IMAGE(mixedPairDelta, mixed, mixed3, mixed4)    /* the integrator's, `mixed` */
