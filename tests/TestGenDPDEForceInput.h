/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
/* GenDPDEForce tests (included by TestGenDPDEForce.h): bad input refused where it enters, and states that go bad
 * stopped with an error naming the particle and the step. */

namespace ForceTests {

/**
 * Every setter refuses values outside its documented range (docs/force.md), naming the parameter and the value, and
 * changes nothing.
 */
void testBadInput() {
    GenDPDEForce force(1.0);
    struct Case {
        std::function<void()> call;
        std::vector<std::string> fragments;
    };
    const std::vector<Case> cases = {
            {[]() { GenDPDEForce(-1.0); }, {"cutoff distance", "-1", "[0.001, 10000] nm"}},
            {[]() { GenDPDEForce(0.0); }, {"cutoff distance", "= 0 nm"}},
            {[]() { GenDPDEForce(1e-320); }, {"cutoff distance", "e-321"}}, // (subnormal: printed 9.99988867183e-321)
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
    assertThrowsMentioning([&]() { Context context(scene.system, integrator, *platform); },
                           {"cutoff distance", "half"});
    // ... and when the box shrinks later.
    Scene big = makeLatticeLiquid(6, referenceDensity, 0.0, GenDPDEForce::VB, true, 82);
    VerletIntegrator integrator2(0.001);
    Context context(big.system, integrator2, *platform);
    context.setPositions(big.positions);
    context.setPeriodicBoxVectors(Vec3(1.5 * cutoff, 0, 0), Vec3(0, 4, 0), Vec3(0, 0, 4));
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
    scene.force->setTaitParameters(1e-4 * referenceDensity, 40.0, 70.0, 100.0); // (n/n0)^99 ~ 1e396
    VerletIntegrator integrator(0.001);
    Context context(scene.system, integrator, *platform);
    context.setPositions(scene.positions);
    assertThrowsMentioning([&]() { context.getState(State::Energy); }, {"overflows", "particle 0", "step 0"});
}

} // namespace ForceTests
