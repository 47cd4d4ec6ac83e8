/* Tests of GenDPDEIntegrator shared by every platform: a platform file defines `platform`, calls
 * runIntegratorTests(). The statistical tests (equilibrium identities, relaxation rate, order of the energy error)
 * are in python/tests/test_integrator_physics.py. */

#include "GenDPDEIntegrator.h"
#include "TestScenes.h"
#include "TestUtilities.h"
#include "internal/GenDPDEPhysics.h"
#include "OpenMM.h"
#include <cmath>
#include <functional>
#include <memory>
#include <random>
#include <sstream>
#include <string>
#include <vector>

using namespace GenDPDEPlugin;
using namespace OpenMM;

extern Platform* platform;

namespace IntegratorTests {

using namespace TestScenes;

// Liquid argon (internal/LiquidArgon.h) at R* = 1.6839 in OpenMM units.
const double boltzmann = Physics::Boltzmann;                                           // kJ/(mol K)
const double energyUnit = LiquidArgon::energy*6.02214076e23/1000.0;                    // u (kJ/mol)
const double timeUnit = lengthUnit*std::sqrt(particleMass/energyUnit);                 // L sqrt(m/u) (ps)
const double temperatureUnit = energyUnit/boltzmann;                                   // u/k_B (K)
const LiquidArgonCutoff argonCutoff = LiquidArgon::getCutoff(1);                       // R* = 1.6839
const double friction = argonCutoff.friction*particleMass/timeUnit;                    // gamma (amu/ps)
const double heatConduction = argonCutoff.heatConduction*energyUnit*temperatureUnit/timeUnit;   // kJ K/(mol ps)
const double heatCapacity = LiquidArgon::heatCapacity*boltzmann;                       // C_V (kJ/(mol K))
const double temperature = LiquidArgon::temperature*temperatureUnit;                   // T0 (K)
const double stepSize = 0.01*timeUnit;                                                 // dt* = 0.01 (ps)

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

void assertStatesIdentical(Context& a, Context& b, GenDPDEIntegrator& ia, GenDPDEIntegrator& ib, const std::string& what) {
    State sa = a.getState(State::Positions | State::Velocities), sb = b.getState(State::Positions | State::Velocities);
    for (size_t i = 0; i < sa.getPositions().size(); i++) {
        if (!(sa.getPositions()[i] == sb.getPositions()[i]) || !(sa.getVelocities()[i] == sb.getVelocities()[i]))
            throw std::runtime_error(what + ": particle " + std::to_string(i) + " differs");
    }
    if (ia.getInternalEnergies() != ib.getInternalEnergies())
        throw std::runtime_error(what + ": internal energies differ");
}

/** One pair update conserves momentum and K + eps_i + eps_j to rounding error, for any masses and velocities. */
void testPairUpdateConservation() {
    std::mt19937 random(5);
    std::uniform_real_distribution<double> uniform(-1.0, 1.0);
    for (int trial = 0; trial < 1000; trial++) {
        double mi = 1.0 + 300.0*(uniform(random) + 1), mj = 1.0 + 300.0*(uniform(random) + 1);
        Vec3 vi(uniform(random), uniform(random), uniform(random)), vj(uniform(random), uniform(random), uniform(random));
        Vec3 e(uniform(random), uniform(random), uniform(random));
        e /= std::sqrt(e.dot(e));
        Vec3 momentum = vi*mi + vj*mj;
        double kinetic = 0.5*mi*vi.dot(vi) + 0.5*mj*vj.dot(vj);
        double change = Physics::dissipativePairUpdate(e, 0.3 + 0.5*(uniform(random) + 1), 2000.0,
                                                       std::sqrt(4000.0*(1.0 + uniform(random))), 0.01, 0.1, 1/mi,
                                                       1/mj, vi, vj, 3*uniform(random));
        double kineticAfter = 0.5*mi*vi.dot(vi) + 0.5*mj*vj.dot(vj);
        assertVectorClose(momentum, vi*mi + vj*mj, 1e-13*(std::sqrt(momentum.dot(momentum)) + mi + mj), "pair momentum");
        assertClose(kineticAfter - kinetic, change, 1e-13*kinetic, "pair kinetic energy change");
    }
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
            Vec3 p = state.getVelocities()[i]*run.scene.system.getParticleMass(i);
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
    const double roundingWalk = 3*std::sqrt((double) steps*numParticles)*std::pow(2.0, -24)
                                *std::sqrt(squaredForce/numParticles)*stepSize;
    run.integrator.step(steps);
    auto after = momentumAndScale();
    assertVectorClose(before.first, after.first,
                      precisionTolerance(1e-10*before.second, std::max(1e-10*before.second, roundingWalk)),
                      "total momentum over 10^4 steps");

    // No conservative force: K + sum eps is conserved by every step to rounding error.
    System free;
    for (int i = 0; i < run.scene.system.getNumParticles(); i++)
        free.addParticle(particleMass);
    free.setDefaultPeriodicBoxVectors(run.scene.box[0], run.scene.box[1], run.scene.box[2]);
    GenDPDEIntegrator integrator(stepSize, friction, heatConduction, heatCapacity);
    integrator.setTemperature(temperature);
    integrator.setCutoffDistance(cutoff);
    Context freeContext(free, integrator, *platform);
    freeContext.setPositions(run.scene.positions);
    freeContext.setVelocitiesToTemperature(3*temperature, 7);
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
        far[i] += Vec3(0.3*(i % 5), -0.2*(i % 3), 0.5);
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

    b.integrator.setRandomNumberSeed(0);      // the checkpoint carries the seed in use
    b.integrator.setTemperature(3*temperature);
    b.start();
    b.context->loadCheckpoint(checkpoint);
    b.integrator.step(150);
    assertStatesIdentical(*a.context, *b.context, a.integrator, b.integrator, "continued from a checkpoint");

    c.integrator.setTemperature(2*temperature);
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
    }
    catch (const OpenMMException& e) {
        message = e.what();
    }
    ASSERT(message.find("step 3") != std::string::npos && message.find("not applied") != std::string::npos);
    const std::string prefix = "internal energy of particle ";
    size_t at = message.find(prefix);
    ASSERT(at != std::string::npos);
    int named = std::stoi(message.substr(at + prefix.size()));
    Vec3 d = before.getPositions()[named] - before.getPositions()[17];
    for (int k = 0; k < 3; k++)
        d[k] -= run.scene.box[k][k]*std::round(d[k]/run.scene.box[k][k]);
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
        temperatures[i] = temperature*(1 + 0.01*i);
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
    const double capacity = 1000*boltzmann;
    GenDPDEIntegrator integrator(stepSize, 0.0, capacity*150.0*150.0/0.15, capacity);
    integrator.setCutoffDistance(cutoff);
    integrator.setRandomNumberSeed(31);
    std::vector<double> temperatures;
    double half = 0.5*scene.box[0][0];
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
        return hot/numHot - cold/numCold;
    };
    assertClose(100.0, halfDifference(), 1e-9, "initial difference");
    integrator.step(2000);
    double difference = 0;
    for (int sample = 0; sample < 20; sample++) {
        integrator.step(50);
        difference += halfDifference()/20;
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
    assertThrowsMentioning([&]() { unset.setParticleTemperatures({300, 300}); }, {"number of particle temperatures", "64"});
    System noForce;
    noForce.addParticle(1.0);
    noForce.addParticle(1.0);
    GenDPDEIntegrator noCutoff(stepSize, friction, heatConduction, heatCapacity);
    noCutoff.setTemperature(300);
    Context context2(noForce, noCutoff, *platform);
    context2.setPositions({Vec3(), Vec3(0.1, 0, 0)});
    assertThrowsMentioning([&]() { noCutoff.step(1); }, {"cutoff", "setCutoffDistance"});
}

