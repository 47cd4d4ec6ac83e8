/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
/* The physics core (core/include/gendpde/GenDPDEPhysicsCore.h) as the host platforms compile it:
 *  - no contraction: the build forbids turning a*b + c into a fused multiply-add (-ffp-contract=off), on which the
 *    bitwise CPU == Reference claim rests (the CPU platform's AVX2 gathers and the scalar core must round alike);
 *    checked in functions compiled for a processor with FMA, where the compiler would otherwise fuse;
 *  - the polynomial branch of the V-B integrals: the core's piece (chosen by frexp) and Estrin evaluation against
 *    a piece chosen from the bits of k and a Horner evaluation in long double, within 2 ulp;
 *  - the temperature-dependent local equations of state (docs/theory.md section 11): every derivative against
 *    central finite differences of the free energy f(theta, n) assembled here from the core's e and sigma, the
 *    closed forms, the work and entropy of an isentropic compression, the Tait law's bits and the domain;
 *  - the sweep's pair update (gendpdePairUpdate): momentum and K + eps_i + eps_j conserved, each term alone, the
 *    positivity flag;
 *  - the pair force (gendpdePairForce): the central force alone, and V-C's moment term against gendpdeMomentPairForce.
 * (The accuracy of I and J against 40-digit quadrature is tested in python/tests/test_volume_estimators.py.) */

#include "TestUtilities.h"
#include "internal/GenDPDEPhysics.h"
#include <cstdint>
#include <cstring>
#include <random>
#include <stdexcept>
#include <string>

using namespace GenDPDEPlugin::Physics;
using namespace OpenMM;

