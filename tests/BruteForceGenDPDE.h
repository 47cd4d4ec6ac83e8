#ifndef GENDPDE_TEST_BRUTE_FORCE_H_
#define GENDPDE_TEST_BRUTE_FORCE_H_

/* An independent O(N^2) evaluation of the GenDPDE conservative force for the tests. It shares no code with the
 * plugin: every pair and every periodic image within the cutoff is visited explicitly (no minimum-image formula,
 * no neighbor list), V-B volumes come from adaptive Simpson quadrature of the defining integral (not the closed
 * forms or the Gauss rule of GenDPDEPhysics.h), and the formulas of docs/theory.md are written out again here. */

#include "openmm/Vec3.h"
#include <algorithm>
#include <cmath>
#include <functional>
#include <vector>

namespace BruteForce {

/** Tait parameters n0, pi0, B_T, gamma_T. */
struct Tait {
    double n0, pi0, bulkModulus, gammaT;
};

struct Model {
    double cutoff;
    bool useVB;
    bool useVC = false;   // V-B times the one-sidedness factor of docs/interfaces.md (useVB must be true too)
    double cutoffScaling;
    double n0, pi0, bulkModulus, gammaT;
    std::vector<Tait> particleTait;   // per particle, for mixtures; empty: every particle has n0, pi0, B_T, gamma_T
    bool periodic;
    OpenMM::Vec3 box[3];
};

struct Result {
    double energy = 0.0, virial = 0.0;
    std::vector<OpenMM::Vec3> forces;
    std::vector<double> primitiveDensity, volume, pressure;
};

inline double simpson(const std::function<double(double)>& f, double a, double b, double fa, double fm, double fb,
                      double whole, double tolerance, int depth) {
    double m = 0.5*(a + b), lm = 0.5*(a + m), rm = 0.5*(m + b);
    double flm = f(lm), frm = f(rm);
    double left = (m - a)/6.0*(fa + 4.0*flm + fm), right = (b - m)/6.0*(fm + 4.0*frm + fb);
    if (depth <= 0 || std::abs(left + right - whole) <= 15.0*tolerance)
        return left + right + (left + right - whole)/15.0;
    return simpson(f, a, m, fa, flm, fm, left, 0.5*tolerance, depth - 1)
         + simpson(f, m, b, fm, frm, fb, right, 0.5*tolerance, depth - 1);
}

/** int_a^b f by adaptive Simpson to an absolute tolerance. */
inline double integrate(const std::function<double(double)>& f, double a, double b, double tolerance) {
    double fa = f(a), fb = f(b), fm = f(0.5*(a + b));
    return simpson(f, a, b, fa, fm, fb, (b - a)/6.0*(fa + 4.0*fm + fb), tolerance, 60);
}

/** Every displacement r_i - r_j + image with |.| < cutoff (images up to two box vectors away). */
inline std::vector<OpenMM::Vec3> displacementsInRange(const Model& model, OpenMM::Vec3 d) {
    std::vector<OpenMM::Vec3> result;
    int range = model.periodic ? 2 : 0;
    for (int a = -range; a <= range; a++)
        for (int b = -range; b <= range; b++)
            for (int c = -range; c <= range; c++) {
                OpenMM::Vec3 image = d + model.box[0]*a + model.box[1]*b + model.box[2]*c;
                if (std::sqrt(image.dot(image)) < model.cutoff)
                    result.push_back(image);
            }
    return result;
}

/** Positions must lie within one box of the origin's cell when periodic (the tests generate them so). */
inline Result evaluate(const Model& model, const std::vector<OpenMM::Vec3>& positions) {
    const int n = positions.size();
    const double R = model.cutoff, pi = 3.14159265358979323846;
    auto w = [&](double r) { return 15.0/(2.0*pi*R*R*R)*(1.0 - r/R)*(1.0 - r/R); };
    auto dw = [&](double r) { return -15.0/(pi*R*R*R*R)*(1.0 - r/R); };
    Result result;
    result.forces.assign(n, OpenMM::Vec3());
    result.primitiveDensity.assign(n, 0.0);
    result.volume.assign(n, 0.0);
    result.pressure.assign(n, 0.0);
    for (int i = 0; i < n; i++)
        for (int j = 0; j < n; j++)
            if (i != j)
                for (const OpenMM::Vec3& d : displacementsInRange(model, positions[i] - positions[j]))
                    result.primitiveDensity[i] += w(std::sqrt(d.dot(d)));
    // V-C: the first moments g_i = sum over neighbours and images of (r/R)(1 - r/R)^2 d/r.
    std::vector<OpenMM::Vec3> moment(n);
    if (model.useVC)
        for (int i = 0; i < n; i++)
            for (int j = 0; j < n; j++)
                if (i != j)
                    for (const OpenMM::Vec3& d : displacementsInRange(model, positions[i] - positions[j])) {
                        const double r = std::sqrt(d.dot(d));
                        if (r > 0.0)
                            moment[i] += d*((r/R)*(1 - r/R)*(1 - r/R)/r);
                    }
    std::vector<double> coefficient(n, 0.0);
    for (int i = 0; i < n; i++) {
        double n0i = result.primitiveDensity[i], V, dV;
        if (model.useVB) {
            double Rt = R/model.cutoffScaling, k = 2.0*pi/15.0*Rt*Rt*Rt*n0i;
            // Relative tolerance 1e-14 from the asymptotes I ~ 1/(3 + 30k) and J ~ 1/(30k^2 + 4 sqrt(k)/pi).
            double toleranceI = 1e-14/(3.0 + 30.0*k), toleranceJ = 1e-14/(30.0*k*k + 4.0*std::sqrt(k)/pi);
            // k = 0 (no neighbor): the integrand is (1-y)^2, whose integral is 1/3.
            double I = k == 0.0 ? 1.0/3.0
                     : integrate([&](double y) { return y*y*(1 - y)*(1 - y)/(y*y + k); }, 0.0, 1.0, toleranceI);
            V = 4.0*pi*Rt*Rt*Rt*I;
            if (k > 0.0) {
                // The integrand of J peaks near y = sqrt(k); split there so that the quadrature sees the peak.
                auto g = [&](double y) { return y*y*(1 - y)*(1 - y)/((y*y + k)*(y*y + k)); };
                double split = std::min(0.5, std::sqrt(k));
                double J = integrate(g, 0.0, split, 0.5*toleranceJ) + integrate(g, split, 1.0, 0.5*toleranceJ);
                dV = -8.0*pi*pi/15.0*std::pow(Rt, 6)*J;
            }
            else
                dV = 0.0;   // no neighbor, no pair to use it
        }
        else {
            V = 1.0/n0i;
            dV = -1.0/(n0i*n0i);
        }
        if (model.useVC) {
            // V = V_B (1 + 3 x^2/(1 + x^2)), x = max(0, a^2 - 0.4)/0.3, a^2 = c^2 |g|^2/(n0^2 + eps^2),
            // c = 30/(pi R^3), eps = 3/(4 pi R^3).
            const double c = 30.0/(pi*R*R*R), eps = 3.0/(4.0*pi*R*R*R);
            const double a2 = c*c*moment[i].dot(moment[i])/(n0i*n0i + eps*eps);
            const double x = std::max(0.0, a2 - 0.4)/0.3;
            V *= 1.0 + 3.0*x*x/(1.0 + x*x);
            dV = 0.0;   // the forces of V-C are checked by finite differences, not here
        }
        double density = 1.0/V;
        const Tait t = model.particleTait.empty() ? Tait{model.n0, model.pi0, model.bulkModulus, model.gammaT}
                                                  : model.particleTait[i];
        double pressure = t.pi0 + t.bulkModulus*(std::pow(density/t.n0, t.gammaT) - 1.0);
        result.energy += (t.bulkModulus - t.pi0)/density
                       + t.bulkModulus/((t.gammaT - 1.0)*t.n0)*std::pow(density/t.n0, t.gammaT - 1.0);
        result.volume[i] = V;
        result.pressure[i] = pressure;
        coefficient[i] = pressure*dV;
    }
    for (int i = 0; i < n; i++)
        for (int j = i + 1; j < n; j++)
            for (const OpenMM::Vec3& d : displacementsInRange(model, positions[i] - positions[j])) {
                double r = std::sqrt(d.dot(d));
                if (r == 0.0)
                    continue;
                OpenMM::Vec3 f = d*((coefficient[i] + coefficient[j])*dw(r)/r);
                result.forces[i] += f;
                result.forces[j] -= f;
                result.virial += f.dot(d);
            }
    return result;
}

} // namespace BruteForce

#endif /*GENDPDE_TEST_BRUTE_FORCE_H_*/