/**
 * The integrator's side of TestScenes::setMixtureTypes: the same types 7, -3, 0 in turn; type 7 with 3 C_V, type -3
 * with C_V/2, type 0 the integrator's; pairs (7, -3) with 2 gamma and kappa/2, (7, 7) with gamma/2 and 3 kappa,
 * (-3, 0) with no friction and 2 kappa, the others the integrator's. With sameAsDefaults, every entry repeats the
 * integrator's own values.
 */
inline void setMixtureTypes(GenDPDEIntegrator& integrator, int numParticles, bool sameAsDefaults) {
    for (int i = 0; i < numParticles; i++)
        if (i % 3 != 2)
            integrator.setParticleType(i, i % 3 == 0 ? 7 : -3);
    const double c = integrator.getHeatCapacity(), g = integrator.getFriction(), k = integrator.getHeatConduction();
    integrator.addTypeHeatCapacity(7, sameAsDefaults ? c : 3*c);
    integrator.addTypeHeatCapacity(-3, sameAsDefaults ? c : 0.5*c);
    integrator.addTypePair(7, -3, sameAsDefaults ? g : 2*g, sameAsDefaults ? k : 0.5*k);
    integrator.addTypePair(7, 7, sameAsDefaults ? g : 0.5*g, sameAsDefaults ? k : 3*k);
    integrator.addTypePair(-3, 0, sameAsDefaults ? g : 0.0, sameAsDefaults ? k : 2*k);
}

