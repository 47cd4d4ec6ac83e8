/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
/* The CPU platform computes exactly what Reference computes, with any number of threads: energies, forces,
 * observables, virials and virial tensors of the force tests' scenes (every estimator), and trajectories (positions, velocities, internal energies)
 * after 1000 isoenergetic steps of a liquid large enough for the sweep to run many blocks of a colour at once
 * (14^3 particles: 8 cells and 4 blocks per direction, 8 blocks per colour). Compared bit for bit. With one thread
 * and these sizes the CPU platform runs Reference's force passes (CpuGenDPDEForceKernel.h), so 2 and 3 threads test
 * its gathers; ctest runs this program again with GENDPDE_CPU_ONE_THREAD_GATHERS=1, where one thread runs them too
 * (as it does from 131,072 particles), and with GENDPDE_CPU_VECTOR=0 (the scalar gathers). */

#include "TestGenDPDEIntegrator.h"
#include "TestPlugins.h"
#include <sstream>

OpenMM::Platform* platform;

using namespace IntegratorTests;

const std::vector<std::string> threadCounts = {"1", "2", "3"};

Context* makeContext(System& system, Integrator& integrator, const std::string& platformName,
                     const std::string& threads) {
    if (platformName == "Reference")
        return new Context(system, integrator, Platform::getPlatformByName("Reference"));
    return new Context(system, integrator, Platform::getPlatformByName("CPU"), {{"Threads", threads}});
}

void assertSame(double expected, double found, const std::string& what) {
    if (!(expected == found)) {
        std::ostringstream message;
        message.precision(17);
        message << what << ": Reference " << expected << ", CPU " << found;
        throw std::runtime_error(message.str());
    }
}

void assertSame(const std::vector<Vec3>& expected, const std::vector<Vec3>& found, const std::string& what) {
    for (size_t i = 0; i < expected.size(); i++)
        for (int k = 0; k < 3; k++)
            assertSame(expected[i][k], found[i][k], what + " of particle " + std::to_string(i));
}

void assertSame(const std::vector<double>& expected, const std::vector<double>& found, const std::string& what) {
    for (size_t i = 0; i < expected.size(); i++)
        assertSame(expected[i], found[i], what + " of particle " + std::to_string(i));
}

void checkForcesAndObservables(Scene& scene, const std::string& label) {
    VerletIntegrator reference(0.001);
    std::unique_ptr<Context> expected(makeContext(scene.system, reference, "Reference", ""));
    expected->setPositions(scene.positions);
    const State state = expected->getState(State::Energy | State::Forces);
    for (const std::string& threads : threadCounts) {
        const std::string what = label + ", " + threads + " thread(s)";
        VerletIntegrator integrator(0.001);
        std::unique_ptr<Context> context(makeContext(scene.system, integrator, "CPU", threads));
        context->setPositions(scene.positions);
        const State found = context->getState(State::Energy | State::Forces);
        assertSame(state.getPotentialEnergy(), found.getPotentialEnergy(), what + ": energy");
        assertSame(state.getForces(), found.getForces(), what + ": force");
        assertSame(scene.force->getParticleDensities(*expected), scene.force->getParticleDensities(*context),
                   what + ": density");
        assertSame(scene.force->getParticlePressures(*expected), scene.force->getParticlePressures(*context),
                   what + ": pressure");
        assertSame(scene.force->getVirial(*expected), scene.force->getVirial(*context), what + ": virial");
        assertSame(scene.force->getParticleVirials(*expected), scene.force->getParticleVirials(*context),
                   what + ": virial tensors");
    }
}

