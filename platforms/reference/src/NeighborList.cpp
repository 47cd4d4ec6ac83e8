/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
#include "NeighborList.h"
#include "internal/BoxGeometry.h"
#include "internal/Buffers.h"
#include "internal/ParallelFor.h"
#include <algorithm>
#include <atomic>
#include <array>
#include <cmath>

using namespace GenDPDEPlugin;
using namespace OpenMM;

PeriodicBox::PeriodicBox(const Vec3 boxVectors[3]) {
    for (int k = 0; k < 3; k++) {
        vectors[k] = boxVectors[k];
        inverseDiagonal[k] = 1.0 / boxVectors[k][k];
    }
    triclinic = (vectors[1][0] != 0.0 || vectors[2][0] != 0.0 || vectors[2][1] != 0.0);
}

NeighborList::NeighborList(double cutoff, double skin, bool periodic) :
        cutoff(cutoff), skin(skin), periodic(periodic) {}

bool NeighborList::needsRebuild(const std::vector<Vec3>& positions, const Vec3 boxVectors[3], int numThreads) const {
    if (!built || positions.size() != builtPositions.size())
        return true;
    if (periodic && !(boxVectors[0] == builtBox[0] && boxVectors[1] == builtBox[1] && boxVectors[2] == builtBox[2]))
        return true;
    return anyMovedFarther(positions, builtPositions, 0.25 * skin * skin, numThreads);   // (skin/2)^2: two particles
            // approach by at most skin
}

bool NeighborList::anyMovedFarther(const std::vector<Vec3>& now, const std::vector<Vec3>& then, double limit2,
                                   int numThreads) {
    const Vec3* current = now.data();
    const Vec3* before = then.data();
    std::atomic<bool> moved(false);
    std::atomic<bool>* anyMoved = &moved;
    parallelFor(numThreads, now.size(), 8192, [=](int begin, int end) {
        bool found = false;
        for (int i = begin; i < end; i++) {
            const Vec3 d = current[i] - before[i];
            found |= d.dot(d) > limit2;
        }
        if (found)
            anyMoved->store(true, std::memory_order_relaxed);
    });
    return moved.load();
}

void NeighborList::build(const std::vector<Vec3>& positions, int numThreads) {
    Vec3 extent;
    // The positions of the last build are not needed until they are replaced at the end: their buffer is the build's
    // scratch (the unit-cell coordinates, then the positions in cell order).
    std::vector<Vec3>& scratch = builtPositions;
    built = false; // (until the end: a build interrupted leaves no stale positions to compare with)
    unitCellCoordinates(positions, extent, numThreads, scratch);
    sortIntoCells(scratch, extent);
    collectCandidates(periodic ? wrappedPositions : positions, numThreads, scratch);
    builtPositions = positions;
    for (int k = 0; k < 3; k++)
        builtBox[k] = box.getVectors()[k];
    built = true;
    buildCount++;
}

void NeighborList::unitCellCoordinates(const std::vector<Vec3>& positions, Vec3& extent, int numThreads,
                                       std::vector<Vec3>& unit) const {
    // Coordinates in [0, 1)^3: fractional coordinates if periodic, the bounding box otherwise.
    const int numParticles = positions.size();
    unit.resize(numParticles);
    if (periodic) {
        extent = BoxGeometry::perpendicularWidths(box.getVectors());
        parallelFor(numThreads, numParticles, 4096, [&](int begin, int end) {
            for (int i = begin; i < end; i++) {
                Vec3 s = BoxGeometry::fractionalCoordinates(wrappedPositions[i], box.getVectors());
                for (int k = 0; k < 3; k++)
                    unit[i][k] = s[k] - BoxGeometry::floorToInteger(s[k]);
            }
        });
        return;
    }
    Vec3 low = numParticles > 0 ? positions[0] : Vec3(), high = low;
    for (const Vec3& r : positions)
        for (int k = 0; k < 3; k++) {
            low[k] = std::min(low[k], r[k]);
            high[k] = std::max(high[k], r[k]);
        }
    for (int k = 0; k < 3; k++)
        extent[k] = high[k] - low[k];
    for (int i = 0; i < numParticles; i++)
        for (int k = 0; k < 3; k++)
            unit[i][k] = extent[k] > 0.0 ? (positions[i][k] - low[k]) / extent[k] : 0.0;
}