namespace {

// Compiled for FMA: with contraction allowed, GCC fuses these products and sums.
#define GENDPDE_WITH_FMA __attribute__((target("avx2,fma"), noinline))

GENDPDE_WITH_FMA double multiplyAddWithFma(double a, double b, double c) {
    return a * b + c;
}

GENDPDE_WITH_FMA double densityWeightWithFma(double r, double inverseCutoff, double valueScale) {
    return gendpdeDensityWeight(r, inverseCutoff, valueScale);
}

GENDPDE_WITH_FMA double impulseWithFma(double u0, double omegaR, double friction, double noise, double xi,
                                       double& kineticChange) {
    return gendpdePairImpulse(u0, omegaR, friction, noise, 0.01, 0.1, 0.37, xi, &kineticChange);
}

__attribute__((noinline)) double impulsePlain(double u0, double omegaR, double friction, double noise, double xi,
                                              double& kineticChange) {
    return gendpdePairImpulse(u0, omegaR, friction, noise, 0.01, 0.1, 0.37, xi, &kineticChange);
}

bool sameBits(double a, double b) {
    return std::memcmp(&a, &b, sizeof(double)) == 0;
}


/* ---- Local equations of state f(theta, n) = e(n) - theta sigma(n) + C theta (1 - ln(theta/theta0)) ---- */

struct LocalLaw {
    int law;
    double p[6];
    const char* name;
};

struct LocalTerms {
    int status;
    double energy, entropy, pressureAtZero, thermalPressure;
};

LocalTerms localTerms(const LocalLaw& law, double n) {
    LocalTerms t;
    t.status = gendpdeLocalEquationOfState(law.law, n, law.p, -1, &t.energy, &t.entropy, &t.pressureAtZero,
                                           &t.thermalPressure);
    return t;
}

// The free energy per particle, from the core's e and sigma (the quantities differentiated below).
double freeEnergy(const LocalLaw& law, double heatCapacity, double theta0, double theta, double n) {
    const LocalTerms t = localTerms(law, n);
    return t.energy - theta * t.entropy + heatCapacity * theta * (1 - std::log(theta / theta0));
}

void testLocalEquationsOfState() {
    // Reduced units of the argon model (docs/theory.md section 9; k_B = 1): n0 = 1, the liquid's 85.31 MPa, B_T for
    // gamma_T = 7 and kappa_T0 = 1, beta = alpha/kappa_T0 = 30 (alpha = 2.64e-3 1/K), theta0 = 125.7 K, C = 12.5;
    // a van der Waals fluid with b n0 = 0.3 and five atoms' k.
    const double heatCapacity = 12.5, theta0 = 0.01105;
    const LocalLaw thermalTait{GENDPDE_EOS_TAIT_THERMAL, {1.0, 0.1271, 1.0 / 7, 7.0, 30.0, theta0}, "Tait with beta"};
    const LocalLaw vanDerWaals{GENDPDE_EOS_VAN_DER_WAALS, {1.0, 0.3, 5.0, 0, 0, 0}, "van der Waals"};
    for (const LocalLaw& law : {thermalTait, vanDerWaals})
        for (double n : {0.6, 0.95, 1.0, 1.3, 2.2})
            for (double theta : {0.5 * theta0, theta0, 3 * theta0, 40 * theta0}) {
                const std::string where =
                        std::string(law.name) + " at n = " + std::to_string(n) + ", theta = " + std::to_string(theta);
                const LocalTerms t = localTerms(law, n);
                ASSERT(t.status == GENDPDE_PARTICLE_VALID);
                const double pressure = t.pressureAtZero + theta * t.thermalPressure;
                // Central differences, step h: truncation ~ h^2 f'''/6, rounding ~ eps f/h; relative 1e-7 leaves a
                // margin of 100 over both at these steps.
                const double hn = 1e-4 * n, ht = 1e-4 * theta;
                const double dfdn = (freeEnergy(law, heatCapacity, theta0, theta, n + hn)
                                     - freeEnergy(law, heatCapacity, theta0, theta, n - hn))
                        / (2 * hn);
                const double scale = std::abs(t.pressureAtZero) + theta * std::abs(t.thermalPressure);
                assertClose(pressure, n * n * dfdn, 1e-7 * scale, "pi = n^2 df/dn, " + where);
                const double dfdt = (freeEnergy(law, heatCapacity, theta0, theta + ht, n)
                                     - freeEnergy(law, heatCapacity, theta0, theta - ht, n))
                        / (2 * ht);
                const double entropy = t.entropy + heatCapacity * std::log(theta / theta0);
                assertClose(entropy, -dfdt, 1e-7 * (std::abs(t.entropy) + heatCapacity), "s = -df/dtheta, " + where);
                const double f = freeEnergy(law, heatCapacity, theta0, theta, n);
                assertClose(t.energy + heatCapacity * theta, f - theta * dfdt,
                            1e-7 * (std::abs(t.energy) + heatCapacity * theta + theta * std::abs(t.entropy)),
                            "u = f - theta df/dtheta, " + where);
                const double d2fdt2 = (freeEnergy(law, heatCapacity, theta0, theta + ht, n) - 2 * f
                                       + freeEnergy(law, heatCapacity, theta0, theta - ht, n))
                        / (ht * ht);
                // The second difference rounds to ~ eps |f|/h^2, at most ~1e-6 of C/theta here (|f| < 2, h = 1e-4
                // theta >= 5.5e-7); 1e-4 leaves a margin of 100.
                assertRelative(heatCapacity, -theta * d2fdt2, 1e-4, "C_V = -theta d2f/dtheta2, " + where);
                // An isentropic compression: the energy u(s, n) = e(n) + C theta(s, n) changes by the work pi dn/n^2
                // (du = -pi dV), and the new state has the old entropy.
                double u[2], thetaAfter[2];
                for (int side = 0; side < 2; side++) {
                    const LocalTerms moved = localTerms(law, side == 0 ? n - hn : n + hn);
                    const double thermal = gendpdeIsentropicThermalEnergy(heatCapacity * theta,
                                                                          moved.entropy - t.entropy, heatCapacity);
                    u[side] = moved.energy + thermal;
                    thetaAfter[side] = thermal / heatCapacity;
                }
                assertClose(pressure / (n * n), (u[1] - u[0]) / (2 * hn), 1e-7 * scale / (n * n),
                            "du/dn at fixed s, " + where);
                const double np = n + hn, htp = 1e-4 * thetaAfter[1];
                const double entropyAfter = -(freeEnergy(law, heatCapacity, theta0, thetaAfter[1] + htp, np)
                                              - freeEnergy(law, heatCapacity, theta0, thetaAfter[1] - htp, np))
                        / (2 * htp);
                assertClose(entropy, entropyAfter, 1e-7 * (std::abs(t.entropy) + heatCapacity), "s kept, " + where);
                // dtheta/dn at fixed s = theta (dpi/dtheta)_n/(n^2 C_V): the adiabatic heating of a compression.
                assertRelative(theta * t.thermalPressure / (n * n * heatCapacity),
                               (thetaAfter[1] - thetaAfter[0]) / (2 * hn), 1e-6, "dtheta/dn at fixed s, " + where);
            }

    // Closed forms, written out independently.
    const LocalTerms atReference = localTerms(thermalTait, 1.0);
    assertRelative(0.1271, atReference.pressureAtZero + theta0 * atReference.thermalPressure, 1e-15, "pi(theta0, n0)");
    ASSERT(atReference.thermalPressure == 30.0);
    for (double n : {0.2, 1.0, 3.0}) {
        const LocalTerms t = localTerms(vanDerWaals, n);
        const double theta = 0.4;
        assertRelative(5.0 * theta * n / (1 - 0.3 * n) - n * n, t.pressureAtZero + theta * t.thermalPressure, 1e-14,
                       "van der Waals pi at n = " + std::to_string(n));
        assertRelative(-n, t.energy, 1e-15, "van der Waals e at n = " + std::to_string(n));
    }

    // The Tait law is gendpdeTait to the bit, and so is the thermal law with beta = 0.
    const LocalLaw tait{GENDPDE_EOS_TAIT, {1.0, 0.1271, 1.0 / 7, 7.0, 0, 0}, "Tait"};
    const LocalLaw taitNoBeta{GENDPDE_EOS_TAIT_THERMAL, {1.0, 0.1271, 1.0 / 7, 7.0, 0.0, theta0}, "Tait, beta = 0"};
    for (double n : {0.3, 0.97, 1.0, 1.8}) {
        double pressure, energy;
        gendpdeTait(n, 1.0, 0.1271, 1.0 / 7, 7.0, -1, &pressure, &energy);
        for (const LocalLaw& law : {tait, taitNoBeta}) {
            const LocalTerms t = localTerms(law, n);
            ASSERT(t.status == GENDPDE_PARTICLE_VALID);
            ASSERT(sameBits(pressure, t.pressureAtZero) && sameBits(energy, t.energy));
            ASSERT(t.entropy == 0 && t.thermalPressure == 0);
        }
    }

    // The domain: van der Waals needs 0 < n < 1/b; a Tait power that overflows is reported as such.
    for (double n : {1 / 0.3, 4.0, 0.0, -1.0, std::nan("")})
        ASSERT(localTerms(vanDerWaals, n).status == GENDPDE_PARTICLE_OUTSIDE_DOMAIN);
    ASSERT(localTerms(vanDerWaals, 0.999 / 0.3).status == GENDPDE_PARTICLE_VALID);
    ASSERT(localTerms(thermalTait, 1e300).status == GENDPDE_PARTICLE_OVERFLOW);
}

} // namespace

