/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
/* The sweep's definition in the core (GenDPDESweepDefinition.h): the greedy levels of a block's pairs on graphs whose
 * colourings are known (a path needs 2, a triangle 3, a star of k pairs k; greedy in (i, j) order is optimal on these),
 * the masks past one 64-bit word, the property every platform relies on (pairs of one level share no particle, and a
 * pair's level is the smallest free one), and the skin's numbers. */

#include "CoreTest.h"
#include "gendpde/GenDPDESweepDefinition.h"
#include <algorithm>
#include <cstdint>
#include <random>
#include <set>
#include <utility>
#include <vector>

using namespace GenDPDEPlugin;

namespace {

/** The levels of these pairs (local particle numbers below numLocal), with masks sized for their largest degree. */
std::vector<int> levelsOf(const std::vector<std::pair<int, int>>& pairs, int numLocal, int& numLevels) {
    std::vector<int> degree(numLocal, 0), first, second, level(pairs.size());
    for (const auto& p : pairs) {
        degree[p.first]++;
        degree[p.second]++;
        first.push_back(p.first);
        second.push_back(p.second);
    }
    int most = 0;
    for (int d : degree)
        most = std::max(most, d);
    const int words = SweepDefinition::levelWords(most);
    std::vector<std::uint64_t> used((size_t) numLocal * words, 0);
    numLevels =
            SweepDefinition::assignLevels(first.data(), second.data(), pairs.size(), words, used.data(), level.data());
    return level;
}

void testKnownColourings() {
    int numLevels;
    CORE_ASSERT(levelsOf({{0, 1}, {1, 2}, {2, 3}, {3, 4}}, 5, numLevels) == std::vector<int>({0, 1, 0, 1}));
    CORE_ASSERT_EQUAL(2, numLevels);
    CORE_ASSERT(levelsOf({{0, 1}, {0, 2}, {1, 2}}, 3, numLevels) == std::vector<int>({0, 1, 2}));
    CORE_ASSERT_EQUAL(3, numLevels);
    // A star of 100 pairs: levels 0 .. 99, the second word of the masks from level 64 on.
    std::vector<std::pair<int, int>> star;
    for (int k = 1; k <= 100; k++)
        star.emplace_back(0, k);
    const std::vector<int> levels = levelsOf(star, 101, numLevels);
    CORE_ASSERT_EQUAL(100, numLevels);
    for (int k = 0; k < 100; k++)
        CORE_ASSERT_EQUAL(k, levels[k]);
    CORE_ASSERT_EQUAL(1, SweepDefinition::levelWords(1));
    CORE_ASSERT_EQUAL(1, SweepDefinition::levelWords(32));
    CORE_ASSERT_EQUAL(2, SweepDefinition::levelWords(33));
}

/** Random blocks: each level's pairs share no particle, and each pair's level is the smallest that no earlier pair
 *  of its particles has (written out here with sets). */
void testRandomBlocks() {
    std::mt19937 random(5);
    for (int trial = 0; trial < 50; trial++) {
        const int numLocal = 5 + trial;
        std::set<std::pair<int, int>> unique;
        while ((int) unique.size() < std::min(4 * numLocal, numLocal * (numLocal - 1) / 2)) {
            int i = random() % numLocal, j = random() % numLocal;
            if (i != j)
                unique.emplace(std::min(i, j), std::max(i, j));
        }
        const std::vector<std::pair<int, int>> pairs(unique.begin(), unique.end());
        int numLevels;
        const std::vector<int> levels = levelsOf(pairs, numLocal, numLevels);
        std::vector<std::set<int>> taken(numLocal);
        int most = 0;
        for (size_t k = 0; k < pairs.size(); k++) {
            int expected = 0;
            while (taken[pairs[k].first].count(expected) || taken[pairs[k].second].count(expected))
                expected++;
            CORE_ASSERT_EQUAL(expected, levels[k]);
            taken[pairs[k].first].insert(expected);
            taken[pairs[k].second].insert(expected);
            most = std::max(most, expected + 1);
        }
        CORE_ASSERT_EQUAL(most, numLevels);
    }
}

void testSkin() {
    CORE_ASSERT_EQUAL(1.1, SweepDefinition::candidateRange(1.0));
    CORE_ASSERT_EQUAL(0.25 * 0.1 * 0.1, SweepDefinition::rebuildDisplacement2(1.0));
    // cells at least 1.1 R wide: a box 4.39 R wide holds 3 (periodic: 2), one 4.41 R wide 4
    CORE_ASSERT_EQUAL(2, SweepDefinition::cellCount(4.39, SweepDefinition::candidateRange(1.0), true));
    CORE_ASSERT_EQUAL(4, SweepDefinition::cellCount(4.41, SweepDefinition::candidateRange(1.0), true));
    CORE_ASSERT_EQUAL(3, SweepDefinition::cellCount(4.39, SweepDefinition::candidateRange(1.0), false));
}

} // namespace

int main() {
    return GenDPDECoreTest::run([]() {
        testKnownColourings();
        testRandomBlocks();
        testSkin();
    });
}