void NeighborList::sortIntoCells(const std::vector<Vec3>& unit, const Vec3& extent) {
    const int numParticles = unit.size();
    // Cells at least cutoff + skin wide; no more cells than are useful for this many particles.
    const double listCutoff = cutoff + skin;
    for (int k = 0; k < 3; k++)
        numCells[k] = std::max(1, (int) std::min(1.0e4, std::floor(extent[k] / listCutoff)));
    const double maxCells = std::max(27.0, 2.0 * numParticles);
    while ((double) numCells[0] * numCells[1] * numCells[2] > maxCells)
        for (int k = 0; k < 3; k++)
            numCells[k] = std::max(1, numCells[k] / 2);
    const int totalCells = numCells[0] * numCells[1] * numCells[2];

    // Counting sort of the particles into cells; within a cell they stay in ascending index order.
    particleCell.resize(numParticles);
    cellStart.assign(totalCells + 1, 0);
    for (int i = 0; i < numParticles; i++) {
        int cell = 0;
        for (int k = 0; k < 3; k++)
            cell = cell * numCells[k] + std::max(0, std::min(numCells[k] - 1, (int) (unit[i][k] * numCells[k])));
        particleCell[i] = cell;
        cellStart[cell + 1]++;
    }
    for (int c = 0; c < totalCells; c++)
        cellStart[c + 1] += cellStart[c];
    cellParticles.resize(numParticles);
    cellFill.assign(cellStart.begin(), cellStart.end() - 1);
    for (int i = 0; i < numParticles; i++)
        cellParticles[cellFill[particleCell[i]]++] = i;
}

std::array<std::vector<std::vector<int>>, 3> NeighborList::neighborCellsPerDimension() const {
    // For each dimension and cell coordinate, the distinct cells within one step (with wrap-around if periodic).
    std::array<std::vector<std::vector<int>>, 3> neighborCells;
    for (int k = 0; k < 3; k++) {
        neighborCells[k].resize(numCells[k]);
        for (int c = 0; c < numCells[k]; c++)
            for (int offset = -1; offset <= 1; offset++) {
                int n = c + offset;
                if (periodic)
                    n = (n + numCells[k]) % numCells[k];
                else if (n < 0 || n >= numCells[k])
                    continue;
                std::vector<int>& cells = neighborCells[k][c];
                if (std::find(cells.begin(), cells.end(), n) == cells.end())
                    cells.push_back(n);
            }
    }
    return neighborCells;
}

