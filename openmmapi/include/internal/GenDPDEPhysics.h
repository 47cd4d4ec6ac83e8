/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
#ifndef GENDPDE_PHYSICS_H_
#define GENDPDE_PHYSICS_H_

/* -------------------------------------------------------------------------- *
 * The physics core (GenDPDEPhysicsCore.h) for the host platforms, the Python *
 * bindings and the tests: the core's functions in double precision, and     *
 * small classes that hold their constants (computed once per parameter set) *
 * and return results as structs and Vec3. No formula is written here: every  *
 * one is in the core, which the device programs compile too.                 *
 *                                                                            *
 * Units are whatever the caller uses consistently (OpenMM: nm, kJ/mol).      *
 * -------------------------------------------------------------------------- */

#include "gendpde/GenDPDEPhysicsCoreDouble.h"
#include "openmm/Vec3.h"
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <vector>

namespace GenDPDEPlugin {
namespace Physics {

static_assert(VolumeVBPolynomials::subintervals == 4 && VolumeVBPolynomials::degree == 13,
              "gendpdeVolumeIntegralsVB reads 4 pieces per octave of 14 coefficients each");

/** Boltzmann's constant in OpenMM units, kJ/(mol K): k_B N_A (exact SI values), as OpenMM defines it. */
constexpr double Boltzmann = 1.380649e-23 * 6.02214076e23 / 1000.0;


/**
 * The normalised density weight of docs/theory.md section 2 (gendpdeDensityWeight), with its constants for one
 * cutoff R: w(r) = 15/(2 pi R^3) (1 - r/R)^2, w'(r) = -15/(pi R^4) (1 - r/R) for r < R, zero beyond.
 */
class DensityWeight {
public:
    explicit DensityWeight(double cutoff) : cutoff(cutoff), inverseCutoff(1.0 / cutoff) {
        gendpdeDensityWeightScales(cutoff, &valueScale, &derivativeScale);
    }
    /** w(r) (1/length^3) */
    double value(double r) const { return r < cutoff ? valueInside(r) : 0.0; }
    /** dw/dr (1/length^4) */
    double derivative(double r) const { return r < cutoff ? derivativeInside(r) : 0.0; }
    /** The formulas without the test r < R, for branch-free loops that mask the terms themselves. */
    double valueInside(double r) const { return gendpdeDensityWeight(r, inverseCutoff, valueScale); }
    double derivativeInside(double r) const {
        return gendpdeDensityWeightDerivative(r, inverseCutoff, derivativeScale);
    }
    double getCutoff() const { return cutoff; }
    double getInverseCutoff() const { return inverseCutoff; }
    double getValueScale() const { return valueScale; }
    double getDerivativeScale() const { return derivativeScale; }

private:
    double cutoff, inverseCutoff, valueScale, derivativeScale;
};

/** A particle volume V and its derivative with respect to the primitive density, dV/dn0. */
struct ParticleVolume {
    double volume;       // length^3
    double derivative;   // dV/dn0, length^6
};

/** A volume and its derivatives with respect to n0 and to the squared first moment G (gendpdeParticleVolume). */
struct ParticleVolumeAndMoment {
    double volume;             // length^3
    double derivative;         // dV/dn0 at fixed G, length^6
    double momentDerivative;   // dV/dG at fixed n0, length^3 (0 unless the estimator reads the moments)
};

/** The two dimensionless V-B integrals I(k), J(k) (gendpdeVolumeIntegralsVB). */
struct VolumeIntegralsVB {
    double I, J;
};

/** I(k) and J(k) at any k >= 0: at k = 0 (no neighbour in range) I = 1/3 exactly and J = +infinity. */
inline VolumeIntegralsVB volumeIntegralsVB(double k) {
    if (k == 0.0)
        return {1.0 / 3.0, std::numeric_limits<double>::infinity()};
    VolumeIntegralsVB integrals;
    gendpdeVolumeIntegralsVB(k, volumePolynomials(), VolumeVBQuadrature::nodeSquared,
                             VolumeVBQuadrature::mirrorNodeSquared, VolumeVBQuadrature::coefficient, &integrals.I,
                             &integrals.J);
    return integrals;
}

/**
 * A density estimator with its constants for one cutoff R and reduced range Rt = R/f_cut (gendpdeParticleVolume):
 * VA (GENDPDE_ESTIMATOR_VA), VB or VC of docs/theory.md section 3.
 */
class VolumeEstimator {
public:
    VolumeEstimator(int estimator, double cutoff, double reducedRange) : estimator(estimator) {
        gendpdeEstimatorConstants(cutoff, reducedRange, &kPerDensity, &volumeScale, &derivativeScale, &momentScale,
                                  &densitySoftening);
    }
    /**
     * V, dV/dn0 and dV/dG at primitive density n0 >= 0 and squared moment G (ignored unless needsMoments()); for VA
     * at n0 = 0 the volume is infinite, and for VB and VC dV/dn0 is given as 0 there (it multiplies no pair).
     */
    ParticleVolumeAndMoment operator()(double primitiveDensity, double squaredMoment = 0.0) const {
        ParticleVolumeAndMoment v;
        gendpdeParticleVolume(estimator, primitiveDensity, squaredMoment, kPerDensity, volumeScale, derivativeScale,
                              momentScale, densitySoftening, volumePolynomials(), VolumeVBQuadrature::nodeSquared,
                              VolumeVBQuadrature::mirrorNodeSquared, VolumeVBQuadrature::coefficient, &v.volume,
                              &v.derivative, &v.momentDerivative);
        return v;
    }
    int getEstimator() const { return estimator; }
    /** Whether the estimator reads the first moments of the neighbourhoods. */
    bool needsMoments() const { return gendpdeEstimatorNeedsMoments(estimator) != 0; }
    /** The constants of gendpdeEstimatorConstants, for platforms that pass them to the core themselves. */
    double getKPerDensity() const { return kPerDensity; }
    double getVolumeScale() const { return volumeScale; }
    double getDerivativeScale() const { return derivativeScale; }
    double getMomentScale() const { return momentScale; }
    double getDensitySoftening() const { return densitySoftening; }

private:
    int estimator;
    double kPerDensity, volumeScale, derivativeScale, momentScale, densitySoftening;
};

/**
 * V-A, the traditional estimator: V = 1/n0, dV/dn0 = -1/n0^2. Undefined for n0 = 0 (an isolated particle);
 * callers must detect that case and report it, this function then returns infinities.
 */
inline ParticleVolume volumeVA(double primitiveDensity) {
    const ParticleVolumeAndMoment v = VolumeEstimator(GENDPDE_ESTIMATOR_VA, 1.0, 1.0)(primitiveDensity);
    return {v.volume, v.derivative};
}

/**
 * V-B for one primitive density n0 >= 0 and reduced range Rt, accurate to ~1e-15 relative for every k: V = (4 pi/3)
 * Rt^3 at n0 = 0, where dV/dn0 is its limit -infinity, and V -> 1/n0 as n0 -> infinity.
 */
inline ParticleVolume volumeVB(double primitiveDensity, double reducedRange) {
    const ParticleVolumeAndMoment v =
            VolumeEstimator(GENDPDE_ESTIMATOR_VB, reducedRange, reducedRange)(primitiveDensity);
    return {v.volume, primitiveDensity == 0.0 ? -std::numeric_limits<double>::infinity() : v.derivative};
}

/**
 * The Tait equation of state and the per-particle mechanical free energy (docs/theory.md section 4, gendpdeTait):
 *   pi(n) = pi0 + B_T [ (n/n0)^gamma_T - 1 ]
 *   f(n)  = (B_T - pi0)/n + B_T/((gamma_T - 1) n0) (n/n0)^(gamma_T - 1),     with pi = n^2 df/dn.
 * n0 is the reference density (1/length^3), pi0 and B_T are pressures (energy/length^3), gamma_T > 1.
 */
class TaitEquationOfState {
public:
    TaitEquationOfState(double referenceDensity, double referencePressure, double bulkModulus, double exponent) :
            referenceDensity(referenceDensity), referencePressure(referencePressure), bulkModulus(bulkModulus),
            exponent(exponent), integerPower(integerPowerOf(exponent)) {}
    /**
     * gamma_T - 1 when gamma_T is an integer in [2, 33], else -1. gamma_T is usually an integer (6 for argon, 7 for
     * water): then x^(gamma_T - 1) by multiplications, exact to a few ulp and several times cheaper than pow().
     */
    static int integerPowerOf(double exponent) { return gendpdeTaitIntegerPower(exponent); }
    /** Pressure pi(n) and free energy per particle f(n) at density n, with one power between them. */
    void evaluate(double density, double& pressure, double& freeEnergy) const {
        gendpdeTait(density, referenceDensity, referencePressure, bulkModulus, exponent, integerPower, &pressure,
                    &freeEnergy);
    }
    double getReferenceDensity() const { return referenceDensity; }
    double getReferencePressure() const { return referencePressure; }
    double getBulkModulus() const { return bulkModulus; }
    double getExponent() const { return exponent; }
    int getIntegerPower() const { return integerPower; }

private:
    double referenceDensity, referencePressure, bulkModulus, exponent;
    int integerPower;
};

/** What a particle contributes to the force (gendpdeParticleState). */
struct ParticleState {
    double volume;             // V (length^3)
    double pressure;           // pi (energy/length^3)
    double freeEnergy;         // its term of U (energy): f(n) for the Tait law (gendpdeParticleState says what for
                               // the laws that depend on temperature)
    double forceCoefficient;   // pi dV/dn0 (energy length^3)
    double momentForceScale;   // 2 pi dV/dG (energy; VC, else 0): q = momentForceScale g
    double thermalEnergy;      // C theta now (energy); a law without temperature: ThermalInput's storedEnergy
    double densityEntropy;     // sigma(n) (energy/temperature); 0 for a law without temperature
};

/**
 * A local equation of state of section 11 (gendpdeLocalEquationOfState): the law (GENDPDE_EOS_*) and its parameters
 * in the core's order (GenDPDEEquationsOfState.h packs them, equationsOfStateByType), with the Tait law's integer
 * power.
 */
struct LocalEquationOfState {
    int law = GENDPDE_EOS_TAIT;
    std::vector<double> parameter;
    int integerPower = -1;
    /** Whether the law depends on temperature (gendpdeLawDependsOnTemperature). */
    bool dependsOnTemperature() const { return gendpdeLawDependsOnTemperature(law) != 0; }
};

/**
 * What a particle reads of its thermal state (gendpdeParticleState): the Isothermal mode's temperature, or the
 * integrator's eps_i and the sigma_i it belongs to, and C_V. A law that does not depend on temperature reads only
 * storedEnergy (kept as it is; 0 where the force has no thermal state).
 */
struct ThermalInput {
    bool isothermal;
    double temperature;      // K (isothermal)
    double storedEnergy;     // eps_i (kJ/mol)
    double storedEntropy;    // sigma at the density of eps_i (kJ/(mol K)), if entropyKnown
    bool entropyKnown;
    double heatCapacity;     // C_V (kJ/(mol K))
    bool checkStep;          // an evaluation of a step: a temperature jump is an error (gendpdeParticleState)
};

/**
 * The state of a particle of primitive density n0 and squared moment G (estimators that read moments) under this
 * estimator and law, with its thermal state (gendpdeParticleState); returns GENDPDE_PARTICLE_VALID or why the state
 * is invalid (then state is not usable).
 */
inline int particleState(const VolumeEstimator& estimator, const LocalEquationOfState& law, double primitiveDensity,
                         double squaredMoment, const ThermalInput& thermal, ParticleState& state) {
    return gendpdeParticleState(estimator.getEstimator(), primitiveDensity, squaredMoment, estimator.getKPerDensity(),
                                estimator.getVolumeScale(), estimator.getDerivativeScale(), estimator.getMomentScale(),
                                estimator.getDensitySoftening(), volumePolynomials(), VolumeVBQuadrature::nodeSquared,
                                VolumeVBQuadrature::mirrorNodeSquared, VolumeVBQuadrature::coefficient, law.law,
                                law.parameter.data(), law.integerPower, thermal.isothermal ? 1 : 0, thermal.temperature,
                                thermal.storedEnergy, thermal.storedEntropy, thermal.entropyKnown ? 1 : 0,
                                thermal.checkStep ? 1 : 0, thermal.heatCapacity, &state.volume, &state.pressure,
                                &state.freeEnergy, &state.forceCoefficient, &state.momentForceScale,
                                &state.thermalEnergy, &state.densityEntropy);
}

/** V-C's moment weight phi(r)/r (gendpdeMomentWeightOverDistance) for r < R: g_i = sum_j (phi/r) d_ij. */
inline double momentWeightOverDistance(double r, double inverseCutoff) {
    return gendpdeMomentWeightOverDistance(r, inverseCutoff);
}

/**
 * The force on i from j of a pair d = r_i - r_j of length r > 0 (gendpdePairForce), as a Vec3 (energy/length):
 * coefficientSum c_i + c_j, weightDerivative w'(r), q_i and q_j V-C's moment forces (read only if moments); virial
 * receives its d . F (energy).
 */
inline OpenMM::Vec3 pairForce(const OpenMM::Vec3& d, double r, double coefficientSum, double weightDerivative,
                              double inverseCutoff, bool moments, const OpenMM::Vec3& qi, const OpenMM::Vec3& qj,
                              double& virial) {
    double force[3];
    virial = gendpdePairForce(d[0], d[1], d[2], r, coefficientSum, weightDerivative, inverseCutoff, moments ? 1 : 0,
                              qi[0], qi[1], qi[2], qj[0], qj[1], qj[2], force);
    return OpenMM::Vec3(force[0], force[1], force[2]);
}

/** A 3 x 3 tensor, row-major (virial tensors: element [3a + b] is W_ab). */
struct Tensor {
    double element[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
};

/** Half of a pair's virial tensor, (F_a/2) d_b, added to a particle's (gendpdeAddHalfPairVirial). */
inline void addHalfPairVirial(const OpenMM::Vec3& force, const OpenMM::Vec3& d, Tensor& virial) {
    gendpdeAddHalfPairVirial(force[0], force[1], force[2], d[0], d[1], d[2], virial.element);
}

} // namespace Physics
} // namespace GenDPDEPlugin

#endif /*GENDPDE_PHYSICS_H_*/