/**
 * Types whose parameters all equal the defaults give bit-identical trajectories to no types, in every mode (the
 * types select table entries and change no arithmetic); with their own parameters the trajectory differs.
 */
void testIdenticalTypesAreBitwiseNoTypes() {
    for (GenDPDEIntegrator::Mode mode : {GenDPDEIntegrator::Isoenergetic, GenDPDEIntegrator::Isothermal}) {
        Run plain(4, 11), typed(4, 11), different(4, 11);
        for (Run* run : {&typed, &different}) {
            setMixtureTypes(run->scene, run == &typed);
            setMixtureTypes(run->integrator, run->scene.system.getNumParticles(), run == &typed);
        }
        for (Run* run : {&plain, &typed, &different}) {
            run->integrator.setMode(mode);
            run->start();
            run->integrator.step(100);
        }
        assertStatesIdentical(*plain.context, *typed.context, plain.integrator, typed.integrator,
                              "types with the default parameters");
        State a = plain.context->getState(State::Velocities), b = different.context->getState(State::Velocities);
        ASSERT(!(a.getVelocities()[0] == b.getVelocities()[0]));
    }
}

/**
 * A mixture (three types with different C_V, friction and conduction) conserves K + sum eps without conservative
 * forces to rounding error, as a single fluid does (each pair update is exact whatever the pair's parameters), and
 * the total momentum with them. Temperatures set per particle become eps_i = C_V(type) theta_i.
 */
void testMixtureConservation() {
    Run run(4, 12);
    setMixtureTypes(run.scene, false);
    const int n = run.scene.system.getNumParticles();
    setMixtureTypes(run.integrator, n, false);
    std::vector<double> temperatures(n);
    for (int i = 0; i < n; i++)
        temperatures[i] = temperature*(0.8 + 0.4*((i*37) % n)/n);
    run.integrator.setParticleTemperatures(temperatures);
    Context& context = run.start();
    const std::vector<double> energies = run.integrator.getInternalEnergies();
    for (int i : {0, 1, 2, 30, 31, 32}) {
        const double capacity = heatCapacity*(i % 3 == 0 ? 3.0 : i % 3 == 1 ? 0.5 : 1.0);
        assertRelative(capacity*temperatures[i], energies[i], 1e-15, "eps_i = C_V(type) theta_i");
    }
    Vec3 before;
    for (int i = 0; i < n; i++)
        before += context.getState(State::Velocities).getVelocities()[i]*particleMass;
    run.integrator.step(1000);
    Vec3 after;
    State state = context.getState(State::Velocities);
    double scale = 0;
    for (int i = 0; i < n; i++) {
        after += state.getVelocities()[i]*particleMass;
        scale += particleMass*std::sqrt(state.getVelocities()[i].dot(state.getVelocities()[i]));
    }
    assertVectorClose(before, after, precisionTolerance(1e-10, 1e-6)*scale, "mixture: total momentum");

    System free;
    for (int i = 0; i < n; i++)
        free.addParticle(particleMass);
    GenDPDEIntegrator integrator(stepSize, friction, heatConduction, heatCapacity);
    integrator.setCutoffDistance(cutoff);
    setMixtureTypes(integrator, n, false);
    integrator.setParticleTemperatures(temperatures);
    Context freeContext(free, integrator, *platform);
    freeContext.setPositions(run.scene.positions);
    freeContext.setVelocitiesToTemperature(3*temperature, 7);
    const double initial = integrator.getConservedEnergy();
    integrator.step(1000);
    assertRelative(initial, integrator.getConservedEnergy(), 1e-12, "mixture: K + sum eps without forces");
}

