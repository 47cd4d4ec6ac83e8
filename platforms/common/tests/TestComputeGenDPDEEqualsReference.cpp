/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
/* A GPU platform (GENDPDE_TEST_PLATFORM: OpenCL or CUDA) against Reference, in single, mixed and double precision.
 *
 * Forces, observables and virial tensors of the force tests' scenes (every estimator, triclinic boxes, a V-C slab):
 * the same sums in another order, so in
 * double precision they agree to rounding (1e-10 relative, 1e-9 of the rms force; a wrong pair, image or formula
 * gives 1e-4 or more); in single and mixed precision positions and sums carry float rounding (2^-24 = 6e-8 relative
 * per operation, ~17 neighbours per particle, V-B's tables and the Tait power x^6 amplifying relative errors ~6x),
 * so 1e-5 relative for energies and per-particle values and 1e-5 of the rms force for the rms force difference.
 *
 * Trajectories in double precision: the device applies the pair updates in the host's sequence with the same random
 * variates, so what separates the two is rounding (the device's forces are fixed point, 2^-32 kJ/mol/nm, and its
 * sums run in another order), amplified by the chaos of a liquid: over 20 steps of 0.005 ps (0.1 ps, a fraction of
 * the ~1 ps Lyapunov time of liquid argon) a 1e-13 relative difference grows by at most a few decades, so positions
 * agree to 1e-9 nm and velocities, internal energies and the kinetic energy to 1e-8 relative. An update out of
 * sequence or a wrong variate gives differences of 1e-3 or more after one step.
 *
 * Failures: an internal energy that becomes <= 0 is reported for the same particle and step as on Reference. */

#include "TestGenDPDEIntegrator.h"
#include "TestPlugins.h"
#include <cmath>

OpenMM::Platform* platform;

using namespace IntegratorTests;

struct Tolerances {
    double relative, force;
};

/** The tolerances of the comparison; V-C's surface factor carries 5 times V-B's float rounding (TestGenDPDEForce.h). */
Tolerances tolerancesFor(const std::string& precision, GenDPDEForce::DensityEstimator estimator) {
    const double scale = (estimator == GenDPDEForce::VC ? 5.0 : 1.0);
    return precision == "double" ? Tolerances{1e-10, 1e-9} : Tolerances{1e-5 * scale, 1e-5 * scale};
}

Context* makeContext(System& system, Integrator& integrator, const std::string& precision) {
    if (precision.empty())
        return new Context(system, integrator, Platform::getPlatformByName("Reference"));
    return new Context(system, integrator, Platform::getPlatformByName(GENDPDE_TEST_PLATFORM),
                       {{"Precision", precision}});
}

void assertAllRelative(const std::vector<double>& expected, const std::vector<double>& found, double tolerance,
                       const std::string& what) {
    for (size_t i = 0; i < expected.size(); i++)
        assertRelative(expected[i], found[i], tolerance, what + " of particle " + std::to_string(i));
}

