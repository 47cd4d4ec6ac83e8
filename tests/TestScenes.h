/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
#ifndef GENDPDE_TEST_SCENES_H_
#define GENDPDE_TEST_SCENES_H_

/* Small liquid-argon-like Systems shared by the C++ tests (docs/theory.md section 9 in OpenMM units). */

#include "BruteForceGenDPDE.h"
#include "GenDPDEForce.h"
#include "internal/GenDPDEPhysics.h"
#include "internal/LiquidArgon.h"
#include "OpenMM.h"
#include <cmath>
#include <functional>
#include <random>
#include <string>
#include <vector>

namespace TestScenes {

using namespace GenDPDEPlugin;
using namespace OpenMM;


// Liquid argon (internal/LiquidArgon.h) at R* = 1.6839 in OpenMM units.
const double lengthUnit = LiquidArgon::length;                                   // nm
const double cutoff = LiquidArgon::getCutoff(1).cutoff * lengthUnit;               // nm
const double referenceDensity = LiquidArgon::density / (lengthUnit * lengthUnit * lengthUnit);   // nm^-3
const double particleMass = LiquidArgon::particleMass * 6.02214076e23 * 1000.0;     // amu

// The integrator tests' liquid argon: units, transport coefficients at R* = 1.6839, C_V, T0 and dt* = 0.01.
const double boltzmann = Physics::Boltzmann;                                           // kJ/(mol K)
const double energyUnit = LiquidArgon::energy * 6.02214076e23 / 1000.0;                    // u (kJ/mol)
const double timeUnit = lengthUnit * std::sqrt(particleMass / energyUnit);                 // L sqrt(m/u) (ps)
const double temperatureUnit = energyUnit / boltzmann;                                   // u/k_B (K)
const LiquidArgonCutoff argonCutoff = LiquidArgon::getCutoff(1);                       // R* = 1.6839
const double friction = argonCutoff.friction * particleMass / timeUnit;                    // gamma (amu/ps)
const double heatConduction = argonCutoff.heatConduction * energyUnit * temperatureUnit / timeUnit;   // kJ K/(mol ps)
const double heatCapacity = LiquidArgon::heatCapacity * boltzmann;                       // C_V (kJ/(mol K))
const double temperature = LiquidArgon::temperature * temperatureUnit;                   // T0 (K)
const double stepSize = 0.01 * timeUnit;                                                 // dt* = 0.01 (ps)

/** A System with only a GenDPDEForce, and positions. */
struct Scene {
    System system;
    GenDPDEForce* force;
    std::vector<Vec3> positions;
    Vec3 box[3];
};

inline Scene makeScene(int numParticles, GenDPDEForce::DensityEstimator estimator, bool periodic,
                       double cutoffScaling = 1.2) {
    Scene scene;
    scene.force = new GenDPDEForce(cutoff);
    scene.force->setDensityEstimator(estimator);
    scene.force->setCutoffScaling(cutoffScaling);
    scene.force->setNonbondedMethod(periodic ? GenDPDEForce::CutoffPeriodic : GenDPDEForce::CutoffNonPeriodic);
    for (int i = 0; i < numParticles; i++)
        scene.system.addParticle(particleMass);
    scene.system.addForce(scene.force);
    return scene;
}

inline void setBox(Scene& scene, Vec3 a, Vec3 b, Vec3 c) {
    scene.box[0] = a;
    scene.box[1] = b;
    scene.box[2] = c;
    scene.system.setDefaultPeriodicBoxVectors(a, b, c);
}

/** A cubic box at `density` (nm^-3) filled by a simple-cubic lattice with Gaussian jitter. */
inline Scene makeLatticeLiquid(int cellsPerSide, double density, double jitter,
                               GenDPDEForce::DensityEstimator estimator, bool periodic, unsigned seed) {
    int n = cellsPerSide * cellsPerSide * cellsPerSide;
    Scene scene = makeScene(n, estimator, periodic);
    double edge = std::cbrt(n / density), spacing = edge / cellsPerSide;
    setBox(scene, Vec3(edge, 0, 0), Vec3(0, edge, 0), Vec3(0, 0, edge));
    std::mt19937 random(seed);
    std::normal_distribution<double> gauss(0.0, jitter * spacing);
    for (int x = 0; x < cellsPerSide; x++)
        for (int y = 0; y < cellsPerSide; y++)
            for (int z = 0; z < cellsPerSide; z++)
                scene.positions.push_back(Vec3((x + 0.5) * spacing + gauss(random), (y + 0.5) * spacing + gauss(random),
                                               (z + 0.5) * spacing + gauss(random)));
    return scene;
}

/** Far-apart dimers of random length < cutoff: a dilute gas in which every particle still has a neighbor. */
inline Scene makeDimerGas(int numDimers, GenDPDEForce::DensityEstimator estimator, bool periodic, unsigned seed) {
    Scene scene = makeScene(2 * numDimers, estimator, periodic);
    int side = (int) std::ceil(std::cbrt((double) numDimers));
    double spacing = 2.5 * cutoff, edge = side * spacing;
    setBox(scene, Vec3(edge, 0, 0), Vec3(0, edge, 0), Vec3(0, 0, edge));
    std::mt19937 random(seed);
    std::uniform_real_distribution<double> uniform(0.0, 1.0);
    for (int d = 0; d < numDimers; d++) {
        Vec3 centre((d % side + 0.5) * spacing, ((d / side) % side + 0.5) * spacing,
                    (d / (side * side) + 0.5) * spacing);
        double cosTheta = 2 * uniform(random) - 1, phi = 2 * M_PI * uniform(random),
               half = 0.5 * cutoff * (0.1 + 0.85 * uniform(random));
        double sinTheta = std::sqrt(1 - cosTheta * cosTheta);
        Vec3 axis(sinTheta * std::cos(phi), sinTheta * std::sin(phi), cosTheta);
        scene.positions.push_back(centre + axis * half);
        scene.positions.push_back(centre - axis * half);
    }
    return scene;
}

/** Uniformly random positions at `density` (nm^-3): with VB some particles may have no neighbor at all. */
inline Scene makeRandomGas(int numParticles, double density, GenDPDEForce::DensityEstimator estimator, bool periodic,
                           unsigned seed) {
    Scene scene = makeScene(numParticles, estimator, periodic);
    double edge = std::cbrt(numParticles / density);
    setBox(scene, Vec3(edge, 0, 0), Vec3(0, edge, 0), Vec3(0, 0, edge));
    std::mt19937 random(seed);
    std::uniform_real_distribution<double> uniform(0.0, edge);
    for (int i = 0; i < numParticles; i++)
        scene.positions.push_back(Vec3(uniform(random), uniform(random), uniform(random)));
    return scene;
}

/** The brute-force oracle of a scene: its force's geometry and Tait parameters, per particle if it has types. */
inline BruteForce::Model bruteForceModel(const Scene& scene) {
    BruteForce::Model model;
    model.cutoff = scene.force->getCutoffDistance();
    model.estimator = scene.force->getDensityEstimator();
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
    model.backgroundPressure = scene.force->getBackgroundPressure();
    model.periodic = scene.force->usesPeriodicBoundaryConditions();
    for (int k = 0; k < 3; k++)
        model.box[k] = scene.box[k];
    return model;
}

/**
 * Give the particles of a scene three types in turn, 7, -3 and 0 (non-consecutive, one negative, one the default):
 * type 7 its own Tait parameters (denser, softer, gamma_T 7), type -3 others (a non-integer gamma_T, by pow()),
 * type 0 the force's. With `sameAsForce`, both entries repeat the force's own parameters.
 */
inline void setMixtureTypes(Scene& scene, bool sameAsForce) {
    for (int i = 0; i < scene.system.getNumParticles(); i++)
        if (i % 3 != 2)
            scene.force->setParticleType(i, i % 3 == 0 ? 7 : -3);
    double n0, pi0, bulkModulus, gammaT;
    scene.force->getTaitParameters(n0, pi0, bulkModulus, gammaT);
    if (sameAsForce) {
        scene.force->addTypeParameters(7, n0, pi0, bulkModulus, gammaT);
        scene.force->addTypeParameters(-3, n0, pi0, bulkModulus, gammaT);
    } else {
        scene.force->addTypeParameters(7, 1.3 * n0, 0.5 * pi0, 0.6 * bulkModulus, 7.0);
        scene.force->addTypeParameters(-3, 0.8 * n0, -0.3 * pi0, 1.5 * bulkModulus, 5.5);
    }
}

/** The estimators every test runs: all those the brute-force oracle evaluates (BruteForceGenDPDE.h). */
inline std::vector<GenDPDEForce::DensityEstimator> testEstimators() {
    std::vector<GenDPDEForce::DensityEstimator> result;
    for (BruteForce::Estimator estimator : BruteForce::estimators)
        result.push_back((GenDPDEForce::DensityEstimator) estimator);
    return result;
}

/** "VA", "VB", ... */
inline std::string estimatorLabel(GenDPDEForce::DensityEstimator estimator) {
    return BruteForce::estimatorName(estimator);
}

/**
 * A liquid slab in vacuum: a lattice liquid of cellsPerSide^3 particles at `density` (nm^-3) in a periodic box three
 * times as long along z, the liquid in the middle third (two free surfaces normal to z).
 */
inline Scene makeSlab(int cellsPerSide, double density, double jitter, GenDPDEForce::DensityEstimator estimator,
                      unsigned seed) {
    Scene scene = makeLatticeLiquid(cellsPerSide, density, jitter, estimator, true, seed);
    const double edge = scene.box[0][0];
    setBox(scene, scene.box[0], scene.box[1], Vec3(0, 0, 3 * edge));
    for (Vec3& r : scene.positions)
        r[2] += edge;
    return scene;
}

/**
 * The scenes that every force test runs through: every estimator (testEstimators), periodic and open, each as a
 * liquid (216 particles on a jittered lattice at n0), a compressed liquid (343 particles at 5 n0), a gas of 27 dimers
 * and, for estimators that allow isolated particles (not V-A), a dilute random gas at 0.1 n0. Open boundaries give
 * the liquids free surfaces, where V-C's surface factor works. `jitter` is the lattice jitter (fraction of the
 * spacing); the four scenes use seeds firstSeed ... firstSeed + 3. check(scene, label) is called on each.
 */
inline void forEachStandardScene(double jitter, unsigned firstSeed,
                                 const std::function<void(Scene&, const std::string&)>& check) {
    for (GenDPDEForce::DensityEstimator estimator : testEstimators())
        for (bool periodic : {true, false}) {
            std::string label = estimatorLabel(estimator) + (periodic ? " periodic" : " open");
            Scene liquid = makeLatticeLiquid(6, referenceDensity, jitter, estimator, periodic, firstSeed);
            check(liquid, label + " liquid");
            Scene compressed = makeLatticeLiquid(7, 5.0 * referenceDensity, jitter, estimator, periodic, firstSeed + 1);
            check(compressed, label + " compressed");
            Scene dimers = makeDimerGas(27, estimator, periodic, firstSeed + 2);
            check(dimers, label + " dimers");
            if (BruteForce::allowsIsolatedParticles(estimator)) {
                Scene gas = makeRandomGas(100, 0.1 * referenceDensity, estimator, periodic, firstSeed + 3);
                check(gas, label + " dilute");
            }
        }
}

} // namespace TestScenes

#endif /*GENDPDE_TEST_SCENES_H_*/
