/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
#ifndef GENDPDE_CELL_ORDERED_CANDIDATES_H_
#define GENDPDE_CELL_ORDERED_CANDIDATES_H_

#include "NeighborList.h"
#include "openmm/Vec3.h"
#include <vector>

namespace GenDPDEPlugin {

/**
 * The candidates of a NeighborList as full neighbor rows, laid out for per-particle gathers on several threads.
 *
 * Rows: one per particle, in the list's cell order, so that particles close in space are close in memory whatever
 * their indices (a liquid mixes its particles within a few thousand steps; in index order every neighbor is then a
 * cache miss). Row s belongs to particle i = getParticle()[s] and holds every candidate neighbor of i, as rows, in
 * increasing order of the neighbor's index: first those j < i (the candidates (j, i) of the list), then those j > i
 * (the candidates (i, j)), from getUpperStart()[s] on. This is the order in which Reference's pair loop, which takes
 * the pairs in (i, j) order, reaches the neighbors of i, so a gather along the row adds the same terms in the same
 * order.
 *
 * update() re-derives the rows when the list has been rebuilt and copies the positions into row order; everything
 * else is read-only between updates.
 */
class CellOrderedCandidates {
public:
    /** Follow the list after its refresh(): new rows if it was rebuilt, the current positions in row order. */
    void update(const NeighborList& list, int numThreads);
    int getNumRows() const { return particle.size(); }
    /** The particle of each row. */
    const std::vector<int>& getParticle() const { return particle; }
    /** The row of each particle. */
    const std::vector<int>& getRow() const { return row; }
    /** Row s is getNeighbors()[getRowStart()[s]] ... [getRowStart()[s + 1] - 1]. */
    const std::vector<int>& getRowStart() const { return rowStart; }
    /** Where the neighbors of larger index begin in each row. */
    const std::vector<int>& getUpperStart() const { return upperStart; }
    /** The neighbors' rows, row after row. */
    const std::vector<int>& getNeighbors() const { return neighbors; }
    /** The positions of the list's last refresh() (wrapped if periodic), in row order (nm), and one padding Vec3. */
    const std::vector<OpenMM::Vec3>& getPositions() const { return positions; }

private:
    void buildRows(const NeighborList& list, int numThreads);
    const NeighborList* followedList = nullptr; // the list and its build count when the rows were derived
    long long followedBuild = -1;
    std::vector<int> particle, row, rowStart, upperStart, neighbors;
    std::vector<int> lowerCount; // scratch of buildRows (then each row's next place), kept: a rebuild allocates nothing
    std::vector<OpenMM::Vec3> positions;
};

} // namespace GenDPDEPlugin

#endif /*GENDPDE_CELL_ORDERED_CANDIDATES_H_*/