/**
 * Heat flow between two materials against the flux the model prescribes. Material A (type 1, C_V = 4000 k_B, 300 K)
 * fills x < 0 and material B (type 2, C_V = 1000 k_B, 75 K) x > 0, particles at rest on a lattice with no force and
 * no friction, so only conduction acts. Pairs (1, 2) have kappa_AB, pairs (1, 1) 3 kappa_AB, pairs (2, 2) the
 * integrator's kappa_AB/4. The heat A gains in a step is, from A-B pairs alone (A-A pairs move heat within A),
 *   dE_A = sum_{i in A, j in B} [kappa_AB omega_R^2 (1/theta_i - 1/theta_j) dt + alpha omega_R sqrt(dt) xi_ij],
 * with theta_i = eps_i/C_V(type i) and alpha^2 = 2 k_B kappa_AB. Over 400 steps the measured loss of A is compared
 * with the sum of the drift terms evaluated from the temperatures at the start of each step, within 4 sigma of the
 * noise (sigma^2 = sum over steps and A-B pairs of alpha^2 omega_R^2 dt; sigma is 3.5% of the flux here: on
 * Reference, expected -1386 kJ/mol, measured -1353, sigma 49). The temperatures
 * change by < 1e-3 per step, so evaluating the drift at the start of the step rather than when each pair is reached
 * biases the sum by < 1e-3 of itself. Using C_V of one type for both particles (theta_B 4 times too high), or the
 * default kappa for A-B pairs, changes the flux by a factor of about 4: far outside the tolerance.
 */
void testTwoMaterialConduction() {
    const int side = 6;
    const double spacing = std::cbrt(1.0/referenceDensity);
    System system;
    std::vector<Vec3> positions;
    std::vector<int> material;
    for (int x = 0; x < side; x++)
        for (int y = 0; y < side; y++)
            for (int z = 0; z < side; z++) {
                system.addParticle(particleMass);
                positions.push_back(Vec3((x - side/2 + 0.5)*spacing, y*spacing, z*spacing));
                material.push_back(x < side/2 ? 1 : 2);
            }
    const int n = positions.size();
    const double kappa = 40.0/stepSize;   // kappa dt = 40 kJ K/mol
    const double capacityA = 4000*boltzmann, capacityB = 1000*boltzmann;
    GenDPDEIntegrator integrator(stepSize, 0.0, 0.25*kappa, capacityB);
    integrator.setCutoffDistance(cutoff);
    integrator.setRandomNumberSeed(41);
    std::vector<double> initialTemperatures;
    for (int i = 0; i < n; i++) {
        integrator.setParticleType(i, material[i]);
        initialTemperatures.push_back(material[i] == 1 ? 300.0 : 75.0);
    }
    integrator.addTypeHeatCapacity(1, capacityA);
    integrator.addTypePair(1, 2, 0.0, kappa);
    integrator.addTypePair(1, 1, 0.0, 3*kappa);
    integrator.setParticleTemperatures(initialTemperatures);
    Context context(system, integrator, *platform);
    context.setPositions(positions);
    // The A-B pairs and their omega_R^2, written out here.
    std::vector<std::pair<int, int>> pairs;
    std::vector<double> omega2;
    for (int i = 0; i < n; i++)
        for (int j = 0; j < n; j++)
            if (material[i] == 1 && material[j] == 2) {
                const Vec3 d = positions[i] - positions[j];
                const double r = std::sqrt(d.dot(d));
                if (r < cutoff) {
                    pairs.emplace_back(i, j);
                    omega2.push_back((1 - r/cutoff)*(1 - r/cutoff));
                }
            }
    auto energyOfA = [&]() {
        const std::vector<double> e = integrator.getInternalEnergies();
        double sum = 0;
        for (int i = 0; i < n; i++)
            sum += material[i] == 1 ? e[i] : 0.0;
        return sum;
    };
    const double initialA = energyOfA(), initialTotal = totalInternalEnergy(integrator);
    double expected = 0, variance = 0;
    for (int step = 0; step < 400; step++) {
        const std::vector<double> e = integrator.getInternalEnergies();
        for (size_t p = 0; p < pairs.size(); p++) {
            const int i = pairs[p].first, j = pairs[p].second;
            expected += kappa*omega2[p]*(capacityA/e[i] - capacityB/e[j])*stepSize;
            variance += 2*boltzmann*kappa*omega2[p]*stepSize;
        }
        integrator.step(1);
    }
    const double measured = energyOfA() - initialA;
    ASSERT(expected < -20*std::sqrt(variance));   // the test is sensitive: the flux is far above the noise
    assertClose(expected, measured, 4*std::sqrt(variance), "heat gained by material A over 400 steps");
    assertRelative(initialTotal, totalInternalEnergy(integrator), 1e-13, "sum eps of the two materials");
}

