#ifndef GENDPDE_PHYSICS_H_
#define GENDPDE_PHYSICS_H_

/* -------------------------------------------------------------------------- *
 * The one home of GenDPDE's pointwise physics (docs/theory.md sections 2-7): *
 * the density weight, the two volume estimators with their numerically       *
 * safe branches, the Tait equation of state and the dissipation weights.     *
 * Plain inline functions of doubles (and OpenMM's header-only Vec3), so that *
 * every platform kernel, the Python bindings and the tests share one code.   *
 *                                                                            *
 * Units are whatever the caller uses consistently (OpenMM: nm, kJ/mol).      *
 * -------------------------------------------------------------------------- */

#include "VolumeVBTables.h"
#include "openmm/Vec3.h"
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

namespace GenDPDEPlugin {
namespace Physics {

// The scalar core shared with the device kernels, in double precision.
#define GENDPDE_REAL double
#include "GenDPDEPhysicsCore.h"
#undef GENDPDE_REAL

constexpr double Pi = 3.14159265358979323846;
/** Boltzmann's constant in OpenMM units, kJ/(mol K): k_B N_A (exact SI values), as OpenMM defines it. */
constexpr double Boltzmann = 1.380649e-23*6.02214076e23/1000.0;

/**
 * The normalised density weight of docs/theory.md section 2,
 *   w(r) = 15/(2 pi R^3) (1 - r/R)^2,   w'(r) = -15/(pi R^4) (1 - r/R)   for r < R, zero beyond.
 * The constants are precomputed once per cutoff because the weight is evaluated for every pair.
 */
class DensityWeight {
public:
    explicit DensityWeight(double cutoff) : cutoff(cutoff), inverseCutoff(1.0/cutoff),
            valueScale(15.0/(2.0*Pi*cutoff*cutoff*cutoff)), derivativeScale(-15.0/(Pi*cutoff*cutoff*cutoff*cutoff)) {
    }
    /** w(r) (1/length^3) */
    double value(double r) const {
        return r < cutoff ? valueInside(r) : 0.0;
    }
    /** dw/dr (1/length^4) */
    double derivative(double r) const {
        return r < cutoff ? derivativeInside(r) : 0.0;
    }
    /** The formulas without the test r < R, for branch-free loops that mask the terms themselves. */
    double valueInside(double r) const {
        double x = 1.0 - r*inverseCutoff;
        return valueScale*x*x;
    }
    double derivativeInside(double r) const {
        return derivativeScale*(1.0 - r*inverseCutoff);
    }
    double getCutoff() const {
        return cutoff;
    }
    double getInverseCutoff() const {
        return inverseCutoff;
    }
    double getValueScale() const {
        return valueScale;
    }
    double getDerivativeScale() const {
        return derivativeScale;
    }
private:
    double cutoff, inverseCutoff, valueScale, derivativeScale;
};

/** A particle volume V and its derivative with respect to the primitive density, dV/dn0. */
struct ParticleVolume {
    double volume;       // length^3
    double derivative;   // dV/dn0, length^6
};

/**
 * V-A, the traditional estimator: V = 1/n0, dV/dn0 = -1/n0^2. Undefined for n0 = 0 (an isolated particle);
 * callers must detect that case and report it, this function then returns infinities.
 */
inline ParticleVolume volumeVA(double primitiveDensity) {
    double volume = 1.0/primitiveDensity;
    return {volume, -volume*volume};
}

/**
 * The two dimensionless integrals behind V-B, as functions of k = (2 pi/15) Rt^3 n0 >= 0:
 *   I(k) = int_0^1 y^2 (1-y)^2 / (y^2 + k)   dy      so that V      =  4 pi Rt^3 I(k),
 *   J(k) = int_0^1 y^2 (1-y)^2 / (y^2 + k)^2 dy      so that dV/dn0 = -(8 pi^2/15) Rt^6 J(k)   (J = -dI/dk).
 *
 * Three branches, each accurate to a few ulp over its range (checked against 40-digit quadrature in the tests):
 *  - 1/16 <= k < 16, the range of liquids: piecewise polynomials of degree 13 in a local variable, 4 pieces per
 *    octave, generated at 60 digits by tools/generate_vb_tables.py (VolumeVBTables.h; max error 1e-16 before
 *    rounding in the evaluation). The piece comes from the bits of k; no division, no transcendental
 *    function, so V-B costs a few ns more than V-A per particle.
 *  - k < 1/16: the closed forms of docs/theory.md section 3, with ln((k+1)/k) written as log1p(k) - log(k) so
 *    that no intermediate overflows for subnormal k (max 2e-15 relative there). They lose digits to cancellation as k grows (two near
 *    k = 1) and are useless for large k (at k = 1e5 the fifth digit of V is wrong).
 *  - k >= 16: 24-point Gauss-Legendre quadrature of the integrands themselves (nodes and weights generated at 60
 *    digits by the same tool). The integrands are positive (no cancellation) and analytic within sqrt(k) of [0, 1],
 *    so the rule converges to rounding error (max 1.8e-16 relative for 16 <= k <= 1e12 in the tests). The weight
 *    y^2 (1-y)^2 is symmetric about 1/2, so the nodes come in mirror pairs y, 1-y sharing one coefficient.
 *  - k = 0 (no neighbor in range): I = 1/3 exactly and J = +infinity (dV/dn0 diverges like k^-1/2). The
 *    derivative only ever multiplies w'(r) of a pair in range, and any such pair makes k > 0.
 */
struct VolumeIntegralsVB {
    double I, J;
};

namespace VolumeVBPolynomials {
/**
 * Both polynomials of one piece at t, as one two-lane vector (I, J), by Estrin's scheme: the 14 coefficients are
 * combined pairwise with t, then t^2, t^4, t^8, so the dependency chain is 4 steps deep instead of 13.
 */
template <class Lanes, class Load>
inline Lanes estrin13(Load load, double t) {
    const double t2 = t*t, t4 = t2*t2, t8 = t4*t4;
    Lanes a[7];
    for (int q = 0; q < 7; q++)
        a[q] = load(2*q) + load(2*q + 1)*t;
    const Lanes b0 = a[0] + a[1]*t2, b1 = a[2] + a[3]*t2, b2 = a[4] + a[5]*t2;
    return (b0 + b1*t4) + (b2 + a[6]*t4)*t8;
}

/** Both polynomials of one piece at t in portable C++, one after the other. */
inline VolumeIntegralsVB evaluatePortable(const double (*c)[2], double t) {
    static_assert(degree == 13, "Estrin evaluation is written for 14 coefficients");
    return {estrin13<double>([&](int p) { return c[p][0]; }, t), estrin13<double>([&](int p) { return c[p][1]; }, t)};
}

/**
 * Both polynomials of one piece at t: with GCC or Clang as one two-lane SIMD vector (the same operations on both
 * lanes, so bit-identical to evaluatePortable, which tests/TestVolumeVB.cpp checks), with other compilers portably.
 */
inline VolumeIntegralsVB evaluate(const double (*c)[2], double t) {
#if defined(__GNUC__)
    typedef double Lanes __attribute__((vector_size(16)));
    const Lanes result = estrin13<Lanes>([&](int p) { return Lanes{c[p][0], c[p][1]}; }, t);
    return {result[0], result[1]};
#else
    return evaluatePortable(c, t);
#endif
}
} // namespace VolumeVBPolynomials

inline VolumeIntegralsVB volumeIntegralsVB(double k) {
    if (k == 0.0)
        return {1.0/3.0, std::numeric_limits<double>::infinity()};
    // k = m 2^octave with m in [1, 2); the top two bits of the mantissa pick the piece.
    std::uint64_t bits;
    std::memcpy(&bits, &k, sizeof(bits));
    const int octave = (int) ((bits >> 52) & 0x7ff) - 1023;
    if (octave >= VolumeVBPolynomials::firstOctave && octave <= VolumeVBPolynomials::lastOctave) {
        const int piece = (int) ((bits >> 50) & 3);
        const std::uint64_t mantissaBits = (bits & 0x000FFFFFFFFFFFFFull) | 0x3FF0000000000000ull;
        double m;
        std::memcpy(&m, &mantissaBits, sizeof(m));
        const double t = 8.0*(m - 1.0) - (2*piece + 1);   // exact, in [-1, 1)
        return VolumeVBPolynomials::evaluate(
                VolumeVBPolynomials::coefficients[(octave - VolumeVBPolynomials::firstOctave)
                                                  *VolumeVBPolynomials::subintervals + piece], t);
    }
    VolumeIntegralsVB integrals;
    if (k < 1.0)   // below the polynomial range: k < 1/16 (or subnormal)
        gendpdeVolumeIntegralsClosedForm(k, &integrals.I, &integrals.J);
    else           // above it, k >= 16: Gauss-Legendre quadrature (VolumeVBTables.h)
        gendpdeVolumeIntegralsQuadrature(k, VolumeVBQuadrature::nodeSquared, VolumeVBQuadrature::mirrorNodeSquared,
                                         VolumeVBQuadrature::coefficient, VolumeVBQuadrature::numPairs,
                                         &integrals.I, &integrals.J);
    return integrals;
}

/**
 * V-B, the partition-of-unity estimator (docs/theory.md section 3), for reduced range Rt = R/f_cut: the volume and its
 * derivative at any primitive density n0 >= 0, accurate to ~1e-15 relative for every k. V = (4 pi/3) Rt^3 at
 * n0 = 0 and V -> 1/n0 as n0 -> infinity. The scale factors are computed once per Rt.
 */
class VolumeEstimatorVB {
public:
    explicit VolumeEstimatorVB(double reducedRange) {
        double rt3 = reducedRange*reducedRange*reducedRange;
        kPerDensity = (2.0*Pi/15.0)*rt3;
        volumeScale = 4.0*Pi*rt3;
        derivativeScale = -(8.0*Pi*Pi/15.0)*rt3*rt3;
    }
    ParticleVolume operator()(double primitiveDensity) const {
        VolumeIntegralsVB integrals = volumeIntegralsVB(kPerDensity*primitiveDensity);
        return {volumeScale*integrals.I, derivativeScale*integrals.J};
    }
    /** k = getKPerDensity() n0; V = getVolumeScale() I(k); dV/dn0 = getDerivativeScale() J(k). */
    double getKPerDensity() const {
        return kPerDensity;
    }
    double getVolumeScale() const {
        return volumeScale;
    }
    double getDerivativeScale() const {
        return derivativeScale;
    }
private:
    double kPerDensity, volumeScale, derivativeScale;
};

/** V-B for one primitive density n0 >= 0 and reduced range Rt (see VolumeEstimatorVB). */
inline ParticleVolume volumeVB(double primitiveDensity, double reducedRange) {
    return VolumeEstimatorVB(reducedRange)(primitiveDensity);
}

/**
 * The first moment of a particle's neighbourhood (docs/interfaces.md), g_i = sum_j phi(r_ij) e_ij with e_ij the unit
 * vector from j to i and the dimensionless weight phi(r) = (r/R)(1 - r/R)^2 for r < R: zero for a particle whose
 * neighbours surround it evenly, pointing away from the neighbours for one at a surface. phi and phi' vanish at R
 * (so g_i and its gradient are continuous as pairs cross the cutoff) and phi at 0 (a close pair does not dominate).
 * Its gradient with respect to the pair vector d = r_i - r_j is H(d) = phi'(r) e e^T + (phi(r)/r)(I - e e^T).
 */
class MomentWeight {
public:
    explicit MomentWeight(double cutoff) : inverseCutoff(1.0/cutoff) {
    }
    /** phi(r) for r < R (dimensionless). */
    double valueInside(double r) const {
        const double x = r*inverseCutoff, y = 1.0 - x;
        return x*y*y;
    }
    /** phi(r)/r = (1/R)(1 - r/R)^2 for r < R (1/length), without a division. */
    double valueOverDistanceInside(double r) const {
        const double y = 1.0 - r*inverseCutoff;
        return inverseCutoff*y*y;
    }
    /** phi'(r) for r < R (1/length). */
    double derivativeInside(double r) const {
        const double x = r*inverseCutoff;
        return inverseCutoff*(1.0 - x)*(1.0 - 3.0*x);
    }
private:
    double inverseCutoff;
};

/** A V-C volume and its derivatives with respect to the primitive density n0 and to G = |g|^2. */
struct ParticleVolumeVC {
    double volume;              // length^3
    double derivative;          // dV/dn0 at fixed G, length^6
    double momentDerivative;    // dV/dG at fixed n0, length^3
};

/**
 * V-C, the partition-of-unity estimator with a surface correction (docs/interfaces.md):
 *   V = V_B(n0) (1 + alpha x^2/(1 + x^2)),   x = max(0, a^2 - t)/w,   a^2 = c^2 G/(n0^2 + eps^2),   G = |g|^2,
 * with c = 30/(pi R^3), so that a = 1 for a particle at the flat surface of a uniform fluid (half its neighbourhood
 * empty), eps = 3/(4 pi R^3) (a tenth of one neighbour's weight at r = 0, which keeps a^2 and its derivatives finite
 * as a particle loses its last neighbours), alpha = 3, threshold t = 0.4 and width w = 0.3 (gendpdeSurfaceFactor;
 * chosen against the exact volume, the slab and the bulk state point, docs/interfaces.md). V_B is V-B with reduced
 * range Rt = R/f_cut.
 * The factor is exactly 1 below the threshold, where the one-sidedness of a liquid's disorder lies (mean a^2 ~ 0.1
 * in bulk argon), so the bulk is V-B's and the correction cannot reward a liquid for restructuring; above it the
 * factor rises smoothly (continuous first derivative) towards 1 + alpha for a particle facing empty space, which
 * the exact partition of unity gives the larger volume of the space it faces.
 */
class VolumeEstimatorVC {
public:
    VolumeEstimatorVC(double cutoff, double reducedRange) : volumeVB(reducedRange) {
        const double r3 = cutoff*cutoff*cutoff;
        const double c = 30.0/(Pi*r3), eps = 3.0/(4.0*Pi*r3);
        momentScale = c*c;
        densitySoftening = eps*eps;
    }
    /** The volume at primitive density n0 >= 0 and squared moment G >= 0; dV/dn0 is -infinity at n0 = 0. */
    ParticleVolumeVC operator()(double primitiveDensity, double squaredMoment) const {
        const ParticleVolume b = volumeVB(primitiveDensity);
        const double inverse = 1.0/(primitiveDensity*primitiveDensity + densitySoftening);
        const double a2 = momentScale*squaredMoment*inverse;
        double factor, slope;   // the factor and its derivative with respect to a^2
        gendpdeSurfaceFactor(a2, &factor, &slope);
        if (slope == 0.0)
            return {b.volume, b.derivative, 0.0};
        return {b.volume*factor, b.derivative*factor - b.volume*slope*2.0*a2*primitiveDensity*inverse,
                b.volume*slope*momentScale*inverse};
    }
    const VolumeEstimatorVB& getVolumeVB() const {
        return volumeVB;
    }
    /** c^2 and eps^2 of the definition (1/length^6). */
    double getMomentScale() const {
        return momentScale;
    }
    double getDensitySoftening() const {
        return densitySoftening;
    }
private:
    VolumeEstimatorVB volumeVB;
    double momentScale, densitySoftening;
};

/**
 * The Tait equation of state and the per-particle mechanical free energy (docs/theory.md section 4):
 *   pi(n) = pi0 + B_T [ (n/n0)^gamma_T - 1 ]
 *   f(n)  = (B_T - pi0)/n + B_T/((gamma_T - 1) n0) (n/n0)^(gamma_T - 1),     with pi = n^2 df/dn.
 * n0 is the reference density (1/length^3), pi0 and B_T are pressures (energy/length^3), gamma_T > 1.
 */
class TaitEquationOfState {
public:
    TaitEquationOfState(double referenceDensity, double referencePressure, double bulkModulus, double exponent) :
            referenceDensity(referenceDensity), referencePressure(referencePressure), bulkModulus(bulkModulus),
            exponent(exponent), integerPower(integerPowerOf(exponent)) {
    }
    /**
     * gamma_T - 1 when gamma_T is an integer in [2, 33], else -1. gamma_T is usually an integer (6 for argon, 7 for
     * water): then x^(gamma_T - 1) by multiplications, exact to a few ulp and several times cheaper than pow().
     */
    static int integerPowerOf(double exponent) {
        return (exponent == std::floor(exponent) && exponent >= 2.0 && exponent <= 33.0) ? (int) exponent - 1 : -1;
    }
    /** Pressure pi(n) and free energy per particle f(n) at density n, with one power between them. */
    void evaluate(double density, double& pressure, double& freeEnergy) const {
        gendpdeTait(density, referenceDensity, referencePressure, bulkModulus, exponent, integerPower, &pressure,
                    &freeEnergy);
    }
private:
    double referenceDensity, referencePressure, bulkModulus, exponent;
    int integerPower;
};

/**
 * The weight of the random forces and of the random heat flux of docs/theory.md section 5 for a pair in range
 * (r < R): omega_R(r) = 1 - r/R. The dissipative and conductive weights are omega_D = omega_q = omega_R^2.
 */
inline double randomWeight(double r, double cutoff) {
    return 1.0 - r/cutoff;
}

/**
 * The dissipative and random update of one pair's momenta (docs/theory.md sections 5-6), in two stages as in
 * Lisal, Brennan and Bonet Avalos (2011): an explicit half (half the friction, half the random impulse) and an implicit half solved
 * exactly for the final relative velocity. Along e this is a Crank-Nicolson step of the relative velocity u, which
 * keeps its stationary variance (1/m_i + 1/m_j) noiseAmplitude^2/(2 friction) exact for any dt.
 *
 * e is the unit vector from j to i, omegaR = 1 - r/R, friction the coefficient of the drift -friction omega_R^2 u,
 * noiseAmplitude the sigma of the random impulse sigma omega_R dW, xi a standard normal variate. The impulse P e
 * goes to i and -P e to j. Returns the change of the pair's kinetic energy, P (u0 + P (1/m_i + 1/m_j)/2), which the
 * caller hands to the internal energies (or to a bath).
 */
inline double dissipativePairUpdate(const OpenMM::Vec3& e, double omegaR, double friction, double noiseAmplitude,
                                    double stepSize, double sqrtStepSize, double inverseMassI, double inverseMassJ,
                                    OpenMM::Vec3& vi, OpenMM::Vec3& vj, double xi) {
    double kineticChange;
    const double impulse = gendpdePairImpulse(e.dot(vi - vj), omegaR, friction, noiseAmplitude, stepSize,
                                              sqrtStepSize, inverseMassI + inverseMassJ, xi, &kineticChange);
    vi += e*(impulse*inverseMassI);
    vj -= e*(impulse*inverseMassJ);
    return kineticChange;
}

/**
 * What a GenDPDE pair update needs from the internal energies eps_i, eps_j (theta = eps/C_V of each particle's type).
 *
 * frictionFactor is the Ito term of the friction: the update uses gamma (1 + frictionFactor) with noise
 * sigma^2 = 2 gamma k_B Theta_ij, frictionFactor = k_B (beta_i^2/C_i + beta_j^2/C_j)/(beta_i + beta_j)^2, beta = 1/theta
 * ((k_B/C_V)(beta_i^2 + beta_j^2)/(beta_i + beta_j)^2 when both particles have the same C_V).
 * Why (derivation: docs/theory.md section 7): Theta_ij depends on eps_i and eps_j, which every random kick changes
 * (mechanical heating), so the noise of the momentum equation is multiplicative. Its equilibrium, the microcanonical
 * density prod_i eps_i^(C_i/k_B) on the energy shell (from which T_kin = <1/theta>^-1 and the Gamma law of eps_i
 * follow), is stationary only if the noise is read post-point (Haenggi-Klimontovich); a pair update draws the noise
 * with the temperatures it starts from (Ito), which needs the drift (1/2) d(b^2)/du, b^2 the variance rate of the
 * relative velocity u. Worked out, that drift is the factor above (k_B/(2 C_V) for equal temperatures). Without it the kinetic temperature exceeds the
 * harmonic-mean temperature by k_B/(2 C_V): 4.0% for liquid argon's C_V = 12.51 k_B, as measured
 * (python/tests/test_integrator_physics.py). In the isothermal limit C_V -> infinity it vanishes.
 */
struct PairTemperatures {
    double pairThermalEnergy;              // k_B Theta_ij, 1/Theta_ij = (1/theta_i + 1/theta_j)/2 (energy)
    double inverseTemperatureDifference;   // 1/theta_i - 1/theta_j (1/temperature)
    double frictionFactor;                 // the Ito term above (dimensionless)
};

inline PairTemperatures pairTemperatures(double energyI, double energyJ, double heatCapacityI, double heatCapacityJ,
                                         double boltzmann) {
    PairTemperatures result;
    gendpdePairTemperatures(energyI, energyJ, heatCapacityI, heatCapacityJ, boltzmann, &result.pairThermalEnergy,
                            &result.inverseTemperatureDifference, &result.frictionFactor);
    return result;
}

/**
 * The heat that flows from j to i in one step (docs/theory.md section 5): kappa omega_q (1/theta_i - 1/theta_j) dt
 * + alpha omega_R sqrt(dt) xi_q, with randomAmplitude alpha = sqrt(2 k_B kappa).
 */
inline double conductiveHeat(double omegaR, double heatConduction, double randomAmplitude,
                             double inverseTemperatureDifference, double stepSize, double sqrtStepSize, double xiQ) {
    return gendpdeConductiveHeat(omegaR, heatConduction, randomAmplitude, inverseTemperatureDifference, stepSize,
                                 sqrtStepSize, xiQ);
}

} // namespace Physics
} // namespace GenDPDEPlugin

#endif /*GENDPDE_PHYSICS_H_*/
