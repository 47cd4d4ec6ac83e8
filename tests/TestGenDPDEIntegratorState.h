/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
/* The state rules of GenDPDEIntegrator, shared by every platform (a platform file defines `platform` and calls
 * runIntegratorStateTests()): one Context per integrator, the bath temperature apart from the particles' state,
 * checkpoints and States validated before anything changes, and simulations that go bad stopped with an error
 * naming the particle and the step. */

#include "TestGenDPDEIntegrator.h"
#include "gendpde/CounterRandom.h"
#include "openmm/serialization/XmlSerializer.h"
#include <cstdint>
#include <cstring>
#include <limits>
#include <sstream>
#include <string>

namespace IntegratorStateTests {

using namespace IntegratorTests;

/** A second Context is refused ("already bound", as OpenMM's integrators say); the first one keeps working. */
void testOneContextPerIntegrator() {
    Run run(4, 31);
    Context& first = run.start();
    assertThrowsMentioning([&]() { Context second(run.scene.system, run.integrator, *platform); },
                           {"already bound to a context"});
    run.integrator.step(2);
    ASSERT_EQUAL(2, first.getStepCount());
    first.reinitialize(true);   // the same Context may reinitialize
    run.integrator.step(1);
}

/** setTemperature() changes the bath only; the particles' state changes only through the calls that set it. */
void testBathTemperatureKeepsTheParticlesState() {
    Run run(4, 32);
    Context& context = run.start();
    run.integrator.step(5);
    const std::vector<double> energies = run.integrator.getInternalEnergies();
    run.integrator.setTemperature(2.0 * temperature);
    ASSERT(energies == run.integrator.getInternalEnergies());
    ASSERT_EQUAL(2.0 * temperature, run.integrator.getTemperature());
    std::vector<double> temperatures(context.getSystem().getNumParticles(), 1.5 * temperature);
    run.integrator.setParticleTemperatures(temperatures);
    assertRelative(1.5 * temperature * heatCapacity, run.integrator.getInternalEnergies()[7], 1e-15,
                   "eps after setting");

    // Before a Context: the configured temperatures are reported; the uniform start is explained, not invented.
    GenDPDEIntegrator unbound(stepSize, friction, heatConduction, heatCapacity);
    assertThrowsMentioning([&]() { unbound.getParticleTemperatures(); }, {"none are set"});
    unbound.setTemperature(300.0);
    assertThrowsMentioning([&]() { unbound.getParticleTemperatures(); }, {"bath temperature", "300 K"});
    unbound.setParticleTemperatures({310.0, 320.0});
    ASSERT(unbound.getParticleTemperatures() == std::vector<double>({310.0, 320.0}));
    assertRelative(320.0 * heatCapacity, unbound.getInternalEnergies()[1], 1e-15, "eps before a Context");
}

/** The integrator's XML holds its parameters and the configured initial temperatures, never a Context's state. */
void testSerializationHoldsNoLiveState() {
    Run run(4, 33);
    run.integrator.setParticleTemperatures(std::vector<double>(run.scene.system.getNumParticles(), temperature));
    run.start();
    run.integrator.step(3);
    std::vector<double> live(run.scene.system.getNumParticles(), 3.0 * temperature);
    run.integrator.setParticleTemperatures(live);
    std::stringstream buffer;
    XmlSerializer::serialize<GenDPDEIntegrator>(&run.integrator, "Integrator", buffer);
    std::unique_ptr<GenDPDEIntegrator> copy(XmlSerializer::deserialize<GenDPDEIntegrator>(buffer));
    const std::vector<double> configured = copy->getParticleTemperatures();
    ASSERT_EQUAL((int) live.size(), (int) configured.size());
    for (double t : configured)
        ASSERT_EQUAL(temperature, t);   // the initial condition, not the 3 T0 of the running Context
}

/**
 * The integrator's data in a checkpoint of version 4 (docs/integrator.md) whose sweep order is built: the end of the
 * stream, magic, version, seed, count, energies, the build (flag 1, box, positions), coverage, checksum (FNV-1a, 64
 * bits), magic. Written again here to make checkpoints that are well formed but say something else.
 */
struct CheckpointTail {
    static const size_t header = 4 * sizeof(std::int32_t);   // magic, version, seed, count
    static const size_t trailer = sizeof(std::int32_t) + sizeof(std::uint64_t) + sizeof(std::int32_t);
    size_t start;   // where the integrator's data begins
    int numParticles;
    static size_t buildBytes(int numParticles) {
        return sizeof(std::int32_t) + (9 + 3 * numParticles) * sizeof(double);
    }
    CheckpointTail(const std::string& bytes, int numParticles) :
            start(bytes.size() - header - numParticles * sizeof(double) - buildBytes(numParticles) - trailer),
            numParticles(numParticles) {}
    size_t energiesAt() const { return start + header; }
    size_t buildAt() const { return energiesAt() + numParticles * sizeof(double); }
    /** Where the build's position of particle i begins (after the flag and the box). */
    size_t buildPositionAt(int i) const { return buildAt() + sizeof(std::int32_t) + (9 + 3 * i) * sizeof(double); }
    size_t coverageAt() const { return buildAt() + buildBytes(numParticles); }
    /** FNV-1a (64 bits) of bytes[from, to), continuing from hash. */
    static std::uint64_t hashOf(const std::string& bytes, size_t from, size_t to,
                                std::uint64_t hash = 14695981039346656037ULL) {
        for (size_t i = from; i < to; i++) {
            hash ^= (unsigned char) bytes[i];
            hash *= 1099511628211ULL;
        }
        return hash;
    }
    /** The checkpoint with its checksum computed again over what it now holds (its coverage word must be 0 or 1). */
    std::string resealed(std::string bytes) const {
        std::int32_t coverage;
        std::memcpy(&coverage, &bytes[coverageAt()], sizeof(coverage));
        std::uint64_t hash = hashOf(bytes, 0, coverage == 1 ? start : 0); // OpenMM's part: all before the integrator's
        hash = hashOf(bytes, start, coverageAt() + sizeof(std::int32_t), hash);
        std::memcpy(&bytes[coverageAt() + sizeof(std::int32_t)], &hash, sizeof(hash));
        return bytes;
    }
};

/**
 * A checkpoint with its last bytes missing, or bytes appended, or any one byte changed, or written by another
 * integrator, or holding a bad internal energy, is refused and leaves the integrator's state (seed, internal
 * energies) untouched. A checkpoint written to a string stream covers OpenMM's part too. Versions 1 and 2 (no
 * checksum) are refused; version 3 is read.
 */
void testCheckpointsAreValidated() {
    Run run(4, 34);
    Context& context = run.start();
    run.integrator.step(3);
    std::stringstream good;
    context.createCheckpoint(good);
    const std::string bytes = good.str();
    const int numParticles = context.getSystem().getNumParticles();
    const CheckpointTail tail(bytes, numParticles);
    ASSERT_EQUAL(1, *(const std::int32_t*) &bytes[tail.coverageAt()]); // a string stream: OpenMM's part covered
    run.integrator.step(2);
    const std::vector<double> energies = run.integrator.getInternalEnergies();
    const int seed = run.integrator.getSeedInUse();
    auto untouched = [&](const std::string& what) {
        if (run.integrator.getInternalEnergies() != energies || run.integrator.getSeedInUse() != seed)
            throw std::runtime_error(what + ": the integrator's state changed");
    };
    auto refused = [&](const std::string& checkpoint, const std::vector<std::string>& words, const std::string& what) {
        std::stringstream stream(checkpoint);
        assertThrowsMentioning([&]() { context.loadCheckpoint(stream); }, words);
        untouched(what);
    };
    for (size_t missing : {1, 4, 8, 12, 100})
        refused(bytes.substr(0, bytes.size() - missing), {"GenDPDEIntegrator", "checkpoint"}, "truncated checkpoint");
    refused(bytes + std::string(1000, '\0'), {"continues after its end"}, "1000 zero bytes appended");
    refused(bytes + "x", {"continues after its end"}, "one byte appended");
    // Any one byte changed: every byte of the integrator's data and, on the host platforms, every 7th of OpenMM's part.
    // (OpenMM reads its part first, with its own reader: the GPU platforms' reader may crash on some damaged bytes,
    // e.g. an atom order, before this plugin sees the checkpoint.)
    const bool hostPlatform = (platform->getName() == "Reference" || platform->getName() == "CPU");
    for (size_t i = hostPlatform ? 0 : tail.start; i < bytes.size(); i += (i >= tail.start ? 1 : 7)) {
        std::string flipped = bytes;
        flipped[i] ^= 0x10;
        std::stringstream stream(flipped);
        bool threw = false;
        try {
            context.loadCheckpoint(stream);
        } catch (const std::exception&) { // (OpenMM's own part may fail otherwise, e.g. a garbage string length)
            threw = true;
        }
        if (!threw)
            throw std::runtime_error("a checkpoint with byte " + std::to_string(i) + " of "
                                     + std::to_string(bytes.size()) + " changed was accepted");
        untouched("a changed byte");
    }
    // Well formed, checksum and all, but with a bad internal energy.
    for (double bad : {std::nan(""), -1.0, 0.0, 1e300}) {
        std::string corrupt = bytes;
        std::memcpy(&corrupt[tail.energiesAt() + 5 * sizeof(double)], &bad, sizeof(double));
        refused(tail.resealed(corrupt), {"corrupt", "particle 5"}, "corrupt internal energy");
    }
    // ... or a position of the sweep order's build that is not finite.
    for (double bad : {std::nan(""), std::numeric_limits<double>::infinity()}) {
        std::string corrupt = bytes;
        std::memcpy(&corrupt[tail.buildPositionAt(3) + sizeof(double)], &bad, sizeof(double));
        refused(tail.resealed(corrupt), {"corrupt", "sweep order's build", "not finite"}, "corrupt build position");
    }
    {
        std::string corrupt = bytes;
        const std::int32_t flag = 2;
        std::memcpy(&corrupt[tail.buildAt()], &flag, sizeof(flag));
        refused(corrupt, {"corrupt", "build flag is 2"}, "corrupt build flag");
    }
    {
        std::string future = bytes;
        const std::int32_t version = 9;
        std::memcpy(&future[tail.start + sizeof(std::int32_t)], &version, sizeof(version));
        refused(future, {"version 9"}, "future version");
    }
    // A checkpoint of the same System made with VerletIntegrator holds no integrator data at all.
    VerletIntegrator verlet(stepSize);
    Context other(run.scene.system, verlet, *platform);
    other.setPositions(run.scene.positions);
    std::stringstream foreign;
    other.createCheckpoint(foreign);
    refused(foreign.str(), {"GenDPDEIntegrator"}, "another integrator's checkpoint");
    // Version 3 (magic, version, seed, count, energies, coverage, checksum, magic: no build) is still read. Version 2
    // (magic, version, seed, count, energies, magic; no checksum) and version 1 (0.1.x: version, seed, a flag byte,
    // count, energies) are refused, named: without a checksum, an internal energy 16 times too large (a damaged
    // byte) would be read as a valid state. A refused checkpoint stops the run; the good one below goes on.
    const std::string openmmPart = bytes.substr(0, tail.start);
    const std::string energyBytes = bytes.substr(tail.energiesAt(), numParticles * sizeof(double));
    const std::int32_t magic = *(const std::int32_t*) &bytes[tail.start], count = numParticles;
    for (std::int32_t version : {1, 2, 3}) {
        const std::int32_t olderSeed = 4240 + version;
        std::string older = openmmPart;
        if (version >= 2)
            older.append((const char*) &magic, sizeof(magic));
        older.append((const char*) &version, sizeof(version));
        older.append((const char*) &olderSeed, sizeof(olderSeed));
        if (version == 1)
            older.push_back(1);
        older.append((const char*) &count, sizeof(count));
        older.append(energyBytes);
        if (version == 3) {
            const std::int32_t coverage = 0; // the integrator's data only
            older.append((const char*) &coverage, sizeof(coverage));
            const std::uint64_t hash = CheckpointTail::hashOf(older, openmmPart.size(), older.size());
            older.append((const char*) &hash, sizeof(hash));
        }
        if (version >= 2)
            older.append((const char*) &magic, sizeof(magic));
        std::stringstream olderStream(older);
        if (version == 3) {
            context.loadCheckpoint(olderStream);
            ASSERT_EQUAL(olderSeed, run.integrator.getSeedInUse());
        } else
            assertThrowsMentioning([&]() { context.loadCheckpoint(olderStream); },
                                   {"version " + std::to_string(version), "no checksum", "saveState"});
    }
    std::stringstream reload(bytes);
    context.loadCheckpoint(reload);
    ASSERT_EQUAL(seed, run.integrator.getSeedInUse());
}

/** A State's integrator parameters are validated the same way: unknown versions, garbage, bad values, wrong count. */
void testStatesAreValidated() {
    Run run(4, 35);
    Context& context = run.start();
    run.integrator.step(2);
    const State saved = context.getState(State::Positions | State::Velocities | State::IntegratorParameters);
    std::stringstream buffer;
    XmlSerializer::serialize<State>(&saved, "State", buffer);
    const std::string xml = buffer.str();
    const std::vector<double> energies = run.integrator.getInternalEnergies();
    auto load = [&](const std::string& text) {
        std::stringstream stream(text);
        std::unique_ptr<State> state(XmlSerializer::deserialize<State>(stream));
        context.setState(*state);
    };
    auto replaced = [&](const std::string& from, const std::string& to) {
        std::string text = xml;
        const size_t at = text.find(from);
        if (at == std::string::npos)
            throw std::runtime_error("test setup: '" + from + "' not in the State XML");
        return text.replace(at, from.size(), to);
    };
    const size_t start = xml.find("internalEnergies=\"") + 18;
    const std::string firstValue = xml.substr(start, xml.find(' ', start) - start);
    const std::vector<std::pair<std::string, std::vector<std::string>>> cases = {
            {replaced("GenDPDEIntegratorVersion=\"3\"", "GenDPDEIntegratorVersion=\"9\""), {"version 9"}},
            {replaced(firstValue + " ", firstValue + " garbage "), {"'garbage'", "not a number"}},
            {replaced(firstValue + " ", "nan "), {"corrupt", "particle 0"}},
            {replaced(firstValue + " ", "-0x1p+0 "), {"corrupt", "particle 0", "-1"}},
            {replaced(firstValue + " ", ""), {"internal energies", "System has 64"}},
            {replaced("seedInUse", "seedNotUsed"), {"does not hold GenDPDEIntegrator parameters"}},
    };
    for (const auto& c : cases) {
        assertThrowsMentioning([&]() { load(c.first); }, c.second);
        ASSERT(energies == run.integrator.getInternalEnergies());
    }
    load(xml);
}

/** A step size far too large blows a simulation up: the step that would move a particle farther than the pair range
 *  is refused before anything changes, naming the particle and the step, in every mode. */
void testBlownUpStepIsRefused() {
    for (GenDPDEIntegrator::Mode mode :
         {GenDPDEIntegrator::Isothermal, GenDPDEIntegrator::Conservative, GenDPDEIntegrator::Isoenergetic}) {
        Run run(4, 36);
        run.integrator.setMode(mode);
        Context& context = run.start();
        std::vector<Vec3> velocities = context.getState(State::Velocities).getVelocities();
        velocities[21] = Vec3(2.0 * cutoff / stepSize, 0, 0); // a particle that has been kicked out of control
        context.setVelocities(velocities);
        const State before = context.getState(State::Positions | State::Velocities);
        assertThrowsMentioning([&]() { run.integrator.step(1); }, {"particle 21", "step 0", "unstable"});
        const State after = context.getState(State::Positions | State::Velocities);
        for (int i = 0; i < context.getSystem().getNumParticles(); i++) {
            ASSERT(before.getPositions()[i] == after.getPositions()[i]);
            ASSERT(before.getVelocities()[i] == after.getVelocities()[i]);
        }
        ASSERT_EQUAL(0, context.getStepCount());
    }
}

/**
 * One message per event, the same words on every platform: a force that is not finite (another Force's, here a
 * CustomExternalForce whose parameter is NaN; the GPU platforms see it through their fixed-point forces) stops the
 * step before anything changes, naming the particle and the step; a position that is not finite (set by the user;
 * OpenMM's own checks name neither particle nor step) is refused when set, naming the particle, and no step starts.
 */
void testNonFiniteValuesAreNamedAlike() {
    {
        Run run(4, 42);
        CustomExternalForce* bad = new CustomExternalForce("a*x");
        bad->addGlobalParameter("a", std::nan(""));
        bad->addParticle(7, {});
        run.scene.system.addForce(bad);
        run.start();
        assertThrowsMentioning([&]() { run.integrator.step(1); },
                               {"GenDPDEIntegrator: the force on particle 7 is not finite (nan, ",
                                "at step 0; the step was not applied"});
        ASSERT_EQUAL(0, (int) run.context->getStepCount());
    }
    {
        Run run(4, 43);
        Context& context = run.start();
        std::vector<Vec3> positions = run.scene.positions;
        positions[5] = Vec3(std::nan(""), 0, 0);
        assertThrowsMentioning([&]() { context.setPositions(positions); },
                               {"GenDPDEIntegrator: the position set for particle 5 is not finite (nan, 0, 0)"});
        assertThrowsMentioning([&]() { run.integrator.step(1); },
                               {"cannot step from the positions set", "particle 5 is not finite (nan, 0, 0)"});
        ASSERT_EQUAL(0, (int) context.getStepCount());
    }
}

/** What the integrator cannot run is refused when the Context is created, naming the particle. */
void testUnsupportedSystemsAreRefused() {
    Run sites(4, 37);
    sites.scene.system.setVirtualSite(4, new TwoParticleAverageSite(0, 1, 0.5, 0.5));
    sites.scene.system.setParticleMass(4, 0.0);
    assertThrowsMentioning([&]() { sites.start(); }, {"virtual sites", "particle 4"});
    Run negative(4, 38);
    negative.scene.system.setParticleMass(2, -200.0);
    assertThrowsMentioning([&]() { negative.start(); }, {"mass of particle 2", "-200"});
}

/** The integrator's own pair list is re-checked against the box at every step, and the error names the integrator. */
void testOwnCutoffCheckedWhenTheBoxChanges() {
    Run run(5, 39);
    System free;
    for (int i = 0; i < run.scene.system.getNumParticles(); i++)
        free.addParticle(particleMass);
    free.setDefaultPeriodicBoxVectors(run.scene.box[0], run.scene.box[1], run.scene.box[2]);
    free.addForce(new CustomExternalForce("0*periodicdistance(x, y, z, 0, 0, 0)")); // makes the System periodic
    GenDPDEIntegrator integrator(stepSize, friction, heatConduction, heatCapacity);
    integrator.setCutoffDistance(cutoff);
    integrator.setTemperature(temperature);
    Context context(free, integrator, *platform);
    context.setPositions(run.scene.positions);
    integrator.step(1);
    context.setPeriodicBoxVectors(Vec3(1.5 * cutoff, 0, 0), Vec3(0, 1.5 * cutoff, 0), Vec3(0, 0, 1.5 * cutoff));
    assertThrowsMentioning([&]() { integrator.step(1); }, {"GenDPDEIntegrator", "cutoff distance", "half"});
}

/**
 * The cutoff is read when the Context is created: a step after setCutoffDistance() changed it is refused (it was
 * accepted and ignored), naming both values; reinitialize() applies it, and setting it back lets the steps go on.
 */
void testCutoffChangeAfterTheContext() {
    Run run(5, 41);
    run.start();
    run.integrator.step(1);
    run.integrator.setCutoffDistance(0.9 * cutoff);
    assertThrowsMentioning([&]() { run.integrator.step(1); },
                           {"cutoff distance was changed to", "after the Context", "reinitialize"});
    ASSERT_EQUAL(1, (int) run.context->getStepCount());
    run.integrator.setCutoffDistance(0.0); // back to the Context's (the force's)
    run.integrator.step(1);
    run.integrator.setCutoffDistance(0.9 * cutoff);
    run.context->reinitialize(true);
    run.integrator.step(1);
    ASSERT_EQUAL(3, (int) run.context->getStepCount());
}

/** setInternalEnergiesToTemperature() is a pure function of (seed, particle): the same draw on every machine. */
void testInternalEnergyDrawIsReproducible() {
    Run run(4, 40);
    run.start();
    run.integrator.setInternalEnergiesToTemperature(temperature, 17);
    const std::vector<double> first = run.integrator.getInternalEnergies();
    run.integrator.setInternalEnergiesToTemperature(temperature, 17);
    ASSERT(first == run.integrator.getInternalEnergies());
    // Particle 3's value is that of its own stream, whatever the number of particles.
    CounterRandom::ParticleStream stream(17, 3);
    const double shape = heatCapacity / Physics::Boltzmann + 1.0;
    ASSERT_EQUAL(Physics::Boltzmann * temperature * stream.gamma(shape), first[3]);
    run.integrator.setInternalEnergiesToTemperature(temperature, 18);
    ASSERT(first != run.integrator.getInternalEnergies());
}

/** C_V of particle i under setMixtureTypes (type 7: 3 C_V, type -3: C_V/2, type 0: C_V), written out here. */
double mixtureHeatCapacity(int i) {
    return i % 3 == 0 ? 3.0 * heatCapacity : (i % 3 == 1 ? 0.5 * heatCapacity : heatCapacity);
}

/**
 * setInternalEnergies() with a Context: the values come back exactly, and they are the state that
 * setParticleTemperatures() gives for the temperatures theta_i = eps_i/C_V(type of i) (a mixture with three heat
 * capacities, the energies computed here from the temperatures): the same energies, and then the same trajectory,
 * bitwise. The Context survives a checkpoint round trip with them.
 */
void testSetInternalEnergiesLikeTemperatures() {
    Run byTemperature(4, 41), byEnergy(4, 41);
    const int n = byTemperature.scene.system.getNumParticles();
    for (Run* run : {&byTemperature, &byEnergy}) {
        setMixtureTypes(run->scene, false);
        setMixtureTypes(run->integrator, n, false);
        run->start();
        run->integrator.step(3);
    }
    std::vector<double> temperatures(n), energies(n);
    for (int i = 0; i < n; i++) {
        temperatures[i] = temperature * (0.8 + 0.4 * std::sin(0.37 * i) * std::sin(0.37 * i));
        energies[i] = mixtureHeatCapacity(i) * temperatures[i];
    }
    byTemperature.integrator.setParticleTemperatures(temperatures);
    byEnergy.integrator.setInternalEnergies(energies);
    ASSERT(byEnergy.integrator.getInternalEnergies() == energies);
    ASSERT(byTemperature.integrator.getInternalEnergies() == energies);
    const std::vector<double> theta = byEnergy.integrator.getParticleTemperatures();
    for (int i = 0; i < n; i++)
        assertRelative(temperatures[i], theta[i], 1e-15, "theta_i of particle " + std::to_string(i));
    byTemperature.integrator.step(20);
    byEnergy.integrator.step(20);
    assertStatesIdentical(*byTemperature.context, *byEnergy.context, byTemperature.integrator, byEnergy.integrator,
                          "after setParticleTemperatures and after setInternalEnergies");

    // A checkpoint holds what setInternalEnergies() set, exactly, into a Context that started elsewhere.
    byEnergy.integrator.setInternalEnergies(energies);
    std::stringstream checkpoint;
    byEnergy.context->createCheckpoint(checkpoint);
    byEnergy.integrator.setInternalEnergiesToTemperature(temperature, 5);
    ASSERT(byEnergy.integrator.getInternalEnergies() != energies);
    byEnergy.context->loadCheckpoint(checkpoint);
    ASSERT(byEnergy.integrator.getInternalEnergies() == energies);
}

/**
 * setInternalEnergies() before a Context: the initial condition, exactly, in place of temperatures set before (and
 * replaced by temperatures set after); the integrator's XML carries it.
 */
void testSetInternalEnergiesBeforeTheContext() {
    Run run(4, 42);
    const int n = run.scene.system.getNumParticles();
    std::vector<double> energies(n);
    for (int i = 0; i < n; i++)
        energies[i] = heatCapacity * temperature * (1.0 + 0.01 * i) + 1e-3 / 3.0;
    run.integrator.setParticleTemperatures(std::vector<double>(n, 2.0 * temperature));
    run.integrator.setInternalEnergies(energies);
    ASSERT(run.integrator.getInternalEnergies() == energies);
    const std::vector<double> theta = run.integrator.getParticleTemperatures();
    for (int i = 0; i < n; i++)
        assertRelative(energies[i] / heatCapacity, theta[i], 1e-15, "configured theta_i");
    std::stringstream buffer;
    XmlSerializer::serialize<GenDPDEIntegrator>(&run.integrator, "Integrator", buffer);
    std::unique_ptr<GenDPDEIntegrator> copy(XmlSerializer::deserialize<GenDPDEIntegrator>(buffer));
    ASSERT(copy->getInternalEnergies() == energies);
    run.start();
    ASSERT(run.integrator.getInternalEnergies() == energies);
    Context fromCopy(run.scene.system, *copy, *platform);
    ASSERT(copy->getInternalEnergies() == energies);

    // Temperatures set last replace the energies.
    GenDPDEIntegrator unbound(stepSize, friction, heatConduction, heatCapacity);
    unbound.setInternalEnergies(energies);
    unbound.setParticleTemperatures(std::vector<double>(n, 2.0 * temperature));
    Context context(run.scene.system, unbound, *platform);
    for (double e : unbound.getInternalEnergies())
        assertRelative(2.0 * temperature * heatCapacity, e, 1e-15, "eps_i after temperatures replaced energies");
}

/**
 * Bad input to setInternalEnergies() (an empty list, a wrong length, a value not finite or <= 0 or beyond the
 * range, the last particle's), before and after a Context exists, is refused with a message naming the parameter,
 * the particle, the value and the range, and changes nothing.
 */
void testSetInternalEnergiesRefusesBadInput() {
    Run run(4, 43);
    const int n = run.scene.system.getNumParticles();
    const std::vector<double> configured(n, heatCapacity * temperature);
    run.integrator.setInternalEnergies(configured);
    const std::string range = "[1e-100, 1e+100] kJ/mol";
    auto withLast = [&](double value) {
        std::vector<double> energies(n, 2.0 * heatCapacity * temperature);
        energies[n - 1] = value;
        return energies;
    };
    const std::string last = "internal energy of particle " + std::to_string(n - 1);
    const std::vector<std::pair<std::vector<double>, std::vector<std::string>>> cases = {
            {withLast(0.0), {last, "= 0 kJ/mol", range}},
            {withLast(-1.5), {last, "= -1.5 kJ/mol", range}},
            {withLast(std::nan("")), {last, "nan", range}},
            {withLast(INFINITY), {last, "inf", range}},
            {withLast(1e300), {last, "1e+300", range}},
            {{}, {"number of internal energies", "= 0", "one per particle"}},
    };
    for (bool bound : {false, true}) {
        if (bound) {
            run.start();
            run.integrator.step(2);
        }
        const std::vector<double> before = run.integrator.getInternalEnergies();
        for (const auto& c : cases) {
            assertThrowsMentioning([&]() { run.integrator.setInternalEnergies(c.first); }, c.second);
            ASSERT(run.integrator.getInternalEnergies() == before);
        }
        if (bound) {
            assertThrowsMentioning([&]() { run.integrator.setInternalEnergies(std::vector<double>(n + 1, 1.0)); },
                                   {"number of internal energies", std::to_string(n + 1), std::to_string(n)});
            ASSERT(run.integrator.getInternalEnergies() == before);
        }
    }
    // A wrong length before a Context is refused when the Context is created.
    GenDPDEIntegrator unbound(stepSize, friction, heatConduction, heatCapacity);
    unbound.setInternalEnergies({1.0, 2.0});
    assertThrowsMentioning([&]() { Context context(run.scene.system, unbound, *platform); },
                           {"number of internal energies", "= 2", std::to_string(n)});
}

void runIntegratorStateTests() {
    testOneContextPerIntegrator();
    testBathTemperatureKeepsTheParticlesState();
    testSerializationHoldsNoLiveState();
    testCheckpointsAreValidated();
    testStatesAreValidated();
    testBlownUpStepIsRefused();
    testUnsupportedSystemsAreRefused();
    testNonFiniteValuesAreNamedAlike();
    testCutoffChangeAfterTheContext();
    testOwnCutoffCheckedWhenTheBoxChanges();
    testInternalEnergyDrawIsReproducible();
    testSetInternalEnergiesLikeTemperatures();
    testSetInternalEnergiesBeforeTheContext();
    testSetInternalEnergiesRefusesBadInput();
}

} // namespace IntegratorStateTests
