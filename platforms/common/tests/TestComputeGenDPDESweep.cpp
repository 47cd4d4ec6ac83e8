/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
/* The device's Shardlow sweep (CommonGenDPDEBlockSweep: blocks ordered in local memory, swept level by level, or
 * streamed by one thread beyond the capacities) against the Reference platform's sequential sweep, and a run of steps
 * that stops on the device against Reference's.
 *
 * Sweep: a liquid without conservative forces (a zero CustomNonbondedForce keeps the box periodic), so that only the
 * pair updates and the drift change the state. The device applies the same pair updates in the same sequence with
 * the same variates, so in double precision the results are Reference's to the last bit but for the normal variates
 * of the ziggurat's rare slow path, whose exp and log may differ by an ulp between the device's library and the
 * host's (seen: one velocity of 96,000 components, 1e-15 relative, after 3 steps of 32,000 particles): the tolerance
 * is 1e-13 relative; an update out of sequence, a pair missed or repeated, or a wrong variate gives 1e-3 or more
 * (a pair update changes a velocity by ~1% of the thermal speed). The same run in every layout a device may use
 * (several blocks per work group, odd thread counts, blocks beyond the local-memory or slab capacities, which are
 * streamed, the 8 colours in one launch or in one each), which the GENDPDE_SWEEP_* settings force here
 * (ScopedEnvironment). A colour swept before the colours before it are done breaks the sequence (checked: the
 * launch's wait for earlier colours taken out, this test and TestComputeGenDPDEEqualsReference fail). Each layout
 * runs in a Context of its own, one after another in this process, as a device's memory is reused: a kernel that
 * read memory it had not written would depend on the Context before it (seen on PoCL while this was written).
 *
 * Runs that stop: a failure at any step of a run (an internal energy that would become <= 0, a step that would move
 * a particle too far, an invalid particle found by the force) is found on the device and reported after the run with
 * Reference's message; the Context is left at the failing step, in the state of before it, as on Reference. */

#include "TestGenDPDEIntegrator.h"
#include "TestPlugins.h"
#include <cstdlib>
#include <map>

OpenMM::Platform* platform;

using namespace IntegratorTests;

/** A jittered lattice of side^3 particles at argon's density without conservative forces; periodic or open. */
Scene forceFreeLiquid(int side, bool periodic, unsigned seed) {
    Scene scene = makeLatticeLiquid(side, referenceDensity, 0.25, GenDPDEForce::VB, periodic, seed);
    scene.system.removeForce(0);
    if (periodic) {
        CustomNonbondedForce* zero = new CustomNonbondedForce("0");
        zero->setNonbondedMethod(CustomNonbondedForce::CutoffPeriodic);
        zero->setCutoffDistance(0.5 * cutoff);
        for (int i = 0; i < scene.system.getNumParticles(); i++)
            zero->addParticle();
        scene.system.addForce(zero);
    }
    return scene;
}

Trajectory runSweeps(Scene& scene, GenDPDEIntegrator::Mode mode, int steps, const std::string& precision,
                     bool mixture = false) {
    GenDPDEIntegrator integrator(stepSize, friction, heatConduction, heatCapacity);
    integrator.setCutoffDistance(cutoff);
    integrator.setTemperature(temperature);
    integrator.setRandomNumberSeed(91);
    integrator.setMode(mode);
    if (mixture)
        setMixtureTypes(integrator, scene.system.getNumParticles(), false);
    Context context(scene.system, integrator, precision.empty() ? Platform::getPlatformByName("Reference") : *platform,
                    precision.empty() ? std::map<std::string, std::string>()
                                      : std::map<std::string, std::string>{{"Precision", precision}});
    context.setPositions(scene.positions);
    context.setVelocitiesToTemperature(temperature, 92);
    integrator.setInternalEnergiesToTemperature(temperature, 93);
    integrator.step(steps);
    const State state = context.getState(State::Positions | State::Velocities | State::Energy);
    return {state.getPositions(), state.getVelocities(), integrator.getInternalEnergies(), state.getKineticEnergy()};
}

void compare(const Trajectory& expected, const Trajectory& found, const std::string& label) {
    assertTrajectoriesClose(expected, found, 1e-13, 1e-13, label);
}