void testPairUpdate() {
    std::mt19937_64 random(17);
    std::uniform_real_distribution<double> uniform(0.0, 1.0);
    const double boltzmann = 0.0083144626, dt = 0.01;
    for (int trial = 0; trial < 4000; trial++) {
        const int dissipation = (trial % 4 != 1), conduction = (trial % 4 != 2);
        const double mi = 1 + 40 * uniform(random), mj = 1 + 40 * uniform(random);
        const Vec3 e0(uniform(random) - 0.5, uniform(random) - 0.5, uniform(random) - 0.5);
        const Vec3 e = e0 / std::sqrt(e0.dot(e0));
        Vec3 vi(uniform(random) - 0.5, uniform(random) - 0.5, uniform(random) - 0.5), vj(-vi[1], vi[2], 0.3);
        const double ci = 0.1 + uniform(random), cj = 0.1 + uniform(random);
        double ei = ci * (50 + 100 * uniform(random)), ej = cj * (50 + 100 * uniform(random));
        const double kappa = 5 * uniform(random), omegaR = uniform(random);
        const double momentum0[3] = {mi * vi[0] + mj * vj[0], mi * vi[1] + mj * vj[1], mi * vi[2] + mj * vj[2]};
        const double total0 = 0.5 * mi * vi.dot(vi) + 0.5 * mj * vj.dot(vj) + ei + ej;
        const double ei0 = ei, ej0 = ej;
        double impulse;
        double theta, difference, factor; // k_B Theta_ij, 1/theta_i - 1/theta_j, the Ito factor
        gendpdePairTemperatures(ei, ej, ci, cj, boltzmann, &theta, &difference, &factor);
        const int failed =
                gendpdePairUpdate(dissipation, conduction, theta, difference, factor, e.dot(vi - vj), omegaR, 1 / mi,
                                  1 / mj, 3.0, kappa, std::sqrt(2 * boltzmann * kappa), dt, std::sqrt(dt),
                                  2 * uniform(random) - 1, 2 * uniform(random) - 1, &ei, &ej, &impulse);
        ASSERT(failed == 0);
        if (!dissipation)
            ASSERT(impulse == 0.0);
        if (!conduction) // the kinetic change alone, in equal halves
            assertClose(ei - ei0, ej - ej0, 1e-13 * (ei0 + ej0), "equal halves of the kinetic change");
        vi += e * (impulse / mi); // (the sweep's pair step applies it so: core/tests/TestSweepPair.cpp)
        vj -= e * (impulse / mj);
        for (int k = 0; k < 3; k++)
            assertClose(momentum0[k], mi * vi[k] + mj * vj[k], 1e-13 * (mi + mj), "pair update momentum");
        assertClose(total0, 0.5 * mi * vi.dot(vi) + 0.5 * mj * vj.dot(vj) + ei + ej, 1e-12 * total0,
                    "pair update energy");
    }
    // An internal energy that the heat drives below zero is reported (i hot, j nearly at 0 K: heat flows to j).
    double ei = 10.0, ej = 1e-6, impulse;
    double theta, difference, factor;
    gendpdePairTemperatures(ei, ej, 1.0, 1.0, 0.0083144626, &theta, &difference, &factor);
    ASSERT(gendpdePairUpdate(0, 1, theta, difference, factor, 0.0, 1.0, 1.0, 1.0, 0.0, 1000.0, 0.0, 0.01, 0.1, 0.0,
                             -3.0, &ei, &ej, &impulse)
           != 0);
}