void NeighborList::collectCandidates(const std::vector<Vec3>& r, int numThreads, std::vector<Vec3>& cellPositions) {
    const int numParticles = r.size();
    const std::array<std::vector<std::vector<int>>, 3> neighborCells = neighborCellsPerDimension();
    // The positions in cell order, so that scanning a cell reads consecutive memory (exact copies: the same
    // candidates), in the build's scratch (the unit-cell coordinates are no longer needed).
    cellPositions.resize(numParticles);
    for (int m = 0; m < numParticles; m++)
        cellPositions[m] = r[cellParticles[m]];
    // (the last build's candidates per particle: room for about as many in each range's scratch)
    const double perParticle = candidateStart.size() == (size_t) numParticles + 1
            ? candidateStart.back() / std::max(1.0, (double) numParticles)
            : 0;
    candidateStart.assign(numParticles + 1, 0);
    // The search runs through the particles in cell order, so that consecutive particles scan the same cells (in
    // index order, with the particles numbered at random, each one's cells are a new place in memory: at 500,000
    // particles the search took 2.5 times as long per particle as at 32,000). Each range of the cell order writes its
    // particles' rows into its own scratch; the rows are then copied into the ranges of particle indices, which keep
    // them between builds.
    const int numChunks = numRanges(numParticles, particleChunk);
    std::vector<std::vector<int>> cellOrderRows(numChunks);
    std::vector<std::int64_t> rowLocation(numParticles); // (range of the cell order) << 32 | offset in its scratch
    parallelFor(numThreads, numChunks, 1, [&](int chunkBegin, int chunkEnd) {
        for (int c = chunkBegin; c < chunkEnd; c++) {
            cellOrderRows[c].reserve((size_t) (1.1 * perParticle * particleChunk) + 64);
            findCandidates(cellPositions, c * particleChunk, std::min(numParticles, (c + 1) * particleChunk),
                           neighborCells, cellOrderRows[c], (std::int64_t) c << 32, rowLocation);
        }
    });
    for (int i = 0; i < numParticles; i++)
        candidateStart[i + 1] += candidateStart[i];
    chunkCandidates.resize(numChunks);
    parallelFor(numThreads, numChunks, 1, [&](int chunkBegin, int chunkEnd) {
        for (int c = chunkBegin; c < chunkEnd; c++) {
            const int begin = c * particleChunk, end = std::min(numParticles, (c + 1) * particleChunk);
            resizeBuffer(chunkCandidates[c], candidateStart[end] - candidateStart[begin]);
            int* out = chunkCandidates[c].data();
            for (int i = begin; i < end; i++) {
                const std::vector<int>& rows = cellOrderRows[rowLocation[i] >> 32];
                const int* row = rows.data() + (rowLocation[i] & 0xFFFFFFFF);
                out = std::copy(row, row + (candidateStart[i + 1] - candidateStart[i]), out);
            }
        }
    });
}

void NeighborList::findCandidates(const std::vector<Vec3>& cellPositions, int begin, int end,
                                  const std::array<std::vector<std::vector<int>>, 3>& neighborCells,
                                  std::vector<int>& found, std::int64_t range, std::vector<std::int64_t>& rowLocation) {
    // Candidates of each particle: all j > i whose nearest image is within cutoff + skin, sorted. Every particle of
    // the surrounding cells is written and kept only if it is one (no branch: which are is close to random).
    const double listCutoff = cutoff + skin, listCutoff2 = listCutoff * listCutoff;
    size_t size = 0;
    found.resize(found.capacity());
    for (int m = begin; m < end; m++) {
        const int i = cellParticles[m];
        const Vec3 ri = cellPositions[m];
        int cell = particleCell[i];
        int cz = cell % numCells[2], cy = (cell / numCells[2]) % numCells[1], cx = cell / (numCells[2] * numCells[1]);
        const size_t first = size;
        for (int nx : neighborCells[0][cx])
            for (int ny : neighborCells[1][cy])
                for (int nz : neighborCells[2][cz]) {
                    const int neighborCell = (nx * numCells[1] + ny) * numCells[2] + nz;
                    const int cellBegin = cellStart[neighborCell], cellEnd = cellStart[neighborCell + 1];
                    if (found.size() < size + (cellEnd - cellBegin)) {
                        found.reserve(std::max(size + (cellEnd - cellBegin), size + size / 4));
                        found.resize(found.capacity());
                    }
                    int* out = found.data();
                    for (int n = cellBegin; n < cellEnd; n++) {
                        const int j = cellParticles[n];
                        const Vec3 d = periodic ? box.nearestImage(ri - cellPositions[n]) : ri - cellPositions[n];
                        out[size] = j;
                        size += (j > i) & (d.dot(d) < listCutoff2);
                    }
                }
        std::sort(found.begin() + first, found.begin() + size);
        candidateStart[i + 1] = size - first;
        rowLocation[i] = range | (std::int64_t) first;
    }
}

template <class Displacement>
void NeighborList::findPairs(int begin, int end, Displacement displacement, std::vector<ParticlePair>& found) const {
    const double cutoff2 = cutoff * cutoff;
    for (int i = begin; i < end; i++) {
        for (int j : candidatesOf(i)) {
            const Vec3 d = displacement(i, j);
            if (d.dot(d) < cutoff2) {
                found.emplace_back();
                ParticlePair& pair = found.back();
                pair.i = i;
                pair.j = j;
                pair.delta = d;
            }
        }
    }
}

