/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
#ifndef GENDPDE_SWEEP_ORDER_H_
#define GENDPDE_SWEEP_ORDER_H_

#include "openmm/Vec3.h"
#include <array>
#include <vector>

namespace GenDPDEPlugin {

/**
 * The order of the pair updates in GenDPDEIntegrator's sweep (docs/theory.md section 6), made on the host platforms
 * from the definition every engine follows (gendpde/GenDPDESweepDefinition.h). Every platform applies the pair
 * updates in exactly this sequence (a parallel one may run the blocks of one colour, or the pairs of one level of a
 * block, at the same time: they share no particle), so every platform follows the same trajectory.
 *
 * The order is made at a build from the candidate pairs, those closer than candidateRange(R) = 1.1 R at the build's
 * positions, and kept until some particle has moved more than half the skin (0.05 R) or the box has changed; each
 * step then updates, in this order, the candidates closer than R at its own positions.
 *
 * Cells: the box (periodic: fractional coordinates; open: the bounding box of the particles at the build) is cut into
 * n_k cells along each direction k, each at least (1 + 1e-9) 1.1 R wide (perpendicular width), so the two particles of
 * a candidate are in the same or adjacent cells. Periodic: n_k is a multiple of 4 (or 2 or 1 when the box holds fewer
 * than 4 cells), so that the blocks below have an even count along k and their parity is consistent across the
 * boundary.
 *
 * Blocks and colours: a pair's home cell is, along each direction, the lower of its two cells (the one the other
 * follows, modulo n_k when periodic); its block is the 2x2x2 group of cells that holds the home cell, (h_x/2, h_y/2,
 * h_z/2); its colour is the parity of the block, (b_x mod 2) + 2 (b_y mod 2) + 4 (b_z mod 2). A block's pairs touch
 * the particles of cells home..home+1 at the build only, so two blocks of one colour never share a particle, however
 * the particles move afterwards. A pair whose cells are not adjacent (impossible for candidates; kept for robustness)
 * goes to a last group of its own, run alone.
 *
 * The sequence: colours 0 to 7, within a colour the blocks by index (b_z n_y + b_y) n_x + b_x, within a block its
 * levels: the block's pairs taken in (i, j) order, each pair's level is the smallest that no earlier pair of either
 * particle has (SweepDefinition::assignLevels), and the block runs level 0, level 1, ..., each level in (i, j) order.
 * The order is a pure function of the build's positions, its box and its candidates: it does not depend on how the
 * candidates were found, on the number of threads, or on any other history.
 */
class GenDPDESweepOrder {
public:
    /**
     * Build the order for the candidates (pairI[k stride], pairJ[k stride]), k < numPairs, i < j, in (i, j) order,
     * all closer than candidateRange(range) at these positions (nm; the build's) and box vectors (used only if
     * periodic), for pairs range R = range (nm). numThreads threads share the work; the result is the same for any
     * number.
     */
    void build(const std::vector<OpenMM::Vec3>& positions, const OpenMM::Vec3 boxVectors[3], bool periodic,
               double range, int numPairs, const int* pairI, const int* pairJ, int stride, int numThreads = 1);
    /** The number of groups run one after another: the colours, then possibly the group of non-adjacent pairs. */
    int getNumGroups() const { return groupStart.size() - 1; }
    /** The blocks of group g are blocks groupStart[g] .. groupStart[g + 1] - 1 (in this numbering). */
    const std::vector<int>& getGroupStart() const { return groupStart; }
    /** The pairs of block b are order[blockStart[b]] ... order[blockStart[b + 1] - 1], in sweep order. */
    const std::vector<int>& getBlockStart() const { return blockStart; }
    /** The number of levels of block b: the dependent updates it takes with its levels run one after another. */
    const std::vector<int>& getBlockLevels() const { return blockLevels; }
    /** Pair indices (into the candidates given to build()) in sweep order (empty after releaseOrder()). */
    const std::vector<int>& getOrder() const { return order; }
    /**
     * Free the order's memory (4 bytes per pair) once the caller has put its pairs in that order: the blocks, groups
     * and slots stay; the next build() allocates it again.
     */
    void releaseOrder() { std::vector<int>().swap(order); }
    /**
     * The number of cells along each direction for a region of these widths (nm: the perpendicular widths of a
     * periodic box, or the extent of the particles' bounding box) and pair range R (nm), as build() chooses them.
     */
    static std::array<int, 3> cellCounts(const OpenMM::Vec3& extent, double range, bool periodic);
    /**
     * The rank of each block in the sweep (numBlocks along each direction, blocks numbered (b_z n_y + b_y) n_x + b_x):
     * colour by colour, by block index within a colour; groupStart[c] is the first rank of colour c (groupStart has
     * 9 elements). Returns the number of ranks.
     */
    static int blockRanks(const std::array<int, 3>& numBlocks, std::vector<int>& rankOfBlock,
                          std::vector<int>& groupStart);
    /** The number of cells along each direction chosen by the last build(). */
    const std::array<int, 3>& getNumCells() const { return numCells; }
    /**
     * A memory layout for the sweep, not part of the order: the particles of the last build() sorted by cell (cells
     * numbered (c_z n_y + c_y) n_x + c_x as the blocks are; by index within a cell). getSlots()[i] is particle i's
     * place in getParticlesByCell(), so that particles that share pairs share cache lines whatever their indices.
     */
    const std::vector<int>& getParticlesByCell() const { return particlesByCell; }
    const std::vector<int>& getSlots() const { return slotOfParticle; }

private:
    void computeCells(const std::vector<OpenMM::Vec3>& positions, const OpenMM::Vec3 boxVectors[3], bool periodic,
                      double range, int numThreads);
    void sortParticlesByCell();
    /** Sort the pairs by rank into order (stably) and set blockStart; the ranks are the sort's scratch. */
    void sortByRank(int numPairs, const int* pairI, const int* pairJ, int stride, int numRanks, int numThreads);
    void orderLevels(const int* pairI, const int* pairJ, int stride, int numThreads);
    std::array<int, 3> numCells, numBlocks;
    bool periodic = false;
    std::vector<std::array<int, 3>> particleCell;
    std::vector<int> rankOfBlock, rangeCount, groupStart, blockStart, blockLevels, order;
    std::vector<int> cellCount, particlesByCell, slotOfParticle;
};

} // namespace GenDPDEPlugin

#endif /*GENDPDE_SWEEP_ORDER_H_*/