/** The type setters refuse bad values, duplicates and unknown types, naming the entry, the parameter and value. */
void testTypesBadInput() {
    GenDPDEIntegrator integrator(0.001, 1, 1, 1);
    integrator.addTypePair(1, 2, 5.0, 6.0);
    integrator.addTypeHeatCapacity(2, 3.0);
    assertThrowsMentioning([&]() { integrator.addTypePair(2, 1, 5.0, 6.0); }, {"types 2, 1", "already", "entry 0"});
    assertThrowsMentioning([&]() { integrator.addTypePair(1, 3, -5.0, 6.0); }, {"type pair 1", "friction", "-5"});
    assertThrowsMentioning([&]() { integrator.addTypePair(1, 3, 5.0, NAN); }, {"heat conduction", "nan"});
    assertThrowsMentioning([&]() { integrator.addTypeHeatCapacity(4, 0.0); }, {"type 4", "heat capacity", "= 0"});
    assertThrowsMentioning([&]() { integrator.addTypeHeatCapacity(2, 1.0); }, {"type 2", "already"});
    assertThrowsMentioning([&]() { integrator.setTypePairParameters(3, 1, 2, 1, 1); }, {"type pair index", "3"});
    assertThrowsMentioning([&]() { integrator.setParticleType(-4, 1); }, {"particle index", "-4"});
    ASSERT_EQUAL(1, integrator.getNumTypePairs());
    ASSERT_EQUAL(1, integrator.getNumTypeHeatCapacities());
    // At Context creation: a pair naming a type that no particle has, and a particle beyond the System.
    Run run(4, 13);
    for (int i = 0; i < 10; i++)
        run.integrator.setParticleType(i, 1);
    run.integrator.addTypePair(1, 5, 1.0, 1.0);
    assertThrowsMentioning([&]() { run.start(); }, {"type pair 0", "type 5", "no particle", "0, 1"});
    Run far(4, 14);
    far.integrator.setParticleType(64, 1);
    assertThrowsMentioning([&]() { far.start(); }, {"particle 64", "64 particles"});
    // An entry added after the Context was created is checked at the next step.
    Run later(4, 15);
    later.start();
    later.integrator.addTypeHeatCapacity(9, 1.0);
    assertThrowsMentioning([&]() { later.integrator.step(1); }, {"type heat capacity 0", "type 9"});
}

void runIntegratorTests() {
    testBadInput();
    testPairUpdateConservation();
    testConservationLaws();
    testReproducibility();
    testCheckpointContinuation();
    testNonPositiveInternalEnergy();
    testConservativeMode();
    testSwitchedOffFriction();
    testHeatConduction();
    testTypesBadInput();
    testIdenticalTypesAreBitwiseNoTypes();
    testMixtureConservation();
    testTwoMaterialConduction();
}

/** The state a run ends in, for comparing platforms. */
struct Trajectory {
    std::vector<Vec3> positions, velocities;
    std::vector<double> energies;
    double kinetic;
};

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
    integrator.setCutoffDistance(ownPairs ? 0.9*cutoff : 0.0);
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
