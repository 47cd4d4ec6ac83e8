/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
#ifndef GENDPDE_TEST_BRUTE_FORCE_H_
#define GENDPDE_TEST_BRUTE_FORCE_H_

/* An independent O(N^2) evaluation of the GenDPDE conservative force for the tests. It shares no code with the
 * plugin: every pair and every periodic image within the cutoff is visited explicitly (no minimum-image formula,
 * no neighbor list), V-B volumes come from adaptive Simpson quadrature of the defining integral (not the closed
 * forms, the polynomials or the Gauss rule of the physics core), V-C's moment force is the gradient matrix H applied
 * as a matrix, and the formulas of docs/theory.md are written out again here.
 *
 * It is the oracle of every estimator: the tests run each estimator listed in `estimators` below. */

#include "openmm/Vec3.h"
#include <algorithm>
#include <cmath>
#include <functional>
#include <vector>

namespace BruteForce {

/** The estimators this oracle evaluates, numbered as GenDPDEForce::DensityEstimator, and their names. */
enum Estimator { VA = 0, VB = 1, VC = 2 };
const std::vector<Estimator> estimators = {VA, VB, VC};
inline const char* estimatorName(int estimator) {
    return estimator == VA ? "VA" : estimator == VB ? "VB" : "VC";
}
/** Whether an estimator allows a particle without neighbours (V-A's 1/n0 does not). */
inline bool allowsIsolatedParticles(int estimator) {
    return estimator != VA;
}

/** Tait parameters n0, pi0, B_T, gamma_T. */
struct Tait {
    double n0, pi0, bulkModulus, gammaT;
};

struct Model {
    double cutoff;
    int estimator;                    // VA, VB or VC
    double cutoffScaling;
    double n0, pi0, bulkModulus, gammaT;
    std::vector<Tait> particleTait;   // per particle, for mixtures; empty: every particle has n0, pi0, B_T, gamma_T
    /**
     * If set, particle i's law at density n in place of Tait: its pressure pi and its term of the energy
     * (temperature-dependent laws, docs/theory.md section 11; the test writes them out).
     */
    std::function<void(int i, double n, double& pressure, double& energy)> particleLaw;
    /**
     * The background pressure p_b: every particle's pressure + p_b and energy - p_b V_i, and the energy + p_b V_box
     * (periodic), whose virial is -3 p_b V_box, shared equally by the particles' tensors.
     */
    double backgroundPressure = 0.0;
    bool periodic;
    OpenMM::Vec3 box[3];
};

/** A 3 x 3 matrix, rows first: element [a][b]. */
struct Matrix {
    double element[3][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
};

struct Result {
    double energy = 0.0, virial = 0.0;
    std::vector<OpenMM::Vec3> forces;
    std::vector<double> primitiveDensity, volume, pressure;
    std::vector<Matrix> particleVirial;   // W_i[a][b] = sum over i's pairs of (1/2) F_a d_b
    Matrix virialTensor;                  // sum over pairs of F_a d_b
};

inline double simpson(const std::function<double(double)>& f, double a, double b, double fa, double fm, double fb,
                      double whole, double tolerance, int depth) {
    double m = 0.5 * (a + b), lm = 0.5 * (a + m), rm = 0.5 * (m + b);
    double flm = f(lm), frm = f(rm);
    double left = (m - a) / 6.0 * (fa + 4.0 * flm + fm), right = (b - m) / 6.0 * (fm + 4.0 * frm + fb);
    if (depth <= 0 || std::abs(left + right - whole) <= 15.0 * tolerance)
        return left + right + (left + right - whole) / 15.0;
    return simpson(f, a, m, fa, flm, fm, left, 0.5 * tolerance, depth - 1)
            + simpson(f, m, b, fm, frm, fb, right, 0.5 * tolerance, depth - 1);
}

/** int_a^b f by adaptive Simpson to an absolute tolerance. */
inline double integrate(const std::function<double(double)>& f, double a, double b, double tolerance) {
    double fa = f(a), fb = f(b), fm = f(0.5 * (a + b));
    return simpson(f, a, b, fa, fm, fb, (b - a) / 6.0 * (fa + 4.0 * fm + fb), tolerance, 60);
}

/** Every displacement r_i - r_j + image with |.| < cutoff (images up to two box vectors away). */
inline std::vector<OpenMM::Vec3> displacementsInRange(const Model& model, OpenMM::Vec3 d) {
    std::vector<OpenMM::Vec3> result;
    int range = model.periodic ? 2 : 0;
    for (int a = -range; a <= range; a++)
        for (int b = -range; b <= range; b++)
            for (int c = -range; c <= range; c++) {
                OpenMM::Vec3 image = d + model.box[0] * a + model.box[1] * b + model.box[2] * c;
                if (std::sqrt(image.dot(image)) < model.cutoff)
                    result.push_back(image);
            }
    return result;
}

/** Positions must lie within one box of the origin's cell when periodic (the tests generate them so). */
inline Result evaluate(const Model& model, const std::vector<OpenMM::Vec3>& positions) {
    const int n = positions.size();
    const double R = model.cutoff, pi = 3.14159265358979323846;
    auto w = [&](double r) { return 15.0 / (2.0 * pi * R * R * R) * (1.0 - r / R) * (1.0 - r / R); };
    auto dw = [&](double r) { return -15.0 / (pi * R * R * R * R) * (1.0 - r / R); };
    // V-C's moment weight phi(r) = (r/R)(1 - r/R)^2 and its derivative.
    auto phi = [&](double r) { return (r / R) * (1.0 - r / R) * (1.0 - r / R); };
    auto dphi = [&](double r) { return (1.0 - r / R) * (1.0 - r / R) / R - 2.0 * (r / R) * (1.0 - r / R) / R; };
    Result result;
    result.forces.assign(n, OpenMM::Vec3());
    result.primitiveDensity.assign(n, 0.0);
    result.volume.assign(n, 0.0);
    result.pressure.assign(n, 0.0);
    result.particleVirial.assign(n, Matrix());
    for (int i = 0; i < n; i++)
        for (int j = 0; j < n; j++)
            if (i != j)
                for (const OpenMM::Vec3& d : displacementsInRange(model, positions[i] - positions[j]))
                    result.primitiveDensity[i] += w(std::sqrt(d.dot(d)));
    // V-C: the first moments g_i = sum over neighbours and images of phi(r) d/r.
    std::vector<OpenMM::Vec3> moment(n);
    if (model.estimator == VC)
        for (int i = 0; i < n; i++)
            for (int j = 0; j < n; j++)
                if (i != j)
                    for (const OpenMM::Vec3& d : displacementsInRange(model, positions[i] - positions[j])) {
                        const double r = std::sqrt(d.dot(d));
                        if (r > 0.0)
                            moment[i] += d * (phi(r) / r);
                    }
    std::vector<double> coefficient(n, 0.0);        // pi_i dV_i/dn0_i
    std::vector<OpenMM::Vec3> momentForce(n);       // q_i = 2 pi_i dV_i/dG_i g_i
    for (int i = 0; i < n; i++) {
        double n0i = result.primitiveDensity[i], V, dV;
        if (model.estimator != VA) {
            double Rt = R / model.cutoffScaling, k = 2.0 * pi / 15.0 * Rt * Rt * Rt * n0i;
            // Relative tolerance 1e-14 from the asymptotes I ~ 1/(3 + 30k) and J ~ 1/(30k^2 + 4 sqrt(k)/pi).
            double toleranceI = 1e-14 / (3.0 + 30.0 * k), toleranceJ = 1e-14 / (30.0 * k * k + 4.0 * std::sqrt(k) / pi);
            // k = 0 (no neighbor): the integrand is (1-y)^2, whose integral is 1/3.
            double I = k == 0.0 ? 1.0 / 3.0
                                : integrate([&](double y) { return y * y * (1 - y) * (1 - y) / (y * y + k); }, 0.0, 1.0,
                                            toleranceI);
            V = 4.0 * pi * Rt * Rt * Rt * I;
            if (k > 0.0) {
                // The integrand of J peaks near y = sqrt(k); split there so that the quadrature sees the peak.
                auto g = [&](double y) { return y * y * (1 - y) * (1 - y) / ((y * y + k) * (y * y + k)); };
                double split = std::min(0.5, std::sqrt(k));
                double J = integrate(g, 0.0, split, 0.5 * toleranceJ) + integrate(g, split, 1.0, 0.5 * toleranceJ);
                dV = -8.0 * pi * pi / 15.0 * std::pow(Rt, 6) * J;
            } else
                dV = 0.0; // no neighbor, no pair to use it
        } else {
            V = 1.0 / n0i;
            dV = -1.0 / (n0i * n0i);
        }
        double dVdG = 0.0;
        if (model.estimator == VC) {
            // V = V_B S(a^2), S = 1 + 3 x^2/(1 + x^2), x = max(0, a^2 - 0.4)/0.3, a^2 = c^2 G/(n0^2 + eps^2),
            // c = 30/(pi R^3), eps = 3/(4 pi R^3); by the chain rule dV/dn0 = V_B' S + V_B S' da^2/dn0 and
            // dV/dG = V_B S' da^2/dG.
            const double c = 30.0 / (pi * R * R * R), eps = 3.0 / (4.0 * pi * R * R * R), G = moment[i].dot(moment[i]);
            const double denominator = n0i * n0i + eps * eps, a2 = c * c * G / denominator;
            const double x = std::max(0.0, a2 - 0.4) / 0.3;
            const double S = 1.0 + 3.0 * x * x / (1.0 + x * x),
                         dSda2 = (x > 0.0 ? 6.0 * x / ((1.0 + x * x) * (1.0 + x * x)) / 0.3 : 0.0);
            const double da2dn0 = -2.0 * c * c * G * n0i / (denominator * denominator), da2dG = c * c / denominator;
            dV = dV * S + V * dSda2 * da2dn0;
            dVdG = V * dSda2 * da2dG;
            V *= S;
        }
        double density = 1.0 / V;
        const Tait t = model.particleTait.empty() ? Tait{model.n0, model.pi0, model.bulkModulus, model.gammaT}
                                                  : model.particleTait[i];
        double pressure = t.pi0 + t.bulkModulus * (std::pow(density / t.n0, t.gammaT) - 1.0);
        double energy = (t.bulkModulus - t.pi0) / density
                + t.bulkModulus / ((t.gammaT - 1.0) * t.n0) * std::pow(density / t.n0, t.gammaT - 1.0);
        if (model.particleLaw)
            model.particleLaw(i, density, pressure, energy);
        pressure += model.backgroundPressure;
        energy -= model.backgroundPressure * V;
        result.energy += energy;
        result.volume[i] = V;
        result.pressure[i] = pressure;
        coefficient[i] = n0i > 0.0 ? pressure * dV : 0.0;
        momentForce[i] = moment[i] * (2.0 * pressure * dVdG);
    }
    for (int i = 0; i < n; i++)
        for (int j = i + 1; j < n; j++)
            for (const OpenMM::Vec3& d : displacementsInRange(model, positions[i] - positions[j])) {
                double r = std::sqrt(d.dot(d));
                if (r == 0.0)
                    continue;
                OpenMM::Vec3 f = d * ((coefficient[i] + coefficient[j]) * dw(r) / r);
                // V-C: H (q_i - q_j) with H = phi'(r) e e^T + (phi(r)/r)(1 - e e^T), the gradient of phi(r) e.
                const OpenMM::Vec3 e = d / r, dq = momentForce[i] - momentForce[j];
                for (int a = 0; a < 3; a++)
                    for (int b = 0; b < 3; b++) {
                        const double H = dphi(r) * e[a] * e[b] + phi(r) / r * ((a == b ? 1.0 : 0.0) - e[a] * e[b]);
                        f[a] += H * dq[b];
                    }
                result.forces[i] += f;
                result.forces[j] -= f;
                result.virial += f.dot(d);
                for (int a = 0; a < 3; a++)
                    for (int b = 0; b < 3; b++) {
                        result.virialTensor.element[a][b] += f[a] * d[b];
                        result.particleVirial[i].element[a][b] += 0.5 * f[a] * d[b];
                        result.particleVirial[j].element[a][b] += 0.5 * f[a] * d[b];
                    }
            }
    if (model.periodic && model.backgroundPressure != 0.0) {
        const double boxVolume = model.box[0][0] * model.box[1][1] * model.box[2][2];
        result.energy += model.backgroundPressure * boxVolume;
        result.virial -= 3.0 * model.backgroundPressure * boxVolume;
        for (int a = 0; a < 3; a++) {
            result.virialTensor.element[a][a] -= model.backgroundPressure * boxVolume;
            for (int i = 0; i < n; i++)
                result.particleVirial[i].element[a][a] -= model.backgroundPressure * boxVolume / n;
        }
    }
    return result;
}

} // namespace BruteForce

#endif /*GENDPDE_TEST_BRUTE_FORCE_H_*/
