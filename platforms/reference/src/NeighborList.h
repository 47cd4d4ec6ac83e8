/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
#ifndef GENDPDE_NEIGHBOR_LIST_H_
#define GENDPDE_NEIGHBOR_LIST_H_

#include "gendpde/GenDPDESweepDefinition.h"
#include "internal/BoxGeometry.h"
#include <cstdint>
#include "openmm/Vec3.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace GenDPDEPlugin {

/**
 * Wrapping and nearest images in an OpenMM periodic box (reduced form: a = (ax,0,0), b = (bx,by,0),
 * c = (cx,cy,cz)). Both are pure functions of their arguments, so displacements computed with them do not depend on
 * any history (needed for bit-for-bit continuation from checkpoints).
 */
class PeriodicBox {
public:
    PeriodicBox() = default;
    explicit PeriodicBox(const OpenMM::Vec3 vectors[3]);
    bool isTriclinic() const { return triclinic; }
    /** r moved by a lattice vector into [0, ax) x [0, by) x [0, cz). */
    OpenMM::Vec3 wrap(OpenMM::Vec3 r) const {
        r -= vectors[2] * BoxGeometry::floorToInteger(r[2] * inverseDiagonal[2]);
        r -= vectors[1] * BoxGeometry::floorToInteger(r[1] * inverseDiagonal[1]);
        r -= vectors[0] * BoxGeometry::floorToInteger(r[0] * inverseDiagonal[0]);
        return r;
    }
    /** The nearest image of a difference d in a rectangular box. */
    OpenMM::Vec3 nearestImageRectangular(OpenMM::Vec3 d) const {
        for (int k = 0; k < 3; k++)
            d[k] -= vectors[k][k] * BoxGeometry::roundToInteger(d[k] * inverseDiagonal[k]);
        return d;
    }
    /** The nearest image of a difference d in a reduced triclinic box (OpenMM's convention). */
    OpenMM::Vec3 nearestImageTriclinic(OpenMM::Vec3 d) const {
        d -= vectors[2] * BoxGeometry::roundToInteger(d[2] * inverseDiagonal[2]);
        d -= vectors[1] * BoxGeometry::roundToInteger(d[1] * inverseDiagonal[1]);
        d -= vectors[0] * BoxGeometry::roundToInteger(d[0] * inverseDiagonal[0]);
        return d;
    }
    OpenMM::Vec3 nearestImage(const OpenMM::Vec3& d) const {
        return triclinic ? nearestImageTriclinic(d) : nearestImageRectangular(d);
    }
    const OpenMM::Vec3* getVectors() const { return vectors; }
    /** 1/ax, 1/by, 1/cz (1/nm). */
    const OpenMM::Vec3& getInverseDiagonal() const { return inverseDiagonal; }

private:
    OpenMM::Vec3 vectors[3], inverseDiagonal;
    bool triclinic = false;
};

/**
 * body(nearestImage) with the nearest-image rule of this box chosen once, not once per pair: the identity (box null:
 * not periodic), or a copy of the box's triclinic or rectangular rule. The CPU platform's gathers and its sweep both
 * take their rule here, so the displacements they compute from the same positions have the same bits.
 */
template <class Body>
void withNearestImage(const PeriodicBox* box, Body body) {
    if (box == nullptr)
        body([](const OpenMM::Vec3& d) { return d; });
    else if (box->isTriclinic())
        body([copy = *box](const OpenMM::Vec3& d) { return copy.nearestImageTriclinic(d); });
    else
        body([copy = *box](const OpenMM::Vec3& d) { return copy.nearestImageRectangular(d); });
}

/** Two particles closer than the cutoff: i < j, delta = r_i - r_j (nearest periodic image), r = |delta|. */
struct ParticlePair {
    int i, j;
    OpenMM::Vec3 delta;
    double r;
};

/** A pair of particles (i < j) without its geometry: the integrator's candidates (8 bytes where a ParticlePair takes 40). */
struct IndexPair {
    int i, j;
};

/** A read-only view of the pairs found by NeighborList::update(), in (i, j) order, valid until the next update. */
class PairView {
public:
    PairView(const ParticlePair* first, size_t count) : first(first), count(count) {}
    const ParticlePair* begin() const { return first; }
    const ParticlePair* end() const { return first + count; }
    size_t size() const { return count; }
    const ParticlePair& operator[](size_t index) const { return first[index]; }

private:
    const ParticlePair* first;
    size_t count;
};

