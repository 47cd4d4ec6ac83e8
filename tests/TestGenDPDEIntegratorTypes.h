/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
/* GenDPDEIntegrator tests (included by TestGenDPDEIntegrator.h): particle types (docs/types.md): per-type heat
 * capacities and per-pair friction and conduction, where the types come from, and their bad input. */

namespace IntegratorTests {

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
    integrator.addTypeHeatCapacity(7, sameAsDefaults ? c : 3 * c);
    integrator.addTypeHeatCapacity(-3, sameAsDefaults ? c : 0.5 * c);
    integrator.addTypePair(7, -3, sameAsDefaults ? g : 2 * g, sameAsDefaults ? k : 0.5 * k);
    integrator.addTypePair(7, 7, sameAsDefaults ? g : 0.5 * g, sameAsDefaults ? k : 3 * k);
    integrator.addTypePair(-3, 0, sameAsDefaults ? g : 0.0, sameAsDefaults ? k : 2 * k);
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
        temperatures[i] = temperature * (0.8 + 0.4 * ((i * 37) % n) / n);
    run.integrator.setParticleTemperatures(temperatures);
    Context& context = run.start();
    const std::vector<double> energies = run.integrator.getInternalEnergies();
    for (int i : {0, 1, 2, 30, 31, 32}) {
        const double capacity = heatCapacity * (i % 3 == 0 ? 3.0 : i % 3 == 1 ? 0.5 : 1.0);
        assertRelative(capacity * temperatures[i], energies[i], 1e-15, "eps_i = C_V(type) theta_i");
    }
    Vec3 before;
    for (int i = 0; i < n; i++)
        before += context.getState(State::Velocities).getVelocities()[i] * particleMass;
    run.integrator.step(1000);
    Vec3 after;
    State state = context.getState(State::Velocities);
    double scale = 0;
    for (int i = 0; i < n; i++) {
        after += state.getVelocities()[i] * particleMass;
        scale += particleMass * std::sqrt(state.getVelocities()[i].dot(state.getVelocities()[i]));
    }
    assertVectorClose(before, after, precisionTolerance(1e-10, 1e-6) * scale, "mixture: total momentum");

    System free;
    for (int i = 0; i < n; i++)
        free.addParticle(particleMass);
    GenDPDEIntegrator integrator(stepSize, friction, heatConduction, heatCapacity);
    integrator.setCutoffDistance(cutoff);
    integrator.setRandomNumberSeed(6);   // fixed: with a seed drawn per run, 1 run in ~80 met an eps <= 0
    setMixtureTypes(integrator, n, false);
    integrator.setParticleTemperatures(temperatures);
    Context freeContext(free, integrator, *platform);
    freeContext.setPositions(run.scene.positions);
    freeContext.setVelocitiesToTemperature(3 * temperature, 7);
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
    const double spacing = std::cbrt(1.0 / referenceDensity);
    System system;
    std::vector<Vec3> positions;
    std::vector<int> material;
    for (int x = 0; x < side; x++)
        for (int y = 0; y < side; y++)
            for (int z = 0; z < side; z++) {
                system.addParticle(particleMass);
                positions.push_back(Vec3((x - side / 2 + 0.5) * spacing, y * spacing, z * spacing));
                material.push_back(x < side / 2 ? 1 : 2);
            }
    const int n = positions.size();
    const double kappa = 40.0 / stepSize;   // kappa dt = 40 kJ K/mol
    const double capacityA = 4000 * boltzmann, capacityB = 1000 * boltzmann;
    GenDPDEIntegrator integrator(stepSize, 0.0, 0.25 * kappa, capacityB);
    integrator.setCutoffDistance(cutoff);
    integrator.setRandomNumberSeed(41);
    std::vector<double> initialTemperatures;
    for (int i = 0; i < n; i++) {
        integrator.setParticleType(i, material[i]);
        initialTemperatures.push_back(material[i] == 1 ? 300.0 : 75.0);
    }
    integrator.addTypeHeatCapacity(1, capacityA);
    integrator.addTypePair(1, 2, 0.0, kappa);
    integrator.addTypePair(1, 1, 0.0, 3 * kappa);
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
                    omega2.push_back((1 - r / cutoff) * (1 - r / cutoff));
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
            expected += kappa * omega2[p] * (capacityA / e[i] - capacityB / e[j]) * stepSize;
            variance += 2 * boltzmann * kappa * omega2[p] * stepSize;
        }
        integrator.step(1);
    }
    const double measured = energyOfA() - initialA;
    ASSERT(expected < -20 * std::sqrt(variance));   // the test is sensitive: the flux is far above the noise
    assertClose(expected, measured, 4 * std::sqrt(variance), "heat gained by material A over 400 steps");
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
}

