/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
/* GenDPDESweepOrder, the order of the pair updates every platform follows (docs/theory.md section 6), made from the
 * candidates (pairs closer than 1.1 R at the build): each candidate exactly once; blocks of one colour share no
 * particle and the pairs of one level of a block share none (what makes the parallel sweeps equal to the sequential
 * one); the order element by element as the definition states it, written out here (cells, blocks, colours, greedy
 * levels with sets); a pure function of positions, box and candidates (periodic images, thread count); one block
 * when the box is too small for blocks. The candidates come from an O(N^2) search written here. */

#include "TestScenes.h"
#include "TestUtilities.h"
#include "internal/BoxGeometry.h"
#include "internal/GenDPDESweepOrder.h"
#include "gendpde/GenDPDESweepDefinition.h"
#include <algorithm>
#include <map>
#include <array>
#include <cmath>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

using namespace GenDPDEPlugin;
using namespace OpenMM;
using namespace TestScenes;

/** The reach of the candidates for the scenes' pair range. */
const double candidates = SweepDefinition::candidateRange(cutoff);

struct Pairs {
    std::vector<int> ij;   // i0, j0, i1, j1, ...
    int size() const { return ij.size() / 2; }
};

/** All pairs closer than range, sorted by (i, j), by brute force (nearest image in a reduced box if periodic). */
Pairs findPairs(const std::vector<Vec3>& positions, const Vec3 box[3], bool periodic, double range) {
    Pairs pairs;
    for (size_t i = 0; i < positions.size(); i++)
        for (size_t j = i + 1; j < positions.size(); j++) {
            Vec3 d = positions[i] - positions[j];
            if (periodic) {
                d -= box[2] * std::round(d[2] / box[2][2]);
                d -= box[1] * std::round(d[1] / box[1][1]);
                d -= box[0] * std::round(d[0] / box[0][0]);
            }
            if (d.dot(d) < range * range) {
                pairs.ij.push_back(i);
                pairs.ij.push_back(j);
            }
        }
    return pairs;
}

GenDPDESweepOrder buildOrder(const Scene& scene, const std::vector<Vec3>& positions, const Pairs& pairs,
                             int numThreads = 1) {
    GenDPDESweepOrder order;
    order.build(positions, scene.box, scene.force->usesPeriodicBoundaryConditions(), cutoff, pairs.size(),
                pairs.ij.data(), pairs.ij.data() + 1, 2, numThreads);
    return order;
}

void checkProperties(const Scene& scene, const std::string& label) {
    const Pairs pairs =
            findPairs(scene.positions, scene.box, scene.force->usesPeriodicBoundaryConditions(), candidates);
    const GenDPDESweepOrder order = buildOrder(scene, scene.positions, pairs);
    // Each pair exactly once.
    std::vector<int> seen(order.getOrder());
    std::sort(seen.begin(), seen.end());
    for (int k = 0; k < pairs.size(); k++)
        if ((int) seen.size() != pairs.size() || seen[k] != k)
            throw std::runtime_error(label + ": the order does not hold every pair exactly once");
    // Blocks of one colour share no particle; the levels of a block (its runs of pairs that share no particle, as many
    // as getBlockLevels() says) cover its sequence.
    const std::vector<int>& groups = order.getGroupStart();
    const std::vector<int>& blocks = order.getBlockStart();
    ASSERT_EQUAL(9, order.getNumGroups());
    int blocksWithPairs = 0;
    for (int g = 0; g < order.getNumGroups(); g++) {
        std::vector<int> owner(scene.positions.size(), -1);
        for (int b = groups[g]; b < groups[g + 1]; b++) {
            blocksWithPairs += blocks[b + 1] > blocks[b];
            std::set<int> levelParticles;
            int levels = blocks[b + 1] > blocks[b] ? 1 : 0;
            for (int n = blocks[b]; n < blocks[b + 1]; n++) {
                const int k = order.getOrder()[n];
                for (int particle : {pairs.ij[2 * k], pairs.ij[2 * k + 1]}) {
                    if (owner[particle] != -1 && owner[particle] != b)
                        throw std::runtime_error(label + ": particle " + std::to_string(particle) + " is in blocks "
                                                 + std::to_string(owner[particle]) + " and " + std::to_string(b)
                                                 + " of group " + std::to_string(g));
                    owner[particle] = b;
                }
                // a new level begins where a pair shares a particle with the current one
                const int i = pairs.ij[2 * k], j = pairs.ij[2 * k + 1];
                if (levelParticles.count(i) || levelParticles.count(j)) {
                    levelParticles.clear();
                    levels++;
                }
                levelParticles.insert(i);
                levelParticles.insert(j);
            }
            if (levels > order.getBlockLevels()[b])
                throw std::runtime_error(label + ": block " + std::to_string(b) + " needs " + std::to_string(levels)
                                         + " runs of pairs that share no particle; it has "
                                         + std::to_string(order.getBlockLevels()[b]) + " levels");
        }
    }
    ASSERT_EQUAL(order.getBlockStart().back(), pairs.size());
    // The extra group (pairs not in adjacent cells) must stay empty for candidates.
    ASSERT_EQUAL(blocks[groups[8]], blocks[groups[9]]);
    if (order.getNumCells()[0] >= 8 && blocksWithPairs < 64)
        throw std::runtime_error(label + ": expected the pairs to spread over many blocks");
}

