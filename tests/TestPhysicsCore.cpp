/* The physics core (openmmapi/include/internal/GenDPDEPhysicsCore.h) as the host platforms compile it:
 *  - no contraction: the build forbids turning a*b + c into a fused multiply-add (-ffp-contract=off), on which the
 *    bitwise CPU == Reference claim rests (the CPU platform's AVX2 gathers and the scalar core must round alike);
 *    checked in functions compiled for a processor with FMA, where the compiler would otherwise fuse;
 *  - the polynomial branch of the V-B integrals: the core's piece (chosen by frexp) and Estrin evaluation against
 *    a piece chosen from the bits of k and a Horner evaluation in long double, within 2 ulp.
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
    return a*b + c;
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

} // namespace

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
        throw std::runtime_error("a*b + c was fused into one rounding (" + std::to_string(found) + " instead of 0): "
                                 "the build must pass -ffp-contract=off");
    // The core's own expressions, inlined into the FMA functions, round as in a plain build.
    const DensityWeight weight(1.3);
    std::mt19937_64 random(5);
    std::uniform_real_distribution<double> uniform(0.0, 1.0);
    for (int n = 0; n < 100000; n++) {
        const double r = 1.3*uniform(random);
        if (!sameBits(weight.valueInside(r), densityWeightWithFma(r, weight.getInverseCutoff(),
                                                                   weight.getValueScale())))
            throw std::runtime_error("gendpdeDensityWeight rounds differently where FMA is available, r = "
                                     + std::to_string(r));
        double kineticPlain, kineticFma;
        const double u0 = uniform(random) - 0.5, omegaR = uniform(random), xi = 3*uniform(random) - 1.5;
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
            const double m = (n < 4 ? 1.0 + 0.25*n : 1.0 + uniform(random));
            const double k = std::ldexp(m, octave);
            // The piece from the top two bits of the mantissa, t exact in [-1, 1).
            std::uint64_t bits;
            std::memcpy(&bits, &k, sizeof(bits));
            const int piece = (int) ((bits >> 50) & 3);
            const long double t = 8.0L*(m - 1.0L) - (2*piece + 1);
            const double (*c)[2] = coefficients[(octave - firstOctave)*subintervals + piece];
            long double I = 0, J = 0;
            for (int p = degree; p >= 0; p--) {
                I = I*t + c[p][0];
                J = J*t + c[p][1];
            }
            const VolumeIntegralsVB core = volumeIntegralsVB(k);
            assertRelative((double) I, core.I, 4.5e-16, "I(k) at k = " + std::to_string(k));
            assertRelative((double) J, core.J, 4.5e-16, "J(k) at k = " + std::to_string(k));
            checked++;
        }
    ASSERT(checked == 4000*(lastOctave - firstOctave + 1));
}

int main() {
    return runTestProgram([]() {
        testNoContraction();
        testPolynomialBranch();
    });
}