/**
 * The integrator's tables are by class (GenDPDETypes.h): 4000 types without entries are one class, the size of the
 * tables of one type; entries give their types classes of their own, and every lookup of a pair of types returns the
 * entry's value or the integrator's.
 */
void testTablesByClass() {
    const int numParticles = 4000;
    std::map<int, int> typeOfParticle;
    for (int i = 0; i < numParticles; i++)
        typeOfParticle[i] = 10 * i - 3;   // 4000 distinct types
    const ParticleTypeIndex types(typeOfParticle, numParticles, "GenDPDEIntegrator");
    GenDPDEIntegrator integrator(0.001, 2.0, 3.0, 4.0);
    TypePairTable table = typePairTable(integrator, types);
    ASSERT_EQUAL(1, table.numClasses);
    ASSERT_EQUAL(1, (int) table.friction.size());
    ASSERT_EQUAL(1, (int) table.heatCapacity.size());
    integrator.addTypeHeatCapacity(47, 5.0);          // particle 5
    integrator.addTypePair(97, 47, 6.0, 7.0);         // particles 10 and 5
    table = typePairTable(integrator, types);
    ASSERT_EQUAL(3, table.numClasses);
    ASSERT_EQUAL(9, (int) table.friction.size());
    const std::vector<int>& index = types.getParticleTypeIndices();
    auto pairValue = [&](const std::vector<double>& values, int i, int j) {
        return values[table.classOf(index[i]) * table.numClasses + table.classOf(index[j])];
    };
    for (int i : {0, 5, 10, 3999})
        for (int j : {0, 5, 10, 3999}) {
            const bool entry = (i == 5 && j == 10) || (i == 10 && j == 5);
            ASSERT_EQUAL(entry ? 6.0 : 2.0, pairValue(table.friction, i, j));
            ASSERT_EQUAL(entry ? 7.0 : 3.0, pairValue(table.heatConduction, i, j));
        }
    const std::vector<double> capacity = particleHeatCapacities(table, types);
    ASSERT(capacity[5] == 5.0 && capacity[10] == 4.0 && capacity[0] == 4.0 && capacity[3999] == 4.0);
}

/**
 * Types after the Context exists (docs/types.md, "Changing types"): they are read when the Context is created, so an
 * entry naming a type no particle of the Context has is refused when added (nothing changes), and a step is refused
 * while a particle's type differs from the Context's (nothing moves), until it is set back or the Context is
 * reinitialized (setting the type a particle runs with, here the force's, is no change); an entry for a type the
 * Context has takes effect at the next step, as if it had been there from the start (bit for bit: same seed, same pairs; the tables by class grow from one class to three).
 */