/** 8,000 particles: 8 cells of R along each direction, 64 blocks, 8 per colour. */
void testSweepIsTheHostSequence() {
    Scene scene = forceFreeLiquid(20, true, 81);
    const Trajectory expected = runSweeps(scene, GenDPDEIntegrator::Isoenergetic, 3, "");
    const std::vector<std::vector<std::pair<std::string, std::string>>> layouts = {
            {},
            {{"GENDPDE_SWEEP_BLOCKS_PER_GROUP", "3"}, {"GENDPDE_SWEEP_BLOCK_THREADS", "5"}},
            {{"GENDPDE_SWEEP_MAX_PARTICLES", "160"}},    // about half the regions are streamed
            {{"GENDPDE_SWEEP_PAIR_CAPACITY", "400"}},    // about half the blocks are streamed
            {{"GENDPDE_SWEEP_BLOCKS_PER_GROUP", "2"},
             {"GENDPDE_SWEEP_BLOCK_THREADS", "2"},
             {"GENDPDE_SWEEP_PAIR_CAPACITY", "420"}},
            {{"GENDPDE_SWEEP_LAUNCH_PER_STAGE", "1"}},  // a launch per colour (and per step of the cells)
            {{"GENDPDE_SWEEP_LAUNCH_PER_STAGE", "1"}, {"GENDPDE_SWEEP_PAIR_CAPACITY", "400"}}};
    for (const auto& values : layouts) {
        ScopedEnvironment settings(values);
        compare(expected, runSweeps(scene, GenDPDEIntegrator::Isoenergetic, 3, "double"),
                "Isoenergetic sweep" + settings.label());
    }
    compare(runSweeps(scene, GenDPDEIntegrator::Isothermal, 3, "", true),
            runSweeps(scene, GenDPDEIntegrator::Isothermal, 3, "double", true), "Isothermal sweep, a mixture");
    Scene cluster = forceFreeLiquid(16, false, 82);
    compare(runSweeps(cluster, GenDPDEIntegrator::Isoenergetic, 3, ""),
            runSweeps(cluster, GenDPDEIntegrator::Isoenergetic, 3, "double"), "Isoenergetic sweep, open boundaries");
}

/** The outcome of a run that should stop: the message, and the Context afterwards. */
struct Stop {
    std::string message;
    long long step;
    double time;
    std::vector<Vec3> positions, velocities;
    std::vector<double> energies;
};

Stop stopOf(Context& context, GenDPDEIntegrator& integrator, int steps) {
    Stop stop;
    try {
        integrator.step(steps);
    } catch (const OpenMMException& e) {
        stop.message = e.what();
    }
    const State state = context.getState(State::Positions | State::Velocities);
    stop.step = context.getStepCount();
    stop.time = state.getTime();
    stop.positions = state.getPositions();
    stop.velocities = state.getVelocities();
    stop.energies = integrator.getInternalEnergies();
    return stop;
}

void compareStops(const Stop& expected, const Stop& found, double tolerance, const std::string& label) {
    if (expected.message.empty() || found.message != expected.message)
        throw std::runtime_error(label + ": Reference stopped with '" + expected.message
                                 + "', " GENDPDE_TEST_PLATFORM " with '" + found.message + "'");
    ASSERT_EQUAL(expected.step, found.step);
    ASSERT_EQUAL(expected.time, found.time);
    for (size_t i = 0; i < expected.positions.size(); i++) {
        assertVectorClose(expected.positions[i], found.positions[i], tolerance, label + ": position");
        assertVectorClose(expected.velocities[i], found.velocities[i], tolerance, label + ": velocity");
        assertClose(expected.energies[i], found.energies[i], tolerance * std::abs(expected.energies[i]),
                    label + ": internal energy");
    }
}

/**
 * An internal energy that becomes <= 0 in the sweep of the first step: particles nearly at 0 K in several blocks
 * and colours; the same particle and state as Reference, in the level-by-level and in the streamed sweep, in double
 * (to the sweep's 1e-13) and mixed precision (the same first failure; the state is that of before the step, so equal
 * to rounding of the initial state, 1e-6 relative).
 */
