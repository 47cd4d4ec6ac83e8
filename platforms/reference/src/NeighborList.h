#ifndef GENDPDE_NEIGHBOR_LIST_H_
#define GENDPDE_NEIGHBOR_LIST_H_

#include "openmm/Vec3.h"
#include <cmath>
#include <vector>

namespace GenDPDEPlugin {

/** Minimum-image displacement in an OpenMM periodic box (reduced triclinic form, or rectangular as a fast path). */
class PeriodicBox {
public:
    PeriodicBox() = default;
    explicit PeriodicBox(const OpenMM::Vec3 vectors[3]);
    /** The minimum-image version of the displacement d (OpenMM's convention for reduced triclinic boxes). */
    OpenMM::Vec3 minimumImage(OpenMM::Vec3 d) const {
        if (triclinic) {
            d -= vectors[2]*std::floor(d[2]*inverseDiagonal[2] + 0.5);
            d -= vectors[1]*std::floor(d[1]*inverseDiagonal[1] + 0.5);
            d -= vectors[0]*std::floor(d[0]*inverseDiagonal[0] + 0.5);
        }
        else {
            d[0] -= vectors[0][0]*std::floor(d[0]*inverseDiagonal[0] + 0.5);
            d[1] -= vectors[1][1]*std::floor(d[1]*inverseDiagonal[1] + 0.5);
            d[2] -= vectors[2][2]*std::floor(d[2]*inverseDiagonal[2] + 0.5);
        }
        return d;
    }
    /** Fractional coordinates s of r = s_0 a + s_1 b + s_2 c, wrapped into [0, 1). */
    OpenMM::Vec3 wrappedFractional(const OpenMM::Vec3& r) const;
    /** Distance between opposite faces of the box along each lattice direction (nm). */
    OpenMM::Vec3 perpendicularWidths() const;
    bool operator==(const PeriodicBox& other) const {
        return vectors[0] == other.vectors[0] && vectors[1] == other.vectors[1] && vectors[2] == other.vectors[2];
    }
private:
    OpenMM::Vec3 vectors[3], inverseDiagonal;
    bool triclinic = false;
};

/** Two particles closer than the cutoff: i < j, delta = r_i - r_j (minimum image if periodic), r = |delta|. */
struct ParticlePair {
    int i, j;
    OpenMM::Vec3 delta;
    double r;
};

/**
 * All pairs of particles closer than a cutoff, listed once each with i < j, in lexicographic (i, j) order whatever
 * the positions or the history of the list. That canonical order makes any sequential sweep over the pairs a pure
 * function of the configuration.
 *
 * Implementation: a Verlet list of candidates within cutoff + skin, built with a cell grid in fractional
 * coordinates (cells at least cutoff + skin wide, so that the 27 surrounding cells hold every candidate) and rebuilt
 * when any particle has moved more than skin/2 since the last build or the box has changed. Each call to update()
 * then costs one distance per candidate: O(N) for a liquid.
 */
class NeighborList {
public:
    NeighborList(double cutoff, double skin, bool periodic);
    /** The pairs at these positions (box ignored unless periodic). Rebuilds the candidate list only when needed. */
    const std::vector<ParticlePair>& update(const std::vector<OpenMM::Vec3>& positions, const OpenMM::Vec3 boxVectors[3]);
    /** The pairs found by the last update(). */
    const std::vector<ParticlePair>& getPairs() const {
        return pairs;
    }
    const PeriodicBox& getBox() const {
        return box;
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
    bool needsRebuild(const std::vector<OpenMM::Vec3>& positions, const PeriodicBox& newBox) const;
    void build(const std::vector<OpenMM::Vec3>& positions);
    OpenMM::Vec3 displacement(const OpenMM::Vec3& ri, const OpenMM::Vec3& rj) const {
        return periodic ? box.minimumImage(ri - rj) : ri - rj;
    }
    double cutoff, skin;
    bool periodic, built = false;
    long long numBuilds = 0;
    PeriodicBox box;
    std::vector<OpenMM::Vec3> builtPositions;
    std::vector<int> candidateStart, candidates;   // CSR: candidates of i (all j > i) in candidates[candidateStart[i]..]
    std::vector<int> cellStart, cellParticles, particleCell;
    std::vector<ParticlePair> pairs;
};

} // namespace GenDPDEPlugin

#endif /*GENDPDE_NEIGHBOR_LIST_H_*/
