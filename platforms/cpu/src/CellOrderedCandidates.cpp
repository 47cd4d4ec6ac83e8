/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
#include "CellOrderedCandidates.h"
#include "internal/Buffers.h"
#include "internal/ParallelFor.h"
#include <algorithm>

using namespace GenDPDEPlugin;
using namespace OpenMM;

namespace {
/** Rows per range of work. */
const int rowChunk = 1024;
}

void CellOrderedCandidates::update(const NeighborList& list, int numThreads) {
    if (&list != followedList || list.getBuildCount() != followedBuild)
        buildRows(list, numThreads);
    const Vec3* source = list.getRefreshedPositions().data();
    const int* particleOf = particle.data();
    positions.resize(particle.size() + 1);   // one Vec3 of padding: vector loads read 4 doubles from a Vec3
    Vec3* target = positions.data();
    parallelFor(numThreads, particle.size(), rowChunk, [=](int begin, int end) {
        for (int s = begin; s < end; s++)
            target[s] = source[particleOf[s]];
    });
}

void CellOrderedCandidates::buildRows(const NeighborList& list, int numThreads) {
    particle = list.getCellOrder();
    const int numRows = particle.size();
    row.resize(numRows);
    for (int s = 0; s < numRows; s++)
        row[particle[s]] = s;

    // Row sizes: the candidates (j, i) of each particle i, then its own candidates (i, j).
    lowerCount.assign(numRows, 0);
    for (int i = 0; i < numRows; i++)
        for (int j : list.candidatesOf(i))
            lowerCount[j]++;
    rowStart.assign(numRows + 1, 0);
    upperStart.resize(numRows);
    for (int s = 0; s < numRows; s++) {
        const int i = particle[s];
        upperStart[s] = rowStart[s] + lowerCount[i];
        rowStart[s + 1] = upperStart[s] + list.candidatesOf(i).size();
    }
    resizeBuffer(neighbors, rowStart[numRows]);

    // The upper parts, row by row in parallel; the lower parts by one pass over the candidates in (i, j) order,
    // which appends each i to the row of j in increasing order of i.
    const int* particleOf = particle.data();
    const int* rowOf = row.data();
    const int* upper = upperStart.data();
    int* neighbor = neighbors.data();
    const NeighborList* candidates = &list;
    parallelFor(numThreads, numRows, rowChunk, [=](int begin, int end) {
        for (int s = begin; s < end; s++) {
            const int i = particleOf[s];
            int m = upper[s];
            for (int j : candidates->candidatesOf(i))
                neighbor[m++] = rowOf[j];
        }
    });
    std::vector<int>& fill = lowerCount; // (one buffer for both)
    fill.assign(rowStart.begin(), rowStart.end() - 1);
    for (int i = 0; i < numRows; i++)
        for (int j : list.candidatesOf(i))
            neighbor[fill[rowOf[j]]++] = rowOf[i];
    followedList = &list;
    followedBuild = list.getBuildCount();
}
