#ifndef GENDPDE_PHYSICS_H_
#define GENDPDE_PHYSICS_H_

/* -------------------------------------------------------------------------- *
 * The one home of GenDPDE's pointwise physics (../shared/MODEL.md, sections   *
 * 1-3): the density weight, the two volume estimators with their numerically *
 * safe branches, the Tait equation of state and the dissipation weights.     *
 * Plain inline functions of doubles, with no OpenMM types, so that every     *
 * platform kernel, the Python bindings and the tests evaluate the same code. *
 *                                                                            *
 * Units are whatever the caller uses consistently (OpenMM: nm, kJ/mol).     *
 * -------------------------------------------------------------------------- */

#include <cmath>
#include <limits>

namespace GenDPDEPlugin {
namespace Physics {

constexpr double Pi = 3.14159265358979323846;

/**
 * The normalised density weight of MODEL.md section 1,
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
        double x = 1.0 - r*inverseCutoff;
        return r < cutoff ? valueScale*x*x : 0.0;
    }
    /** dw/dr (1/length^4) */
    double derivative(double r) const {
        return r < cutoff ? derivativeScale*(1.0 - r*inverseCutoff) : 0.0;
    }
    double getCutoff() const {
        return cutoff;
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
 * Two branches, each accurate to a few ulp over its range (checked against 40-digit quadrature in the tests):
 *  - k < 1: the closed forms of MODEL.md, with ln((k+1)/k) written as log1p(k) - log(k) so that no intermediate
 *    overflows for subnormal k. They lose about two digits to cancellation as k approaches 1 and are useless for
 *    large k (at k = 1e5 the fifth digit of V is wrong).
 *  - k >= 1: 16-point Gauss-Legendre quadrature of the integrands themselves. The integrands are positive (no
 *    cancellation) and analytic within sqrt(k) >= 1 of [0, 1], so the rule converges to rounding error
 *    (max 6e-16 relative for 1 <= k <= 1e12). The weight y^2 (1-y)^2 is symmetric about 1/2, so the nodes come
 *    in mirror pairs y, 1-y that share one coefficient.
 *  - k = 0 (no neighbour in range): I = 1/3 exactly and J = +infinity (dV/dn0 diverges like k^-1/2). The
 *    derivative only ever multiplies w'(r) of a pair in range, and any such pair makes k > 0.
 */
struct VolumeIntegralsVB {
    double I, J;
};

inline VolumeIntegralsVB volumeIntegralsVB(double k) {
    if (k == 0.0)
        return {1.0/3.0, std::numeric_limits<double>::infinity()};
    if (k < 1.0) {
        double s = std::sqrt(k);
        double arctangent = std::atan(1.0/s);
        double logarithm = std::log1p(k) - std::log(k);  // ln((k+1)/k)
        double I = 1.0/3.0 - k - (1.0 - k)*s*arctangent + k*logarithm;
        double J = 1.5 - logarithm + (1.0 - 3.0*k)/(2.0*s)*arctangent;
        return {I, J};
    }
    // Gauss-Legendre on [0,1]: y_m^2, (1-y_m)^2 and w_m y_m^2 (1-y_m)^2 for the 8 nodes with y_m < 1/2
    // (computed with 40-digit arithmetic; twice their sum is 1/30 = int_0^1 y^2 (1-y)^2 dy, which the rule integrates
    // exactly).
    static const double nodeSquared[8] = {
        0.000028085044762807703601, 0.00076798201683317532895, 0.0045137434429349584119, 0.014956750863041527413,
        0.036504641147957013297, 0.073436453325263823811, 0.1290233645632422067, 0.20475058933759306774};
    static const double mirrorNodeSquared[8] = {
        0.9894290200364127403, 0.94534300509006575141, 0.87014494583076670229, 0.77036115921804456131,
        0.65438088555060076174, 0.53145323098249121015, 0.41062691534250111993, 0.29976309917523050793};
    static const double coefficient[8] = {
        0.00000037725842041953469552, 0.000022598229261604835721, 0.00018687281069056717853,
        0.00071799373067588504207, 0.0017867699577495334381, 0.0033009237357258526629,
        0.0048372070291874590846, 0.0058139239149553448901};
    double I = 0.0, J = 0.0;
    for (int m = 0; m < 8; m++) {
        double a = 1.0/(nodeSquared[m] + k);
        double b = 1.0/(mirrorNodeSquared[m] + k);
        I += coefficient[m]*(a + b);
        J += coefficient[m]*(a*a + b*b);
    }
    return {I, J};
}

/**
 * V-B, the partition-of-unity estimator (MODEL.md section 1) for primitive density n0 >= 0 and reduced range
 * Rt = R/f_cut. Accurate to ~1e-15 relative for every k; V = (4 pi/3) Rt^3 at n0 = 0 and V -> 1/n0 as n0 -> inf.
 */
inline ParticleVolume volumeVB(double primitiveDensity, double reducedRange) {
    double rt3 = reducedRange*reducedRange*reducedRange;
    VolumeIntegralsVB integrals = volumeIntegralsVB((2.0*Pi/15.0)*rt3*primitiveDensity);
    return {4.0*Pi*rt3*integrals.I, -(8.0*Pi*Pi/15.0)*rt3*rt3*integrals.J};
}

/**
 * The Tait equation of state and the per-particle mechanical free energy (MODEL.md section 2):
 *   pi(n) = pi0 + B_T [ (n/n0)^gamma_T - 1 ]
 *   f(n)  = (B_T - pi0)/n + B_T/((gamma_T - 1) n0) (n/n0)^(gamma_T - 1),     with pi = n^2 df/dn.
 * n0 is the reference density (1/length^3), pi0 and B_T are pressures (energy/length^3), gamma_T > 1.
 */
class TaitEquationOfState {
public:
    TaitEquationOfState(double referenceDensity, double referencePressure, double bulkModulus, double exponent) :
            referenceDensity(referenceDensity), referencePressure(referencePressure), bulkModulus(bulkModulus),
            exponent(exponent) {
    }
    /** Pressure pi(n) and free energy per particle f(n) at density n, with one pow() between them. */
    void evaluate(double density, double& pressure, double& freeEnergy) const {
        double x = density/referenceDensity;
        double xPowGammaMinusOne = std::pow(x, exponent - 1.0);
        pressure = referencePressure + bulkModulus*(xPowGammaMinusOne*x - 1.0);
        freeEnergy = (bulkModulus - referencePressure)/density
                   + bulkModulus/((exponent - 1.0)*referenceDensity)*xPowGammaMinusOne;
    }
    double pressure(double density) const {
        double p, f;
        evaluate(density, p, f);
        return p;
    }
    double freeEnergy(double density) const {
        double p, f;
        evaluate(density, p, f);
        return f;
    }
    /** The density that minimises f(n) with V-A: n0 (1 - pi0/B_T)^(1/gamma_T); NaN if pi0 >= B_T. */
    double freeEnergyMinimumDensity() const {
        return referenceDensity*std::pow(1.0 - referencePressure/bulkModulus, 1.0/exponent);
    }
private:
    double referenceDensity, referencePressure, bulkModulus, exponent;
};

/**
 * The dissipation weights of MODEL.md section 3 (unnormalised, same cutoff R as the density weight):
 * omega_R(r) = 1 - r/R (random forces and random heat flux), omega_D = omega_q = omega_R^2.
 */
inline double randomWeight(double r, double cutoff) {
    return r < cutoff ? 1.0 - r/cutoff : 0.0;
}

} // namespace Physics
} // namespace GenDPDEPlugin

#endif /*GENDPDE_PHYSICS_H_*/
