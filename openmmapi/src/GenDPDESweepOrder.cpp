/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
#include "internal/GenDPDESweepOrder.h"
#include "internal/BoxGeometry.h"
#include "internal/Buffers.h"
#include "gendpde/GenDPDESweepDefinition.h"
#include "internal/ParallelFor.h"
#include <algorithm>
#include <cmath>

using namespace GenDPDEPlugin;
using namespace OpenMM;

using SweepDefinition::interleaveRuns;
using SweepDefinition::numColours;

std::array<int, 3> GenDPDESweepOrder::cellCounts(const Vec3& extent, double range, bool periodic) {
    std::array<int, 3> cells;
    for (int k = 0; k < 3; k++)
        cells[k] = SweepDefinition::cellCount(extent[k], range, periodic);
    return cells;
}

int GenDPDESweepOrder::blockRanks(const std::array<int, 3>& numBlocks, std::vector<int>& rankOfBlock,
                                  std::vector<int>& groupStart) {
    const int totalBlocks = numBlocks[0] * numBlocks[1] * numBlocks[2];
    rankOfBlock.resize(totalBlocks);
    groupStart.assign(1, 0);
    int rank = 0;
    for (int colour = 0; colour < numColours; colour++) {
        for (int block = 0; block < totalBlocks; block++) {
            const int bx = block % numBlocks[0], by = (block / numBlocks[0]) % numBlocks[1];
            const int bz = block / (numBlocks[0] * numBlocks[1]);
            if (SweepDefinition::blockColour(bx, by, bz) == colour)
                rankOfBlock[block] = rank++;
        }
        groupStart.push_back(rank);
    }
    return rank;
}

void GenDPDESweepOrder::computeCells(const std::vector<Vec3>& positions, const Vec3 boxVectors[3], bool periodic,
                                     double range, int numThreads) {
    this->periodic = periodic;
    const int numParticles = positions.size();
    Vec3 extent, low;
    if (periodic)
        extent = BoxGeometry::perpendicularWidths(boxVectors);
    else if (numParticles > 0) {
        low = positions[0];
        Vec3 high = low;
        for (const Vec3& r : positions)
            for (int k = 0; k < 3; k++) {
                low[k] = std::min(low[k], r[k]);
                high[k] = std::max(high[k], r[k]);
            }
        extent = high - low;
    }
    numCells = cellCounts(extent, range, periodic);
    for (int k = 0; k < 3; k++)
        numBlocks[k] = (numCells[k] + 1) / 2;
    particleCell.resize(numParticles);
    const Vec3* position = positions.data();
    const Vec3 box[3] = {boxVectors[0], boxVectors[1], boxVectors[2]};
    const std::array<int, 3> cells = numCells;
    std::array<int, 3>* cell = particleCell.data();
    parallelFor(numThreads, numParticles, 4096, [=](int begin, int end) {
        for (int i = begin; i < end; i++) {
            const Vec3 s = periodic ? BoxGeometry::fractionalCoordinates(position[i], box) : Vec3();
            for (int k = 0; k < 3; k++) {
                if (periodic)
                    cell[i][k] = SweepDefinition::periodicCell(s[k], cells[k]);
                else {
                    const double unit = extent[k] > 0.0 ? (position[i][k] - low[k]) / extent[k] : 0.0;
                    cell[i][k] = std::max(0, std::min(cells[k] - 1, (int) (unit * cells[k])));
                }
            }
        }
    });
}

void GenDPDESweepOrder::sortParticlesByCell() {
    // A counting sort by cell, stable: within a cell by index.
    const int numParticles = particleCell.size();
    cellCount.assign((size_t) numCells[0] * numCells[1] * numCells[2] + 1, 0);
    auto cellIndex = [&](const std::array<int, 3>& c) { return (c[2] * numCells[1] + c[1]) * numCells[0] + c[0]; };
    for (const std::array<int, 3>& c : particleCell)
        cellCount[cellIndex(c) + 1]++;
    for (size_t c = 1; c < cellCount.size(); c++)
        cellCount[c] += cellCount[c - 1];
    particlesByCell.resize(numParticles);
    slotOfParticle.resize(numParticles);
    for (int i = 0; i < numParticles; i++) {
        const int slot = cellCount[cellIndex(particleCell[i])]++;
        particlesByCell[slot] = i;
        slotOfParticle[i] = slot;
    }
}

