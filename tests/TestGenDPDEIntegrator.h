/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
/* Tests of GenDPDEIntegrator shared by every platform: a platform file defines `platform`, calls
 * runIntegratorTests(). Particle types are tested in TestGenDPDEIntegratorTypes.h. The statistical tests (equilibrium
 * identities, relaxation rate, order of the energy error) are in python/tests/test_integrator_physics.py. */

#include "GenDPDEIntegrator.h"
#include "TestScenes.h"
#include "TestUtilities.h"
#include "internal/GenDPDEPhysics.h"
#include "internal/GenDPDETypes.h"
#include "OpenMM.h"
#include <cmath>
#include <functional>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

using namespace GenDPDEPlugin;
using namespace OpenMM;

extern Platform* platform;

namespace IntegratorTests {

using namespace TestScenes;


struct Run {
    Scene scene;
    GenDPDEIntegrator integrator;
    std::unique_ptr<Context> context;
    Run(int cellsPerSide, unsigned seed, double frictionValue = friction, double conduction = heatConduction) :
            scene(makeLatticeLiquid(cellsPerSide, referenceDensity, 0.1, GenDPDEForce::VB, true, seed)),
            integrator(stepSize, frictionValue, conduction, heatCapacity) {
        integrator.setTemperature(temperature);
        integrator.setRandomNumberSeed(1234);
    }
    Context& start() {
        context.reset(new Context(scene.system, integrator, *platform));
        context->setPositions(scene.positions);
        context->setVelocitiesToTemperature(temperature, 99);
        return *context;
    }
};

double totalInternalEnergy(const GenDPDEIntegrator& integrator) {
    double sum = 0;
    for (double e : integrator.getInternalEnergies())
        sum += e;
    return sum;
}

void assertStatesIdentical(Context& a, Context& b, GenDPDEIntegrator& ia, GenDPDEIntegrator& ib,
                           const std::string& what) {
    State sa = a.getState(State::Positions | State::Velocities), sb = b.getState(State::Positions | State::Velocities);
    for (size_t i = 0; i < sa.getPositions().size(); i++) {
        if (!(sa.getPositions()[i] == sb.getPositions()[i]) || !(sa.getVelocities()[i] == sb.getVelocities()[i]))
            throw std::runtime_error(what + ": particle " + std::to_string(i) + " differs");
    }
    if (ia.getInternalEnergies() != ib.getInternalEnergies())
        throw std::runtime_error(what + ": internal energies differ");
}

/**
 * Over 10^4 steps of full GenDPDE the total momentum stays constant to 1e-10 of the momentum scale sum_i m_i |v_i|
 * (each pair update conserves it to rounding error, ~1e-16 per update), and with no conservative force, K + sum eps
 * too: the only energy exchange left is the exact bookkeeping of the pair updates.
 */
void testConservationLaws() {
    Run run(4, 1);
    Context& context = run.start();
    auto momentumAndScale = [&]() {
        State state = context.getState(State::Velocities);
        Vec3 total;
        double scale = 0;
        for (size_t i = 0; i < state.getVelocities().size(); i++) {
            Vec3 p = state.getVelocities()[i] * run.scene.system.getParticleMass(i);
            total += p;
            scale += std::sqrt(p.dot(p));
        }
        return std::make_pair(total, scale);
    };
    auto before = momentumAndScale();
    // With float forces, OpenMM's OpenCL platform rounds each particle's total force to float once per step (its
    // force reduction): a random walk of sqrt(steps N) roundings of 2^-24 of the rms force times dt, allowed 3 times.
    // (The device's own sums are exactly antisymmetric; the CUDA platform keeps them exact.)
    const std::vector<Vec3> forces = context.getState(State::Forces).getForces();
    double squaredForce = 0;
    for (const Vec3& f : forces)
        squaredForce += f.dot(f);
    const int steps = 10000, numParticles = forces.size();
    const double roundingWalk = 3 * std::sqrt((double) steps * numParticles) * std::pow(2.0, -24)
            * std::sqrt(squaredForce / numParticles) * stepSize;
    run.integrator.step(steps);
    auto after = momentumAndScale();
    assertVectorClose(before.first, after.first,
                      precisionTolerance(1e-10 * before.second, std::max(1e-10 * before.second, roundingWalk)),
                      "total momentum over 10^4 steps");

    // No conservative force: K + sum eps is conserved by every step to rounding error.
    System free;
    for (int i = 0; i < run.scene.system.getNumParticles(); i++)
        free.addParticle(particleMass);
    free.setDefaultPeriodicBoxVectors(run.scene.box[0], run.scene.box[1], run.scene.box[2]);
    GenDPDEIntegrator integrator(stepSize, friction, heatConduction, heatCapacity);
    integrator.setTemperature(temperature);
    integrator.setCutoffDistance(cutoff);
    integrator.setRandomNumberSeed(5); // fixed: with a seed drawn per run, 1 run in ~80 met an eps <= 0
    Context freeContext(free, integrator, *platform);
    freeContext.setPositions(run.scene.positions);
    freeContext.setVelocitiesToTemperature(3 * temperature, 7);
    double initial = integrator.getConservedEnergy();
    integrator.step(1000);
    assertRelative(initial, integrator.getConservedEnergy(), 1e-12, "K + sum eps without conservative forces");
}

/**
 * Same seed, same trajectory (bitwise); another seed, another trajectory. The trajectory does not depend on when
 * the neighbor lists were built: run b is interrupted by an evaluation at far-away positions (forcing the lists to
 * be rebuilt at other steps than in run a) and still follows run a bit for bit, because the pairs are visited in
 * canonical order with displacements and random numbers that are pure functions of the configuration.
 */
void testReproducibility() {
    Run a(4, 2), b(4, 2), c(4, 2);
    c.integrator.setRandomNumberSeed(4321);
    for (Run* run : {&a, &b, &c})
        run->start();
    a.integrator.step(200);
    b.integrator.step(77);
    State middle = b.context->getState(State::Positions);
    std::vector<Vec3> far = middle.getPositions();
    for (size_t i = 0; i < far.size(); i++)
        far[i] += Vec3(0.3 * (i % 5), -0.2 * (i % 3), 0.5);
    b.context->setPositions(far);
    b.context->getState(State::Energy);
    b.context->setPositions(middle.getPositions());
    b.integrator.step(123);
    c.integrator.step(200);
    assertStatesIdentical(*a.context, *b.context, a.integrator, b.integrator, "same seed, lists rebuilt differently");
    State sa = a.context->getState(State::Positions), sc = c.context->getState(State::Positions);
    ASSERT(!(sa.getPositions()[0] == sc.getPositions()[0]));
}

/** A checkpoint taken mid-run, loaded into a new Context, continues exactly like the uninterrupted run; so does a
 *  State with the integrator parameters. */
void testCheckpointContinuation() {
    Run a(4, 3), b(4, 3), c(4, 3);
    a.start();
    a.integrator.step(100);
    std::stringstream checkpoint;
    a.context->createCheckpoint(checkpoint);
    State state = a.context->getState(State::Positions | State::Velocities | State::IntegratorParameters);
    a.integrator.step(150);

    b.integrator.setRandomNumberSeed(0); // the checkpoint carries the seed in use
    b.integrator.setTemperature(3 * temperature);
    b.start();
    b.context->loadCheckpoint(checkpoint);
    b.integrator.step(150);
    assertStatesIdentical(*a.context, *b.context, a.integrator, b.integrator, "continued from a checkpoint");

    c.integrator.setTemperature(2 * temperature);
    c.start();
    c.context->setState(state);
    c.integrator.step(150);
    assertStatesIdentical(*a.context, *c.context, a.integrator, c.integrator, "continued from a State");
}

/**
 * An internal energy that would become <= 0 stops the run naming the particle and the step, leaving the Context as
 * it was before that step. Particle 17 is nearly at 0 K: conduction (proportional to 1/theta) draws so much heat
 * from its first neighbor in pair order that the neighbor's eps turns negative; that neighbor is named.
 */
void testNonPositiveInternalEnergy() {
    Run run(4, 4);
    Context& context = run.start();
    run.integrator.step(3);
    std::vector<double> temperatures(run.scene.system.getNumParticles(), temperature);
    temperatures[17] = 1e-9;
    run.integrator.setParticleTemperatures(temperatures);
    State before = context.getState(State::Positions | State::Velocities);
    std::vector<double> energiesBefore = run.integrator.getInternalEnergies();
    std::string message;
    try {
        run.integrator.step(1);
    } catch (const OpenMMException& e) {
        message = e.what();
    }
    ASSERT(message.find("step 3") != std::string::npos && message.find("not applied") != std::string::npos);
    const std::string prefix = "internal energy of particle ";
    size_t at = message.find(prefix);
    ASSERT(at != std::string::npos);
    int named = std::stoi(message.substr(at + prefix.size()));
    Vec3 d = before.getPositions()[named] - before.getPositions()[17];
    for (int k = 0; k < 3; k++)
        d[k] -= run.scene.box[k][k] * std::round(d[k] / run.scene.box[k][k]);
    ASSERT(named == 17 || std::sqrt(d.dot(d)) < cutoff);
    State after = context.getState(State::Positions | State::Velocities);
    for (size_t i = 0; i < before.getPositions().size(); i++) {
        ASSERT(before.getPositions()[i] == after.getPositions()[i]);
        ASSERT(before.getVelocities()[i] == after.getVelocities()[i]);
    }
    ASSERT(energiesBefore == run.integrator.getInternalEnergies());
    ASSERT_EQUAL(3, context.getStepCount());
}

/** Conservative mode is velocity Verlet: it follows OpenMM's VerletIntegrator (to rounding error over 100 steps);
 *  Isoenergetic with gamma = kappa = 0 is the same dynamics, bitwise. */
void testConservativeMode() {
    Run run(4, 5);
    run.integrator.setMode(GenDPDEIntegrator::Conservative);
    run.start();
    Run none(4, 5, 0.0, 0.0);
    none.start();
    VerletIntegrator verlet(stepSize);
    Context reference(run.scene.system, verlet, *platform);
    reference.setPositions(run.scene.positions);
    reference.setVelocities(run.context->getState(State::Velocities).getVelocities());
    run.integrator.step(100);
    none.integrator.step(100);
    verlet.step(100);
    assertStatesIdentical(*run.context, *none.context, run.integrator, none.integrator, "gamma = kappa = 0");
    State a = run.context->getState(State::Positions), b = reference.getState(State::Positions);
    for (size_t i = 0; i < a.getPositions().size(); i++)
        assertVectorClose(b.getPositions()[i], a.getPositions()[i], 1e-9, "Conservative mode vs VerletIntegrator");
    // No heat moves without conduction or friction, even between particles at different temperatures.
    std::vector<double> temperatures(run.scene.system.getNumParticles());
    for (size_t i = 0; i < temperatures.size(); i++)
        temperatures[i] = temperature * (1 + 0.01 * i);
    none.integrator.setParticleTemperatures(temperatures);
    std::vector<double> initial = none.integrator.getInternalEnergies();
    none.integrator.step(50);
    ASSERT(initial == none.integrator.getInternalEnergies());
}

/** With gamma = 0 no random number touches the momenta: velocities do not depend on the seed. */
void testSwitchedOffFriction() {
    Run a(4, 6, 0.0, heatConduction), b(4, 6, 0.0, heatConduction);
    b.integrator.setRandomNumberSeed(999);
    a.start();
    b.start();
    a.integrator.step(50);
    b.integrator.step(50);
    State sa = a.context->getState(State::Velocities), sb = b.context->getState(State::Velocities);
    for (size_t i = 0; i < sa.getVelocities().size(); i++)
        ASSERT(sa.getVelocities()[i] == sb.getVelocities()[i]);
    ASSERT(a.integrator.getInternalEnergies() != b.integrator.getInternalEnergies());
}

/**
 * Heat conduction alone (gamma = 0, no conservative force): two halves of a box started at 100 K and 200 K relax to
 * a common temperature while sum eps stays constant to rounding error.
 * With C_V = 1000 k_B each theta_i fluctuates by sqrt(k_B/C_V) = 3% (4.7 K at 150 K), so the mean of a half (32
 * particles) by 0.84 K and the difference of the halves by 1.2 K. kappa is chosen for a relaxation rate of ~1/ps
 * per pair (kappa ~ C_V theta^2/<omega_q>), so the box relaxes in ~0.2 ps; 20 samples 50 steps apart over the
 * last 1000 of 3000 steps are nearly independent, so their averaged difference has sigma ~0.3 K: tolerance 1.5 K.
 */
void testHeatConduction() {
    Scene scene = makeLatticeLiquid(4, referenceDensity, 0.1, GenDPDEForce::VB, true, 8);
    System free;
    for (int i = 0; i < scene.system.getNumParticles(); i++)
        free.addParticle(particleMass);
    free.setDefaultPeriodicBoxVectors(scene.box[0], scene.box[1], scene.box[2]);
    const double capacity = 1000 * boltzmann;
    GenDPDEIntegrator integrator(stepSize, 0.0, capacity * 150.0 * 150.0 / 0.15, capacity);
    integrator.setCutoffDistance(cutoff);
    integrator.setRandomNumberSeed(31);
    std::vector<double> temperatures;
    double half = 0.5 * scene.box[0][0];
    for (const Vec3& r : scene.positions)
        temperatures.push_back(r[0] < half ? 100.0 : 200.0);
    integrator.setParticleTemperatures(temperatures);
    Context context(free, integrator, *platform);
    context.setPositions(scene.positions);
    double initial = totalInternalEnergy(integrator);
    auto halfDifference = [&]() {
        std::vector<double> theta = integrator.getParticleTemperatures();
        double cold = 0, hot = 0;
        int numCold = 0, numHot = 0;
        for (size_t i = 0; i < theta.size(); i++)
            (scene.positions[i][0] < half ? (numCold++, cold) : (numHot++, hot)) += theta[i];
        return hot / numHot - cold / numCold;
    };
    assertClose(100.0, halfDifference(), 1e-9, "initial difference");
    integrator.step(2000);
    double difference = 0;
    for (int sample = 0; sample < 20; sample++) {
        integrator.step(50);
        difference += halfDifference() / 20;
    }
    assertRelative(initial, totalInternalEnergy(integrator), 1e-13, "sum eps under conduction");
    assertClose(0.0, difference, 1.5, "temperature difference of the two halves");
}

/** Bad input is rejected, naming the parameter and the value, and nothing changes. */
/** Every setter refuses values outside its documented range (docs/integrator.md), naming parameter and value. */
void testBadInput() {
    GenDPDEIntegrator integrator(0.001, 1, 1, 1);
    struct Case {
        std::function<void()> call;
        std::vector<std::string> fragments;
    };
    const std::vector<Case> cases = {
            {[]() { GenDPDEIntegrator(0.0, 1, 1, 1); }, {"step size", "= 0 ps", "(0, 1000] ps"}},
            {[]() { GenDPDEIntegrator(0.001, -1, 1, 1); }, {"friction", "-1", "[0, 1e+12] amu/ps"}},
            {[]() { GenDPDEIntegrator(0.001, 1, -2, 1); }, {"heat conduction", "-2"}},
            {[]() { GenDPDEIntegrator(0.001, 1, 1, 0); }, {"heat capacity", "= 0 kJ/(mol K)", "[1e-20, 1e+20]"}},
            {[]() { GenDPDEIntegrator(0.001, NAN, 1, 1); }, {"friction", "nan"}},
            {[&]() { integrator.setStepSize(-0.1); }, {"step size", "-0.1"}},
            {[&]() { integrator.setStepSize(1e6); }, {"step size", "1000000"}},
            {[&]() { integrator.setFriction(1e300); }, {"friction", "1e+300"}},
            {[&]() { integrator.setHeatConduction(INFINITY); }, {"heat conduction", "inf"}},
            {[&]() { integrator.setHeatCapacity(1e-30); }, {"heat capacity", "1e-30"}},
            {[&]() { integrator.setTemperature(0.0); }, {"temperature", "= 0 K", "[1e-50, 1e+50] K"}},
            {[&]() { integrator.setTemperature(INFINITY); }, {"temperature", "inf"}},
            {[&]() { integrator.setTemperature(1e-200); }, {"temperature", "1e-200"}},
            {[&]() { integrator.setParticleTemperatures({300, -1}); }, {"temperature of particle 1", "-1"}},
            {[&]() { integrator.setParticleTemperatures({300, 1e153}); }, {"temperature of particle 1", "1e+153"}},
            {[&]() { integrator.setParticleTemperatures({}); }, {"number of particle temperatures", "= 0"}},
            {[&]() { integrator.setInternalEnergiesToTemperature(-3, 1); }, {"temperature", "-3"}},
            {[&]() { integrator.setMode((GenDPDEIntegrator::Mode) 3); }, {"mode", "3"}},
            {[&]() { integrator.setCutoffDistance(-1); }, {"cutoff", "-1"}},
            {[&]() { integrator.setCutoffDistance(1e-320); }, {"cutoff", "e-321"}},
    };
    for (const Case& c : cases)
        assertThrowsMentioning(c.call, c.fragments);
    ASSERT_EQUAL(0.001, integrator.getStepSize());
    ASSERT_EQUAL(1.0, integrator.getFriction());
    ASSERT_EQUAL(1.0, integrator.getHeatCapacity());
    ASSERT_EQUAL(0.0, integrator.getTemperature());
    ASSERT_EQUAL(0.0, integrator.getCutoffDistance());

    // Stepping without temperatures in Isoenergetic mode, without a cutoff, with the wrong number of temperatures.
    Run run(4, 9);
    GenDPDEIntegrator unset(stepSize, friction, heatConduction, heatCapacity);
    Context context(run.scene.system, unset, *platform);
    context.setPositions(run.scene.positions);
    assertThrowsMentioning([&]() { unset.step(1); }, {"temperatures are not set"});
    unset.setMode(GenDPDEIntegrator::Isothermal);
    assertThrowsMentioning([&]() { unset.step(1); }, {"Isothermal", "temperature"});
    assertThrowsMentioning([&]() { unset.setParticleTemperatures({300, 300}); },
                           {"number of particle temperatures", "64"});
    System noForce;
    noForce.addParticle(1.0);
    noForce.addParticle(1.0);
    GenDPDEIntegrator noCutoff(stepSize, friction, heatConduction, heatCapacity);
    noCutoff.setTemperature(300);
    Context context2(noForce, noCutoff, *platform);
    context2.setPositions({Vec3(), Vec3(0.1, 0, 0)});
    assertThrowsMentioning([&]() { noCutoff.step(1); }, {"cutoff", "setCutoffDistance"});
}

} // namespace IntegratorTests