void testTypeChangesAfterTheContext() {
    Run later(4, 15);
    later.start();
    assertThrowsMentioning([&]() { later.integrator.addTypeHeatCapacity(9, 1.0); },
                           {"type heat capacity 0", "type 9", "no particle of the Context", "its types are 0"});
    assertThrowsMentioning([&]() { later.integrator.addTypePair(0, 9, 1.0, 1.0); }, {"type pair 0", "type 9"});
    ASSERT_EQUAL(0, later.integrator.getNumTypeHeatCapacities());
    ASSERT_EQUAL(0, later.integrator.getNumTypePairs());
    later.integrator.step(1);   // nothing was added: the run goes on

    const std::vector<Vec3> before = later.context->getState(State::Positions).getPositions();
    later.integrator.setParticleType(5, 3);
    assertThrowsMentioning([&]() { later.integrator.step(1); },
                           {"particle 5", "changed to 3", "runs with type 0", "reinitialize"});
    const std::vector<Vec3> after = later.context->getState(State::Positions).getPositions();
    ASSERT(before == after);
    later.integrator.setParticleType(5, 0);   // set back: the run goes on
    later.integrator.step(1);
    later.integrator.setParticleType(5, 3);
    later.context->reinitialize(true);        // applied: the entry for type 3 is now one the Context has
    later.integrator.addTypeHeatCapacity(3, 2 * heatCapacity);
    later.integrator.step(1);

    // An entry for types the Context has, added after it was created, against the same entry from the start.
    Run first(4, 16), added(4, 16);
    for (Run* run : {&first, &added})
        setMixtureTypes(run->scene, false);   // types 7, -3, 0 on the force, which the integrator takes
    first.integrator.addTypePair(7, -3, 3 * friction, 0.25 * heatConduction);
    first.start();
    added.start();
    added.integrator.addTypePair(7, -3, 3 * friction, 0.25 * heatConduction);
    added.integrator.setParticleType(0, 7);   // the type particle 0 runs with (the force's): not a change
    first.integrator.step(30);
    added.integrator.step(30);
    assertStatesIdentical(*first.context, *added.context, first.integrator, added.integrator,
                          "a type pair added after the Context was created");
}

/**
 * A particle's type is one setting (GenDPDEIntegratorUtilities::particleTypes): the integrator takes the types of the
 * System's GenDPDEForce when it sets none (then its per-type heat capacities apply to them, and the run is the run
 * with the same types set on both, bit for bit), and a Context whose integrator and force (or two forces) give a
 * particle different types is refused, naming the particle and both types.
 */
void testParticleTypesFromTheForce() {
    Run both(4, 16), taken(4, 16);
    setMixtureTypes(both.scene, false);
    setMixtureTypes(both.integrator, both.scene.system.getNumParticles(), false);
    // The same entries, but the types only on the force.
    setMixtureTypes(taken.scene, false);
    taken.integrator.addTypeHeatCapacity(7, 3 * heatCapacity);
    taken.integrator.addTypeHeatCapacity(-3, 0.5 * heatCapacity);
    taken.integrator.addTypePair(7, -3, 2 * friction, 0.5 * heatConduction);
    taken.integrator.addTypePair(7, 7, 0.5 * friction, 3 * heatConduction);
    taken.integrator.addTypePair(-3, 0, 0.0, 2 * heatConduction);
    both.start();
    taken.start();
    // Every particle starts at the bath temperature: eps_i = C_V(type) T with the force's types.
    const std::vector<double> eps = taken.integrator.getInternalEnergies();
    for (int i : {0, 1, 2, 30, 31, 32})
        assertRelative((i % 3 == 0           ? 3.0
                                : i % 3 == 1 ? 0.5
                                             : 1.0)
                               * heatCapacity * temperature,
                       eps[i], 1e-15, "the force's types select the integrator's heat capacities");
    both.integrator.step(50);
    taken.integrator.step(50);
    assertStatesIdentical(*both.context, *taken.context, both.integrator, taken.integrator,
                          "types taken from the force");
    // Different types for one particle: refused, naming it.
    Run mismatch(4, 17);
    setMixtureTypes(mismatch.scene, false);
    setMixtureTypes(mismatch.integrator, mismatch.scene.system.getNumParticles(), false);
    mismatch.integrator.setParticleType(4, 7);   // type -3 on the force
    assertThrowsMentioning([&]() { mismatch.start(); }, {"particle 4", "type 7", "type -3", "GenDPDEForce"});
    Run twoForces(4, 18);
    twoForces.scene.force->setParticleType(3, 1);
    GenDPDEForce* second = new GenDPDEForce(cutoff);
    second->setParticleType(3, 2);
    second->setForceGroup(1);
    twoForces.scene.system.addForce(second);
    assertThrowsMentioning([&]() { twoForces.start(); }, {"particle 3", "type 1", "type 2", "force 1"});
}

} // namespace IntegratorTests