void GenDPDESweepOrder::build(const std::vector<Vec3>& positions, const Vec3 boxVectors[3], bool periodic, double range,
                              int numPairs, const int* pairI, const int* pairJ, int stride, int numThreads,
                              const int* rowPairStart) {
    computeCells(positions, boxVectors, periodic, range, numThreads);
    sortParticlesByCell();

    // The pairs as runs: runs of 4096 consecutive pairs of an (i, j)-ordered list; or, stored by rows, one run per row,
    // read in storage order (then each block's runs are put in order of their first particles below) or in particle
    // order (each run then the pairs of particle `run`, and the blocks come out in (i, j) order).
    const bool byRows = (rowPairStart != nullptr);
    const bool storageOrder = byRows
            && (rowReading == RowReading::StorageOrder
                || (rowReading == RowReading::BySize && numPairs >= storageOrderFromPairs));
    if (storageOrder) {
        const int numRows = positions.size();
        runBound.resize(2 * (size_t) numRows);
        for (int r = 0; r < numRows; r++) {
            runBound[2 * r] = rowPairStart[r];
            runBound[2 * r + 1] = rowPairStart[r + 1];
        }
    } else if (byRows) {
        const int numParticles = positions.size();
        runBound.assign(2 * (size_t) numParticles, 0); // (a particle without pairs: an empty run)
        for (int r = 0; r < numParticles; r++)
            if (rowPairStart[r + 1] > rowPairStart[r]) {
                const int i = pairI[(size_t) rowPairStart[r] * stride];
                runBound[2 * i] = rowPairStart[r];
                runBound[2 * i + 1] = rowPairStart[r + 1];
            }
    } else {
        runBound.resize(2 * (size_t) numRanges(numPairs, 4096));
        for (size_t r = 0; 2 * r < runBound.size(); r++) {
            runBound[2 * r] = r * 4096;
            runBound[2 * r + 1] = std::min(numPairs, (int) (r + 1) * 4096);
        }
    }
    const int numRuns = runBound.size() / 2;

    // Ranks: the blocks in sweep order (colour by colour, by block index within a colour), then one rank for the
    // pairs whose cells are not adjacent.
    int rank = blockRanks(numBlocks, rankOfBlock, groupStart);
    const int extraRank = rank++;
    groupStart.push_back(rank);

    // Each pair's rank. Along each direction the home cell is the one the other follows (d = c_j - c_i, taken
    // modulo n_k into [-1, 1] if periodic); a pair with |d| > 1 along some direction goes to the extra rank. (Stored:
    // computing it again where the sort reads it, in the runs' order, reaches the cells at random and cost 1.12x the
    // two-thread step at 32,000 particles.)
    resizeBuffer(pairRank, numPairs);
    const std::array<int, 3>* cell = particleCell.data();
    const int* blockRank = rankOfBlock.data();
    int* rankOfPair = pairRank.data();
    const std::array<int, 3> cells = numCells, blocks = numBlocks;
    parallelFor(numThreads, numPairs, 4096, [=](int begin, int end) {
        for (int k = begin; k < end; k++) {
            const std::array<int, 3>& ci = cell[pairI[(size_t) k * stride]];
            const std::array<int, 3>& cj = cell[pairJ[(size_t) k * stride]];
            int block[3];
            bool adjacent = true;
            for (int dim = 0; dim < 3; dim++) {
                int d = cj[dim] - ci[dim];
                if (periodic)
                    d += (d < -1 ? cells[dim] : 0) - (d > 1 ? cells[dim] : 0);
                adjacent = adjacent & ((unsigned) (d + 1) <= 2u);
                block[dim] = (d == -1 ? cj[dim] : ci[dim]) >> 1;
            }
            rankOfPair[k] = adjacent ? blockRank[(block[2] * blocks[1] + block[1]) * blocks[0] + block[0]] : extraRank;
        }
    });

    // A stable counting sort by rank, reading the runs one after another: counts per range of runs, then each range
    // writes its pairs from its own offsets (the result does not depend on the ranges). Each block then holds its
    // pairs in (i, j) order, or, rows read in storage order, as runs of one first particle each (increasing j within a
    // run, the runs in storage order), which the last pass puts in order of i. (The first particles are kept beside
    // the sorted pairs: reading them per block instead, at random, cost 1.03-1.06x the step at 256,000 particles.)
    const int numRanks = rank;
    const int numRunRanges = std::max(1, std::min(64, numRanges(numPairs, 4096)));
    const int runsPerRange = numRanges(numRuns, numRunRanges);
    rangeCount.assign((size_t) numRunRanges * numRanks, 0);
    int* count = rangeCount.data();
    const int* bound = runBound.data();
    parallelFor(numThreads, numRunRanges, 1, [=](int rangeBegin, int rangeEnd) {
        for (int r = rangeBegin; r < rangeEnd; r++)
            for (int run = r * runsPerRange; run < std::min(numRuns, (r + 1) * runsPerRange); run++)
                for (int k = bound[2 * run]; k < bound[2 * run + 1]; k++)
                    count[(size_t) r * numRanks + rankOfPair[k]]++;
    });
    blockStart.assign(numRanks + 1, 0);
    int total = 0;
    for (int s = 0; s < numRanks; s++) {
        blockStart[s] = total;
        for (int r = 0; r < numRunRanges; r++) {
            const int n = count[(size_t) r * numRanks + s];
            count[(size_t) r * numRanks + s] = total; // now the range's first position in rank s
            total += n;
        }
    }
    blockStart[numRanks] = total;
    resizeBuffer(order, numPairs);
    resizeBuffer(sortedFirst, numPairs);
    int* sortedPairs = order.data(); // (sorted in place by the pass below)
    int* firstOfSorted = sortedFirst.data(); // their first particles, for the pass below to read in order
    const bool runIsParticle = byRows && !storageOrder;
    parallelFor(numThreads, numRunRanges, 1, [=](int rangeBegin, int rangeEnd) {
        for (int r = rangeBegin; r < rangeEnd; r++)
            for (int run = r * runsPerRange; run < std::min(numRuns, (r + 1) * runsPerRange); run++)
                for (int k = bound[2 * run]; k < bound[2 * run + 1]; k++) {
                    const int position = count[(size_t) r * numRanks + rankOfPair[k]]++;
                    sortedPairs[position] = k;
                    firstOfSorted[position] = runIsParticle ? run : pairI[(size_t) k * stride];
                }
    });

    // Within each block, the runs of one first particle in increasing order of it (pairs stored by rows) and the
    // lists of four consecutive first particles interleaved, block by block in place.
    parallelFor(numThreads, numRanks, 8, [&](int begin, int end) {
        // a copy of the block's sorted pairs, (first particle, start) of each run of a block, and the block's pairs with
        // their runs in order: scratch of the size of a block, kept by each thread (a step allocates nothing)
        thread_local std::vector<int> blockCopy, listed, first;
        thread_local std::vector<std::pair<int, int>> runs;
        for (int s = begin; s < end; s++) {
            const int start = blockStart[s], count = blockStart[s + 1] - start;
            blockCopy.assign(&order[start], &order[start] + count);
            const int* blockPairs = blockCopy.data();
            const int* blockFirst = &sortedFirst[start];
            if (std::is_sorted(blockFirst, blockFirst + count)) {
                interleaveRuns(blockPairs, blockFirst, count, &order[start]);
                continue;
            }
            runs.clear();
            for (int k = 0; k < count; k++)
                if (k == 0 || blockFirst[k] != blockFirst[k - 1])
                    runs.emplace_back(blockFirst[k], k);
            std::sort(runs.begin(), runs.end());
            listed.clear();
            first.clear();
            for (const std::pair<int, int>& run : runs)
                for (int k = run.second; k < count && blockFirst[k] == run.first; k++) {
                    listed.push_back(blockPairs[k]);
                    first.push_back(run.first);
                }
            interleaveRuns(listed.data(), first.data(), count, &order[start]);
        }
    });
}
