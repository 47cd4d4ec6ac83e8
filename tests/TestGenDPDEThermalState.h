/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
#ifndef GENDPDE_TEST_THERMAL_STATE_H_
#define GENDPDE_TEST_THERMAL_STATE_H_

/* The rule of the particles' thermal state with laws that depend on temperature (docs/integrator.md, "The particles'
 * thermal state: one rule"), shared by every platform: runThermalStateTests(). What each call keeps (a parameter
 * update and a move keep every theta_i; an adiabatic move keeps every entropy, fixed where the temperatures were set;
 * a refused checkpoint changes nothing of the integrator's), checked against the oracle's isentropic law
 * theta'/theta = exp(-(sigma(n') - sigma(n))/C) with its own densities, and reading the state changes no later bit. */

#include "TestGenDPDEThermal.h"
#include "openmm/MonteCarloBarostat.h"
#include "openmm/serialization/XmlSerializer.h"
#include <cstring>
#include <functional>

namespace ThermalTests {

/**
 * theta_i(after)/theta_i(before) of an isentropic change of every particle from positions `from` to `to` (in the
 * boxes given, else the System's), by the oracle.
 */
inline std::vector<double> isentropicRatios(const Run& run, const std::vector<Vec3>& from, const std::vector<Vec3>& to,
                                            const Vec3* fromBox = nullptr, const Vec3* toBox = nullptr) {
    const std::vector<double> n0 = oracleDensities(run.scene, from, fromBox);
    const std::vector<double> n1 = oracleDensities(run.scene, to, toBox);
    std::vector<double> ratio;
    for (size_t i = 0; i < n0.size(); i++) {
        double e, sigma0, sigma1, p0, pt;
        run.laws.parts(isVanDerWaals(i), n0[i], e, sigma0, p0, pt);
        run.laws.parts(isVanDerWaals(i), n1[i], e, sigma1, p0, pt);
        ratio.push_back(std::exp(-(sigma1 - sigma0) / heatCapacity));
    }
    return ratio;
}

/**
 * Every theta_i(after)/theta_i(before) equals ratio_i (to 1e-9; float forces 1e-5), and some differ from 1 by more than
 * 1e-4.
 */
inline void assertTemperatureRatios(const std::vector<double>& before, const std::vector<double>& after,
                                    const std::vector<double>& ratio, const std::string& what) {
    double largest = 0;
    for (size_t i = 0; i < before.size(); i++) {
        assertRelative(ratio[i], after[i] / before[i], precisionTolerance(1e-9, 1e-5),
                       what + ": particle " + std::to_string(i));
        largest = std::max(largest, std::fabs(ratio[i] - 1));
    }
    if (!(largest > 1e-4))
        throw std::runtime_error(what + ": the move changed the densities too little to test");
}

inline std::vector<Vec3> scaled(const std::vector<Vec3>& positions, double factor) {
    std::vector<Vec3> result = positions;
    for (Vec3& r : result)
        r *= factor;
    return result;
}

inline void assertSameTemperatures(const std::vector<double>& expected, const std::vector<double>& found,
                                   const std::string& what) {
    for (size_t i = 0; i < expected.size(); i++)
        if (!(expected[i] == found[i]))
            throw std::runtime_error(what + ": the temperature of particle " + std::to_string(i) + " changed from "
                                     + std::to_string(expected[i]) + " to " + std::to_string(found[i]) + " K");
}

/**
 * updateParametersInContext() changes the law, not the particles: every theta_i is kept exactly, whatever changes
 * (beta, a van der Waals parameter, the Tait parameters, f_cut, the estimator), with adiabatic position changes or
 * without, as Context.reinitialize(preserveState=True) keeps them. A step then runs.
 */
void testParameterUpdatesKeepTemperatures() {
    const std::vector<std::pair<std::string, std::function<void(GenDPDEForce&, const Laws&)>>> changes = {
            {"beta x2",
             [](GenDPDEForce& f, const Laws& l) {
                 f.setEquationOfState(GenDPDEForce::TaitThermalExpansion, {2 * l.beta, l.theta0});
             }},
            {"van der Waals a",
             [](GenDPDEForce& f, const Laws& l) {
                 f.setTypeEquationOfState(0, 1, GenDPDEForce::VanDerWaals, {1.1 * l.a, l.b, l.k});
             }},
            {"Tait parameters",
             [](GenDPDEForce& f, const Laws& l) {
                 f.setTaitParameters(l.n0, 0.9 * l.pi0, 1.2 * l.bulkModulus, l.gammaT);
             }},
            {"f_cut", [](GenDPDEForce& f, const Laws& l) { f.setCutoffScaling(1.1); }},
            {"estimator", [](GenDPDEForce& f, const Laws& l) { f.setDensityEstimator(GenDPDEForce::VA); }}};
    for (bool adiabatic : {false, true})
        for (const auto& change : changes) {
            const std::string what = "updateParametersInContext (" + change.first + (adiabatic ? ", adiabatic)" : ")");
            Run run(GenDPDEIntegrator::Isoenergetic, stepSize, true);
            run.start();
            run.integrator.step(6);
            run.integrator.setAdiabaticPositionChanges(adiabatic);
            const std::vector<double> before = run.integrator.getParticleTemperatures();
            change.second(*run.scene.force, run.laws);
            run.scene.force->updateParametersInContext(*run.context);
            assertSameTemperatures(before, run.integrator.getParticleTemperatures(), what);
            run.context->reinitialize(true);
            assertSameTemperatures(before, run.integrator.getParticleTemperatures(), what + ", reinitialized");
            run.integrator.step(2);
        }
}

/**
 * The temperatures set are those of the positions where they are set, and an adiabatic move then keeps each
 * particle's entropy: after setParticleTemperatures() before the Context (the first positions set), after
 * setInternalEnergies(), and after loadCheckpoint(), a move by setPositions() (the positions scaled by 0.99 in the
 * same box: a compression, and a gap at the box's faces) changes every particle's temperature as the oracle's
 * isentropic law says. Nothing is read between setting the temperatures and the move (the temperatures
 * before are those set), so that a getter cannot be what fixes the entropies (see testReadingChangesNothing).
 */
void testAdiabaticMovesAfterSettingTemperatures() {
    for (const std::string how : {"set before the Context", "setInternalEnergies", "loadCheckpoint"}) {
        Run run(GenDPDEIntegrator::Conservative);
        run.integrator.setAdiabaticPositionChanges(true);
        std::vector<double> before = run.integrator.getParticleTemperatures();   // (those set: no Context yet)
        Context& context = run.start();
        if (how != "set before the Context") {
            run.integrator.step(4);
            const std::vector<double> energies = run.integrator.getInternalEnergies();
            std::stringstream checkpoint;
            context.createCheckpoint(checkpoint);
            run.integrator.step(3);
            if (how == "loadCheckpoint")
                context.loadCheckpoint(checkpoint);
            else
                run.integrator.setInternalEnergies(energies);
            for (size_t i = 0; i < energies.size(); i++)
                before[i] = energies[i] / heatCapacity;
        }
        const std::vector<Vec3> from = run.positions(), to = scaled(from, 0.99);
        context.setPositions(to);
        assertTemperatureRatios(before, run.integrator.getParticleTemperatures(), isentropicRatios(run, from, to),
                                "adiabatic move after the temperatures were " + how);
    }
}

/**
 * Reading changes nothing: the same sequence of steps, adiabatic and plain moves, parameter updates, a checkpoint
 * loaded and temperatures set gives the same bits whether or not every getter (the integrator's, the force's
 * observables, States with every kind of data, the conserved energy, checkpoints) is called between the calls.
 */
void testReadingChangesNothing() {
    auto script = [](Run& run, bool read) {
        Context& context = *run.context;
        auto readEverything = [&]() {
            if (!read)
                return;
            run.integrator.getInternalEnergies();
            run.integrator.getParticleTemperatures();
            run.integrator.getConservedEnergy();
            context.getState(State::Positions | State::Velocities | State::Forces | State::Energy | State::Parameters
                             | State::IntegratorParameters);
            context.getState(State::Energy, false, 1 << 5);   // another force group
            run.scene.force->getParticleDensities(context);
            run.scene.force->getParticlePressures(context);
            run.scene.force->getParticleVirials(context);
            run.scene.force->getVirial(context);
            std::stringstream discarded;
            context.createCheckpoint(discarded);
        };
        run.integrator.step(5);
        readEverything();
        std::stringstream checkpoint;
        context.createCheckpoint(checkpoint);
        run.integrator.step(1);
        readEverything();
        run.integrator.step(3);
        run.integrator.setAdiabaticPositionChanges(true);
        readEverything();
        context.setPositions(scaled(run.positions(), 0.998));   // adiabatic
        readEverything();
        context.setPositions(scaled(run.positions(), 0.999));   // adiabatic again, before any step
        readEverything();
        run.integrator.step(4);
        readEverything();
        context.loadCheckpoint(checkpoint);
        readEverything();
        context.setPositions(scaled(run.positions(), 0.997));   // adiabatic, from the loaded state
        readEverything();
        run.integrator.step(2);
        run.scene.force->setEquationOfState(GenDPDEForce::TaitThermalExpansion, {1.3 * run.laws.beta, run.laws.theta0});
        run.scene.force->updateParametersInContext(context);
        readEverything();
        context.setPositions(scaled(run.positions(), 1.002));   // adiabatic, under the new law
        readEverything();
        run.integrator.setAdiabaticPositionChanges(false);
        run.integrator.step(3);
        readEverything();
        context.setPositions(scaled(run.positions(), 1.001));   // keeps the temperatures
        readEverything();
        run.integrator.setInternalEnergies(run.integrator.getInternalEnergies());
        readEverything();
        run.integrator.step(3);
    };
    Run plain(GenDPDEIntegrator::Isoenergetic, stepSize, true);
    Run reading(GenDPDEIntegrator::Isoenergetic, stepSize, true);
    plain.start();
    reading.start();
    script(plain, false);
    script(reading, true);
    assertSameState(plain, reading, "the same calls with and without every getter between them");
}

/**
 * However a run is split into step() calls, and whatever is read between them, it is the same run bit for bit
 * (step() reuses the forces of the previous call's last evaluation when nothing changed since).
 */
void testSplitRunsAreTheSameRun() {
    Run whole(GenDPDEIntegrator::Isoenergetic, stepSize, true), split(GenDPDEIntegrator::Isoenergetic, stepSize, true),
            read(GenDPDEIntegrator::Isoenergetic, stepSize, true);
    whole.start();
    split.start();
    read.start();
    whole.integrator.step(24);
    for (int i = 0; i < 24; i++)
        split.integrator.step(1);
    for (int i = 0; i < 8; i++) {
        read.integrator.step(3);
        read.context->getState(State::Energy | State::Forces);
        read.integrator.getConservedEnergy();
    }
    assertSameState(whole, split, "24 steps in 24 calls");
    assertSameState(whole, read, "24 steps in 8 calls, with energies and forces read between them");
}

/**
 * A barostat's accepted moves follow the rule: each particle keeps its temperature, or with adiabatic position
 * changes its entropy. The particles have no mass, so that the integrator moves none of them and the barostat's
 * moves are the only change (Conservative mode, a MonteCarloBarostat at every step).
 */
void testBarostatMovesFollowTheRule() {
    for (bool adiabatic : {false, true}) {
        Run run(GenDPDEIntegrator::Conservative);
        for (int i = 0; i < run.scene.system.getNumParticles(); i++)
            run.scene.system.setParticleMass(i, 0.0);
        // ~780 bar is the Tait liquid's pressure at n0 (pi0): moves both ways are accepted.
        MonteCarloBarostat* barostat = new MonteCarloBarostat(780.0, temperature, 1);
        barostat->setRandomNumberSeed(11);
        run.scene.system.addForce(barostat);
        run.integrator.setAdiabaticPositionChanges(adiabatic);
        Context& context = run.start();
        const std::vector<double> before = run.integrator.getParticleTemperatures();
        const std::vector<Vec3> from = run.positions();
        Vec3 fromBox[3], toBox[3];
        context.getState(0).getPeriodicBoxVectors(fromBox[0], fromBox[1], fromBox[2]);
        run.integrator.step(20);
        context.getState(0).getPeriodicBoxVectors(toBox[0], toBox[1], toBox[2]);
        const double changed =
                toBox[0][0] * toBox[1][1] * toBox[2][2] / (fromBox[0][0] * fromBox[1][1] * fromBox[2][2]) - 1;
        if (!(std::fabs(changed) > 1e-4))
            throw std::runtime_error("the barostat moved too little to test: V/V0 - 1 = " + std::to_string(changed));
        const std::vector<double> after = run.integrator.getParticleTemperatures();
        if (adiabatic)
            assertTemperatureRatios(before, after, isentropicRatios(run, from, run.positions(), fromBox, toBox),
                                    "barostat moves with adiabatic position changes");
        else
            assertSameTemperatures(before, after, "barostat moves");
    }
}

/**
 * A refused checkpoint (truncated, or one byte changed) leaves the integrator's state as it was: OpenMM has already
 * restored the checkpoint's positions, and for the particles that is a move, which keeps every temperature (or with
 * adiabatic position changes every entropy).
 */
void testRefusedCheckpointKeepsTheState() {
    for (bool adiabatic : {false, true})
        for (const std::string damage : {"truncated", "one byte changed"}) {
            const std::string what = "a " + damage + " checkpoint refused" + (adiabatic ? " (adiabatic)" : "");
            Run run(GenDPDEIntegrator::Isoenergetic, stepSize, true);
            Context& context = run.start();
            run.integrator.step(10);
            std::stringstream checkpoint;
            context.createCheckpoint(checkpoint);
            std::string bytes = checkpoint.str();
            run.integrator.step(10);
            run.integrator.setAdiabaticPositionChanges(adiabatic);
            const std::vector<double> before = run.integrator.getParticleTemperatures();
            const std::vector<Vec3> from = run.positions();
            if (damage == "truncated")
                bytes.resize(bytes.size() - 10);
            else
                bytes[bytes.size() - 40] ^= 1;   // a bit of an internal energy
            std::stringstream damaged(bytes);
            assertThrowsMentioning([&]() { context.loadCheckpoint(damaged); }, {"GenDPDEIntegrator", "checkpoint"});
            const std::vector<double> after = run.integrator.getParticleTemperatures();
            if (adiabatic)
                assertTemperatureRatios(before, after, isentropicRatios(run, from, run.positions()), what);
            else
                assertSameTemperatures(before, after, what);
        }
}

/** The force's observables follow the particles' state: heating them at the same positions raises the pressures. */
void testObservablesFollowTheState() {
    Run run(GenDPDEIntegrator::Conservative);
    Context& context = run.start();
    run.integrator.step(2);
    const std::vector<double> cold = run.scene.force->getParticlePressures(context);
    std::vector<double> hot = run.integrator.getParticleTemperatures();
    for (double& t : hot)
        t *= 2;
    run.integrator.setParticleTemperatures(hot);
    const std::vector<double> pressures = run.scene.force->getParticlePressures(context);
    const std::vector<double> density = oracleDensities(run.scene, run.positions());
    double scale = 0;   // (relative to the largest: a pressure may be near 0)
    for (double p : cold)
        scale = std::max(scale, std::fabs(p));
    for (size_t i = 0; i < cold.size(); i++) {
        double e, sigma, pressureAtZero, thermalPressure;
        run.laws.parts(isVanDerWaals(i), density[i], e, sigma, pressureAtZero, thermalPressure);
        // pi = pi_0(n) + theta pi_theta(n): doubling theta adds theta pi_theta.
        assertClose(cold[i] + 0.5 * hot[i] * thermalPressure, pressures[i], precisionTolerance(1e-9, 1e-5) * scale,
                    "pressure of particle " + std::to_string(i) + " after heating it");
    }
}

/**
 * A particle whose temperature a step's motion changes by more than a factor 2 stops the run at once, naming it (the
 * lowest index of those, by the oracle's densities before and after the step) and the step, and the internal
 * energies stay those the integrator kept before (the failed evaluation keeps nothing). A heat capacity 1/1000 of the
 * liquid's makes every compression change the temperatures ~1000 times as much (the log of the factor is
 * (sigma(n') - sigma(n))/C), so that one ordinary step does it; on the GPU platforms the second step's evaluation,
 * inside the run, finds it.
 */
void testTemperatureJumpStopsTheRun() {
    Run run(GenDPDEIntegrator::Conservative);
    run.integrator.setHeatCapacity(heatCapacity / 1000);
    std::vector<double> temperatures = run.integrator.getParticleTemperatures();
    run.integrator.setParticleTemperatures(temperatures);   // (the same temperatures with the new C_V)
    Context& context = run.start();
    const std::vector<double> before = run.integrator.getInternalEnergies();
    const std::vector<Vec3> from = run.positions();
    assertThrowsMentioning([&]() { run.integrator.step(2); },
                           {"GenDPDEForce: the temperature of particle", "more than a factor 2", "at step 1"});
    ASSERT_EQUAL(1, (int) context.getStepCount());
    if (run.integrator.getInternalEnergies() != before)
        throw std::runtime_error("the failed evaluation changed the internal energies");
    // The particle named: the first whose isentropic factor over the step exceeds 2 (the oracle's densities).
    const std::vector<double> n0 = oracleDensities(run.scene, from), n1 = oracleDensities(run.scene, run.positions());
    int first = -1;
    for (size_t i = 0; i < n0.size() && first < 0; i++) {
        double e, sigma0, sigma1, p0, pt;
        run.laws.parts(isVanDerWaals(i), n0[i], e, sigma0, p0, pt);
        run.laws.parts(isVanDerWaals(i), n1[i], e, sigma1, p0, pt);
        if (std::fabs(sigma1 - sigma0) > std::log(2.0) * heatCapacity / 1000)
            first = i;
    }
    ASSERT(first >= 0);
    assertThrowsMentioning([&]() { run.integrator.step(1); },
                           {"temperature of particle " + std::to_string(first) + " went from"});
}

void runThermalStateTests() {
    testParameterUpdatesKeepTemperatures();
    testAdiabaticMovesAfterSettingTemperatures();
    testReadingChangesNothing();
    testSplitRunsAreTheSameRun();
    testBarostatMovesFollowTheRule();
    testRefusedCheckpointKeepsTheState();
    testObservablesFollowTheState();
    testTemperatureJumpStopsTheRun();
}

} // namespace ThermalTests

#endif /*GENDPDE_TEST_THERMAL_STATE_H_*/