void compareScene(Scene& scene, const std::string& label, const std::string& precision) {
    const Tolerances tolerance = tolerancesFor(precision, scene.force->getDensityEstimator());
    const std::string what = label + " (" + precision + ")";
    VerletIntegrator referenceIntegrator(0.001), integrator(0.001);
    std::unique_ptr<Context> expected(makeContext(scene.system, referenceIntegrator, ""));
    std::unique_ptr<Context> context(makeContext(scene.system, integrator, precision));
    expected->setPositions(scene.positions);
    context->setPositions(scene.positions);
    const State a = expected->getState(State::Energy | State::Forces);
    const State b = context->getState(State::Energy | State::Forces);
    assertRelative(a.getPotentialEnergy(), b.getPotentialEnergy(), tolerance.relative, what + ": energy");
    double squaredForce = 0.0, squaredDifference = 0.0;
    for (size_t i = 0; i < a.getForces().size(); i++) {
        squaredForce += a.getForces()[i].dot(a.getForces()[i]);
        const Vec3 d = a.getForces()[i] - b.getForces()[i];
        squaredDifference += d.dot(d);
    }
    assertClose(0.0, std::sqrt(squaredDifference), tolerance.force * std::sqrt(squaredForce), what + ": rms force");
    assertAllRelative(scene.force->getParticleVolumes(*expected), scene.force->getParticleVolumes(*context),
                      tolerance.relative, what + ": volume");
    assertAllRelative(scene.force->getParticleDensities(*expected), scene.force->getParticleDensities(*context),
                      tolerance.relative, what + ": density");
    const std::vector<double> pa = scene.force->getParticlePressures(*expected);
    const std::vector<double> pb = scene.force->getParticlePressures(*context);
    double pressureScale = 0.0; // pressures pass through zero: relative to the largest
    for (double p : pa)
        pressureScale = std::max(pressureScale, std::abs(p));
    for (size_t i = 0; i < pa.size(); i++)
        assertClose(pa[i], pb[i], tolerance.relative * pressureScale,
                    what + ": pressure of particle " + std::to_string(i));
    assertRelative(scene.force->getVirial(*expected), scene.force->getVirial(*context), 10 * tolerance.relative,
                   what + ": virial");
    const std::vector<double> wa = scene.force->getParticleVirials(*expected);
    const std::vector<double> wb = scene.force->getParticleVirials(*context);
    double squaredElement = 0.0, squaredElementDifference = 0.0;
    for (size_t k = 0; k < wa.size(); k++) {
        squaredElement += wa[k] * wa[k];
        squaredElementDifference += (wa[k] - wb[k]) * (wa[k] - wb[k]);
    }
    assertClose(0.0, std::sqrt(squaredElementDifference), tolerance.force * std::sqrt(squaredElement),
                what + ": rms virial tensor element");
}

void testForcesAndObservables(const std::string& precision) {
    TestScenes::forEachStandardScene(
            0.2, 51, [&](Scene& scene, const std::string& label) { compareScene(scene, label, precision); });
    for (GenDPDEForce::DensityEstimator estimator : testEstimators()) {
        Scene scene = makeLatticeLiquid(6, referenceDensity, 0.3, estimator, true, 57);
        const double edge = scene.box[0][0];
        setBox(scene, Vec3(edge, 0, 0), Vec3(0.3 * edge, edge, 0), Vec3(-0.4 * edge, 0.2 * edge, edge));
        compareScene(scene, estimatorLabel(estimator) + " triclinic", precision);
    }
    Scene mixture = makeLatticeLiquid(6, referenceDensity, 0.2, GenDPDEForce::VB, true, 58);
    setMixtureTypes(mixture, false);
    compareScene(mixture, "VB three-type mixture", precision);
    Scene slab = makeSlab(6, 0.82 * referenceDensity, 0.2, GenDPDEForce::VC, 59);
    compareScene(slab, "VC slab", precision);
}

Trajectory run(const std::string& precision, GenDPDEIntegrator::Mode mode, int steps, bool periodic, bool ownPairs,
               bool mixture) {
    return runLatticeLiquid(
            8, periodic, mode, steps, ownPairs,
            [&](System& system, Integrator& integrator) { return makeContext(system, integrator, precision); },
            mixture);
}

void compareTrajectories(GenDPDEIntegrator::Mode mode, bool periodic, bool ownPairs, const std::string& label,
                         bool mixture = false) {
    const int steps = 20;
    const Trajectory expected = run("", mode, steps, periodic, ownPairs, mixture);
    const Trajectory found = run("double", mode, steps, periodic, ownPairs, mixture);
    assertTrajectoriesClose(expected, found, 1e-9, 1e-8, label);
}

