/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
/* The sweep's pair step (GenDPDESweepPair.h) that every engine calls, against what it must do:
 *  - the Isothermal mode's update is the Crank-Nicolson step of the relative velocity along e in closed form,
 *    u1 = (u0 (1 - M f) + 2 M R)/(1 + M f) with M = 1/m_i + 1/m_j, f = gamma omega_R^2 dt/2 and
 *    R = sigma omega_R sqrt(dt) xi/2 (xi the stream's first variate), and leaves the velocities across e as they were;
 *  - the Isoenergetic mode conserves momentum and K + eps_i + eps_j to rounding, for any masses and states, and
 *    reads the stream's variates in the order the engines agree on: the impulse's, then the heat's, each only where
 *    its term runs (checked against gendpdePairUpdate fed those variates by hand);
 *  - a pair at r = 0 and a pair of two massless particles are skipped, untouched, with no variate drawn;
 *  - an internal energy driven to <= 0 is reported. */

#include "CoreTest.h"
#include "gendpde/GenDPDEPhysicsCoreDouble.h"
#include <cmath>
#include <random>

using namespace GenDPDEPlugin;
using namespace GenDPDEPlugin::Physics;

namespace {

const double boltzmann = 0.0083144626, dt = 0.01, cutoff = 1.2;

struct Pair {
    double d[3], r, mi, mj, vi[3], vj[3], ei, ej, ci, cj;
};

Pair randomPair(std::mt19937_64& random) {
    std::uniform_real_distribution<double> uniform(0.0, 1.0);
    Pair p;
    double length2 = 0;
    for (int k = 0; k < 3; k++) {
        p.d[k] = uniform(random) - 0.5;
        length2 += p.d[k] * p.d[k];
    }
    const double scale = cutoff * (0.05 + 0.9 * uniform(random)) / std::sqrt(length2);
    for (double& component : p.d)
        component *= scale;
    p.r = std::sqrt(p.d[0] * p.d[0] + p.d[1] * p.d[1] + p.d[2] * p.d[2]);
    p.mi = 1 + 40 * uniform(random);
    p.mj = 1 + 40 * uniform(random);
    for (int k = 0; k < 3; k++) {
        p.vi[k] = uniform(random) - 0.5;
        p.vj[k] = uniform(random) - 0.5;
    }
    p.ci = 0.1 + uniform(random);
    p.cj = 0.1 + uniform(random);
    p.ei = p.ci * (50 + 100 * uniform(random));
    p.ej = p.cj * (50 + 100 * uniform(random));
    return p;
}

double along(const double* e, const double* vi, const double* vj) {
    return e[0] * (vi[0] - vj[0]) + e[1] * (vi[1] - vj[1]) + e[2] * (vi[2] - vj[2]);
}

void testIsothermalIsTheCrankNicolsonStep() {
    std::mt19937_64 random(11);
    for (int trial = 0; trial < 2000; trial++) {
        Pair p = randomPair(random);
        const double friction = 50 * (trial % 7), temperature = 100 + trial % 300;
        const double sigma = gendpdeBathNoise(friction, boltzmann, temperature);
        CounterRandom::PairStream stream(3, trial, 5, 9), copy(3, trial, 5, 9);
        const double xi = copy.normal();
        const double e[3] = {p.d[0] / p.r, p.d[1] / p.r, p.d[2] / p.r}, zero[3] = {0, 0, 0};
        const double u0 = along(e, p.vi, p.vj), omegaR = 1 - p.r / cutoff, M = 1 / p.mi + 1 / p.mj;
        const double f = 0.5 * friction * omegaR * omegaR * dt, R = 0.5 * sigma * omegaR * std::sqrt(dt) * xi;
        const double expected = (u0 * (1 - M * f) + 2 * M * R) / (1 + M * f);
        double vi[3] = {p.vi[0], p.vi[1], p.vi[2]}, vj[3] = {p.vj[0], p.vj[1], p.vj[2]};
        CORE_ASSERT(gendpdeSweepPair(1, 0, 0, p.d[0], p.d[1], p.d[2], p.r, cutoff, 1 / p.mi, 1 / p.mj, vi, vj, nullptr,
                                     nullptr, 0.0, 0.0, friction, 0.0, 0.0, sigma, boltzmann, dt, std::sqrt(dt),
                                     &stream)
                    == 0);
        GenDPDECoreTest::checkClose(expected, along(e, vi, vj), 1e-13 * (1 + std::fabs(expected)),
                                    "u after the Isothermal update");
        for (int k = 0; k < 3; k++) {   // momentum, and the motion across e
            GenDPDECoreTest::checkClose(p.mi * p.vi[k] + p.mj * p.vj[k], p.mi * vi[k] + p.mj * vj[k],
                                        1e-13 * (p.mi + p.mj), "momentum");
            GenDPDECoreTest::checkClose(p.vi[k] - e[k] * along(e, p.vi, zero), vi[k] - e[k] * along(e, vi, zero), 1e-13,
                                        "velocity of i across e");
        }
    }
}

void testIsoenergeticConservesAndReadsTheVariatesInOrder() {
    std::mt19937_64 random(17);
    for (int trial = 0; trial < 4000; trial++) {
        const int dissipation = (trial % 4 != 1), conduction = (trial % 4 != 2);
        Pair p = randomPair(random);
        const double friction = 3.0 * (trial % 5), kappa = 5.0 * ((trial / 5) % 3);
        const double alpha = gendpdeHeatNoise(kappa, boltzmann);
        double vi[3] = {p.vi[0], p.vi[1], p.vi[2]}, vj[3] = {p.vj[0], p.vj[1], p.vj[2]};
        double ei = p.ei, ej = p.ej;
        CounterRandom::PairStream stream(7, trial, 2, 4), copy(7, trial, 2, 4);
        CORE_ASSERT(gendpdeSweepPair(dissipation, conduction, 1, p.d[0], p.d[1], p.d[2], p.r, cutoff, 1 / p.mi,
                                     1 / p.mj, vi, vj, &ei, &ej, p.ci, p.cj, friction, kappa, alpha, 0.0, boltzmann, dt,
                                     std::sqrt(dt), &stream)
                    == 0);
        double total0 = p.ei + p.ej, total = ei + ej;
        for (int k = 0; k < 3; k++) {
            total0 += 0.5 * (p.mi * p.vi[k] * p.vi[k] + p.mj * p.vj[k] * p.vj[k]);
            total += 0.5 * (p.mi * vi[k] * vi[k] + p.mj * vj[k] * vj[k]);
            GenDPDECoreTest::checkClose(p.mi * p.vi[k] + p.mj * p.vj[k], p.mi * vi[k] + p.mj * vj[k],
                                        1e-13 * (p.mi + p.mj), "momentum");
        }
        GenDPDECoreTest::checkClose(total0, total, 1e-12 * total0, "K + eps_i + eps_j");
        // The same update by hand, the variates taken from a copy of the stream in the agreed order.
        const double xi = dissipation ? copy.normal() : 0.0, xiQ = conduction ? copy.normal() : 0.0;
        double theta, difference, factor, hi = p.ei, hj = p.ej, impulse;
        gendpdePairTemperatures(p.ei, p.ej, p.ci, p.cj, boltzmann, &theta, &difference, &factor);
        const double e[3] = {p.d[0] * (1 / p.r), p.d[1] * (1 / p.r), p.d[2] * (1 / p.r)};
        gendpdePairUpdate(dissipation, conduction, theta, difference, factor, along(e, p.vi, p.vj),
                          gendpdeRandomWeight(p.r, cutoff), 1 / p.mi, 1 / p.mj, friction, kappa, alpha, dt,
                          std::sqrt(dt), xi, xiQ, &hi, &hj, &impulse);
        CORE_ASSERT_EQUAL(hi, ei);
        CORE_ASSERT_EQUAL(hj, ej);
        for (int k = 0; k < 3; k++)
            CORE_ASSERT_EQUAL(p.vi[k] + (dissipation ? e[k] * (impulse * (1 / p.mi)) : 0.0), vi[k]);
    }
}

void testSkippedPairsAreUntouched() {
    std::mt19937_64 random(23);
    Pair p = randomPair(random);
    for (int skip = 0; skip < 2; skip++) {
        double vi[3] = {p.vi[0], p.vi[1], p.vi[2]}, vj[3] = {p.vj[0], p.vj[1], p.vj[2]};
        double ei = p.ei, ej = p.ej;
        const double r = skip == 0 ? 0.0 : p.r, inverseMass = skip == 0 ? 1 / p.mi : 0.0;
        CounterRandom::PairStream stream(1, 2, 3, 4), fresh(1, 2, 3, 4);
        CORE_ASSERT(gendpdeSweepPair(1, 1, 1, p.d[0], p.d[1], p.d[2], r, cutoff, inverseMass, inverseMass, vi, vj, &ei,
                                     &ej, p.ci, p.cj, 10.0, 10.0, 1.0, 1.0, boltzmann, dt, std::sqrt(dt), &stream)
                    == 0);
        CORE_ASSERT(ei == p.ei && ej == p.ej);
        for (int k = 0; k < 3; k++)
            CORE_ASSERT(vi[k] == p.vi[k] && vj[k] == p.vj[k]);
        CORE_ASSERT_EQUAL(fresh.normal(), stream.normal());   // nothing drawn
    }
}

void testAFailedEnergyIsReported() {
    // i hot, j nearly at 0 K, strong conduction: kappa omega_q (1/theta_i - 1/theta_j) dt ~ -10^6 (the stream's
    // variate, whatever it is, adds at most a few units) flows from i to j and leaves eps_i = 10 far below zero.
    double vi[3] = {0, 0, 0}, vj[3] = {0, 0, 0}, ei = 10.0, ej = 1e-6;
    CounterRandom::PairStream stream(1, 1, 1, 2);
    CORE_ASSERT(gendpdeSweepPair(0, 1, 1, 0.5, 0.0, 0.0, 0.5, cutoff, 1.0, 1.0, vi, vj, &ei, &ej, 1.0, 1.0, 0.0, 1000.0,
                                 0.0, 0.0, boltzmann, dt, std::sqrt(dt), &stream)
                != 0);
    CORE_ASSERT(!(ei > 0) && ej > 0);
}

void testNoiseAmplitudes() {
    GenDPDECoreTest::checkClose(std::sqrt(2 * boltzmann * 3.5), gendpdeHeatNoise(3.5, boltzmann), 1e-15,
                                "alpha = sqrt(2 k_B kappa)");
    GenDPDECoreTest::checkClose(std::sqrt(2 * 4.5 * boltzmann * 300), gendpdeBathNoise(4.5, boltzmann, 300.0), 1e-14,
                                "sigma = sqrt(2 gamma k_B T)");
}

} // namespace

int main() {
    return GenDPDECoreTest::run([]() {
        testIsothermalIsTheCrankNicolsonStep();
        testIsoenergeticConservesAndReadsTheVariatesInOrder();
        testSkippedPairsAreUntouched();
        testAFailedEnergyIsReported();
        testNoiseAmplitudes();
    });
}
