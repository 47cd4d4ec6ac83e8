#include "NeighborList.h"
#include <algorithm>
#include <array>

using namespace GenDPDEPlugin;
using namespace OpenMM;

PeriodicBox::PeriodicBox(const Vec3 boxVectors[3]) {
    for (int k = 0; k < 3; k++) {
        vectors[k] = boxVectors[k];
        inverseDiagonal[k] = 1.0/boxVectors[k][k];
    }
    triclinic = (vectors[1][0] != 0.0 || vectors[2][0] != 0.0 || vectors[2][1] != 0.0);
}

Vec3 PeriodicBox::wrappedFractional(const Vec3& r) const {
    // Reduced form: a = (ax,0,0), b = (bx,by,0), c = (cx,cy,cz); solve r = s0 a + s1 b + s2 c from z upwards.
    Vec3 s;
    s[2] = r[2]*inverseDiagonal[2];
    s[1] = (r[1] - s[2]*vectors[2][1])*inverseDiagonal[1];
    s[0] = (r[0] - s[2]*vectors[2][0] - s[1]*vectors[1][0])*inverseDiagonal[0];
    for (int k = 0; k < 3; k++) {
        s[k] -= std::floor(s[k]);
        if (s[k] >= 1.0)   // floor of a tiny negative number can round s up to exactly 1
            s[k] = 0.0;
    }
    return s;
}

Vec3 PeriodicBox::perpendicularWidths() const {
    double volume = vectors[0][0]*vectors[1][1]*vectors[2][2];
    Vec3 widths;
    for (int k = 0; k < 3; k++) {
        Vec3 normal = vectors[(k+1)%3].cross(vectors[(k+2)%3]);
        widths[k] = volume/std::sqrt(normal.dot(normal));
    }
    return widths;
}

NeighborList::NeighborList(double cutoff, double skin, bool periodic) : cutoff(cutoff), skin(skin), periodic(periodic) {
}

bool NeighborList::needsRebuild(const std::vector<Vec3>& positions, const PeriodicBox& newBox) const {
    if (!built || positions.size() != builtPositions.size() || (periodic && !(newBox == box)))
        return true;
    double limit = 0.25*skin*skin;   // (skin/2)^2: two particles approach each other by at most skin
    for (size_t i = 0; i < positions.size(); i++) {
        Vec3 moved = positions[i] - builtPositions[i];
        if (moved.dot(moved) > limit)
            return true;
    }
    return false;
}

void NeighborList::build(const std::vector<Vec3>& positions) {
    const int numParticles = positions.size();
    const double listCutoff = cutoff + skin;

    // Cell coordinates in [0, 1)^3: fractional coordinates if periodic, the bounding box otherwise.
    std::vector<Vec3> unit(numParticles);
    Vec3 extent;
    if (periodic) {
        extent = box.perpendicularWidths();
        for (int i = 0; i < numParticles; i++)
            unit[i] = box.wrappedFractional(positions[i]);
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

    // For each dimension and cell coordinate, the distinct cells within one step (with wrap-around if periodic).
    std::array<std::vector<std::vector<int>>, 3> neighbourCells;
    for (int k = 0; k < 3; k++) {
        neighbourCells[k].resize(numCells[k]);
        for (int c = 0; c < numCells[k]; c++)
            for (int offset = -1; offset <= 1; offset++) {
                int n = c + offset;
                if (periodic)
                    n = (n + numCells[k]) % numCells[k];
                else if (n < 0 || n >= numCells[k])
                    continue;
                std::vector<int>& cells = neighbourCells[k][c];
                if (std::find(cells.begin(), cells.end(), n) == cells.end())
                    cells.push_back(n);
            }
    }

    // Candidates of each particle: all j > i within listCutoff, sorted.
    candidateStart.assign(numParticles + 1, 0);
    candidates.clear();
    const double listCutoff2 = listCutoff*listCutoff;
    for (int i = 0; i < numParticles; i++) {
        int cell = particleCell[i];
        int cz = cell % numCells[2], cy = (cell/numCells[2]) % numCells[1], cx = cell/(numCells[2]*numCells[1]);
        size_t first = candidates.size();
        for (int nx : neighbourCells[0][cx])
            for (int ny : neighbourCells[1][cy])
                for (int nz : neighbourCells[2][cz]) {
                    int neighbour = (nx*numCells[1] + ny)*numCells[2] + nz;
                    for (int m = cellStart[neighbour]; m < cellStart[neighbour + 1]; m++) {
                        int j = cellParticles[m];
                        if (j <= i)
                            continue;
                        Vec3 d = displacement(positions[i], positions[j]);
                        if (d.dot(d) < listCutoff2)
                            candidates.push_back(j);
                    }
                }
        std::sort(candidates.begin() + first, candidates.end());
        candidateStart[i + 1] = candidates.size();
    }
    builtPositions = positions;
    built = true;
    numBuilds++;
}

const std::vector<ParticlePair>& NeighborList::update(const std::vector<Vec3>& positions, const Vec3 boxVectors[3]) {
    PeriodicBox newBox = periodic ? PeriodicBox(boxVectors) : PeriodicBox();
    if (needsRebuild(positions, newBox)) {
        box = newBox;
        build(positions);
    }
    pairs.clear();
    const double cutoff2 = cutoff*cutoff;
    const int numParticles = positions.size();
    for (int i = 0; i < numParticles; i++) {
        const Vec3 ri = positions[i];
        for (int m = candidateStart[i]; m < candidateStart[i + 1]; m++) {
            int j = candidates[m];
            Vec3 d = displacement(ri, positions[j]);
            double r2 = d.dot(d);
            if (r2 < cutoff2)
                pairs.push_back({i, j, d, std::sqrt(r2)});
        }
    }
    return pairs;
}
