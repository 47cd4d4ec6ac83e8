#ifndef GENDPDE_NEIGHBOR_LIST_H_
#define GENDPDE_NEIGHBOR_LIST_H_

#include "openmm/Vec3.h"
#include <vector>

namespace GenDPDEPlugin {

/** Two particles closer than the cutoff: i < j, delta = r_i - r_j (nearest periodic image), r = |delta|. */
struct ParticlePair {
    int i, j;
    OpenMM::Vec3 delta;
    double r;
};

/** A read-only view of the pairs found by NeighborList::update(), valid until the next update. */
class PairView {
public:
    PairView(const ParticlePair* first, size_t count) : first(first), count(count) {
    }
    const ParticlePair* begin() const {
        return first;
    }
    const ParticlePair* end() const {
        return first + count;
    }
    size_t size() const {
        return count;
    }
    const ParticlePair& operator[](size_t index) const {
        return first[index];
    }
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
 * coordinates (cells at least cutoff + skin wide, so that the 27 surrounding cells hold every candidate) and rebuilt
 * when any particle has moved more than skin/2 since the last build or the box has changed. The periodic image of
 * each candidate is fixed when the list is built: positions are wrapped into the box once (offset o_i) and each
 * candidate records which of the 27 neighbouring images it was found in, so that an update costs a few additions
 * per candidate and no rounding. This is exact because cutoff + skin is kept below half the smallest perpendicular
 * box width (the skin shrinks if needed): then at most one image of a pair can come within range before the next
 * rebuild. Each call to update() costs one distance per candidate: O(N) for a liquid.
 */
class NeighborList {
public:
    NeighborList(double cutoff, double skin, bool periodic);
    /** The pairs at these positions (box ignored unless periodic). Rebuilds the candidate list only when needed. */
    PairView update(const std::vector<OpenMM::Vec3>& positions, const OpenMM::Vec3 boxVectors[3]);
    /** The pairs found by the last update(). */
    PairView getPairs() const {
        return PairView(pairs.data(), numPairs);
    }
    double getCutoff() const {
        return cutoff;
    }
    bool isPeriodic() const {
        return periodic;
    }
    /** How many times the candidate list has been built (for tests and benchmarks). */
    long long getNumBuilds() const {
        return numBuilds;
    }
    /** Forget the candidate list so that the next update() rebuilds it. */
    void invalidate() {
        built = false;
    }
private:
    /** A candidate partner j of particle i and the periodic image (index into imageShift) it was found in. */
    struct Candidate {
        int j, image;
    };
    bool needsRebuild(const std::vector<OpenMM::Vec3>& positions, const OpenMM::Vec3 boxVectors[3]) const;
    void build(const std::vector<OpenMM::Vec3>& positions, const OpenMM::Vec3 boxVectors[3]);
    double cutoff, maxSkin, skin;
    bool periodic, built = false;
    long long numBuilds = 0;
    OpenMM::Vec3 builtBox[3];
    std::vector<OpenMM::Vec3> builtPositions;
    std::vector<OpenMM::Vec3> wrapOffset;          // o_i: r_i + o_i lies in the box (zero if not periodic)
    std::vector<OpenMM::Vec3> shiftedPositions;    // r_i + o_i at the current positions
    OpenMM::Vec3 imageShift[27];                   // sa a + sb b + sc c for sa, sb, sc in {-1, 0, 1}
    std::vector<int> candidateStart;               // candidates of i in candidates[candidateStart[i]..[i+1])
    std::vector<Candidate> candidates;
    std::vector<int> cellStart, cellParticles, particleCell;
    std::vector<ParticlePair> pairs;               // a buffer with room for every candidate; numPairs are in use
    size_t numPairs = 0;
};

} // namespace GenDPDEPlugin

#endif /*GENDPDE_NEIGHBOR_LIST_H_*/
