/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
/* The counter-based random numbers: Philox4x32-10 against the Random123 known-answer vectors, and the normal
 * variates of the ziggurat against the normal distribution. */

#include "CoreTest.h"
#include "gendpde/CounterRandom.h"
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

using namespace GenDPDEPlugin::CounterRandom;

void testPhiloxKnownAnswers() {
    struct Case {
        std::uint32_t counter[4], key[2], expected[4];
    };
    const Case cases[] = {
            {{0, 0, 0, 0}, {0, 0}, {0x6627e8d5u, 0xe169c58du, 0xbc57ac4cu, 0x9b00dbd8u}},
            {{0xffffffffu, 0xffffffffu, 0xffffffffu, 0xffffffffu},
             {0xffffffffu, 0xffffffffu},
             {0x408f276du, 0x41c83b0eu, 0xa20bc7c6u, 0x6d5451fdu}},
            {{0x243f6a88u, 0x85a308d3u, 0x13198a2eu, 0x03707344u},
             {0xa4093822u, 0x299f31d0u},
             {0xd16cfe09u, 0x94fdccebu, 0x5001e420u, 0x24126ea1u}},
    };
    for (const Case& c : cases) {
        std::uint32_t output[4];
        philox4x32(c.counter, c.key, output);
        for (int k = 0; k < 4; k++)
            CORE_ASSERT_EQUAL(c.expected[k], output[k]);
    }
}

/**
 * 2x10^6 normal variates from distinct (step, i, j) streams, the first two of each stream as the integrator uses
 * them. Mean, variance and fourth moment within 5 standard errors of 0, 1 and 3 (standard errors sqrt(1/n),
 * sqrt(2/n), sqrt(96/n)); the Kolmogorov-Smirnov distance to the normal CDF below 1.95/sqrt(n), its 0.1% critical
 * value; the two variates of a stream uncorrelated within 5/sqrt(n); the tails beyond 3.6541 (the ziggurat's
 * special region) populated with the normal probability 2.58e-4 within 5 standard errors.
 */
void testNormalVariates() {
    const int numStreams = 1000000;
    std::vector<double> values;
    values.reserve(2 * numStreams);
    double sum = 0, sum2 = 0, sum4 = 0, product = 0;
    long tail = 0;
    for (int s = 0; s < numStreams; s++) {
        PairStream stream(42, s / 1000, s % 1000, 1000 + s % 7);
        double a = stream.normal(), b = stream.normal();
        for (double x : {a, b}) {
            values.push_back(x);
            sum += x;
            sum2 += x * x;
            sum4 += x * x * x * x;
            tail += std::abs(x) > 3.6541528853610088;
        }
        product += a * b;
    }
    const double n = values.size();
    GenDPDECoreTest::checkClose(0.0, sum / n, 5 * std::sqrt(1 / n), "mean of the normal variates");
    GenDPDECoreTest::checkClose(1.0, sum2 / n, 5 * std::sqrt(2 / n), "variance of the normal variates");
    GenDPDECoreTest::checkClose(3.0, sum4 / n, 5 * std::sqrt(96 / n), "fourth moment of the normal variates");
    GenDPDECoreTest::checkClose(0.0, product / numStreams, 5 / std::sqrt((double) numStreams),
                                "correlation within a stream");
    const double tailProbability = std::erfc(3.6541528853610088 / std::sqrt(2.0));
    GenDPDECoreTest::checkClose(tailProbability, tail / n, 5 * std::sqrt(tailProbability / n), "tail beyond R");
    std::sort(values.begin(), values.end());
    double distance = 0;
    for (size_t k = 0; k < values.size(); k++) {
        double cdf = 0.5 * std::erfc(-values[k] / std::sqrt(2.0));
        distance = std::max(distance, std::max(std::abs(cdf - k / n), std::abs(cdf - (k + 1) / n)));
    }
    CORE_ASSERT(distance < 1.95 / std::sqrt(n));
}

/** The regularized lower incomplete gamma function P(a, x) (series below a + 1, continued fraction above), written
 *  here independently of the generator under test. */
double regularizedGammaP(double a, double x) {
    if (x <= 0)
        return 0;
    const double logPrefactor = a * std::log(x) - x - std::lgamma(a);
    if (x < a + 1) {
        double term = 1 / a, sum = term;
        for (int n = 1; n < 10000 && std::abs(term) > 1e-17 * std::abs(sum); n++) {
            term *= x / (a + n);
            sum += term;
        }
        return sum * std::exp(logPrefactor);
    }
    // Lentz's algorithm for the continued fraction of Q(a, x).
    double b = x + 1 - a, c = 1 / 1e-300, d = 1 / b, h = d;
    for (int n = 1; n < 10000; n++) {
        const double an = -n * (n - a);
        b += 2;
        d = an * d + b;
        d = std::abs(d) < 1e-300 ? 1e-300 : d;
        c = b + an / c;
        c = std::abs(c) < 1e-300 ? 1e-300 : c;
        d = 1 / d;
        const double delta = d * c;
        h *= delta;
        if (std::abs(delta - 1) < 1e-16)
            break;
    }
    return 1 - std::exp(logPrefactor) * h;
}

/**
 * Gamma variates (the draw of setInternalEnergiesToTemperature) for shapes 1 (the smallest possible, C_V -> 0),
 * 13.51 (liquid argon's C_V/k_B + 1) and 1000: 10^6 particle streams each. Mean a and variance a within 5 standard
 * errors (sqrt(a/n), sqrt((2a^2 + 6a)/n)); Kolmogorov-Smirnov distance to the Gamma law below its 0.1% critical
 * value 1.95/sqrt(n).
 */
void testGammaVariates() {
    const int n = 1000000;
    for (double shape : {1.0, 13.51, 1000.0}) {
        std::vector<double> values(n);
        double sum = 0;
        for (int i = 0; i < n; i++) {
            ParticleStream stream(11, i);
            values[i] = stream.gamma(shape);
            sum += values[i];
        }
        const double mean = sum / n;
        double sum2 = 0;
        for (double x : values)
            sum2 += (x - mean) * (x - mean);
        const std::string label = "Gamma(" + std::to_string(shape) + ")";
        GenDPDECoreTest::checkClose(shape, mean, 5 * std::sqrt(shape / n), label + " mean");
        GenDPDECoreTest::checkClose(shape, sum2 / (n - 1), 5 * std::sqrt((2 * shape * shape + 6 * shape) / n),
                                    label + " variance");
        std::sort(values.begin(), values.end());
        double distance = 0;
        for (int k = 0; k < n; k++) {
            const double cdf = regularizedGammaP(shape, values[k]);
            distance = std::max(distance, std::max(std::abs(cdf - (double) k / n), std::abs(cdf - (k + 1.0) / n)));
        }
        if (!(distance < 1.95 / std::sqrt((double) n)))
            throw std::runtime_error(label + ": Kolmogorov-Smirnov distance " + std::to_string(distance));
    }
}

/** Streams are pure functions of (seed, step, i, j). */
void testStreamsAreReproducible() {
    PairStream a(7, 123456789012LL, 3, 9), b(7, 123456789012LL, 3, 9), c(7, 123456789012LL, 3, 10);
    double x = a.normal(), y = b.normal();
    CORE_ASSERT_EQUAL(x, y);
    CORE_ASSERT(c.normal() != x);
}

int main() {
    return GenDPDECoreTest::run([]() {
        testPhiloxKnownAnswers();
        testNormalVariates();
        testStreamsAreReproducible();
        testGammaVariates();
    });
}
