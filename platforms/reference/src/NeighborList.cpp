#include "NeighborList.h"
#include "internal/BoxGeometry.h"
#include <algorithm>
#include <array>
#include <cmath>

using namespace GenDPDEPlugin;
using namespace OpenMM;

NeighborList::NeighborList(double cutoff, double skin, bool periodic) :
        cutoff(cutoff), maxSkin(skin), skin(skin), periodic(periodic) {
}

bool NeighborList::needsRebuild(const std::vector<Vec3>& positions, const Vec3 boxVectors[3]) const {
    if (!built || positions.size() != builtPositions.size())
        return true;
    if (periodic && !(boxVectors[0] == builtBox[0] && boxVectors[1] == builtBox[1] && boxVectors[2] == builtBox[2]))
        return true;
    double limit = 0.25*skin*skin;   // (skin/2)^2: two particles approach each other by at most skin
    for (size_t i = 0; i < positions.size(); i++) {
        Vec3 moved = positions[i] - builtPositions[i];
        if (moved.dot(moved) >= limit)
            return true;
    }
    return false;
}

void NeighborList::build(const std::vector<Vec3>& positions, const Vec3 boxVectors[3]) {
    const int numParticles = positions.size();
    for (int k = 0; k < 3; k++)
        builtBox[k] = boxVectors[k];

    // Unit cell coordinates in [0, 1)^3 and wrap offsets: fractional coordinates if periodic, else the bounding box.
    std::vector<Vec3> unit(numParticles);
    wrapOffset.assign(numParticles, Vec3());
    Vec3 extent;
    if (periodic) {
        // Keep cutoff + skin below half the smallest width, so that each pair has at most one image in range.
        skin = std::max(0.0, std::min(maxSkin, BoxGeometry::halfSmallestWidth(boxVectors)*(1 - 1e-12) - cutoff));
        extent = BoxGeometry::perpendicularWidths(boxVectors);
        for (int i = 0; i < numParticles; i++) {
            Vec3 s = BoxGeometry::fractionalCoordinates(positions[i], boxVectors);
            Vec3 cells(std::floor(s[0]), std::floor(s[1]), std::floor(s[2]));
            for (int k = 0; k < 3; k++)
                unit[i][k] = std::min(std::max(s[k] - cells[k], 0.0), std::nextafter(1.0, 0.0));
            wrapOffset[i] = -(boxVectors[0]*cells[0] + boxVectors[1]*cells[1] + boxVectors[2]*cells[2]);
        }
    }
    else {
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
                unit[i][k] = extent[k] > 0.0 ? (positions[i][k] - low[k])/extent[k] : 0.0;
    }
    const double listCutoff = cutoff + skin;

    // Cells at least listCutoff wide; no more cells than are useful for this many particles.
    std::array<int, 3> numCells;
    for (int k = 0; k < 3; k++)
        numCells[k] = std::max(1, (int) std::min(1.0e4, std::floor(extent[k]/listCutoff)));
    const double maxCells = std::max(27.0, 2.0*numParticles);
    while ((double) numCells[0]*numCells[1]*numCells[2] > maxCells)
        for (int k = 0; k < 3; k++)
            numCells[k] = std::max(1, numCells[k]/2);
    const int totalCells = numCells[0]*numCells[1]*numCells[2];

    // Counting sort of the particles into cells; within a cell they stay in ascending index order.
    particleCell.resize(numParticles);
    cellStart.assign(totalCells + 1, 0);
    for (int i = 0; i < numParticles; i++) {
        int cell = 0;
        for (int k = 0; k < 3; k++)
            cell = cell*numCells[k] + std::min(numCells[k] - 1, (int) (unit[i][k]*numCells[k]));
        particleCell[i] = cell;
        cellStart[cell + 1]++;
    }
    for (int c = 0; c < totalCells; c++)
        cellStart[c + 1] += cellStart[c];
    cellParticles.resize(numParticles);
    std::vector<int> fill(cellStart.begin(), cellStart.end() - 1);
    for (int i = 0; i < numParticles; i++)
        cellParticles[fill[particleCell[i]]++] = i;

    // The 27 images: imageShift[9 (sa+1) + 3 (sb+1) + (sc+1)] = sa a + sb b + sc c.
    for (int sa = -1; sa <= 1; sa++)
        for (int sb = -1; sb <= 1; sb++)
            for (int sc = -1; sc <= 1; sc++)
                imageShift[9*(sa + 1) + 3*(sb + 1) + (sc + 1)] = periodic ?
                        boxVectors[0]*sa + boxVectors[1]*sb + boxVectors[2]*sc : Vec3();

    // Candidates of each particle: all j > i with an image within listCutoff, sorted by j. A neighbouring cell
    // across the box boundary is the wrapped cell seen through the image shifted by one box vector; with fewer than
    // three cells along a dimension the same cell is visited through different images, which is what is wanted.
    shiftedPositions.resize(numParticles);
    for (int i = 0; i < numParticles; i++)
        shiftedPositions[i] = positions[i] + wrapOffset[i];
    candidateStart.assign(numParticles + 1, 0);
    candidates.clear();
    const double listCutoff2 = listCutoff*listCutoff;
    for (int i = 0; i < numParticles; i++) {
        const int cell = particleCell[i];
        const int cellIndex[3] = {cell/(numCells[2]*numCells[1]), (cell/numCells[2]) % numCells[1], cell % numCells[2]};
        const Vec3 ri = shiftedPositions[i];
        const size_t first = candidates.size();
        for (int neighbour = 0; neighbour < 27; neighbour++) {
            int offset[3] = {neighbour/9 - 1, (neighbour/3) % 3 - 1, neighbour % 3 - 1};
            int target[3], shift[3];
            bool exists = true;
            for (int k = 0; k < 3; k++) {
                int c = cellIndex[k] + offset[k];
                shift[k] = (c < 0 ? -1 : (c >= numCells[k] ? 1 : 0));
                if (!periodic && shift[k] != 0)
                    exists = false;
                target[k] = c - shift[k]*numCells[k];
            }
            if (!exists)
                continue;   // beyond the edge of a non-periodic grid
            const int image = 9*(shift[0] + 1) + 3*(shift[1] + 1) + (shift[2] + 1);
            const Vec3 imageOffset = imageShift[image];
            const int targetCell = (target[0]*numCells[1] + target[1])*numCells[2] + target[2];
            for (int m = cellStart[targetCell]; m < cellStart[targetCell + 1]; m++) {
                int j = cellParticles[m];
                if (j <= i)
                    continue;
                Vec3 d = ri - shiftedPositions[j] - imageOffset;
                if (d.dot(d) < listCutoff2)
                    candidates.push_back({j, image});
            }
        }
        std::sort(candidates.begin() + first, candidates.end(),
                  [](const Candidate& a, const Candidate& b) { return a.j < b.j; });
        candidateStart[i + 1] = candidates.size();
    }
    builtPositions = positions;
    built = true;
    numBuilds++;
}