void testPairForce() {
    const double cutoff = 1.3, inverseCutoff = 1 / cutoff;
    const DensityWeight weight(cutoff);
    const Vec3 d(0.3, -0.5, 0.4), qi(0.2, 0.1, -0.3), qj(-0.1, 0.4, 0.05);
    const double r = std::sqrt(d.dot(d)), w = weight.derivative(r), scale = gendpdePairForceScale(-2.5, w, r);
    double virial;
    const Vec3 central = pairForce(d, r, -2.5, w, inverseCutoff, false, qi, qj, virial);
    for (int k = 0; k < 3; k++)
        ASSERT(sameBits(central[k], d[k] * scale));
    ASSERT(sameBits(virial, scale * r * r));
    ASSERT(sameBits(pairForce(d, r, -2.5, w, inverseCutoff, true, Vec3(), Vec3(), virial)[0], central[0]));
    const Vec3 full = pairForce(d, r, -2.5, w, inverseCutoff, true, qi, qj, virial);
    double moment[3];
    const Vec3 dq = qi - qj;
    const double momentVirial =
            gendpdeMomentPairForce(d[0] / r, d[1] / r, d[2] / r, r, inverseCutoff, dq[0], dq[1], dq[2], moment);
    for (int k = 0; k < 3; k++)
        assertClose(central[k] + moment[k], full[k], 1e-13, "moment pair force");
    assertClose(scale * r * r + momentVirial, virial, 1e-13, "moment pair virial");
    assertClose(d.dot(full), virial, 1e-14, "pair virial is d . F");
}

