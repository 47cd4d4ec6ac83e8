/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
#ifndef GENDPDE_SWEEP_DEFINITION_H_
#define GENDPDE_SWEEP_DEFINITION_H_

/* The definition of the sweep's order of pair updates (docs/theory.md section 6; GenDPDESweepOrder.h says it in full)
 * as small functions with no dependencies, so that every engine that runs the sweep computes the same candidates,
 * cells, blocks, colours and levels, and builds them at the same steps: the OpenMM platforms (through
 * GenDPDESweepOrder on the host, the same rules in the device programs) and the LAMMPS package (lammps/, across MPI
 * ranks).
 *
 * The order is made once per build from the candidate pairs (closer than candidateRange(R) at the build's positions)
 * and kept while no particle has moved farther than the skin's half (rebuildDisplacement2) and the box is the same;
 * each step updates, in that order, the candidates closer than R at the step's positions. */

#include "gendpde/IntegerRounding.h"
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace GenDPDEPlugin {
namespace SweepDefinition {

/**
 * The skin of the sweep's candidate pairs as a fraction of the pair range R: the order is made from the pairs closer
 * than (1 + skinFraction) R at the positions of its build, and made again when some particle has moved more than half
 * the skin from its position at the build (or the box has changed). Until then no pair outside the candidates can
 * come closer than R: two particles approach each other by at most the skin.
 */
constexpr double skinFraction = 0.1;

/** The reach of the candidate pairs (nm, or any length unit): (1 + skinFraction) R for pair range R. */
inline double candidateRange(double range) {
    return range + skinFraction * range;
}

/**
 * The square of the displacement from its position at the build beyond which a particle makes the order be built
 * again, (skin/2)^2 with skin = skinFraction R: a particle displaced by (dx, dy, dz) requires a build when
 * dx^2 + dy^2 + dz^2 > rebuildDisplacement2(R).
 */
inline double rebuildDisplacement2(double range) {
    const double skin = skinFraction * range;
    return 0.25 * skin * skin;
}

/** The number of colours: the parities of a block's three indices. */
const int numColours = 8;

/** Cells are at least this factor times the range wide, so that rounding can never put a pair in range two cells
 *  apart. */
const double cellMargin = 1.0 + 1e-9;

/**
 * The number of cells along one direction of a region this wide (a periodic box's perpendicular width, or the extent
 * of the particles' bounding box) for pairs closer than range (the sweep's cells: candidateRange(R)): as many cells at least cellMargin range wide as fit,
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
        widest = std::max(widest, widths[d] / cellCount(widths[d], candidateRange(range), true));
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
 * The number of 64-bit words per particle that assignLevels needs when no particle has more than maxDegree pairs in a
 * block: greedy levels are below 2 maxDegree - 1.
 */
inline int levelWords(int maxDegree) {
    return std::max(1, (2 * maxDegree - 1 + 63) / 64);
}

/**
 * The levels of a block's pairs, the order within a block: the pairs taken in (i, j) order (k = 0 .. count - 1, their
 * particles numbered within the block as localI[k], localJ[k]), each pair's level is the smallest level that no
 * earlier pair of either of its particles has. The pairs of one level share no particle; the block's sequence is
 * level 0, then level 1, ..., each level in (i, j) order. used: words 64-bit words per local particle (levelWords),
 * zero on entry (a mask of the levels each particle has; left set). Returns the number of levels.
 */
inline int assignLevels(const int* localI, const int* localJ, int count, int words, std::uint64_t* used, int* level) {
    int numLevels = 0;
    for (int k = 0; k < count; k++) {
        std::uint64_t* usedI = used + (std::size_t) localI[k] * words;
        std::uint64_t* usedJ = used + (std::size_t) localJ[k] * words;
        int l = 0;
        for (int w = 0; w < words; w++) {
            const std::uint64_t free = ~(usedI[w] | usedJ[w]);
            if (free != 0) {
                int bit = 0;
                while (((free >> bit) & 1u) == 0)
                    bit++;
                l = 64 * w + bit;
                break;
            }
        }
        usedI[l / 64] |= std::uint64_t(1) << (l % 64);
        usedJ[l / 64] |= std::uint64_t(1) << (l % 64);
        level[k] = l;
        numLevels = std::max(numLevels, l + 1);
    }
    return numLevels;
}

/** What orderBlock needs besides its arguments, kept by the caller from block to block (it allocates nothing once
 *  large enough). */
struct BlockScratch {
    std::vector<int> members, degree, localI, localJ, level, levelStart;
    std::vector<std::uint64_t> used;
};

/**
 * The order within one block: its pairs k = 0 .. count - 1 in (i, j) order, pair k's particles particle(k, 0) and
 * particle(k, 1) (any indices, below the size of localOf), are numbered within the block in the order they first
 * appear, given their levels (assignLevels) and sorted by level, stably: place[k] receives pair k's place in the
 * block's sweep order. localOf: -1 for every index on entry, and again on return. Returns the number of levels.
 */
template <class Particle>
int orderBlock(int count, Particle particle, int* localOf, BlockScratch& scratch, int* place) {
    std::vector<int>& members = scratch.members;
    std::vector<int>& degree = scratch.degree;
    members.clear();
    degree.clear();
    scratch.localI.resize(count);
    scratch.localJ.resize(count);
    int maxDegree = 0;
    for (int k = 0; k < count; k++)
        for (int end = 0; end < 2; end++) {
            const int i = particle(k, end);
            if (localOf[i] < 0) {
                localOf[i] = members.size();
                members.push_back(i);
                degree.push_back(0);
            }
            maxDegree = std::max(maxDegree, ++degree[localOf[i]]);
            (end == 0 ? scratch.localI : scratch.localJ)[k] = localOf[i];
        }
    const int words = levelWords(maxDegree);
    scratch.used.assign(members.size() * words, 0);
    scratch.level.resize(count);
    const int numLevels = assignLevels(scratch.localI.data(), scratch.localJ.data(), count, words, scratch.used.data(),
                                       scratch.level.data());
    scratch.levelStart.assign(numLevels + 1, 0);
    for (int k = 0; k < count; k++)
        scratch.levelStart[scratch.level[k] + 1]++;
    for (int l = 0; l < numLevels; l++)
        scratch.levelStart[l + 1] += scratch.levelStart[l];
    for (int k = 0; k < count; k++)
        place[k] = scratch.levelStart[scratch.level[k]]++;
    for (int i : members)
        localOf[i] = -1;
    return numLevels;
}

} // namespace SweepDefinition
} // namespace GenDPDEPlugin

#endif /*GENDPDE_SWEEP_DEFINITION_H_*/