void testSameFailure() {
    std::vector<std::string> messages;
    for (const std::string precision : {"", "double", "mixed"}) {
        Scene scene = makeLatticeLiquid(8, referenceDensity, 0.1, GenDPDEForce::VB, true, 62);
        GenDPDEIntegrator integrator(stepSize, friction, heatConduction, heatCapacity);
        std::vector<double> temperatures(scene.system.getNumParticles(), temperature);
        for (int i : {100, 300, 450})
            temperatures[i] = 1e-9;
        integrator.setParticleTemperatures(temperatures);
        std::unique_ptr<Context> context(makeContext(scene.system, integrator, precision));
        context->setPositions(scene.positions);
        context->setVelocitiesToTemperature(temperature, 5);
        const State before = context->getState(State::Velocities);
        try {
            integrator.step(1);
        } catch (const OpenMMException& e) {
            messages.push_back(e.what());
        }
        // Rolled back: the velocities and internal energies of before the step.
        const State after = context->getState(State::Velocities);
        for (size_t i = 0; i < before.getVelocities().size(); i++)
            assertVectorClose(before.getVelocities()[i], after.getVelocities()[i], 0.0, "rolled-back velocity");
        assertClose(1e-9, integrator.getParticleTemperatures()[100], 1e-15, "rolled-back temperature");
    }
    ASSERT_EQUAL(3, (int) messages.size());
    for (int k = 1; k < 3; k++)
        if (messages[0] != messages[k])
            throw std::runtime_error("different failures: Reference '" + messages[0] + "', " GENDPDE_TEST_PLATFORM " '"
                                     + messages[k] + "'");
}

/**
 * A particle with more neighbours than the device's list holds is gathered from the cells around it, by original
 * index as the list is, with forces summed in fixed point: the results equal the list's to the last bit (a list of 3
 * neighbours, GENDPDE_LIST_CAPACITY, sends every particle that way), in double and in single precision.
 */
void testListOverflowIsExact() {
    for (const std::string precision : {"double", "single"})
        for (GenDPDEForce::DensityEstimator estimator : testEstimators())
            for (bool periodic : {true, false}) {
                Scene scene = makeLatticeLiquid(6, referenceDensity, 0.3, estimator, periodic, 63);
                const std::string label =
                        estimatorLabel(estimator) + (periodic ? " periodic" : " open") + " (" + precision + ")";
                std::vector<State> states;
                std::vector<std::vector<double>> densities;
                for (const std::string capacity : {"", "3"}) {
                    ScopedEnvironment settings(capacity.empty() ? std::vector<std::pair<std::string, std::string>>()
                                                                : std::vector<std::pair<std::string, std::string>>{
                                                                          {"GENDPDE_LIST_CAPACITY", capacity}});
                    VerletIntegrator integrator(0.001);
                    std::unique_ptr<Context> context(makeContext(scene.system, integrator, precision));
                    context->setPositions(scene.positions);
                    states.push_back(context->getState(State::Energy | State::Forces));
                    densities.push_back(scene.force->getParticleDensities(*context));
                }
                ASSERT_EQUAL(states[0].getPotentialEnergy(), states[1].getPotentialEnergy());
                for (size_t i = 0; i < scene.positions.size(); i++) {
                    if (!(states[0].getForces()[i] == states[1].getForces()[i]))
                        throw std::runtime_error(label + ": the cells' force on particle " + std::to_string(i)
                                                 + " differs from the list's");
                    ASSERT_EQUAL(densities[0][i], densities[1][i]);
                }
            }
}

int main() {
    return runTestProgram([]() {
        loadComputePlugins(GENDPDE_TEST_PLATFORM);
        platform = &Platform::getPlatformByName(GENDPDE_TEST_PLATFORM);
        for (const std::string precision : {"double", "mixed", "single"})
            testForcesAndObservables(precision);
        compareTrajectories(GenDPDEIntegrator::Isoenergetic, true, false, "Isoenergetic");
        compareTrajectories(GenDPDEIntegrator::Isothermal, true, false, "Isothermal");
        compareTrajectories(GenDPDEIntegrator::Conservative, true, false, "Conservative");
        compareTrajectories(GenDPDEIntegrator::Isoenergetic, false, false, "Isoenergetic, open boundaries");
        compareTrajectories(GenDPDEIntegrator::Isoenergetic, true, true, "Isoenergetic, the sweep's own cells");
        compareTrajectories(GenDPDEIntegrator::Isoenergetic, true, false, "Isoenergetic, a three-type mixture", true);
        compareTrajectories(GenDPDEIntegrator::Isothermal, true, false, "Isothermal, a three-type mixture", true);
        testSameFailure();
        testListOverflowIsExact();
    });
}
