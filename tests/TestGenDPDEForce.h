/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
/* Tests of GenDPDEForce shared by every platform: a platform file defines `platform`, calls runForceTests(). Every
 * estimator the brute-force oracle evaluates runs through every test (TestScenes::testEstimators). The physics
 * against the oracle and finite differences is here; the virial tensors in TestGenDPDEForceVirial.h, particle types
 * in TestGenDPDEForceTypes.h, bad input and failing states in TestGenDPDEForceInput.h. */

#include "BruteForceGenDPDE.h"
#include "TestScenes.h"
#include "GenDPDEForce.h"
#include "TestUtilities.h"
#include "OpenMM.h"
#include <cmath>
#include <functional>
#include <iostream>
#include <limits>
#include <random>
#include <vector>

using namespace GenDPDEPlugin;
using namespace OpenMM;

extern Platform* platform;

namespace ForceTests {

using namespace TestScenes;

double energyAt(Context& context, const std::vector<Vec3>& positions) {
    context.setPositions(positions);
    return context.getState(State::Energy).getPotentialEnergy();
}

double rmsForce(const std::vector<Vec3>& forces) {
    double sum = 0;
    for (const Vec3& f : forces)
        sum += f.dot(f);
    return std::sqrt(sum / forces.size());
}

/**
 * How much more float rounding (single and mixed precision) an estimator's results carry than V-A's and V-B's: V-C's
 * surface factor depends on a^2 = c^2 |g|^2/(n0^2 + eps^2), whose relative error (2e-6, from n0^2) the factor's
 * elasticity a^2 factor'/factor (at most 2.2, at a^2 = 0.54) carries into V: 6 (1e-6 + 2.2 x 2e-6) ~ 3e-5 against
 * V-B's ~6e-6 (the Tait power x^6 times the density's 1e-6), hence 5.
 */
inline double floatErrorScale(GenDPDEForce::DensityEstimator estimator) {
    return estimator == GenDPDEForce::VC ? 5.0 : 1.0;
}

/** The root mean square of the elements of per-particle tensors (9 per particle). */
inline double rmsElement(const std::vector<double>& tensors) {
    double sum = 0.0;
    for (double w : tensors)
        sum += w * w;
    return std::sqrt(sum / std::max<size_t>(1, tensors.size()));
}

/**
 * Energy, forces, observables, virial and per-particle virial tensors equal the independent O(N^2) evaluation. Both
 * are double-precision evaluations of the same sums; they differ by summation order and the 1e-14 quadrature
 * tolerance of the brute force, so 1e-10 relative (energy, per-particle values) and 1e-9 of the rms force (or rms
 * tensor element) are generous yet catch any wrong formula, pair or image (those give errors of 1e-3 or more). With
 * float forces (single and mixed precision) positions carry 2^-24 relative rounding (~2e-7 nm here), each of the ~17
 * terms of a density ~1e-6 relative, and the Tait power x^(gamma-1) ~ x^5 multiplies relative density errors by ~6 in
 * the pressures: 1e-5 relative for the energy and per-particle values; a force component (and a tensor element) sums
 * ~17 pair terms of up to ~3 rms each, hence 1e-4 of the rms; V-C's factor multiplies all of these by
 * floatErrorScale.
 */
void checkAgainstBruteForce(Scene& scene, const std::string& label) {
    VerletIntegrator integrator(0.001);
    Context context(scene.system, integrator, *platform);
    context.setPositions(scene.positions);
    State state = context.getState(State::Energy | State::Forces);
    BruteForce::Result expected = BruteForce::evaluate(bruteForceModel(scene), scene.positions);
    const double scale = floatErrorScale(scene.force->getDensityEstimator());
    const double relative = precisionTolerance(1e-10, 1e-5 * scale),
                 forceTolerance = precisionTolerance(1e-9, 1e-4 * scale);
    assertRelative(expected.energy, state.getPotentialEnergy(), relative, label + " energy");
    double forceScale = rmsForce(expected.forces);
    for (size_t i = 0; i < scene.positions.size(); i++)
        assertVectorClose(expected.forces[i], state.getForces()[i], forceTolerance * forceScale, label + " force");
    std::vector<double> n0 = scene.force->getPrimitiveDensities(context);
    std::vector<double> volumes = scene.force->getParticleVolumes(context);
    std::vector<double> densities = scene.force->getParticleDensities(context);
    std::vector<double> pressures = scene.force->getParticlePressures(context);
    double pressureScale = scene.force->getBulkModulus();
    for (size_t i = 0; i < scene.positions.size(); i++) {
        assertClose(expected.primitiveDensity[i], n0[i], relative * referenceDensity, label + " n0_i");
        assertRelative(expected.volume[i], volumes[i], relative, label + " V_i");
        assertRelative(1.0 / expected.volume[i], densities[i], relative, label + " n_i");
        assertClose(expected.pressure[i], pressures[i],
                    relative * std::max(pressureScale, std::abs(expected.pressure[i])), label + " pi_i");
    }
    assertClose(expected.virial, scene.force->getVirial(context),
                10 * relative * std::max(1.0, std::abs(expected.virial)), label + " virial");
    const std::vector<double> tensors = scene.force->getParticleVirials(context);
    ASSERT_EQUAL(9 * scene.positions.size(), tensors.size());
    std::vector<double> expectedTensors;
    for (const BruteForce::Matrix& w : expected.particleVirial)
        for (int a = 0; a < 3; a++)
            for (int b = 0; b < 3; b++)
                expectedTensors.push_back(w.element[a][b]);
    const double tensorScale = std::max(1e-300, rmsElement(expectedTensors));
    for (size_t k = 0; k < tensors.size(); k++)
        assertClose(expectedTensors[k], tensors[k], forceTolerance * tensorScale,
                    label + " virial tensor of particle " + std::to_string(k / 9) + ", element "
                            + std::to_string(k % 9));
}

void testAgainstBruteForce() {
    forEachStandardScene(0.15, 1, checkAgainstBruteForce);
}

/** Both ways of raising (n/n0) to gamma_T - 1: multiplications for integer exponents, pow() otherwise. */
void testTaitExponents() {
    for (double exponent : {2.0, 6.5, 7.0, 12.0}) {
        Scene scene = makeLatticeLiquid(6, 1.3 * referenceDensity, 0.2, GenDPDEForce::VB, true, 6);
        scene.force->setTaitParameters(referenceDensity, 40.0, 70.0, exponent);
        checkAgainstBruteForce(scene, "gamma_T = " + std::to_string(exponent));
    }
}

void testTriclinicBox() {
    for (GenDPDEForce::DensityEstimator estimator : testEstimators()) {
        Scene scene = makeLatticeLiquid(6, referenceDensity, 0.3, estimator, true, 5);
        double edge = scene.box[0][0];
        setBox(scene, Vec3(edge, 0, 0), Vec3(0.3 * edge, edge, 0), Vec3(-0.4 * edge, 0.2 * edge, edge));
        checkAgainstBruteForce(scene, estimatorLabel(estimator) + " triclinic");
    }
}

/**
 * Forces equal minus the central finite difference of the energy. With h = 1e-4 nm the truncation error is
 * ~(h/l)^2/6 ~ 1e-7 relative (l ~ 0.1 nm, the scale over which forces vary) and the rounding error eps |U|/h stays
 * below 1e-6 of the rms force for these systems, hence the 1e-5 tolerance.
 */
void checkFiniteDifferences(Scene& scene, const std::string& label, double h = 1e-4) {
    VerletIntegrator integrator(0.001);
    Context context(scene.system, integrator, *platform);
    context.setPositions(scene.positions);
    std::vector<Vec3> forces = context.getState(State::Forces).getForces();
    double scale = rmsForce(forces);
    int numParticles = scene.positions.size();
    for (int i = 0; i < numParticles; i += std::max(1, numParticles / 12))
        for (int k = 0; k < 3; k++) {
            std::vector<Vec3> moved = scene.positions;
            moved[i][k] += h;
            double plus = energyAt(context, moved);
            moved[i][k] -= 2 * h;
            double minus = energyAt(context, moved);
            assertClose(-(plus - minus) / (2 * h), forces[i][k], 1e-5 * scale, label + " finite difference");
        }
}

/**
 * The step of the finite differences for an estimator: 1e-4 nm (above), except for V-C, whose factor bends sharply
 * above its threshold in a dilute gas (its curvature in a^2 is 2 alpha/w^2 = 67): 2.5e-5 nm keeps the central
 * difference's truncation error below the tolerance (at 1e-4 nm it reaches 3e-5 of a 2000 kJ/mol/nm force there),
 * while the rounding error eps |U|/h stays ~4e-6 of the rms force.
 */
inline double finiteDifferenceStep(GenDPDEForce::DensityEstimator estimator) {
    return estimator == GenDPDEForce::VC ? 2.5e-5 : 1e-4;
}

void testFiniteDifferences() {
    // With float forces the energy carries ~1e-6 relative rounding, which a central difference divides by 2h: no h
    // resolves the derivative there. The float kernels evaluate the formulas that this test checks in double
    // precision (on every platform), against the brute force above.
    if (floatForces())
        return;
    forEachStandardScene(0.2, 11, [](Scene& scene, const std::string& label) {
        checkFiniteDifferences(scene, label, finiteDifferenceStep(scene.force->getDensityEstimator()));
    });
}

/** Sum of forces vanishes; energy is invariant under translation, rotation (open) and periodic image shifts. */
void testSymmetries() {
    for (GenDPDEForce::DensityEstimator estimator : testEstimators()) {
        for (bool periodic : {true, false}) {
            Scene scene = makeLatticeLiquid(6, referenceDensity, 0.25, estimator, periodic, 21);
            VerletIntegrator integrator(0.001);
            Context context(scene.system, integrator, *platform);
            context.setPositions(scene.positions);
            State state = context.getState(State::Energy | State::Forces);
            double energy = state.getPotentialEnergy(), scale = rmsForce(state.getForces());
            Vec3 total;
            for (const Vec3& f : state.getForces())
                total += f;
            // Pairwise antisymmetric: the sum cancels to rounding, ~eps per pair contribution. With float forces the
            // sum is exact on the device (fixed point), but the forces a State returns are rounded to float each
            // (2^-24 of a force of up to a few rms): 1e-7 of the rms force per particle.
            // The energies below move by float rounding of the moved positions (~1e-7 relative each): 1e-5 (times
            // V-C's floatErrorScale).
            const double floatScale = floatErrorScale(estimator);
            const double sumTolerance = precisionTolerance(1e-12, 1e-7),
                         energyTolerance = precisionTolerance(1e-12, 1e-5 * floatScale),
                         forceTolerance = precisionTolerance(1e-10, 1e-4 * floatScale);
            assertVectorClose(Vec3(), total, sumTolerance * scale * scene.positions.size(), "sum of forces");

            std::vector<Vec3> shifted = scene.positions;
            for (Vec3& r : shifted)
                r += Vec3(0.37, -1.21, 2.05);
            assertRelative(energy, energyAt(context, shifted), energyTolerance, "translation");
            if (periodic) {
                std::vector<Vec3> imaged = scene.positions;
                imaged[3] += scene.box[0] * 2 - scene.box[1] + scene.box[2] * 3;
                imaged[17] -= scene.box[2];
                assertRelative(energy, energyAt(context, imaged), energyTolerance, "periodic image");
                State imagedState = context.getState(State::Forces);
                for (size_t i = 0; i < imaged.size(); i++)
                    assertVectorClose(state.getForces()[i], imagedState.getForces()[i], forceTolerance * scale,
                                      "image forces");
            } else {
                // Rotation by 0.7 rad about the axis (1, 2, 2)/3 through an arbitrary point.
                Vec3 u(1.0 / 3, 2.0 / 3, 2.0 / 3), centre(1.0, -2.0, 0.5);
                double c = std::cos(0.7), s = std::sin(0.7);
                auto rotate = [&](Vec3 v) { return v * c + u.cross(v) * s + u * (u.dot(v) * (1 - c)); };
                std::vector<Vec3> rotated = scene.positions;
                for (Vec3& r : rotated)
                    r = centre + rotate(r - centre);
                assertRelative(energy, energyAt(context, rotated), energyTolerance, "rotation");
                State rotatedState = context.getState(State::Forces);
                for (size_t i = 0; i < rotated.size(); i++)
                    assertVectorClose(rotate(state.getForces()[i]), rotatedState.getForces()[i], forceTolerance * scale,
                                      "rotated forces");
            }
        }
    }
}

/** Coincident particles: finite energy, no force between them, no NaN anywhere. */
void testCoincidentParticles() {
    for (GenDPDEForce::DensityEstimator estimator : testEstimators()) {
        Scene scene = makeLatticeLiquid(5, referenceDensity, 0.2, estimator, true, 41);
        scene.positions[7] = scene.positions[8];
        scene.positions[20] = scene.positions[21] = scene.positions[22];
        checkAgainstBruteForce(scene, estimatorLabel(estimator) + " coincident");
        // Two coincident particles alone: each is the other's only neighbor, at zero distance.
        Scene pair = makeScene(2, estimator, false);
        pair.positions = {Vec3(1, 2, 3), Vec3(1, 2, 3)};
        VerletIntegrator integrator(0.001);
        Context context(pair.system, integrator, *platform);
        context.setPositions(pair.positions);
        State state = context.getState(State::Energy | State::Forces);
        ASSERT(std::isfinite(state.getPotentialEnergy()));
        assertVectorClose(Vec3(), state.getForces()[0], 0.0, "coincident pair force");
        assertVectorClose(Vec3(), state.getForces()[1], 0.0, "coincident pair force");
    }
}

/**
 * An isolated particle: the estimators that allow it give V = (4 pi/3) Rt^3 (V-C's factor is 1 without neighbours)
 * and U = f(1/V), with no force; VA reports the particle by index.
 */
void testIsolatedParticle() {
    for (GenDPDEForce::DensityEstimator estimator : testEstimators()) {
        if (!BruteForce::allowsIsolatedParticles(estimator))
            continue;
        Scene scene = makeScene(3, estimator, false, 1.3);
        scene.positions = {Vec3(0, 0, 0), Vec3(0.5 * cutoff, 0, 0), Vec3(10 * cutoff, 0, 0)};
        VerletIntegrator integrator(0.001);
        Context context(scene.system, integrator, *platform);
        context.setPositions(scene.positions);
        double Rt = cutoff / 1.3, expectedVolume = 4.0 * M_PI / 3.0 * Rt * Rt * Rt;
        assertRelative(expectedVolume, scene.force->getParticleVolumes(context)[2], precisionTolerance(1e-15, 1e-6),
                       estimatorLabel(estimator) + " isolated volume");
        State state = context.getState(State::Energy | State::Forces);
        assertVectorClose(Vec3(), state.getForces()[2], 0.0, "isolated particle force");
        ASSERT(std::isfinite(state.getPotentialEnergy()));
    }
    Scene scene = makeScene(3, GenDPDEForce::VA, false, 1.3);
    scene.positions = {Vec3(0, 0, 0), Vec3(0.5 * cutoff, 0, 0), Vec3(10 * cutoff, 0, 0)};
    VerletIntegrator integrator(0.001);
    Context context(scene.system, integrator, *platform);
    context.setPositions(scene.positions);
    assertThrowsMentioning([&]() { context.getState(State::Energy); }, {"particle 2", "no neighbor", "step 0"});
    assertThrowsMentioning([&]() { scene.force->getParticleDensities(context); }, {"particle 2"});
}

/** Energy-only evaluation and force groups. */
void testEnergyOnlyAndForceGroups() {
    Scene scene = makeLatticeLiquid(5, referenceDensity, 0.2, GenDPDEForce::VB, true, 51);
    scene.force->setForceGroup(3);
    VerletIntegrator integrator(0.001);
    Context context(scene.system, integrator, *platform);
    context.setPositions(scene.positions);
    double both = context.getState(State::Energy | State::Forces).getPotentialEnergy();
    double energyOnly = context.getState(State::Energy).getPotentialEnergy();
    ASSERT_EQUAL(both, energyOnly);
    ASSERT_EQUAL(both, context.getState(State::Energy, false, 1 << 3).getPotentialEnergy());
    ASSERT_EQUAL(0.0, context.getState(State::Energy, false, 1 << 2).getPotentialEnergy());
    State otherGroup = context.getState(State::Forces, false, 1 << 2);
    for (const Vec3& f : otherGroup.getForces())
        ASSERT_EQUAL_VEC(Vec3(), f, 0.0);
}

/** updateParametersInContext() gives the same energy as a new Context built with the new parameters. */
void testUpdateParametersInContext() {
    Scene scene = makeLatticeLiquid(5, referenceDensity, 0.2, GenDPDEForce::VA, true, 61);
    VerletIntegrator integrator(0.001);
    Context context(scene.system, integrator, *platform);
    context.setPositions(scene.positions);
    double before = context.getState(State::Energy).getPotentialEnergy();
    scene.force->setDensityEstimator(GenDPDEForce::VB);
    scene.force->setCutoffScaling(1.41);
    scene.force->setTaitParameters(1.1 * referenceDensity, 20.0, 80.0, 7.0);
    ASSERT_EQUAL(before, context.getState(State::Energy).getPotentialEnergy()); // not applied yet
    scene.force->updateParametersInContext(context);
    double updated = context.getState(State::Energy).getPotentialEnergy();
    VerletIntegrator integrator2(0.001);
    Context fresh(scene.system, integrator2, *platform);
    fresh.setPositions(scene.positions);
    ASSERT_EQUAL_TOL(fresh.getState(State::Energy).getPotentialEnergy(), updated, 1e-14);
    std::vector<double> freshDensities = scene.force->getParticleDensities(fresh);
    std::vector<double> updatedDensities = scene.force->getParticleDensities(context);
    for (size_t i = 0; i < freshDensities.size(); i++)
        ASSERT_EQUAL_TOL(freshDensities[i], updatedDensities[i], 1e-14);
    // The cutoff and the boundary conditions are fixed for the lifetime of a Context.
    scene.force->setCutoffDistance(1.1 * cutoff);
    assertThrowsMentioning([&]() { scene.force->updateParametersInContext(context); }, {"cutoff", "reinitialize"});
    scene.force->setCutoffDistance(cutoff);
    scene.force->setNonbondedMethod(GenDPDEForce::CutoffNonPeriodic);
    assertThrowsMentioning([&]() { scene.force->updateParametersInContext(context); }, {"nonbonded method"});
}

/** The neighbor list stays exact while particles move far (many rebuilds): compare with the brute force. */
void testMovingParticles() {
    Scene scene = makeLatticeLiquid(5, referenceDensity, 0.2, GenDPDEForce::VB, true, 71);
    VerletIntegrator integrator(0.001);
    Context context(scene.system, integrator, *platform);
    std::mt19937 random(72);
    std::normal_distribution<double> gauss(0.0, 0.04 * cutoff);
    BruteForce::Model model = bruteForceModel(scene);
    for (int step = 0; step < 40; step++) {
        for (Vec3& r : scene.positions)
            r += Vec3(gauss(random), gauss(random), gauss(random));
        double energy = energyAt(context, scene.positions);
        if (step % 8 == 7)
            assertRelative(BruteForce::evaluate(model, scene.positions).energy, energy, precisionTolerance(1e-10, 1e-5),
                           "moving particles"); // as checkAgainstBruteForce
    }
}

/**
 * Forces are a pure function of the positions: two Contexts whose neighbor lists were built at different
 * configurations give bitwise identical forces at the same positions (needed for bit-for-bit continuation from a
 * checkpoint, where the list is rebuilt at another step than in the uninterrupted run).
 */
void testHistoryIndependence() {
    for (bool periodic : {true, false}) {
        // Lattice planes 0.01 nm inside the faces of the box, so that the small move below takes many particles
        // across the periodic boundary between the two list builds.
        Scene scene = makeLatticeLiquid(6, referenceDensity, 0.02, GenDPDEForce::VB, periodic, 75);
        double spacing = scene.box[0][0] / 6;
        for (Vec3& r : scene.positions)
            r -= Vec3(1, 1, 1) * (0.5 * spacing - 0.01);
        VerletIntegrator integrator1(0.001), integrator2(0.001);
        Context fresh(scene.system, integrator1, *platform), aged(scene.system, integrator2, *platform);
        std::vector<Vec3> earlier = scene.positions;
        for (Vec3& r : earlier)
            r -= Vec3(0.03, 0.03, 0.03); // within half the Verlet skin: no rebuild when moved back
        energyAt(aged, earlier); // the aged Context builds its list here
        double agedEnergy = energyAt(aged, scene.positions);
        double freshEnergy = energyAt(fresh, scene.positions);
        ASSERT_EQUAL(freshEnergy, agedEnergy);
        State a = fresh.getState(State::Forces), b = aged.getState(State::Forces);
        for (size_t i = 0; i < scene.positions.size(); i++)
            ASSERT(a.getForces()[i] == b.getForces()[i]);
    }
}

/**
 * V-C's surface correction where it matters: at a free surface (the outer layer of an open lattice liquid) a
 * particle gets a larger volume than with VB, deep inside V-B's (below the threshold the factor is exactly 1).
 */
void testVCSurfaceCorrection() {
    Scene open = makeLatticeLiquid(6, referenceDensity, 0.0, GenDPDEForce::VB, false, 112);
    open.force->setCutoffScaling(1.35);
    VerletIntegrator integrator(0.001);
    Context context(open.system, integrator, *platform);
    context.setPositions(open.positions);
    const std::vector<double> vb = open.force->getParticleVolumes(context);
    open.force->setDensityEstimator(GenDPDEForce::VC);
    open.force->updateParametersInContext(context);
    const std::vector<double> vc = open.force->getParticleVolumes(context);
    // Particle 0 is a corner of the lattice (three faces empty), particle 3*36 + 3*6 + 3 near the centre.
    ASSERT(vc[0] / vb[0] > 2.0);
    ASSERT_EQUAL_TOL(vb[129], vc[129], precisionTolerance(1e-15, 1e-6));
}

} // namespace ForceTests

#include "TestGenDPDEForceInput.h"
#include "TestGenDPDEForceTypes.h"
#include "TestGenDPDEForceVirial.h"
#include "TestGenDPDEBackgroundPressure.h"

namespace ForceTests {

void runForceTests() {
    testBadInput();
    testEquationOfStateOverflow();
    testTypesBadInput();
    testMixtureAgainstBruteForce();
    testIdenticalTypesAreBitwiseNoTypes();
    testTypesInContext();
    testAgainstBruteForce();
    testTriclinicBox();
    testTaitExponents();
    testFiniteDifferences();
    testSymmetries();
    testVirial();
    testVirialTensor();
    testBackgroundPressure();
    testBackgroundPressureInput();
    testCoincidentParticles();
    testIsolatedParticle();
    testVCSurfaceCorrection();
    testEnergyOnlyAndForceGroups();
    testUpdateParametersInContext();
    testMovingParticles();
    testHistoryIndependence();
}

} // namespace ForceTests
