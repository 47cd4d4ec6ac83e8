/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
#include "internal/GenDPDESweepOrder.h"
#include "internal/BoxGeometry.h"
#include "internal/Buffers.h"
#include "gendpde/GenDPDESweepDefinition.h"
#include "internal/ParallelFor.h"
#include <algorithm>
#include <cmath>
#include <cstdint>

using namespace GenDPDEPlugin;
using namespace OpenMM;

using SweepDefinition::numColours;

std::array<int, 3> GenDPDESweepOrder::cellCounts(const Vec3& extent, double range, bool periodic) {
    std::array<int, 3> cells;
    for (int k = 0; k < 3; k++)
        cells[k] = SweepDefinition::cellCount(extent[k], SweepDefinition::candidateRange(range), periodic);
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
                              int numPairs, const int* pairI, const int* pairJ, int stride, int numThreads) {
    computeCells(positions, boxVectors, periodic, range, numThreads);
    sortParticlesByCell();
    // Ranks: the blocks in sweep order (colour by colour, by block index within a colour), then one rank for the
    // pairs whose cells are not adjacent.
    const int numRanks = blockRanks(numBlocks, rankOfBlock, groupStart) + 1;
    groupStart.push_back(numRanks);
    sortByRank(numPairs, pairI, pairJ, stride, numRanks, numThreads);
    orderLevels(pairI, pairJ, stride, numThreads);
}

void GenDPDESweepOrder::sortByRank(int numPairs, const int* pairI, const int* pairJ, int stride, int numRanks,
                                   int numThreads) {
    // The rank of pair k: along each direction the home cell is the one the other follows (d = c_j - c_i, taken
    // modulo n_k into [-1, 1] if periodic); a pair with |d| > 1 along some direction has the extra rank, the last.
    const std::array<int, 3>* cell = particleCell.data();
    const int* blockRank = rankOfBlock.data();
    const std::array<int, 3> cells = numCells, blocks = numBlocks;
    const bool periodic = this->periodic;
    const int extraRank = numRanks - 1;
    auto rankOf = [=](int k) {
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
        return adjacent ? blockRank[(block[2] * blocks[1] + block[1]) * blocks[0] + block[0]] : extraRank;
    };
    // A stable counting sort by rank over ranges of consecutive pairs: counts per range, then each range writes its
    // pairs from its own offsets (the result does not depend on the ranges). Each block then holds its pairs in (i, j)
    // order, the candidates' order.
    const int numPairRanges = std::max(1, std::min(64, numRanges(numPairs, 4096)));
    const int pairsPerRange = numRanges(numPairs, numPairRanges);
    rangeCount.assign((size_t) numPairRanges * numRanks, 0);
    int* count = rangeCount.data();
    std::vector<int> pairRank(numPairs); // (the build's scratch: not kept between builds)
    int* rankOfPair = pairRank.data();
    parallelFor(numThreads, numPairRanges, 1, [=](int rangeBegin, int rangeEnd) {
        for (int r = rangeBegin; r < rangeEnd; r++)
            for (int k = r * pairsPerRange; k < std::min(numPairs, (r + 1) * pairsPerRange); k++) {
                rankOfPair[k] = rankOf(k);
                count[(size_t) r * numRanks + rankOfPair[k]]++;
            }
    });
    blockStart.assign(numRanks + 1, 0);
    int total = 0;
    for (int s = 0; s < numRanks; s++) {
        blockStart[s] = total;
        for (int r = 0; r < numPairRanges; r++) {
            const int n = count[(size_t) r * numRanks + s];
            count[(size_t) r * numRanks + s] = total; // now the range's first position in rank s
            total += n;
        }
    }
    blockStart[numRanks] = total;
    resizeBuffer(order, numPairs);
    int* sorted = order.data();
    parallelFor(numThreads, numPairRanges, 1, [=](int rangeBegin, int rangeEnd) {
        for (int r = rangeBegin; r < rangeEnd; r++)
            for (int k = r * pairsPerRange; k < std::min(numPairs, (r + 1) * pairsPerRange); k++)
                sorted[count[(size_t) r * numRanks + rankOfPair[k]]++] = k;
    });
}

void GenDPDESweepOrder::orderLevels(const int* pairI, const int* pairJ, int stride, int numThreads) {
    // Within each block (its pairs in (i, j) order), the levels (SweepDefinition::assignLevels) and the pairs sorted by
    // level, stably: block by block in place.
    const int numRanks = blockStart.size() - 1;
    blockLevels.assign(numRanks, 0);
    const int numParticles = particleCell.size();
    parallelFor(numThreads, numRanks, 8, [&](int begin, int end) {
        // scratch of the size of a block (and each particle's number within its block), kept by each thread
        thread_local std::vector<int> localOf, place, blockCopy;
        thread_local SweepDefinition::BlockScratch scratch;
        if ((int) localOf.size() < numParticles)
            localOf.assign(numParticles, -1);
        for (int s = begin; s < end; s++) {
            const int start = blockStart[s], count = blockStart[s + 1] - start;
            if (count == 0)
                continue;
            const int* pairs = &order[start];
            place.resize(count);
            blockLevels[s] = SweepDefinition::orderBlock(
                    count, [&](int k, int end2) { return (end2 == 0 ? pairI : pairJ)[(size_t) pairs[k] * stride]; },
                    localOf.data(), scratch, place.data());
            blockCopy.assign(pairs, pairs + count);
            for (int k = 0; k < count; k++)
                order[start + place[k]] = blockCopy[k];
        }
    });
}
