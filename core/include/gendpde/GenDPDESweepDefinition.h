/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
#ifndef GENDPDE_SWEEP_DEFINITION_H_
#define GENDPDE_SWEEP_DEFINITION_H_

/* The definition of the sweep's order of pair updates (GenDPDESweepOrder.h says it in full) as small functions with
 * no dependencies, so that every engine that runs the sweep computes the same cells, blocks, colours and order within
 * a block: the OpenMM platforms (through GenDPDESweepOrder) and the LAMMPS package (lammps/, across MPI ranks). */

#include "gendpde/IntegerRounding.h"
#include <algorithm>
#include <cmath>

namespace GenDPDEPlugin {
namespace SweepDefinition {

/** The number of colours: the parities of a block's three indices. */
const int numColours = 8;

/** Cells are at least this factor times the range wide, so that rounding can never put a pair in range two cells
 *  apart. */
const double cellMargin = 1.0 + 1e-9;

/**
 * The number of cells along one direction of a region this wide (a periodic box's perpendicular width, or the extent
 * of the particles' bounding box) for pairs closer than range: as many cells at least cellMargin range wide as fit,
 * rounded down to a multiple of 4 when periodic (or 2 or 1 when fewer than 4 fit), at most 10^6.
 */
inline int cellCount(double extent, double range, bool periodic) {
    const double fit = std::floor(extent / (cellMargin * range));
    const int m = (int) std::min(fit, 1e6);
    if (periodic)
        return m >= 4 ? 4 * (m / 4) : (m >= 2 ? 2 : 1);
    return std::max(1, m);
}

/**
 * The fewest cells per direction of a periodic box that a sweep split across subdomains takes (the LAMMPS fix: a
 * block of 2 cells and its neighbours' reach must fit in the box without meeting their own images).
 */
const int minCellsAcrossSubdomains = 4;

/**
 * How far around its subdomain an engine that splits the sweep across subdomains (the LAMMPS fix) needs the other
 * subdomains' particles (ghosts), for a periodic box of these three widths, pair range and neighbour skin: 1.5
 * widths of the widest sweep cell (a block's pairs reach its 3 x 3 x 3 cells around a centre that may lie anywhere
 * in the subdomain) plus the skin (a particle moves up to half the skin between neighbour lists, and so may its
 * partner). The box must have at least minCellsAcrossSubdomains cells along each direction.
 */
inline double ghostCutoff(const double widths[3], double range, double skin) {
    double widest = 0.0;
    for (int d = 0; d < 3; d++)
        widest = std::max(widest, widths[d] / cellCount(widths[d], range, true));
    return 1.5 * widest + skin;
}

/**
 * The cell along one direction of a particle at fractional coordinate s of a periodic box (any real s: the particle
 * is wrapped), of numCells cells.
 */
inline int periodicCell(double s, int numCells) {
    const double unit = s - BoxGeometry::floorToInteger(s);
    return std::max(0, std::min(numCells - 1, (int) (unit * numCells)));
}

/** The colour of block (bx, by, bz): blocks of one colour share no particle. */
inline int blockColour(int bx, int by, int bz) {
    return (bx % 2) + 2 * (by % 2) + 4 * (bz % 2);
}

/**
 * The order within a block: copy its pairs listed[0..count) (sorted by their first particles first[0..count)) to
 * output, with the lists of each four consecutive distinct first particles interleaved: the first pair of each list,
 * then the second of each, ...
 */
inline void interleaveRuns(const int* listed, const int* first, int count, int* output) {
    int next = 0, start = 0;
    while (start < count) {
        // Up to four runs of equal first particle, starting at `start`.
        int runStart[5], numRuns = 0, end = start;
        while (numRuns < 4 && end < count) {
            runStart[numRuns++] = end;
            const int particle = first[end];
            while (end < count && first[end] == particle)
                end++;
        }
        runStart[numRuns] = end;
        int longest = 0;
        for (int r = 0; r < numRuns; r++)
            longest = std::max(longest, runStart[r + 1] - runStart[r]);
        for (int rank = 0; rank < longest; rank++)
            for (int r = 0; r < numRuns; r++)
                if (runStart[r] + rank < runStart[r + 1])
                    output[next++] = listed[runStart[r] + rank];
        start = end;
    }
}

} // namespace SweepDefinition
} // namespace GenDPDEPlugin

#endif /*GENDPDE_SWEEP_DEFINITION_H_*/