void testSweepFailure() {
    for (const std::string precision : {"double", "mixed"})
        for (const std::vector<std::pair<std::string, std::string>>& values :
             std::vector<std::vector<std::pair<std::string, std::string>>>{{},
                                                                           {{"GENDPDE_SWEEP_PAIR_CAPACITY", "64"}}}) {
            std::vector<Stop> stops;
            for (const std::string& on : {std::string(), precision}) {
                ScopedEnvironment settings(values);
                Scene scene = forceFreeLiquid(20, true, 83);
                GenDPDEIntegrator integrator(stepSize, friction, heatConduction, heatCapacity);
                integrator.setCutoffDistance(cutoff);
                integrator.setRandomNumberSeed(94);
                std::vector<double> temperatures(scene.system.getNumParticles(), temperature);
                for (int i : {7000, 2500, 4321, 6100})
                    temperatures[i] = 1e-9;
                integrator.setParticleTemperatures(temperatures);
                Context context(scene.system, integrator,
                                on.empty() ? Platform::getPlatformByName("Reference") : *platform,
                                on.empty() ? std::map<std::string, std::string>()
                                           : std::map<std::string, std::string>{{"Precision", on}});
                context.setPositions(scene.positions);
                context.setVelocitiesToTemperature(temperature, 95);
                stops.push_back(stopOf(context, integrator, 5));
            }
            ASSERT(stops[0].message.find("step 0") != std::string::npos);
            compareStops(stops[0], stops[1], precision == "double" ? 1e-13 : 1e-6,
                         "a cold particle (" + precision + ")" + ScopedEnvironment::describe(values));
        }
}

/**
 * A step that would move a particle too far, reached in the middle of a run: a constant force accelerates particle
 * 5 until its step would exceed the pair range (at step 41). Reference and the device stop at the same step, in the
 * state of before it (trajectories of 40 steps agree to 1e-9 in double precision, as TestComputeGenDPDEEqualsReference
 * explains; the accelerated particle's velocity by 1e-9 of its own scale).
 */
void testUnstableStepInARun() {
    std::vector<Stop> stops;
    for (const std::string& on : {std::string(), std::string("double")}) {
        Scene scene = makeLatticeLiquid(10, referenceDensity, 0.1, GenDPDEForce::VB, true, 84);
        CustomExternalForce* pull = new CustomExternalForce("-a*x");
        pull->addGlobalParameter("a", 2.0e5);
        pull->addParticle(5);
        scene.system.addForce(pull);
        GenDPDEIntegrator integrator(stepSize, friction, heatConduction, heatCapacity);
        integrator.setTemperature(temperature);
        integrator.setRandomNumberSeed(96);
        Context context(scene.system, integrator, on.empty() ? Platform::getPlatformByName("Reference") : *platform,
                        on.empty() ? std::map<std::string, std::string>()
                                   : std::map<std::string, std::string>{{"Precision", on}});
        context.setPositions(scene.positions);
        context.setVelocitiesToTemperature(temperature, 97);
        stops.push_back(stopOf(context, integrator, 60));
    }
    ASSERT(stops[0].message.find("particle 5") != std::string::npos);
    ASSERT(stops[0].step > 10 && stops[0].step < 60);
    double speed = 0.0;
    for (const Vec3& v : stops[0].velocities)
        speed = std::max(speed, std::sqrt(v.dot(v)));
    compareStops(stops[0], stops[1], 1e-9 * std::max(1.0, speed), "an accelerated particle");
}

/**
 * An invalid particle found by the force in the middle of a run (the V-A estimator has no neighbour for a particle
 * that has left the others): particle 0 of an open cluster flies off and loses its last neighbour at some step;
 * Reference and the device stop there with the same message, in the state of before that step.
 */
void testForceErrorInARun() {
    std::vector<Stop> stops;
    for (const std::string& on : {std::string(), std::string("double")}) {
        Scene scene = makeLatticeLiquid(6, referenceDensity, 0.1, GenDPDEForce::VA, false, 85);
        GenDPDEIntegrator integrator(stepSize, 0.0, 0.0, heatCapacity);   // Isoenergetic without pair terms
        integrator.setTemperature(temperature);
        Context context(scene.system, integrator, on.empty() ? Platform::getPlatformByName("Reference") : *platform,
                        on.empty() ? std::map<std::string, std::string>()
                                   : std::map<std::string, std::string>{{"Precision", on}});
        context.setPositions(scene.positions);
        std::vector<Vec3> velocities(scene.system.getNumParticles(), Vec3());
        velocities[0] = Vec3(-0.35 * cutoff / stepSize, 0, 0);   // corner particle, leaving the cluster outwards
        context.setVelocities(velocities);
        stops.push_back(stopOf(context, integrator, 40));
    }
    ASSERT(stops[0].message.find("particle 0") != std::string::npos);
    ASSERT(stops[0].step > 1 && stops[0].step < 40);
    compareStops(stops[0], stops[1], 1e-9, "a particle that leaves its neighbours");
}

int main() {
    return runTestProgram([]() {
        loadComputePlugins(GENDPDE_TEST_PLATFORM);
        platform = &Platform::getPlatformByName(GENDPDE_TEST_PLATFORM);
        testSweepIsTheHostSequence();
        testSweepFailure();
        testUnstableStepInARun();
        testForceErrorInARun();
    });
}