void testProperties() {
    for (bool periodic : {true, false}) {
        const std::string label = periodic ? "periodic" : "open";
        // 16^3 particles: 8 cells and 4 blocks per direction, 8 blocks per colour; 20^3: an odd number of blocks
        // would break the parity across the boundary, so the periodic box gets 8 cells, the open one 11.
        checkProperties(makeLatticeLiquid(16, referenceDensity, 0.3, GenDPDEForce::VB, periodic, 1), label + " liquid");
        checkProperties(makeLatticeLiquid(20, referenceDensity, 0.3, GenDPDEForce::VB, periodic, 2), label + " large");
        checkProperties(makeRandomGas(2000, 0.3 * referenceDensity, GenDPDEForce::VB, periodic, 3), label + " gas");
    }
    Scene triclinic = makeLatticeLiquid(16, referenceDensity, 0.3, GenDPDEForce::VB, true, 4);
    const double edge = triclinic.box[0][0];
    setBox(triclinic, Vec3(edge, 0, 0), Vec3(0.3 * edge, edge, 0), Vec3(-0.4 * edge, 0.2 * edge, edge));
    checkProperties(triclinic, "triclinic");
}

/** Moving particles by lattice vectors (another periodic image) or sharing the work among threads changes nothing. */
void testPureFunction() {
    Scene scene = makeLatticeLiquid(16, referenceDensity, 0.3, GenDPDEForce::VB, true, 5);
    const Pairs pairs = findPairs(scene.positions, scene.box, true, candidates);
    const std::vector<int> reference = buildOrder(scene, scene.positions, pairs).getOrder();
    std::vector<Vec3> shifted = scene.positions;
    for (size_t i = 0; i < shifted.size(); i++)
        shifted[i] += scene.box[i % 3] * ((int) (i % 5) - 2);
    ASSERT(reference == buildOrder(scene, shifted, pairs).getOrder());
    for (int numThreads : {1, 2, 3})
        ASSERT(reference == buildOrder(scene, scene.positions, pairs, numThreads).getOrder());
}

std::vector<int> definedOrder(const std::vector<Vec3>& positions, const Vec3 box[3], bool periodic, double range,
                              const Pairs& pairs);

/** A box that holds fewer than four cells along every direction is one block: the candidates by their greedy levels
 *  over the whole list, as the definition states it (definedOrder below). */
void testSmallBoxIsOneBlock() {
    Scene scene = makeLatticeLiquid(3, referenceDensity, 0.2, GenDPDEForce::VB, true, 6);
    const Pairs pairs = findPairs(scene.positions, scene.box, true, candidates);
    const GenDPDESweepOrder order = buildOrder(scene, scene.positions, pairs);
    for (int k = 0; k < 3; k++)
        ASSERT(order.getNumCells()[k] <= 2);
    int blocksWithPairs = 0;
    for (size_t b = 0; b + 1 < order.getBlockStart().size(); b++)
        blocksWithPairs += order.getBlockStart()[b + 1] > order.getBlockStart()[b];
    ASSERT_EQUAL(1, blocksWithPairs);
    ASSERT(definedOrder(scene.positions, scene.box, true, cutoff, pairs) == order.getOrder());
}

/** The cell of each particle as the definition states it (docs/theory.md section 6), written out here. */
std::vector<std::array<int, 3>> definedCells(const std::vector<Vec3>& positions, const Vec3 box[3], bool periodic,
                                             double range, std::array<int, 3>& numCells) {
    Vec3 low = positions[0], high = positions[0];
    for (const Vec3& r : positions)
        for (int k = 0; k < 3; k++) {
            low[k] = std::min(low[k], r[k]);
            high[k] = std::max(high[k], r[k]);
        }
    const Vec3 extent = periodic ? BoxGeometry::perpendicularWidths(box) : high - low;
    numCells = GenDPDESweepOrder::cellCounts(extent, range, periodic);
    std::vector<std::array<int, 3>> cells;
    for (const Vec3& r : positions) {
        const Vec3 s = BoxGeometry::fractionalCoordinates(r, box);
        std::array<int, 3> c;
        for (int k = 0; k < 3; k++) {
            const double unit = periodic ? s[k] - std::floor(s[k]) : (r[k] - low[k]) / extent[k];
            c[k] = std::max(0, std::min(numCells[k] - 1, (int) (unit * numCells[k])));
        }
        cells.push_back(c);
    }
    return cells;
}

