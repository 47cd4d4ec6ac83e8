/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
/* GenDPDEForce tests (included by TestGenDPDEForce.h): particle types (docs/types.md), per-type Tait laws against
 * the brute force, their identities, their lifetime in a Context and their bad input. */

namespace ForceTests {

/** A three-component mixture equals the brute force, which evaluates each particle with its own type's Tait law. */
void testMixtureAgainstBruteForce() {
    for (GenDPDEForce::DensityEstimator estimator : testEstimators())
        for (bool periodic : {true, false}) {
            const std::string label = "mixture " + estimatorLabel(estimator) + (periodic ? " periodic" : " open");
            Scene liquid = makeLatticeLiquid(6, referenceDensity, 0.15, estimator, periodic, 101);
            setMixtureTypes(liquid, false);
            checkAgainstBruteForce(liquid, label);
            Scene compressed = makeLatticeLiquid(7, 2.0 * referenceDensity, 0.15, estimator, periodic, 102);
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
    for (GenDPDEForce::DensityEstimator estimator : testEstimators()) {
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
        typed.force->setTypeParameters(0, 7, 1.3 * referenceDensity, 10.0, 50.0, 7.0);
        typed.force->updateParametersInContext(b);
        ASSERT(std::abs(b.getState(State::Energy).getPotentialEnergy() - sa.getPotentialEnergy())
               > 1e-3 * std::abs(sa.getPotentialEnergy()));
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
    scene.force->setTypeParameters(1, -3, 0.9 * referenceDensity, 5.0, 90.0, 6.0);
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

} // namespace ForceTests