/**
 * All pairs of particles closer than a cutoff, listed once each with i < j, in lexicographic (i, j) order whatever
 * the positions or the history of the list. That canonical order makes any sequential sweep over the pairs a pure
 * function of the configuration.
 *
 * Implementation: a Verlet list of candidates within cutoff + skin, built with a cell grid in fractional
 * coordinates (cells at least cutoff + skin wide, so that the surrounding cells hold every candidate) and rebuilt
 * when any particle has moved more than skin/2 since the last build or the box has changed. Each update wraps the
 * positions into the box and takes the nearest image of each candidate's difference: one distance per candidate,
 * O(N) for a liquid. The displacement of a pair is a pure function of the current positions, never of the list's
 * history, so a run continued from a checkpoint (with a freshly built list) reproduces the uninterrupted run bit
 * for bit.
 *
 * Given several threads (the CPU platform), they share the work: the candidates and pairs are the same, in the same
 * order.
 */
class NeighborList {
public:
    /**
     * The skin the kernels use, as a fraction of the cutoff: candidates within 1.1 R, rebuilt after 0.05 R (the sweep
     * order's rule, SweepDefinition, which the integrator's list applies).
     */
    static constexpr double defaultSkinFraction = SweepDefinition::skinFraction;
    NeighborList(double cutoff, double skin, bool periodic);
    /** The pairs at these positions (box ignored unless periodic). Rebuilds the candidate list only when needed. */
    PairView update(const std::vector<OpenMM::Vec3>& positions, const OpenMM::Vec3 boxVectors[3], int numThreads = 1);
    /**
     * Wrap these positions and rebuild the candidates if needed, without collecting the pairs: for a caller that
     * evaluates the candidates itself (displacement()).
     */
    void refresh(const std::vector<OpenMM::Vec3>& positions, const OpenMM::Vec3 boxVectors[3], int numThreads = 1);
    bool isPeriodic() const { return periodic; }
    /** The box of the last refresh() (periodic only). */
    const PeriodicBox& getBox() const { return box; }
    /** The positions of the last refresh(), wrapped into the box if periodic (nm). */
    const std::vector<OpenMM::Vec3>& getRefreshedPositions() const {
        return periodic ? wrappedPositions : *currentPositions;
    }
    /** A particle's candidates, for (int j : list.candidatesOf(i)). */
    struct Candidates {
        const int *first, *last;
        const int* begin() const { return first; }
        const int* end() const { return last; }
        int size() const { return last - first; }
    };
    /** The candidates j > i of particle i, in increasing order. */
    Candidates candidatesOf(int i) const {
        const int chunk = i / particleChunk;
        const int* first = chunkCandidates[chunk].data() + (candidateStart[i] - candidateStart[chunk * particleChunk]);
        return {first, first + (candidateStart[i + 1] - candidateStart[i])};
    }
    /** All particles' candidates: the sum of candidatesOf(i).size(). */
    int getNumCandidates() const { return candidateStart.back(); }
    /** The particles sorted by cell at the last build (neighbors in space are neighbors in this order). */
    const std::vector<int>& getCellOrder() const { return cellParticles; }
    /**
     * Whether this list's candidates are those that `other` (a list of the same cutoff, skin and boundaries) would find
     * at these positions (nm) and box: it was last built at exactly these positions (and box, if periodic).
     */
    bool holdsCandidatesAt(const std::vector<OpenMM::Vec3>& positions, const OpenMM::Vec3 boxVectors[3],
                           const NeighborList& other) const {
        if (!built || cutoff != other.cutoff || skin != other.skin || periodic != other.periodic
            || builtPositions.size() != positions.size())
            return false;
        if (periodic && !(boxVectors[0] == builtBox[0] && boxVectors[1] == builtBox[1] && boxVectors[2] == builtBox[2]))
            return false;
        return std::equal(positions.begin(), positions.end(), builtPositions.begin(),
                          [](const OpenMM::Vec3& a, const OpenMM::Vec3& b) { return a == b; });
    }
    /**
     * Whether some particle is farther from its place in `then` than sqrt(limit2) (nm) in `now` (the same size; plain
     * differences, no periodic images), on this many threads: the rule of rebuilds.
     */
    static bool anyMovedFarther(const std::vector<OpenMM::Vec3>& now, const std::vector<OpenMM::Vec3>& then,
                                double limit2, int numThreads);
    /** Forget the candidates: the next refresh() builds them whatever the positions. */
    void invalidate() { built = false; }
    /** How many times the candidates have been built: a change means new candidates. */
    long long getBuildCount() const { return buildCount; }
    double getCutoff() const { return cutoff; }
    /** The pairs found by the last update(). */
    PairView getPairs() const { return PairView(pairs.data(), numPairs); }

private:
    bool needsRebuild(const std::vector<OpenMM::Vec3>& positions, const OpenMM::Vec3 boxVectors[3],
                      int numThreads) const;
    void build(const std::vector<OpenMM::Vec3>& positions, int numThreads);
    /**
     * Positions mapped into [0, 1)^3 (fractional if periodic, else the bounding box) into `unit`; extent: its widths
     * (nm).
     */
    void unitCellCoordinates(const std::vector<OpenMM::Vec3>& positions, OpenMM::Vec3& extent, int numThreads,
                             std::vector<OpenMM::Vec3>& unit) const;
    /** Choose the cell grid for this extent and sort the particles into it (cellStart, cellParticles). */
    void sortIntoCells(const std::vector<OpenMM::Vec3>& unit, const OpenMM::Vec3& extent);
    /** For each dimension and cell coordinate, the distinct cell coordinates within one step. */
    std::array<std::vector<std::vector<int>>, 3> neighborCellsPerDimension() const;
    /**
     * The candidates of each particle (j > i within cutoff + skin), from the cells around it; cellPositions: a buffer
     * for the positions in cell order.
     */
    void collectCandidates(const std::vector<OpenMM::Vec3>& positions, int numThreads,
                           std::vector<OpenMM::Vec3>& cellPositions);
    /**
     * The candidates of the particles at places begin .. end - 1 of the cell order, their rows one after another into
     * `found`: the count of particle i's in candidateStart[i + 1], where its row begins in rowLocation[i] (range, the
     * range's number shifted left by 32 bits, or the row's offset in `found`).
     */
    void findCandidates(const std::vector<OpenMM::Vec3>& cellPositions, int begin, int end,
                        const std::array<std::vector<std::vector<int>>, 3>& neighborCells, std::vector<int>& found,
                        std::int64_t range, std::vector<std::int64_t>& rowLocation);
    /** Fill the pair buffer from the candidates, with `displacement(i, j)` giving r_i - r_j. */
    template <class Displacement>
    void collectPairs(int numParticles, Displacement displacement, int numThreads);
    /** The pairs among the candidates of particles begin .. end - 1, appended to `found`. */
    template <class Displacement>
    void findPairs(int begin, int end, Displacement displacement, std::vector<ParticlePair>& found) const;
    double cutoff, skin;
    bool periodic, built = false;
    long long buildCount = 0;
    PeriodicBox box; // the current box
    OpenMM::Vec3 builtBox[3]; // the box when the candidates were built
    std::vector<OpenMM::Vec3> builtPositions;
    std::vector<OpenMM::Vec3> wrappedPositions; // positions wrapped into the box (periodic only)
    /** Particles per range when threads share the work (fixed, so ranges do not depend on the thread count). */
    static const int particleChunk = 256;
    // The candidates by ranges of particle indices (not in one array: that would hold them twice while it is made):
    // those of particles [c particleChunk, (c + 1) particleChunk) in chunkCandidates[c]; candidateStart[i]: the
    // candidates of the particles before i. (A build finds them in cell order, into scratch it frees afterwards.)
    std::vector<int> candidateStart;
    std::vector<std::vector<int>> chunkCandidates;
    std::array<int, 3> numCells; // the cell grid of the last build
    std::vector<int> cellStart, cellParticles, particleCell;
    // Scratch of a build kept between builds: each cell's next place. (The unit-cell coordinates
    // and the positions in cell order use builtPositions' buffer, build().)
    std::vector<int> cellFill;
    const std::vector<OpenMM::Vec3>* currentPositions = nullptr; // those of the last refresh (not periodic)
    std::vector<ParticlePair> pairs; // a buffer with room for every candidate; numPairs are in use
    size_t numPairs = 0;
    std::vector<std::vector<ParticlePair>> chunkPairs;
};

} // namespace GenDPDEPlugin

#endif /*GENDPDE_NEIGHBOR_LIST_H_*/