template <class Displacement>
void NeighborList::collectPairs(int numParticles, Displacement displacement, int numThreads) {
    if (numThreads < 2) {
        // Fill a buffer field by field (a push_back of a temporary pair stalls on store-to-load forwarding), every
        // candidate written and kept only if in range (no branch: a quarter of the candidates are not, at random):
        // the buffer has room for every candidate of the particle at hand. It only grows (by 1/16 when it must), so
        // it is rarely re-initialised, and holds little more than the pairs.
        size_t found = 0;
        const double cutoff2 = cutoff * cutoff;
        for (int i = 0; i < numParticles; i++) {
            const Candidates candidates = candidatesOf(i);
            if (pairs.size() < found + candidates.size())
                resizeBuffer(pairs, found + candidates.size());
            ParticlePair* pair = pairs.data();
            for (int j : candidates) {
                const Vec3 d = displacement(i, j);
                pair[found].i = i;
                pair[found].j = j;
                pair[found].delta = d;
                found += (d.dot(d) < cutoff2);
            }
        }
        numPairs = found;
    } else {
        // Each range of particles finds its pairs, then the ranges are copied in order: the same list.
        const int numChunks = numRanges(numParticles, particleChunk);
        chunkPairs.resize(numChunks);
        parallelFor(numThreads, numChunks, 1, [&](int chunkBegin, int chunkEnd) {
            for (int c = chunkBegin; c < chunkEnd; c++) {
                chunkPairs[c].clear();
                findPairs(c * particleChunk, std::min(numParticles, (c + 1) * particleChunk), displacement,
                          chunkPairs[c]);
            }
        });
        std::vector<size_t> offset(numChunks + 1, 0);
        for (int c = 0; c < numChunks; c++)
            offset[c + 1] = offset[c] + chunkPairs[c].size();
        numPairs = offset[numChunks];
        if (pairs.size() < numPairs)
            resizeBuffer(pairs, numPairs);
        parallelFor(numThreads, numChunks, 1, [&](int chunkBegin, int chunkEnd) {
            for (int c = chunkBegin; c < chunkEnd; c++)
                std::copy(chunkPairs[c].begin(), chunkPairs[c].end(), pairs.begin() + offset[c]);
        });
    }
    // Distances in a pass of their own: independent square roots pipeline instead of stalling the search above.
    parallelFor(numThreads, numPairs, 8192, [&](int begin, int end) {
        for (int k = begin; k < end; k++)
            pairs[k].r = std::sqrt(pairs[k].delta.dot(pairs[k].delta));
    });
}

void NeighborList::refresh(const std::vector<Vec3>& positions, const Vec3 boxVectors[3], int numThreads) {
    const int numParticles = positions.size();
    currentPositions = &positions;
    if (periodic) {
        box = PeriodicBox(boxVectors);
        wrappedPositions.resize(numParticles);
        const PeriodicBox current = box;
        const Vec3* position = positions.data();
        Vec3* wrapped = wrappedPositions.data();
        parallelFor(numThreads, numParticles, 4096, [=](int begin, int end) {
            for (int i = begin; i < end; i++)
                wrapped[i] = current.wrap(position[i]);
        });
    }
    if (needsRebuild(positions, boxVectors, numThreads))
        build(positions, numThreads);
}

PairView NeighborList::update(const std::vector<Vec3>& positions, const Vec3 boxVectors[3], int numThreads) {
    refresh(positions, boxVectors, numThreads);
    const int numParticles = positions.size();
    if (!periodic)
        collectPairs(numParticles, [&](int i, int j) { return positions[i] - positions[j]; }, numThreads);
    else if (box.isTriclinic())
        collectPairs(
                numParticles,
                [&](int i, int j) { return box.nearestImageTriclinic(wrappedPositions[i] - wrappedPositions[j]); },
                numThreads);
    else
        collectPairs(
                numParticles,
                [&](int i, int j) { return box.nearestImageRectangular(wrappedPositions[i] - wrappedPositions[j]); },
                numThreads);
    return getPairs();
}
