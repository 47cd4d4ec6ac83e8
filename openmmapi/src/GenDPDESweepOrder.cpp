#include "internal/GenDPDESweepOrder.h"
#include "internal/BoxGeometry.h"
#include "internal/ParallelFor.h"
#include <algorithm>
#include <cmath>

using namespace GenDPDEPlugin;
using namespace OpenMM;

namespace {

const int numColours = 8;
/** Cells are at least this factor times the range wide, so that rounding can never put a pair in range two cells
 *  apart. */
const double cellMargin = 1.0 + 1e-9;

/**
 * Copy the pairs listed[0..count) (sorted by their first particle) to output, with the lists of each four
 * consecutive distinct first particles interleaved: the first pair of each list, then the second of each, ...
 */
void interleaveRuns(const int* listed, int count, const int* pairI, int stride, int* output) {
    int next = 0, start = 0;
    while (start < count) {
        // Up to four runs of equal first particle, starting at `start`.
        int runStart[5], numRuns = 0, end = start;
        while (numRuns < 4 && end < count) {
            runStart[numRuns++] = end;
            const int first = pairI[(size_t) listed[end]*stride];
            while (end < count && pairI[(size_t) listed[end]*stride] == first)
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

} // namespace

void GenDPDESweepOrder::computeCells(const std::vector<Vec3>& positions, const Vec3 boxVectors[3], bool periodic,
                                     double range, ThreadPool* threads) {
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
    for (int k = 0; k < 3; k++) {
        const double fit = std::floor(extent[k]/(cellMargin*range));
        const int m = (int) std::min(fit, 1e6);
        if (periodic)
            numCells[k] = (m >= 4 ? 4*(m/4) : (m >= 2 ? 2 : 1));
        else
            numCells[k] = std::max(1, m);
        numBlocks[k] = (numCells[k] + 1)/2;
    }
    particleCell.resize(numParticles);
    parallelFor(threads, numParticles, 4096, [&](int begin, int end) {
        for (int i = begin; i < end; i++) {
            const Vec3 s = periodic ? BoxGeometry::fractionalCoordinates(positions[i], boxVectors) : Vec3();
            for (int k = 0; k < 3; k++) {
                double unit;
                if (periodic)
                    unit = s[k] - std::floor(s[k]);
                else
                    unit = extent[k] > 0.0 ? (positions[i][k] - low[k])/extent[k] : 0.0;
                particleCell[i][k] = std::max(0, std::min(numCells[k] - 1, (int) (unit*numCells[k])));
            }
        }
    });
}

int GenDPDESweepOrder::homeCell(int a, int b, int k) const {
    if (a == b)
        return a;
    const int n = numCells[k];
    if (periodic) {
        if ((a + 1) % n == b)
            return a;
        if ((b + 1) % n == a)
            return b;
    }
    else {
        if (b == a + 1)
            return a;
        if (a == b + 1)
            return b;
    }
    return -1;
}

void GenDPDESweepOrder::build(const std::vector<Vec3>& positions, const Vec3 boxVectors[3], bool periodic,
                              double range, int numPairs, const int* pairI, const int* pairJ, int stride,
                              ThreadPool* threads) {
    computeCells(positions, boxVectors, periodic, range, threads);

    // Slots: the blocks in sweep order (colour by colour, by block index within a colour), then one slot for the
    // pairs whose cells are not adjacent.
    const int totalBlocks = numBlocks[0]*numBlocks[1]*numBlocks[2];
    slotOfBlock.resize(totalBlocks);
    groupStart.assign(1, 0);
    int slot = 0;
    for (int colour = 0; colour < numColours; colour++) {
        for (int block = 0; block < totalBlocks; block++) {
            const int bx = block % numBlocks[0], by = (block/numBlocks[0]) % numBlocks[1];
            const int bz = block/(numBlocks[0]*numBlocks[1]);
            if ((bx % 2) + 2*(by % 2) + 4*(bz % 2) == colour)
                slotOfBlock[block] = slot++;
        }
        groupStart.push_back(slot);
    }
    const int extraSlot = slot++;
    groupStart.push_back(slot);

    // Each pair's slot.
    pairSlot.resize(numPairs);
    parallelFor(threads, numPairs, 4096, [&](int begin, int end) {
        for (int k = begin; k < end; k++) {
            const std::array<int, 3>& ci = particleCell[pairI[(size_t) k*stride]];
            const std::array<int, 3>& cj = particleCell[pairJ[(size_t) k*stride]];
            int home[3];
            bool adjacent = true;
            for (int d = 0; d < 3; d++) {
                home[d] = homeCell(ci[d], cj[d], d);
                adjacent = adjacent && home[d] >= 0;
            }
            pairSlot[k] = adjacent ? slotOfBlock[((home[2]/2)*numBlocks[1] + home[1]/2)*numBlocks[0] + home[0]/2]
                                   : extraSlot;
        }
    });

    // A stable counting sort by slot keeps each block's pairs in (i, j) order.
    blockStart.assign(slot + 1, 0);
    for (int k = 0; k < numPairs; k++)
        blockStart[pairSlot[k] + 1]++;
    for (int s = 0; s < slot; s++)
        blockStart[s + 1] += blockStart[s];
    sorted.resize(numPairs);
    slotCount.assign(blockStart.begin(), blockStart.end() - 1);
    for (int k = 0; k < numPairs; k++)
        sorted[slotCount[pairSlot[k]]++] = k;

    // Within each block, the lists of four consecutive first particles interleaved.
    order.resize(numPairs);
    parallelFor(threads, slot, 8, [&](int begin, int end) {
        for (int s = begin; s < end; s++)
            interleaveRuns(&sorted[blockStart[s]], blockStart[s + 1] - blockStart[s], pairI, stride,
                           &order[blockStart[s]]);
    });
}
