/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
#ifndef GENDPDE_SWEEP_ORDER_H_
#define GENDPDE_SWEEP_ORDER_H_

#include "openmm/Vec3.h"
#include <array>
#include <vector>

namespace GenDPDEPlugin {

/**
 * The order of the pair updates in GenDPDEIntegrator's sweep (docs/theory.md section 6), defined once here for every
 * platform. Every platform applies the pair updates in exactly this sequence (a parallel one may run the blocks of
 * one colour at the same time, since they share no particle), so every platform follows the same trajectory.
 *
 * Cells: the box (periodic: fractional coordinates of the wrapped positions; open: the bounding box of the
 * particles) is cut into n_k cells along each direction k, each at least (1 + 1e-9) R wide (perpendicular width),
 * so two particles closer than R are in the same or adjacent cells. Periodic: n_k is a multiple of 4 (or 2 or 1
 * when the box holds fewer than 4 cells), so that the blocks below have an even count along k and their parity is
 * consistent across the boundary.
 *
 * Blocks and colours: a pair's home cell is, along each direction, the lower of its two cells (the one the other
 * follows, modulo n_k when periodic); its block is the 2x2x2 group of cells that holds the home cell, (h_x/2, h_y/2,
 * h_z/2); its colour is the parity of the block, (b_x mod 2) + 2 (b_y mod 2) + 4 (b_z mod 2). A block's pairs touch
 * cells home..home+1 only, so two blocks of one colour never share a particle. A pair whose cells are not adjacent
 * (impossible for pairs closer than R; kept for robustness) goes to a last group of its own, run alone.
 *
 * The sequence: colours 0 to 7, within a colour the blocks by index (b_z n_y + b_y) n_x + b_x, within a block the
 * block's pairs in (i, j) order with the lists of each four consecutive distinct first particles interleaved (the
 * first pair of each, then the second of each, ...), so that consecutive updates rarely share a particle. The order
 * is a pure function of the positions, the box and the set of pairs: it does not depend on how the pairs were found,
 * on the number of threads, or on any history.
 */
class GenDPDESweepOrder {
public:
    /**
     * Build the order for the pairs (pairI[k stride], pairJ[k stride]), k < numPairs, i < j, all closer than range
     * (nm), at these positions (nm) and box vectors (used only if periodic). The pairs are in (i, j) order, or, if
     * rowPairStart is given, stored by rows: row r holds pairs rowPairStart[r] ... rowPairStart[r + 1] - 1, all of
     * one first particle, in increasing j; one row per particle, the rows in any order (the CPU platform's cell
     * order; read as getRowReading() says). The order is the same either way and holds indices into the pairs as
     * stored. numThreads threads share the work; the result is the same for any number.
     */
    void build(const std::vector<OpenMM::Vec3>& positions, const OpenMM::Vec3 boxVectors[3], bool periodic,
               double range, int numPairs, const int* pairI, const int* pairJ, int stride, int numThreads = 1,
               const int* rowPairStart = nullptr);
    /**
     * How build() reads pairs stored by rows (the order is the same; only the speed differs): in particle order, the
     * rows at random in memory when the particles are numbered at random in space, each block's pairs then in (i, j)
     * order; or in storage order (cell order), each block's runs of one first particle then sorted by it. BySize (the
     * default): storage order from storageOrderFromPairs pairs, where reading rows at random costs more than the sort
     * (docs/performance.md, "Where a step's time goes").
     */
    enum class RowReading { BySize, ParticleOrder, StorageOrder };
    static const int storageOrderFromPairs = 1000000;
    void setRowReading(RowReading reading) { rowReading = reading; }
    RowReading getRowReading() const { return rowReading; }
    /** The number of groups run one after another: the colours, then possibly the group of non-adjacent pairs. */
    int getNumGroups() const { return groupStart.size() - 1; }
    /** The blocks of group g are blocks groupStart[g] .. groupStart[g + 1] - 1 (in this numbering). */
    const std::vector<int>& getGroupStart() const { return groupStart; }
    /** The pairs of block b are order[blockStart[b]] ... order[blockStart[b + 1] - 1], in sweep order. */
    const std::vector<int>& getBlockStart() const { return blockStart; }
    /** Pair indices (into the pair list given to build()) in sweep order. */
    const std::vector<int>& getOrder() const { return order; }
    /**
     * The number of cells along each direction for a region of these widths (nm: the perpendicular widths of a
     * periodic box, or the extent of the particles' bounding box) and pair range (nm), as build() chooses them.
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
    std::array<int, 3> numCells, numBlocks;
    bool periodic = false;
    RowReading rowReading = RowReading::BySize;
    std::vector<std::array<int, 3>> particleCell;
    std::vector<int> pairRank, rankOfBlock, rangeCount, groupStart, blockStart, order, sortedFirst;
    std::vector<int> cellCount, particlesByCell, slotOfParticle, runBound;
};

} // namespace GenDPDEPlugin

#endif /*GENDPDE_SWEEP_ORDER_H_*/
