/* Tests of GenDPDEForce shared by every platform: a platform file defines `platform`, calls runForceTests(). */

#include "BruteForceGenDPDE.h"
#include "TestScenes.h"
#include "GenDPDEForce.h"
#include "TestUtilities.h"
#include "internal/GenDPDEPhysics.h"
#include "OpenMM.h"
#include <cmath>
#include <functional>
#include <iostream>
#include <random>
#include <vector>

using namespace GenDPDEPlugin;
using namespace OpenMM;

extern Platform* platform;

namespace ForceTests {

using namespace TestScenes;

inline BruteForce::Model bruteForceModel(const Scene& scene) {
    BruteForce::Model model;
    model.cutoff = scene.force->getCutoffDistance();
    model.useVB = scene.force->getDensityEstimator() != GenDPDEForce::VA;
    model.useVC = scene.force->getDensityEstimator() == GenDPDEForce::VC;
    model.cutoffScaling = scene.force->getCutoffScaling();
    scene.force->getTaitParameters(model.n0, model.pi0, model.bulkModulus, model.gammaT);
    if (!scene.force->getParticleTypes().empty() || scene.force->getNumTypeParameters() > 0)
        for (int i = 0; i < scene.system.getNumParticles(); i++) {
            // Each particle's type, then that type's entry if it has one (written out here, not GenDPDETypes.h).
            BruteForce::Tait tait{model.n0, model.pi0, model.bulkModulus, model.gammaT};
            for (int entry = 0; entry < scene.force->getNumTypeParameters(); entry++) {
                int type;
                BruteForce::Tait p;
                scene.force->getTypeParameters(entry, type, p.n0, p.pi0, p.bulkModulus, p.gammaT);
                if (type == scene.force->getParticleType(i))
                    tait = p;
            }
            model.particleTait.push_back(tait);
        }
    model.periodic = scene.force->usesPeriodicBoundaryConditions();
    for (int k = 0; k < 3; k++)
        model.box[k] = scene.box[k];
    return model;
}

double energyAt(Context& context, const std::vector<Vec3>& positions) {
    context.setPositions(positions);
    return context.getState(State::Energy).getPotentialEnergy();
}

double rmsForce(const std::vector<Vec3>& forces) {
    double sum = 0;
    for (const Vec3& f : forces)
        sum += f.dot(f);
    return std::sqrt(sum/forces.size());
}

/**
 * Energy, forces, observables and virial equal the independent O(N^2) evaluation. Both are double-precision
 * evaluations of the same sums; they differ by summation order and the 1e-14 quadrature tolerance of the brute
 * force, so 1e-10 relative (energy, per-particle values) and 1e-9 of the rms force are generous yet catch any
 * wrong formula, pair or image (those give errors of 1e-3 or more). With float forces (single and mixed precision)
 * positions carry 2^-24 relative rounding (~2e-7 nm here), each of the ~17 terms of a density ~1e-6 relative, and
 * the Tait power x^(gamma-1) ~ x^5 multiplies relative density errors by ~6 in the pressures: 1e-5 relative for the
 * energy and per-particle values; a force component sums ~17 pair forces of up to ~3 rms each, hence 1e-4 of the
 * rms force.
 */
void checkAgainstBruteForce(Scene& scene, const std::string& label) {
    VerletIntegrator integrator(0.001);
    Context context(scene.system, integrator, *platform);
    context.setPositions(scene.positions);
    State state = context.getState(State::Energy | State::Forces);
    BruteForce::Result expected = BruteForce::evaluate(bruteForceModel(scene), scene.positions);
    const double relative = precisionTolerance(1e-10, 1e-5), forceTolerance = precisionTolerance(1e-9, 1e-4);
    assertRelative(expected.energy, state.getPotentialEnergy(), relative, label + " energy");
    double forceScale = rmsForce(expected.forces);
    for (size_t i = 0; i < scene.positions.size(); i++)
        assertVectorClose(expected.forces[i], state.getForces()[i], forceTolerance*forceScale, label + " force");
    std::vector<double> n0 = scene.force->getPrimitiveDensities(context);
    std::vector<double> volumes = scene.force->getParticleVolumes(context);
    std::vector<double> densities = scene.force->getParticleDensities(context);
    std::vector<double> pressures = scene.force->getParticlePressures(context);
    double pressureScale = scene.force->getBulkModulus();
    for (size_t i = 0; i < scene.positions.size(); i++) {
        assertClose(expected.primitiveDensity[i], n0[i], relative*referenceDensity, label + " n0_i");
        assertRelative(expected.volume[i], volumes[i], relative, label + " V_i");
        assertRelative(1.0/expected.volume[i], densities[i], relative, label + " n_i");
        assertClose(expected.pressure[i], pressures[i], relative*std::max(pressureScale, std::abs(expected.pressure[i])),
                    label + " pi_i");
    }
    assertClose(expected.virial, scene.force->getVirial(context), 10*relative*std::max(1.0, std::abs(expected.virial)),
                label + " virial");
}

void testAgainstBruteForce() {
    forEachStandardScene(0.15, 1, checkAgainstBruteForce);
}

/** Both ways of raising (n/n0) to gamma_T - 1: multiplications for integer exponents, pow() otherwise. */
void testTaitExponents() {
    for (double exponent : {2.0, 6.5, 7.0, 12.0}) {
        Scene scene = makeLatticeLiquid(6, 1.3*referenceDensity, 0.2, GenDPDEForce::VB, true, 6);
        scene.force->setTaitParameters(referenceDensity, 40.0, 70.0, exponent);
        checkAgainstBruteForce(scene, "gamma_T = " + std::to_string(exponent));
    }
}

void testTriclinicBox() {
    for (GenDPDEForce::DensityEstimator estimator : {GenDPDEForce::VA, GenDPDEForce::VB}) {
        Scene scene = makeLatticeLiquid(6, referenceDensity, 0.3, estimator, true, 5);
        double edge = scene.box[0][0];
        setBox(scene, Vec3(edge, 0, 0), Vec3(0.3*edge, edge, 0), Vec3(-0.4*edge, 0.2*edge, edge));
        checkAgainstBruteForce(scene, "triclinic");
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
    for (int i = 0; i < numParticles; i += std::max(1, numParticles/12))
        for (int k = 0; k < 3; k++) {
            std::vector<Vec3> moved = scene.positions;
            moved[i][k] += h;
            double plus = energyAt(context, moved);
            moved[i][k] -= 2*h;
            double minus = energyAt(context, moved);
            assertClose(-(plus - minus)/(2*h), forces[i][k], 1e-5*scale, label + " finite difference");
        }
}

void testFiniteDifferences() {
    // With float forces the energy carries ~1e-6 relative rounding, which a central difference divides by 2h: no h
    // resolves the derivative there. The float kernels evaluate the formulas that this test checks in double
    // precision (on every platform), against the brute force above.
    if (floatForces())
        return;
    forEachStandardScene(0.2, 11, [](Scene& scene, const std::string& label) { checkFiniteDifferences(scene, label); });
}

/** Sum of forces vanishes; energy is invariant under translation, rotation (open) and periodic image shifts. */
void testSymmetries() {
    for (GenDPDEForce::DensityEstimator estimator : {GenDPDEForce::VA, GenDPDEForce::VB}) {
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
            // The energies below move by float rounding of the moved positions (~1e-7 relative each): 1e-5.
            const double sumTolerance = precisionTolerance(1e-12, 1e-7), energyTolerance = precisionTolerance(1e-12, 1e-5),
                         forceTolerance = precisionTolerance(1e-10, 1e-4);
            assertVectorClose(Vec3(), total, sumTolerance*scale*scene.positions.size(), "sum of forces");

            std::vector<Vec3> shifted = scene.positions;
            for (Vec3& r : shifted)
                r += Vec3(0.37, -1.21, 2.05);
            assertRelative(energy, energyAt(context, shifted), energyTolerance, "translation");
            if (periodic) {
                std::vector<Vec3> imaged = scene.positions;
                imaged[3] += scene.box[0]*2 - scene.box[1] + scene.box[2]*3;
                imaged[17] -= scene.box[2];
                assertRelative(energy, energyAt(context, imaged), energyTolerance, "periodic image");
                State imagedState = context.getState(State::Forces);
                for (size_t i = 0; i < imaged.size(); i++)
                    assertVectorClose(state.getForces()[i], imagedState.getForces()[i], forceTolerance*scale,
                                      "image forces");
            }
            else {
                // Rotation by 0.7 rad about the axis (1, 2, 2)/3 through an arbitrary point.
                Vec3 u(1.0/3, 2.0/3, 2.0/3), centre(1.0, -2.0, 0.5);
                double c = std::cos(0.7), s = std::sin(0.7);
                auto rotate = [&](Vec3 v) { return v*c + u.cross(v)*s + u*(u.dot(v)*(1 - c)); };
                std::vector<Vec3> rotated = scene.positions;
                for (Vec3& r : rotated)
                    r = centre + rotate(r - centre);
                assertRelative(energy, energyAt(context, rotated), energyTolerance, "rotation");
                State rotatedState = context.getState(State::Forces);
                for (size_t i = 0; i < rotated.size(); i++)
                    assertVectorClose(rotate(state.getForces()[i]), rotatedState.getForces()[i], forceTolerance*scale,
                                      "rotated forces");
            }
        }
    }
}

/**
 * The virial equals sum_i r_i . F_i for open boundaries, and -dU/d(lambda) under uniform scaling r -> lambda r of
 * positions and box (= -3 V dU/dV) for periodic ones; the finite difference uses lambda = 1 +- 1e-6, whose
 * truncation error is ~1e-12 relative, and the rounding error eps |U| / 1e-6 is ~1e-9 of |W|.
 */
void testVirial() {
    for (GenDPDEForce::DensityEstimator estimator : {GenDPDEForce::VA, GenDPDEForce::VB, GenDPDEForce::VC}) {
        Scene open = makeLatticeLiquid(6, referenceDensity, 0.2, estimator, false, 31);
        VerletIntegrator integrator(0.001);
        Context context(open.system, integrator, *platform);
        context.setPositions(open.positions);
        State state = context.getState(State::Forces);
        double sum = 0;
        for (size_t i = 0; i < open.positions.size(); i++)
            sum += open.positions[i].dot(state.getForces()[i]);
        // Float forces: the State's forces are rounded to float each, and the terms r_i . F_i (of either sign, their
        // magnitudes summing to ~100 |W|) carry that: 1e-5.
        assertRelative(sum, open.force->getVirial(context), precisionTolerance(1e-10, 1e-5), "open virial");

        for (double density : {referenceDensity, 3.0*referenceDensity}) {
            Scene periodic = makeLatticeLiquid(6, density, 0.2, estimator, true, 32);
            VerletIntegrator integrator2(0.001);
            Context context2(periodic.system, integrator2, *platform);
            context2.setPositions(periodic.positions);
            double virial = periodic.force->getVirial(context2);
            auto scaledEnergy = [&](double lambda) {
                context2.setPeriodicBoxVectors(periodic.box[0]*lambda, periodic.box[1]*lambda, periodic.box[2]*lambda);
                std::vector<Vec3> scaled = periodic.positions;
                for (Vec3& r : scaled)
                    r *= lambda;
                return energyAt(context2, scaled);
            };
            // Float forces: the energy's ~1e-7 relative rounding over 2 epsilon needs epsilon = 1e-3 (rounding
            // ~1e-4 of U/W, truncation ~1e-6): 1e-3.
            const double epsilon = precisionTolerance(1e-6, 1e-3);
            double derivative = (scaledEnergy(1 + epsilon) - scaledEnergy(1 - epsilon))/(2*epsilon);
            assertRelative(-derivative, virial, precisionTolerance(1e-7, 1e-3), "virial = -3V dU/dV");
        }
    }
}

/** Coincident particles: finite energy, no force between them, no NaN anywhere. */
void testCoincidentParticles() {
    for (GenDPDEForce::DensityEstimator estimator : {GenDPDEForce::VA, GenDPDEForce::VB}) {
        Scene scene = makeLatticeLiquid(5, referenceDensity, 0.2, estimator, true, 41);
        scene.positions[7] = scene.positions[8];
        scene.positions[20] = scene.positions[21] = scene.positions[22];
        checkAgainstBruteForce(scene, "coincident");
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

/** An isolated particle: VB gives V = (4 pi/3) Rt^3 and U = f(1/V); VA reports the particle by index. */
void testIsolatedParticle() {
    Scene scene = makeScene(3, GenDPDEForce::VB, false, 1.3);
    scene.positions = {Vec3(0, 0, 0), Vec3(0.5*cutoff, 0, 0), Vec3(10*cutoff, 0, 0)};
    VerletIntegrator integrator(0.001);
    Context context(scene.system, integrator, *platform);
    context.setPositions(scene.positions);
    double Rt = cutoff/1.3, expectedVolume = 4.0*M_PI/3.0*Rt*Rt*Rt;
    assertRelative(expectedVolume, scene.force->getParticleVolumes(context)[2], precisionTolerance(1e-15, 1e-6),
                   "isolated VB volume");
    State state = context.getState(State::Energy | State::Forces);
    assertVectorClose(Vec3(), state.getForces()[2], 0.0, "isolated particle force");
    ASSERT(std::isfinite(state.getPotentialEnergy()));

    scene.force->setDensityEstimator(GenDPDEForce::VA);
    scene.force->updateParametersInContext(context);
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
    ASSERT_EQUAL(both, context.getState(State::Energy, false, 1<<3).getPotentialEnergy());
    ASSERT_EQUAL(0.0, context.getState(State::Energy, false, 1<<2).getPotentialEnergy());
    State otherGroup = context.getState(State::Forces, false, 1<<2);
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
    scene.force->setTaitParameters(1.1*referenceDensity, 20.0, 80.0, 7.0);
    ASSERT_EQUAL(before, context.getState(State::Energy).getPotentialEnergy());   // not applied yet
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
    scene.force->setCutoffDistance(1.1*cutoff);
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
    std::normal_distribution<double> gauss(0.0, 0.04*cutoff);
    BruteForce::Model model = bruteForceModel(scene);
    for (int step = 0; step < 40; step++) {
        for (Vec3& r : scene.positions)
            r += Vec3(gauss(random), gauss(random), gauss(random));
        double energy = energyAt(context, scene.positions);
        if (step % 8 == 7)
            assertRelative(BruteForce::evaluate(model, scene.positions).energy, energy,
                           precisionTolerance(1e-10, 1e-5), "moving particles");   // as checkAgainstBruteForce
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
        double spacing = scene.box[0][0]/6;
        for (Vec3& r : scene.positions)
            r -= Vec3(1, 1, 1)*(0.5*spacing - 0.01);
        VerletIntegrator integrator1(0.001), integrator2(0.001);
        Context fresh(scene.system, integrator1, *platform), aged(scene.system, integrator2, *platform);
        std::vector<Vec3> earlier = scene.positions;
        for (Vec3& r : earlier)
            r -= Vec3(0.03, 0.03, 0.03);             // within half the Verlet skin: no rebuild when moved back
        energyAt(aged, earlier);                     // the aged Context builds its list here
        double agedEnergy = energyAt(aged, scene.positions);
        double freshEnergy = energyAt(fresh, scene.positions);
        ASSERT_EQUAL(freshEnergy, agedEnergy);
        State a = fresh.getState(State::Forces), b = aged.getState(State::Forces);
        for (size_t i = 0; i < scene.positions.size(); i++)
            ASSERT(a.getForces()[i] == b.getForces()[i]);
    }
}

/** Bad input is rejected with a message naming the parameter and the value, and changes nothing. */
/** Every setter refuses values outside its documented range (docs/force.md), naming the parameter and the value. */
void testBadInput() {
    GenDPDEForce force(1.0);
    struct Case {
        std::function<void()> call;
        std::vector<std::string> fragments;
    };
    const std::vector<Case> cases = {
        {[]() { GenDPDEForce(-1.0); }, {"cutoff distance", "-1", "[0.001, 10000] nm"}},
        {[]() { GenDPDEForce(0.0); }, {"cutoff distance", "= 0 nm"}},
        {[]() { GenDPDEForce(1e-320); }, {"cutoff distance", "e-321"}},   // (subnormal: printed 9.99988867183e-321)
        {[]() { GenDPDEForce(std::nan("")); }, {"cutoff distance", "nan"}},
        {[&]() { force.setCutoffDistance(INFINITY); }, {"cutoff distance", "inf"}},
        {[&]() { force.setCutoffDistance(2e4); }, {"cutoff distance", "20000"}},
        {[&]() { force.setCutoffScaling(0.99); }, {"f_cut", "0.99", "[1, 100]"}},
        {[&]() { force.setCutoffScaling(1e100); }, {"f_cut", "1e+100"}},
        {[&]() { force.setTaitParameters(0.0, 1, 1, 2); }, {"reference density", "= 0 nm^-3", "[1e-12, 1e+12]"}},
        {[&]() { force.setTaitParameters(1e-300, 1, 1, 2); }, {"reference density", "1e-300"}},
        {[&]() { force.setTaitParameters(1, INFINITY, 1, 2); }, {"reference pressure", "inf"}},
        {[&]() { force.setTaitParameters(1, -2e12, 1, 2); }, {"reference pressure", "-2e+12"}},
        {[&]() { force.setTaitParameters(1, 1, -3, 2); }, {"bulk modulus", "-3"}},
        {[&]() { force.setTaitParameters(1, 1, 1e300, 2); }, {"bulk modulus", "1e+300"}},
        {[&]() { force.setTaitParameters(1, 1, 1, 1.0); }, {"gamma_T", "= 1 ", "(1, 100]"}},
        {[&]() { force.setTaitParameters(1, 1, 1, 101); }, {"gamma_T", "101"}},
        {[&]() { force.setDensityEstimator((GenDPDEForce::DensityEstimator) 7); }, {"estimator", "7"}},
        {[&]() { force.setNonbondedMethod((GenDPDEForce::NonbondedMethod) -1); }, {"method", "-1"}},
    };
    for (const Case& c : cases)
        assertThrowsMentioning(c.call, c.fragments);
    // Nothing above changed the force.
    ASSERT_EQUAL(1.0, force.getCutoffDistance());
    ASSERT_EQUAL(1.0, force.getCutoffScaling());
    ASSERT_EQUAL(6.0, force.getTaitExponent());
    ASSERT_EQUAL(GenDPDEForce::VB, force.getDensityEstimator());

    // Cutoff larger than half the box, at Context creation.
    Scene scene = makeLatticeLiquid(3, referenceDensity, 0.0, GenDPDEForce::VB, true, 81);
    VerletIntegrator integrator(0.001);
    assertThrowsMentioning([&]() { Context context(scene.system, integrator, *platform); }, {"cutoff distance", "half"});
    // ... and when the box shrinks later.
    Scene big = makeLatticeLiquid(6, referenceDensity, 0.0, GenDPDEForce::VB, true, 82);
    VerletIntegrator integrator2(0.001);
    Context context(big.system, integrator2, *platform);
    context.setPositions(big.positions);
    context.setPeriodicBoxVectors(Vec3(1.5*cutoff, 0, 0), Vec3(0, 4, 0), Vec3(0, 0, 4));
    assertThrowsMentioning([&]() { context.getState(State::Energy); }, {"cutoff distance", "half"});
    // NaN positions name the particle.
    context.setPeriodicBoxVectors(big.box[0], big.box[1], big.box[2]);
    std::vector<Vec3> bad = big.positions;
    bad[11][1] = std::nan("");
    context.setPositions(bad);
    // (The CPU platform checks coordinates itself before any force runs, with its own message.)
    if (platform->getName() == "CPU")
        assertThrowsMentioning([&]() { context.getState(State::Forces); }, {"nan"});
    else
        assertThrowsMentioning([&]() { context.getState(State::Forces); }, {"particle 11", "not finite"});
}

/** A density at which the Tait equation of state overflows stops the evaluation with an error naming the particle
 *  and the step, instead of returning infinite energies and forces. */
void testEquationOfStateOverflow() {
    Scene scene = makeLatticeLiquid(5, referenceDensity, 0.2, GenDPDEForce::VB, true, 91);
    scene.force->setTaitParameters(1e-4*referenceDensity, 40.0, 70.0, 100.0);   // (n/n0)^99 ~ 1e396
    VerletIntegrator integrator(0.001);
    Context context(scene.system, integrator, *platform);
    context.setPositions(scene.positions);
    assertThrowsMentioning([&]() { context.getState(State::Energy); }, {"overflows", "particle 0", "step 0"});
}

/** A three-component mixture equals the brute force, which evaluates each particle with its own type's Tait law. */
void testMixtureAgainstBruteForce() {
    for (GenDPDEForce::DensityEstimator estimator : {GenDPDEForce::VA, GenDPDEForce::VB})
        for (bool periodic : {true, false}) {
            const std::string label = std::string("mixture ") + (estimator == GenDPDEForce::VA ? "VA" : "VB")
                                      + (periodic ? " periodic" : " open");
            Scene liquid = makeLatticeLiquid(6, referenceDensity, 0.15, estimator, periodic, 101);
            setMixtureTypes(liquid, false);
            checkAgainstBruteForce(liquid, label);
            Scene compressed = makeLatticeLiquid(7, 2.0*referenceDensity, 0.15, estimator, periodic, 102);
            setMixtureTypes(compressed, false);
            checkAgainstBruteForce(compressed, label + " compressed");
        }
}

/**
 * Types whose parameters all equal the force's give bit-identical energies, forces and observables to no types:
 * the types select table entries, they change no arithmetic. A mixture's energy and forces also are a sum over
 * its particles' own laws: swapping two types' parameters changes them (so the test can fail).
 */
void testIdenticalTypesAreBitwiseNoTypes() {
    for (GenDPDEForce::DensityEstimator estimator : {GenDPDEForce::VA, GenDPDEForce::VB}) {
        Scene plain = makeLatticeLiquid(6, referenceDensity, 0.15, estimator, true, 103);
        Scene typed = makeLatticeLiquid(6, referenceDensity, 0.15, estimator, true, 103);
        setMixtureTypes(typed, true);
        VerletIntegrator integrator1(0.001), integrator2(0.001);
        Context a(plain.system, integrator1, *platform), b(typed.system, integrator2, *platform);
        a.setPositions(plain.positions);
        b.setPositions(typed.positions);
        State sa = a.getState(State::Energy | State::Forces), sb = b.getState(State::Energy | State::Forces);
        ASSERT_EQUAL(sa.getPotentialEnergy(), sb.getPotentialEnergy());
        for (size_t i = 0; i < plain.positions.size(); i++)
            ASSERT(sa.getForces()[i] == sb.getForces()[i]);
        ASSERT(plain.force->getParticlePressures(a) == typed.force->getParticlePressures(b));
        ASSERT_EQUAL(plain.force->getVirial(a), typed.force->getVirial(b));
        // The same types with different parameters: a different energy.
        typed.force->setTypeParameters(0, 7, 1.3*referenceDensity, 10.0, 50.0, 7.0);
        typed.force->updateParametersInContext(b);
        ASSERT(std::abs(b.getState(State::Energy).getPotentialEnergy() - sa.getPotentialEnergy())
               > 1e-3*std::abs(sa.getPotentialEnergy()));
    }
}

/**
 * Per-type Tait parameters change through updateParametersInContext() (as a new Context would give them); the
 * particle types cannot, and an entry naming a type no particle has is refused when the Context is created or
 * updated, naming the type.
 */
void testTypesInContext() {
    Scene scene = makeLatticeLiquid(5, referenceDensity, 0.2, GenDPDEForce::VB, true, 104);
    setMixtureTypes(scene, false);
    VerletIntegrator integrator(0.001);
    Context context(scene.system, integrator, *platform);
    context.setPositions(scene.positions);
    scene.force->setTypeParameters(1, -3, 0.9*referenceDensity, 5.0, 90.0, 6.0);
    scene.force->updateParametersInContext(context);
    const double updated = context.getState(State::Energy).getPotentialEnergy();
    VerletIntegrator integrator2(0.001);
    Context fresh(scene.system, integrator2, *platform);
    fresh.setPositions(scene.positions);
    ASSERT_EQUAL_TOL(fresh.getState(State::Energy).getPotentialEnergy(), updated, 1e-14);
    scene.force->setParticleType(5, 7);   // was type 0
    assertThrowsMentioning([&]() { scene.force->updateParametersInContext(context); },
                           {"particle types", "reinitialize"});
    scene.force->setParticleType(5, 0);
    scene.force->addTypeParameters(12, referenceDensity, 1.0, 50.0, 6.0);
    assertThrowsMentioning([&]() { scene.force->updateParametersInContext(context); },
                           {"type parameters 2", "type 12", "no particle"});
    VerletIntegrator integrator3(0.001);
    assertThrowsMentioning([&]() { Context bad(scene.system, integrator3, *platform); }, {"type 12", "-3, 0, 7"});
    // A particle index beyond the System, at Context creation.
    Scene small = makeLatticeLiquid(5, referenceDensity, 0.2, GenDPDEForce::VB, true, 105);
    small.force->setParticleType(125, 1);
    VerletIntegrator integrator4(0.001);
    assertThrowsMentioning([&]() { Context bad(small.system, integrator4, *platform); },
                           {"particle 125", "125 particles"});
}

/** The type setters refuse bad values and duplicate entries, naming the entry, the parameter and the value. */
void testTypesBadInput() {
    GenDPDEForce force(1.0);
    force.addTypeParameters(4, 1.0, 0.0, 1.0, 2.0);
    assertThrowsMentioning([&]() { force.setParticleType(-1, 2); }, {"particle index", "-1", ">= 0"});
    assertThrowsMentioning([&]() { force.addTypeParameters(5, -1.0, 0.0, 1.0, 2.0); },
                           {"type 5", "reference density", "-1"});
    assertThrowsMentioning([&]() { force.addTypeParameters(5, 1.0, 0.0, 1.0, 0.5); }, {"type 5", "gamma_T", "0.5"});
    assertThrowsMentioning([&]() { force.addTypeParameters(4, 2.0, 0.0, 1.0, 2.0); }, {"type 4", "already", "entry 0"});
    assertThrowsMentioning([&]() { force.setTypeParameters(1, 4, 2.0, 0.0, 1.0, 2.0); },
                           {"type parameters index", "= 1", "[0, 0]"});
    int type;
    double values[4];
    assertThrowsMentioning([&]() { force.getTypeParameters(-2, type, values[0], values[1], values[2], values[3]); },
                           {"index", "-2"});
    ASSERT_EQUAL(1, force.getNumTypeParameters());
    force.getTypeParameters(0, type, values[0], values[1], values[2], values[3]);
    ASSERT(type == 4 && values[0] == 1.0 && values[3] == 2.0);
}

/**
 * VC's energy, volumes, densities and pressures equal the independent brute-force evaluation (which computes the
 * moments g_i over every image and applies the factor of docs/interfaces.md itself), and its forces and virial are
 * the exact derivatives of its energy (finite differences, as for VA and VB), on the standard scenes: liquids,
 * compressed liquids, open boundaries (free surfaces, where the factor matters), dimers and a dilute gas with
 * isolated particles.
 */
void testVCAgainstBruteForceAndFiniteDifferences() {
    forEachStandardScene(0.15, 111, [](Scene& scene, const std::string& label) {
        if (label.compare(0, 2, "VB") != 0)
            return;
        scene.force->setDensityEstimator(GenDPDEForce::VC);
        scene.force->setCutoffScaling(1.35);
        const std::string vc = "VC" + label.substr(2);
        VerletIntegrator integrator(0.001);
        Context context(scene.system, integrator, *platform);
        context.setPositions(scene.positions);
        const BruteForce::Result expected = BruteForce::evaluate(bruteForceModel(scene), scene.positions);
        // Float forces: as checkAgainstBruteForce (densities ~1e-6 relative, the Tait power x6), and the surface
        // factor depends on a^2 = c^2 |g|^2/(n0^2 + eps^2), whose relative error (2e-6, from n0^2) the factor's
        // elasticity a^2 factor'/factor (at most 2.2, at a^2 = 0.54) carries into V: 6 (1e-6 + 2.2 x 2e-6) ~ 3e-5,
        // hence 5e-5.
        const double relative = precisionTolerance(1e-10, 5e-5);
        assertRelative(expected.energy, context.getState(State::Energy).getPotentialEnergy(), relative,
                       vc + " energy");
        const std::vector<double> volumes = scene.force->getParticleVolumes(context);
        const std::vector<double> pressures = scene.force->getParticlePressures(context);
        for (size_t i = 0; i < volumes.size(); i++) {
            assertRelative(expected.volume[i], volumes[i], relative, vc + " V_i");
            assertClose(expected.pressure[i], pressures[i],
                        relative*std::max(scene.force->getBulkModulus(), std::abs(expected.pressure[i])), vc + " pi_i");
        }
        // VC's factor bends sharply above its threshold in a dilute gas (its curvature in a^2 is 2 alpha/w^2 = 67):
        // a step of 2.5e-5 nm keeps the central difference's truncation error below the tolerance (at 1e-4 nm it
        // reaches 3e-5 of a 2000 kJ/mol/nm force there). With float forces no step resolves the derivative
        // (testFiniteDifferences says why): there the brute force above checks the formulas.
        if (!floatForces())
            checkFiniteDifferences(scene, vc, 2.5e-5);
    });
    // A free surface: the outer layer of an open lattice liquid gets a larger volume than with VB.
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
    ASSERT(vc[0]/vb[0] > 2.0);
    ASSERT(vc[129]/vb[129] < 1.2);
}

void runForceTests() {
    testVCAgainstBruteForceAndFiniteDifferences();
    testTypesBadInput();
    testMixtureAgainstBruteForce();
    testIdenticalTypesAreBitwiseNoTypes();
    testTypesInContext();
    testBadInput();
    testEquationOfStateOverflow();
    testAgainstBruteForce();
    testTriclinicBox();
    testTaitExponents();
    testFiniteDifferences();
    testSymmetries();
    testVirial();
    testCoincidentParticles();
    testIsolatedParticle();
    testEnergyOnlyAndForceGroups();
    testUpdateParametersInContext();
    testMovingParticles();
    testHistoryIndependence();
}

} // namespace ForceTests