void testNoContraction() {
    __builtin_cpu_init();
    if (!__builtin_cpu_supports("fma")) {
        std::cout << "(no FMA on this processor: the contraction test does not apply)" << std::endl;
        return;
    }
    // a b = 1 - 2^-60 exactly, which rounds to 1: a b + c is 0 when rounded twice, -2^-60 when fused.
    volatile double a = 1.0 + std::ldexp(1.0, -30), b = 1.0 - std::ldexp(1.0, -30), c = -1.0;
    const double found = multiplyAddWithFma(a, b, c);
    if (found != 0.0)
        throw std::runtime_error("a*b + c was fused into one rounding (" + std::to_string(found)
                                 + " instead of 0): "
                                   "the build must pass -ffp-contract=off");
    // The core's own expressions, inlined into the FMA functions, round as in a plain build.
    const DensityWeight weight(1.3);
    std::mt19937_64 random(5);
    std::uniform_real_distribution<double> uniform(0.0, 1.0);
    for (int n = 0; n < 100000; n++) {
        const double r = 1.3 * uniform(random);
        if (!sameBits(weight.valueInside(r),
                      densityWeightWithFma(r, weight.getInverseCutoff(), weight.getValueScale())))
            throw std::runtime_error("gendpdeDensityWeight rounds differently where FMA is available, r = "
                                     + std::to_string(r));
        double kineticPlain, kineticFma;
        const double u0 = uniform(random) - 0.5, omegaR = uniform(random), xi = 3 * uniform(random) - 1.5;
        const double plain = impulsePlain(u0, omegaR, 7.0, 2.0, xi, kineticPlain);
        const double fused = impulseWithFma(u0, omegaR, 7.0, 2.0, xi, kineticFma);
        if (!sameBits(plain, fused) || !sameBits(kineticPlain, kineticFma))
            throw std::runtime_error("gendpdePairImpulse rounds differently where FMA is available");
    }
}

void testPolynomialBranch() {
    using namespace VolumeVBPolynomials;
    std::mt19937_64 random(11);
    std::uniform_real_distribution<double> uniform(0.0, 1.0);
    int checked = 0;
    for (int octave = firstOctave; octave <= lastOctave; octave++)
        for (int n = 0; n < 4000; n++) {
            // k = m 2^octave with m in [1, 2), including the pieces' end points.
            const double m = (n < 4 ? 1.0 + 0.25 * n : 1.0 + uniform(random));
            const double k = std::ldexp(m, octave);
            // The piece from the top two bits of the mantissa, t exact in [-1, 1).
            std::uint64_t bits;
            std::memcpy(&bits, &k, sizeof(bits));
            const int piece = (int) ((bits >> 50) & 3);
            const long double t = 8.0L * (m - 1.0L) - (2 * piece + 1);
            const double(*c)[2] = coefficients[(octave - firstOctave) * subintervals + piece];
            long double I = 0, J = 0;
            for (int p = degree; p >= 0; p--) {
                I = I * t + c[p][0];
                J = J * t + c[p][1];
            }
            const VolumeIntegralsVB core = volumeIntegralsVB(k);
            assertRelative((double) I, core.I, 4.5e-16, "I(k) at k = " + std::to_string(k));
            assertRelative((double) J, core.J, 4.5e-16, "J(k) at k = " + std::to_string(k));
            checked++;
        }
    ASSERT(checked == 4000 * (lastOctave - firstOctave + 1));
}

int main() {
    return runTestProgram([]() {
        testNoContraction();
        testPolynomialBranch();
        testPairUpdate();
        testPairForce();
        testLocalEquationsOfState();
    });
}
