/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
#ifndef GENDPDE_TEST_THERMAL_H_
#define GENDPDE_TEST_THERMAL_H_

/* Tests of the equations of state that depend on temperature (docs/theory.md section 11), shared by the platforms
 * that run them (Reference, CPU): runThermalTests(). The laws are written out again here, from the free energy
 * f(theta, n) = e(n) - theta sigma(n) + C theta (1 - ln(theta/theta0)), as the brute-force oracle's particle law:
 *   Tait with thermal expansion: e = f_Tait(n) + beta theta0/n, sigma = beta/n;
 *   van der Waals:               e = -a n,                     sigma = k ln((1 - b n)/(b n)). */

#include "GenDPDEForce.h"
#include "GenDPDEIntegrator.h"
#include "TestScenes.h"
#include "TestUtilities.h"
#include "internal/GenDPDEPhysics.h"
#include "internal/LiquidArgon.h"
#include "OpenMM.h"
#include <algorithm>
#include <cmath>
#include <memory>
#include <random>
#include <sstream>
#include <string>
#include <vector>

using namespace GenDPDEPlugin;
using namespace OpenMM;

extern Platform* platform;

namespace ThermalTests {

using namespace TestScenes;


/**
 * The laws of the tests: type 0 (the force's default law) Tait with the thermal pressure of liquid argon,
 * beta = alpha/kappa_T0 = alpha gamma_T B_T with alpha = 2.64e-3 1/K (the liquid state); type 1 van der Waals
 * with k = C_V/10 and a, b chosen so that pi and dpi/dn match the Tait law's at (n0, T0): a mixture whose two laws
 * push alike, so that its dynamics stays as gentle as the liquid's.
 */
struct Laws {
    double n0, pi0, bulkModulus, gammaT;   // the force's Tait parameters
    double beta, theta0;                   // TaitThermalExpansion
    double a, b, k;                        // VanDerWaals
    Laws() {
        GenDPDEForce force(cutoff);
        force.getTaitParameters(n0, pi0, bulkModulus, gammaT);
        beta = 2.64e-3 * gammaT * bulkModulus;
        theta0 = temperature;
        // pi = k T n y - a n^2 with y = 1/(1 - b n): matching pi0 and dpi/dn = gamma_T B_T/n0 at n0 gives
        // k T (y^2 - 2 y) = (gamma_T B_T - 2 pi0)/n0.
        k = heatCapacity / 10;
        const double kT = k * temperature;
        const double y = 1 + std::sqrt(1 + (gammaT * bulkModulus - 2 * pi0) / (n0 * kT));
        b = (1 - 1 / y) / n0;
        a = (kT * y * n0 - pi0) / (n0 * n0);
        if (!(a > 0 && b > 0 && b * n0 < 1))
            throw std::runtime_error("ThermalTests::Laws: no van der Waals law matches the Tait law");
    }
    /** e(n) and sigma(n) of a law (written out from the free energy, independently of the physics core). */
    void parts(bool vanDerWaals, double n, double& e, double& sigma, double& pressureAtZero,
               double& thermalPressure) const {
        if (vanDerWaals) {
            e = -a * n;
            sigma = k * std::log((1 - b * n) / (b * n));
            pressureAtZero = -a * n * n;
            thermalPressure = k * n / (1 - b * n);
        } else {
            const double x = n / n0;
            e = (bulkModulus - pi0) / n + bulkModulus / ((gammaT - 1) * n0) * std::pow(x, gammaT - 1)
                    + beta * theta0 / n;
            sigma = beta / n;
            pressureAtZero = pi0 + bulkModulus * (std::pow(x, gammaT) - 1) - beta * theta0;
            thermalPressure = beta;
        }
    }
};

/** Every third particle (i % 3 == 2) has type 1, van der Waals; the others the default, Tait with thermal expansion. */
inline bool isVanDerWaals(int i) {
    return i % 3 == 2;
}

inline void setLaws(Scene& scene, const Laws& laws, bool mixture) {
    scene.force->setEquationOfState(GenDPDEForce::TaitThermalExpansion, {laws.beta, laws.theta0});
    if (!mixture)
        return;
    for (int i = 0; i < scene.system.getNumParticles(); i++)
        if (isVanDerWaals(i))
            scene.force->setParticleType(i, 1);
    scene.force->addTypeEquationOfState(1, GenDPDEForce::VanDerWaals, {laws.a, laws.b, laws.k});
}

/** The particles' densities n_i = 1/V_i at these positions, by the oracle (in this box if given, else the System's). */
inline std::vector<double> oracleDensities(const Scene& scene, const std::vector<Vec3>& positions,
                                           const Vec3* box = nullptr) {
    BruteForce::Model model = bruteForceModel(scene);
    if (box != nullptr)
        std::copy(box, box + 3, model.box);
    const BruteForce::Result result = BruteForce::evaluate(model, positions);
    std::vector<double> density;
    for (double v : result.volume)
        density.push_back(1 / v);
    return density;
}

/**
 * A mixture liquid of 64 particles, its integrator (mode, no pair terms unless asked) and Context, with the
 * particles at temperatures scattered by +-10% around T0 so that the thermal pressures differ.
 */
struct Run {
    Laws laws;
    Scene scene;
    GenDPDEIntegrator integrator;
    std::unique_ptr<Context> context;
    Run(GenDPDEIntegrator::Mode mode, double dt = stepSize, bool pairTerms = false, bool mixture = true,
        unsigned seed = 3) :
            scene(makeLatticeLiquid(4, referenceDensity, 0.1, GenDPDEForce::VB, true, seed)),
            integrator(dt, pairTerms ? friction : 0.0, pairTerms ? heatConduction : 0.0, heatCapacity) {
        setLaws(scene, laws, mixture);
        integrator.setMode(mode);
        integrator.setTemperature(temperature);
        integrator.setRandomNumberSeed(77);
        std::vector<double> temperatures;
        std::mt19937 random(seed);
        std::uniform_real_distribution<double> uniform(-0.1, 0.1);
        for (int i = 0; i < scene.system.getNumParticles(); i++)
            temperatures.push_back(temperature * (1 + uniform(random)));
        integrator.setParticleTemperatures(temperatures);
    }
    Context& start() {
        context.reset(new Context(scene.system, integrator, *platform));
        context->setPositions(scene.positions);
        context->setVelocitiesToTemperature(temperature, 99);
        return *context;
    }
    std::vector<Vec3> positions() const { return context->getState(State::Positions).getPositions(); }
};

/** The oracle's U and forces at positions, with each particle's theta given by thetaOf(i, n_i, e, sigma). */
struct OracleLaw {
    const Laws& laws;
    bool isothermal;
    std::vector<double> storedEnergy, storedEntropy; // eps_i and the sigma_i it belongs to (not isothermal)
    void operator()(int i, double n, double& pressure, double& energy) const {
        double e, sigma, pressureAtZero, thermalPressure;
        laws.parts(isVanDerWaals(i), n, e, sigma, pressureAtZero, thermalPressure);
        if (isothermal) {
            pressure = pressureAtZero + temperature * thermalPressure;
            energy = e - temperature * sigma;
            return;
        }
        // s fixed: C theta = eps exp(-(sigma(n) - sigma_i)/C); the particle's term of U is e + C theta - eps.
        const double thermal = thermalEnergy(i, n);
        pressure = pressureAtZero + thermal / heatCapacity * thermalPressure;
        energy = e + thermal - storedEnergy[i];
    }
    /** C theta_i of particle i at density n, its entropy fixed (not isothermal). */
    double thermalEnergy(int i, double n) const {
        double e, sigma, pressureAtZero, thermalPressure;
        laws.parts(isVanDerWaals(i), n, e, sigma, pressureAtZero, thermalPressure);
        return storedEnergy[i] * std::exp(-(sigma - storedEntropy[i]) / heatCapacity);
    }
};

/**
 * The platform's energy, forces and pressures against the oracle, with and without a background pressure (to 1e-9
 * in double precision; with float forces to 2e-6 for U and 1e-5 for the rest, float rounding), and its forces against central differences of the
 * oracle's U, in the Isothermal mode (theta = T, U = sum e - T sigma) and in the Conservative mode one step after the
 * state was read, so that the entropies carry theta_i away from eps_i/C (sigma(n) - sigma_i != 0 in the step's
 * evaluations). Outside step() the platform has kept the thermal energies of the current positions (docs/integrator.md,
 * "The particles' thermal state: one rule"): its eps_i is the oracle's C theta_i there, and its U lacks the work
 * sum_i (C theta_i - eps_i) the compression did, which its internal energies now hold.
 */
void testAgainstOracle() {
    for (bool isothermal : {true, false})
        for (double background : {0.0, 60.0}) { // (the background pressure adds to both laws: the oracle adds it too)
            const std::string mode = std::string(isothermal ? "Isothermal" : "Conservative")
                    + (background != 0 ? ", background pressure" : "");
            Run run(isothermal ? GenDPDEIntegrator::Isothermal : GenDPDEIntegrator::Conservative);
            run.scene.force->setBackgroundPressure(background);
            Context& context = run.start();
            run.integrator.step(2);
            OracleLaw law{run.laws, isothermal, {}, {}};
            if (!isothermal) {
                // eps_i and sigma(n_i) at these positions: the state the next step carries isentropically.
                law.storedEnergy = run.integrator.getInternalEnergies();
                const std::vector<double> density = oracleDensities(run.scene, run.positions());
                for (int i = 0; i < (int) density.size(); i++) {
                    double e, sigma, p0, pt;
                    run.laws.parts(isVanDerWaals(i), density[i], e, sigma, p0, pt);
                    law.storedEntropy.push_back(sigma);
                }
            }
            run.integrator.step(1);
            const std::vector<Vec3> positions = run.positions();
            BruteForce::Model model = bruteForceModel(run.scene);
            model.particleLaw = law;
            const BruteForce::Result expected = BruteForce::evaluate(model, positions);
            double work = 0; // sum_i (C theta_i - eps_i): now in the platform's internal energies, not in its U
            if (!isothermal) {
                const std::vector<double> energies = run.integrator.getInternalEnergies();
                double largestEnergy = 0, largestChange = 0;
                for (double e : law.storedEnergy)
                    largestEnergy = std::max(largestEnergy, e);
                for (int i = 0; i < (int) energies.size(); i++) {
                    const double thermal = law.thermalEnergy(i, 1 / expected.volume[i]);
                    // (float forces: the float densities' rounding enters exp(-sigma(n)/C), sigma/C ~ 2: 1e-5 as above)
                    assertClose(thermal, energies[i], precisionTolerance(1e-12, 1e-5) * largestEnergy,
                                mode + ": eps_i after the step (C theta_i at the positions reached)");
                    work += thermal - law.storedEnergy[i];
                    largestChange = std::max(largestChange, std::fabs(thermal - law.storedEnergy[i]));
                }
                if (!(largestChange > 1e-4 * largestEnergy)) // (else the comparison would not see a stale state)
                    throw std::runtime_error(mode + ": the step compressed the particles too little to test");
            }
            const State state = context.getState(State::Energy | State::Forces);
            // (float forces, the GPU platforms' single and mixed precision: rounding of float densities and pressures)
            assertRelative(expected.energy - work, state.getPotentialEnergy(), precisionTolerance(1e-9, 2e-6),
                           mode + ": U");
            double largest = 0;
            for (const Vec3& f : expected.forces)
                largest = std::max(largest, std::sqrt(f.dot(f)));
            for (size_t i = 0; i < positions.size(); i++)
                assertVectorClose(expected.forces[i], state.getForces()[i], precisionTolerance(1e-9, 1e-5) * largest,
                                  mode + ": force");
            const std::vector<double> pressures = run.scene.force->getParticlePressures(context);
            double pressureScale = 0; // (relative to the largest: a pressure may be near 0)
            for (double p : expected.pressure)
                pressureScale = std::max(pressureScale, std::fabs(p));
            for (size_t i = 0; i < positions.size(); i++)
                assertClose(expected.pressure[i], pressures[i], precisionTolerance(1e-9, 1e-5) * pressureScale,
                            mode + ": pressure");
            // -dU/dr by central differences of the oracle's U (h = 1e-5 nm: truncation ~h^2 U''' ~1e-8 of the force).
            const double h = 1e-5;
            for (int i : {0, 2, 29, 47})
                for (int c = 0; c < 3; c++) {
                    std::vector<Vec3> plus = positions, minus = positions;
                    plus[i][c] += h;
                    minus[i][c] -= h;
                    const double derivative =
                            (BruteForce::evaluate(model, plus).energy - BruteForce::evaluate(model, minus).energy)
                            / (2 * h);
                    assertClose(-derivative, state.getForces()[i][c], precisionTolerance(1e-6, 1e-5) * largest,
                                mode + ": -dU/dr");
                }
        }
}

/**
 * Conservative mode (velocity Verlet, isentropic particles): K + U + sum eps is conserved to the order of the
 * integrator, dt^2: over the same time, the largest excursion at dt/2 is 1/4 of that at dt (allowed 3-5.3: the
 * excursion's leading term dominates by far at these steps), and every particle's entropy
 * s_i = sigma(n_i) + C ln(theta_i) is unchanged to rounding (1e-9 C: ~100 exact isentropic updates of 1e-16).
 */
void testConservation() {
    if (floatForces())
        return; // float forces: rounding, not the step, sets the excursion (the double precision runs it)
    double excursion[2];
    for (int halving = 0; halving < 2; halving++) {
        const double dt = stepSize / (1 << halving);
        Run run(GenDPDEIntegrator::Conservative, dt);
        run.start();
        auto entropies = [&]() {
            const std::vector<double> theta = run.integrator.getParticleTemperatures();
            const std::vector<double> density = oracleDensities(run.scene, run.positions());
            std::vector<double> s;
            for (size_t i = 0; i < theta.size(); i++) {
                double e, sigma, p0, pt;
                run.laws.parts(isVanDerWaals(i), density[i], e, sigma, p0, pt);
                s.push_back(sigma + heatCapacity * std::log(theta[i]));
            }
            return s;
        };
        const std::vector<double> s0 = entropies();
        const double h0 = run.integrator.getConservedEnergy();
        double largest = 0;
        for (int block = 0; block < 20; block++) {
            run.integrator.step(5 << halving);
            largest = std::max(largest, std::fabs(run.integrator.getConservedEnergy() - h0));
        }
        excursion[halving] = largest;
        const std::vector<double> s1 = entropies();
        for (size_t i = 0; i < s0.size(); i++)
            assertClose(s0[i], s1[i], 1e-9 * heatCapacity, "the entropy of particle " + std::to_string(i));
    }
    const double ratio = excursion[0] / excursion[1];
    std::ostringstream what;
    what << "energy excursion ratio dt/(dt/2) = " << ratio << " (" << excursion[0] << ", " << excursion[1]
         << " kJ/mol)";
    std::fprintf(stderr, "%s\n", what.str().c_str());
    if (!(ratio > 3 && ratio < 5.3))
        throw std::runtime_error(what.str() + ", expected 4 (second order)");
}

/**
 * The particles heat up where they are compressed: after a Conservative run, theta_i/theta_i(0) of each particle
 * equals exp(-(sigma(n_i) - sigma(n_i(0)))/C) (the isentropic law, checked per particle to 1e-9), and the run did
 * change the temperatures (by more than 1e-4 somewhere).
 */
void testCompressionHeats() {
    Run run(GenDPDEIntegrator::Conservative);
    run.start();
    const std::vector<double> theta0 = run.integrator.getParticleTemperatures();
    const std::vector<double> n0 = oracleDensities(run.scene, run.positions());
    run.integrator.step(50);
    const std::vector<double> theta1 = run.integrator.getParticleTemperatures();
    const std::vector<double> n1 = oracleDensities(run.scene, run.positions());
    double largestChange = 0;
    for (size_t i = 0; i < theta0.size(); i++) {
        double e, sigma0, sigma1, p0, pt;
        run.laws.parts(isVanDerWaals(i), n0[i], e, sigma0, p0, pt);
        run.laws.parts(isVanDerWaals(i), n1[i], e, sigma1, p0, pt);
        assertRelative(std::exp(-(sigma1 - sigma0) / heatCapacity), theta1[i] / theta0[i],
                       precisionTolerance(1e-9, 1e-5), "isentropic temperature of particle " + std::to_string(i));
        largestChange = std::max(largestChange, std::fabs(theta1[i] / theta0[i] - 1));
    }
    ASSERT(largestChange > 1e-4);
}

void assertSameState(Run& a, Run& b, const std::string& what) {
    const State sa = a.context->getState(State::Positions | State::Velocities);
    const State sb = b.context->getState(State::Positions | State::Velocities);
    for (size_t i = 0; i < sa.getPositions().size(); i++)
        if (!(sa.getPositions()[i] == sb.getPositions()[i]) || !(sa.getVelocities()[i] == sb.getVelocities()[i]))
            throw std::runtime_error(what + ": particle " + std::to_string(i) + " differs");
    if (a.integrator.getInternalEnergies() != b.integrator.getInternalEnergies())
        throw std::runtime_error(what + ": internal energies differ");
}

/**
 * The state of a Context: a run continued from a checkpoint or a State reproduces the uninterrupted run bit for
 * bit (full GenDPDE, the mixture); reading the temperatures or saving mid-run changes nothing; setPositions() keeps
 * each particle's temperature exactly (it sets a state, it does not compress the particles).
 */
void testStateHandling() {
    Run a(GenDPDEIntegrator::Isoenergetic, stepSize, true), b(GenDPDEIntegrator::Isoenergetic, stepSize, true),
            c(GenDPDEIntegrator::Isoenergetic, stepSize, true), d(GenDPDEIntegrator::Isoenergetic, stepSize, true);
    a.start();
    a.integrator.step(30);
    std::stringstream checkpoint;
    a.context->createCheckpoint(checkpoint);
    const State state = a.context->getState(State::Positions | State::Velocities | State::IntegratorParameters);
    a.integrator.step(30);
    b.start();
    b.context->loadCheckpoint(checkpoint);
    b.integrator.step(30);
    assertSameState(a, b, "continued from a checkpoint");
    c.start();
    c.context->setState(state);
    c.integrator.step(30);
    assertSameState(a, c, "continued from a State");
    // d: the same run as a, never interrupted.
    d.start();
    d.integrator.step(60);
    assertSameState(a, d, "an uninterrupted run");

    const std::vector<double> before = a.integrator.getParticleTemperatures();
    std::vector<Vec3> squeezed = a.positions();
    for (Vec3& r : squeezed)
        r *= 0.999;
    a.context->setPositions(squeezed);
    ASSERT(a.integrator.getParticleTemperatures() == before);

    // With adiabatic position changes, the same move keeps each particle's entropy instead: theta_i/theta_i(before)
    // = exp(-(sigma(n_i') - sigma(n_i))/C) with the oracle's densities before and after (to 1e-9).
    d.integrator.setAdiabaticPositionChanges(true);
    const std::vector<double> thetaBefore = d.integrator.getParticleTemperatures();
    const std::vector<double> densityBefore = oracleDensities(d.scene, d.positions());
    std::vector<Vec3> moved = d.positions();
    for (Vec3& r : moved)
        r *= 0.995;
    d.context->setPositions(moved);
    const std::vector<double> thetaAfter = d.integrator.getParticleTemperatures();
    const std::vector<double> densityAfter = oracleDensities(d.scene, moved);
    double largest = 0;
    for (size_t i = 0; i < thetaAfter.size(); i++) {
        double e, sigma0, sigma1, p0, pt;
        d.laws.parts(isVanDerWaals(i), densityBefore[i], e, sigma0, p0, pt);
        d.laws.parts(isVanDerWaals(i), densityAfter[i], e, sigma1, p0, pt);
        assertRelative(std::exp(-(sigma1 - sigma0) / heatCapacity), thetaAfter[i] / thetaBefore[i],
                       precisionTolerance(1e-9, 1e-5), "adiabatic move, particle " + std::to_string(i));
        largest = std::max(largest, std::fabs(thetaAfter[i] / thetaBefore[i] - 1));
    }
    ASSERT(largest > 1e-4);
}

/** Bad input and bad states: refused with the parameter, the value, the particle and the step named. */
void testErrors() {
    Laws laws;
    GenDPDEForce force(cutoff);
    assertThrowsMentioning([&]() { force.setEquationOfState(GenDPDEForce::VanDerWaals, {1.0, 0.1}); },
                           {"VanDerWaals", "takes 3 parameters", "not 2"});
    assertThrowsMentioning([&]() { force.setEquationOfState(GenDPDEForce::VanDerWaals, {1.0, 0.0, 1.0}); },
                           {"excluded volume b", "= 0"});
    assertThrowsMentioning([&]() { force.setEquationOfState(GenDPDEForce::TaitThermalExpansion, {1.0, -5.0}); },
                           {"reference temperature theta0", "-5"});
    assertThrowsMentioning([&]() { force.setEquationOfState((GenDPDEForce::EquationOfState) 7, {}); },
                           {"equation of state = 7"});
    force.addTypeEquationOfState(2, GenDPDEForce::Tait, {});
    assertThrowsMentioning([&]() { force.addTypeEquationOfState(2, GenDPDEForce::Tait, {}); },
                           {"type 2 already has an equation of state"});
    GenDPDEForce::EquationOfState law;
    std::vector<double> parameters;
    force.getEquationOfState(law, parameters);
    ASSERT(law == GenDPDEForce::Tait && parameters.empty()); // the refused calls changed nothing

    // A temperature-dependent law needs a GenDPDEIntegrator, and temperatures.
    {
        Scene scene = makeLatticeLiquid(4, referenceDensity, 0.1, GenDPDEForce::VB, true, 1);
        setLaws(scene, laws, true);
        VerletIntegrator verlet(stepSize);
        assertThrowsMentioning([&]() { Context context(scene.system, verlet, *platform); },
                               {"GenDPDEIntegrator", "TaitThermalExpansion", "depends on temperature"});
        GenDPDEIntegrator unset(stepSize, 0.0, 0.0, heatCapacity);
        unset.setMode(GenDPDEIntegrator::Conservative);
        Context context(scene.system, unset, *platform);
        context.setPositions(scene.positions);
        assertThrowsMentioning([&]() { context.getState(State::Energy); }, {"temperatures", "setParticleTemperatures"});
        // Whether the force depends on temperature is fixed with the Context.
        scene.force->setEquationOfState(GenDPDEForce::Tait, {});
        scene.force->setTypeEquationOfState(0, 1, GenDPDEForce::Tait, {});
        assertThrowsMentioning([&]() { scene.force->updateParametersInContext(context); },
                               {"cannot change whether an equation of state depends on temperature"});
    }
    // Outside the integration force groups, the integrator could not follow the temperatures.
    {
        Run run(GenDPDEIntegrator::Conservative);
        run.scene.force->setForceGroup(3);
        run.integrator.setIntegrationForceGroups(1 << 0);
        assertThrowsMentioning([&]() { run.start(); }, {"force group 3", "integration force groups"});
    }
    // A van der Waals particle packed beyond its excluded volume stops the evaluation, naming it and the step.
    {
        Run run(GenDPDEIntegrator::Conservative);
        run.scene.force->setTypeEquationOfState(0, 1, GenDPDEForce::VanDerWaals, {laws.a, 0.5, laws.k});
        assertThrowsMentioning([&]() { run.start().getState(State::Forces); },
                               {"particle 2 has the density", "at step 0", "outside the domain", "van der Waals"});
    }
}

/**
 * Laws that do not depend on temperature keep today's bits: a force whose default law is Tait and whose type-1
 * entry is Tait gives the same energy and forces, bit for bit, as the same force without entries.
 */
void testTaitUnchanged() {
    Scene plain = makeLatticeLiquid(4, referenceDensity, 0.1, GenDPDEForce::VB, true, 5);
    Scene entries = makeLatticeLiquid(4, referenceDensity, 0.1, GenDPDEForce::VB, true, 5);
    entries.force->addTypeEquationOfState(0, GenDPDEForce::Tait, {});
    VerletIntegrator i1(stepSize), i2(stepSize);
    Context c1(plain.system, i1, *platform), c2(entries.system, i2, *platform);
    c1.setPositions(plain.positions);
    c2.setPositions(entries.positions);
    const State s1 = c1.getState(State::Energy | State::Forces), s2 = c2.getState(State::Energy | State::Forces);
    ASSERT(s1.getPotentialEnergy() == s2.getPotentialEnergy());
    for (size_t i = 0; i < s1.getForces().size(); i++)
        ASSERT(s1.getForces()[i] == s2.getForces()[i]);
}

/**
 * On the CPU platform: the same run as Reference, bit for bit (full GenDPDE, the mixture). (The GPU platforms are
 * compared with the oracle by testAgainstOracle.)
 */
void testEqualsReference() {
    if (platform->getName() != "CPU")
        return;
    Platform* own = platform;
    Run here(GenDPDEIntegrator::Isoenergetic, stepSize, true);
    here.start();
    here.integrator.step(40);
    platform = &Platform::getPlatformByName("Reference");
    Run reference(GenDPDEIntegrator::Isoenergetic, stepSize, true);
    reference.start();
    reference.integrator.step(40);
    platform = own;
    assertSameState(here, reference, platform->getName() + " against Reference");
}

/**
 * A Tait type in a force whose other type's law depends on temperature: its particles' internal energies are left
 * exactly as they are by Conservative steps (no sweep), while the thermal particles' change with their densities.
 */
void testTaitParticlesInAThermalForce() {
    Run run(GenDPDEIntegrator::Conservative);
    run.scene.force->setTypeEquationOfState(0, 1, GenDPDEForce::Tait, {});
    run.start();
    const std::vector<double> before = run.integrator.getInternalEnergies();
    run.integrator.step(20);
    const std::vector<double> after = run.integrator.getInternalEnergies();
    double thermalChange = 0;
    for (size_t i = 0; i < before.size(); i++) {
        if (isVanDerWaals(i)) { // (type 1, Tait here)
            ASSERT(after[i] == before[i]);
        } else
            thermalChange = std::max(thermalChange, std::fabs(after[i] / before[i] - 1));
    }
    ASSERT(thermalChange > 1e-5);
}

void runThermalTests() {
    testTaitParticlesInAThermalForce();
    testErrors();
    testTaitUnchanged();
    testAgainstOracle();
    testCompressionHeats();
    testConservation();
    testStateHandling();
    testEqualsReference();
}

} // namespace ThermalTests

#endif /*GENDPDE_TEST_THERMAL_H_*/