void testForcesAndObservables() {
    TestScenes::forEachStandardScene(0.2, 51, checkForcesAndObservables);
    // Triclinic boxes (the CPU kernels' scalar path; open and rectangular boxes take the vector one where the
    // processor has AVX2, and the scalar one under GENDPDE_CPU_VECTOR=0), for every estimator.
    for (GenDPDEForce::DensityEstimator estimator : testEstimators()) {
        Scene scene = makeLatticeLiquid(6, referenceDensity, 0.3, estimator, true, 57);
        const double edge = scene.box[0][0];
        setBox(scene, Vec3(edge, 0, 0), Vec3(0.3 * edge, edge, 0), Vec3(-0.4 * edge, 0.2 * edge, edge));
        checkForcesAndObservables(scene, estimatorLabel(estimator) + " triclinic");
    }
    Scene mixture = makeLatticeLiquid(6, referenceDensity, 0.2, GenDPDEForce::VB, true, 58);
    setMixtureTypes(mixture, false);
    checkForcesAndObservables(mixture, "VB three-type mixture");
    Scene slab = makeSlab(6, 0.82 * referenceDensity, 0.2, GenDPDEForce::VC, 59);
    checkForcesAndObservables(slab, "VC slab");
}

Trajectory run(const std::string& platformName, const std::string& threads, GenDPDEIntegrator::Mode mode, int steps,
               bool ownPairs, bool mixture) {
    return runLatticeLiquid(
            14, true, mode, steps, ownPairs,
            [&](System& system, Integrator& integrator) {
                return makeContext(system, integrator, platformName, threads);
            },
            mixture);
}

void compareTrajectories(GenDPDEIntegrator::Mode mode, int steps, bool ownPairs, const std::string& label,
                         bool mixture = false) {
    const Trajectory expected = run("Reference", "", mode, steps, ownPairs, mixture);
    for (const std::string& threads : threadCounts) {
        const std::string what = label + ", " + threads + " thread(s)";
        const Trajectory found = run("CPU", threads, mode, steps, ownPairs, mixture);
        assertSame(expected.positions, found.positions, what + ": position");
        assertSame(expected.velocities, found.velocities, what + ": velocity");
        assertSame(expected.energies, found.energies, what + ": internal energy");
        assertSame(expected.kinetic, found.kinetic, what + ": kinetic energy");
    }
}

/** An internal energy that becomes <= 0 is reported for the same particle and step on both platforms. */
void testSameFailure() {
    std::vector<std::string> messages;
    for (const std::string platformName : {"Reference", "CPU"}) {
        Scene scene = makeLatticeLiquid(14, referenceDensity, 0.1, GenDPDEForce::VB, true, 62);
        GenDPDEIntegrator integrator(stepSize, friction, heatConduction, heatCapacity);
        std::vector<double> temperatures(scene.system.getNumParticles(), temperature);
        for (int i : {100, 1500, 2600})
            temperatures[i] = 1e-9;
        integrator.setParticleTemperatures(temperatures);
        std::unique_ptr<Context> context(makeContext(scene.system, integrator, platformName, "3"));
        context->setPositions(scene.positions);
        context->setVelocitiesToTemperature(temperature, 5);
        try {
            integrator.step(1);
        } catch (const OpenMMException& e) {
            messages.push_back(e.what());
        }
    }
    ASSERT_EQUAL(2, (int) messages.size());
    if (messages[0] != messages[1])
        throw std::runtime_error("different failures: Reference '" + messages[0] + "', CPU '" + messages[1] + "'");
}

int main() {
    return runTestProgram([]() {
        loadPlugins();
        platform = &Platform::getPlatformByName("CPU");
        testForcesAndObservables();
        compareTrajectories(GenDPDEIntegrator::Isoenergetic, 1000, false, "1000 isoenergetic steps");
        compareTrajectories(GenDPDEIntegrator::Isothermal, 200, false, "200 isothermal steps");
        compareTrajectories(GenDPDEIntegrator::Isoenergetic, 100, true, "100 steps on the integrator's own pairs");
        compareTrajectories(GenDPDEIntegrator::Isoenergetic, 200, false, "200 isoenergetic steps of a mixture", true);
        testSameFailure();
    });
}