/**
 * The order by its definition, with none of build()'s machinery: each candidate's key (colour, block index) from its
 * home cell (cells at least 1.1 R wide), a stable sort of the (i, j)-sorted candidates by key, then each block's
 * greedy levels.
 */
std::vector<int> definedOrder(const std::vector<Vec3>& positions, const Vec3 box[3], bool periodic, double range,
                              const Pairs& pairs) {
    std::array<int, 3> n;
    const std::vector<std::array<int, 3>> cells = definedCells(positions, box, periodic, range, n);
    const int numBlocks[3] = {(n[0] + 1) / 2, (n[1] + 1) / 2, (n[2] + 1) / 2};
    std::vector<long long> key(pairs.size());
    for (int k = 0; k < pairs.size(); k++) {
        const std::array<int, 3>& ci = cells[pairs.ij[2 * k]];
        const std::array<int, 3>& cj = cells[pairs.ij[2 * k + 1]];
        int block[3];
        bool adjacent = true;
        for (int dim = 0; dim < 3; dim++) {
            int d = cj[dim] - ci[dim];
            if (periodic && d > 1)
                d -= n[dim];
            if (periodic && d < -1)
                d += n[dim];
            adjacent = adjacent && std::abs(d) <= 1;
            if (d == -1)
                block[dim] = cj[dim] / 2; // the home cell is the one the other follows, across the boundary too
            else
                block[dim] = ci[dim] / 2;
        }
        const long long colour = (block[0] % 2) + 2 * (block[1] % 2) + 4 * (block[2] % 2);
        const long long index = ((long long) block[2] * numBlocks[1] + block[1]) * numBlocks[0] + block[0];
        key[k] = adjacent ? colour * (1LL << 40) + index : 8LL * (1LL << 40);
    }
    std::vector<int> sorted(pairs.size());
    for (int k = 0; k < pairs.size(); k++)
        sorted[k] = k;
    std::stable_sort(sorted.begin(), sorted.end(), [&](int a, int b) { return key[a] < key[b]; });
    std::vector<int> order;
    for (size_t start = 0; start < sorted.size();) {
        size_t end = start;
        while (end < sorted.size() && key[sorted[end]] == key[sorted[start]])
            end++;
        // One block: each pair (in (i, j) order) at the smallest level neither particle has yet, then the block's
        // pairs by level, in (i, j) order within a level.
        std::map<int, std::set<int>> levelsOf;
        std::vector<std::pair<int, int>> byLevel; // (level, pair)
        for (size_t m = start; m < end; m++) {
            const int k = sorted[m];
            std::set<int>& li = levelsOf[pairs.ij[2 * k]];
            std::set<int>& lj = levelsOf[pairs.ij[2 * k + 1]];
            int level = 0;
            while (li.count(level) || lj.count(level))
                level++;
            li.insert(level);
            lj.insert(level);
            byLevel.emplace_back(level, k);
        }
        std::stable_sort(byLevel.begin(), byLevel.end(),
                         [](const std::pair<int, int>& a, const std::pair<int, int>& b) { return a.first < b.first; });
        for (const std::pair<int, int>& pair : byLevel)
            order.push_back(pair.second);
        start = end;
    }
    return order;
}

/** build() gives the order of the definition, element by element, for any number of threads. */
void testOrderIsTheDefinition() {
    auto check = [](const Scene& scene) {
        const bool periodic = scene.force->usesPeriodicBoundaryConditions();
        const Pairs pairs = findPairs(scene.positions, scene.box, periodic, candidates);
        const std::vector<int> expected = definedOrder(scene.positions, scene.box, periodic, cutoff, pairs);
        ASSERT_EQUAL((int) expected.size(), pairs.size());
        for (int numThreads : {1, 2, 3})
            ASSERT(expected == buildOrder(scene, scene.positions, pairs, numThreads).getOrder());
    };
    for (bool periodic : {true, false}) {
        check(makeLatticeLiquid(16, referenceDensity, 0.3, GenDPDEForce::VB, periodic, 7));
        check(makeRandomGas(2000, 0.3 * referenceDensity, GenDPDEForce::VB, periodic, 8));
    }
    Scene triclinic = makeLatticeLiquid(16, referenceDensity, 0.3, GenDPDEForce::VB, true, 9);
    const double edge = triclinic.box[0][0];
    setBox(triclinic, Vec3(edge, 0, 0), Vec3(0.3 * edge, edge, 0), Vec3(-0.4 * edge, 0.2 * edge, edge));
    check(triclinic);
}

int main() {
    return runTestProgram([]() {
        testProperties();
        testPureFunction();
        testSmallBoxIsOneBlock();
        testOrderIsTheDefinition();
    });
}