PairView NeighborList::update(const std::vector<Vec3>& positions, const Vec3 boxVectors[3]) {
    if (needsRebuild(positions, boxVectors))
        build(positions, boxVectors);
    else
        for (size_t i = 0; i < positions.size(); i++)
            shiftedPositions[i] = positions[i] + wrapOffset[i];
    // Fill a buffer with room for every candidate, field by field (a push_back of a temporary pair stalls on
    // store-to-load forwarding). The buffer only grows, so it is never re-initialised.
    if (pairs.size() < candidates.size())
        pairs.resize(candidates.size());
    numPairs = 0;
    const double cutoff2 = cutoff*cutoff;
    const int numParticles = positions.size();
    for (int i = 0; i < numParticles; i++) {
        const Vec3 ri = shiftedPositions[i];
        for (int m = candidateStart[i]; m < candidateStart[i + 1]; m++) {
            const Candidate& candidate = candidates[m];
            Vec3 d = ri - shiftedPositions[candidate.j] - imageShift[candidate.image];
            double r2 = d.dot(d);
            if (r2 < cutoff2) {
                ParticlePair& pair = pairs[numPairs++];
                pair.i = i;
                pair.j = candidate.j;
                pair.delta = d;
                pair.r = r2;
            }
        }
    }
    // Square roots in a pass of their own: independent, so they pipeline instead of stalling the search above.
    for (size_t k = 0; k < numPairs; k++)
        pairs[k].r = std::sqrt(pairs[k].r);
    return getPairs();
}