#include "TestGenDPDEIntegratorTypes.h"

namespace IntegratorTests {

void runIntegratorTests() {
    testBadInput();
    testConservationLaws();
    testReproducibility();
    testCheckpointContinuation();
    testNonPositiveInternalEnergy();
    testConservativeMode();
    testSwitchedOffFriction();
    testHeatConduction();
    testTypesBadInput();
    testTablesByClass();
    testTypeChangesAfterTheContext();
    testIdenticalTypesAreBitwiseNoTypes();
    testMixtureConservation();
    testTwoMaterialConduction();
    testParticleTypesFromTheForce();
}

/** The state a run ends in, for comparing platforms. */
struct Trajectory {
    std::vector<Vec3> positions, velocities;
    std::vector<double> energies;
    double kinetic;
};

/**
 * Two runs end in the same state: positions within positionTolerance (nm), velocities within relativeTolerance of
 * the rms speed, internal energies (and the kinetic energy) within relativeTolerance of their values.
 */
inline void assertTrajectoriesClose(const Trajectory& expected, const Trajectory& found, double positionTolerance,
                                    double relativeTolerance, const std::string& label) {
    double speed2 = 0.0;
    for (const Vec3& v : expected.velocities)
        speed2 += v.dot(v);
    const double speedScale = std::sqrt(speed2 / expected.velocities.size());
    for (size_t i = 0; i < expected.positions.size(); i++) {
        const std::string particle = " of particle " + std::to_string(i);
        assertVectorClose(expected.positions[i], found.positions[i], positionTolerance,
                          label + ": position" + particle);
        assertVectorClose(expected.velocities[i], found.velocities[i], relativeTolerance * speedScale,
                          label + ": velocity" + particle);
        assertRelative(expected.energies[i], found.energies[i], relativeTolerance,
                       label + ": internal energy" + particle);
    }
    assertRelative(expected.kinetic, found.kinetic, relativeTolerance, label + ": kinetic energy");
}

/**
 * A lattice liquid of cellsPerSide^3 particles (V-B, seed 61) after `steps` steps in `mode` (seed 77, velocities and
 * internal energies drawn at T0 with seeds 5 and 6), in the Context that makeContext creates. ownPairs: the pair
 * range is 0.9 R, so the integrator cannot reuse the force's pairs and finds its own. mixture: the particles have
 * the types of setMixtureTypes, on the force and on the integrator.
 */
inline Trajectory runLatticeLiquid(int cellsPerSide, bool periodic, GenDPDEIntegrator::Mode mode, int steps,
                                   bool ownPairs, const std::function<Context*(System&, Integrator&)>& makeContext,
                                   bool mixture = false) {
    Scene scene = makeLatticeLiquid(cellsPerSide, referenceDensity, 0.1, GenDPDEForce::VB, periodic, 61);
    GenDPDEIntegrator integrator(stepSize, friction, heatConduction, heatCapacity);
    if (mixture) {
        setMixtureTypes(scene, false);
        setMixtureTypes(integrator, scene.system.getNumParticles(), false);
    }
    integrator.setCutoffDistance(ownPairs ? 0.9 * cutoff : 0.0);
    integrator.setTemperature(temperature);
    integrator.setRandomNumberSeed(77);
    integrator.setMode(mode);
    std::unique_ptr<Context> context(makeContext(scene.system, integrator));
    context->setPositions(scene.positions);
    context->setVelocitiesToTemperature(temperature, 5);
    integrator.setInternalEnergiesToTemperature(temperature, 6);
    integrator.step(steps);
    const State state = context->getState(State::Positions | State::Velocities | State::Energy);
    return {state.getPositions(), state.getVelocities(), integrator.getInternalEnergies(), state.getKineticEnergy()};
}

} // namespace IntegratorTests
