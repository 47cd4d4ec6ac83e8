/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
#ifndef GENDPDE_PAIR_SWEEP_H_
#define GENDPDE_PAIR_SWEEP_H_

/* The pair updates of GenDPDEIntegrator's sweep (docs/theory.md sections 5-7) for the host platforms (Reference,
 * CPU): the loop over a run of candidates in sweep order (GenDPDESweepOrder), written once. A platform calls it on
 * the whole sequence (one thread) or on the blocks of one colour in parallel: blocks of one colour share no particle,
 * so the result is the same. */

#include "gendpde/CounterRandom.h"
#include "internal/GenDPDEIntegratorUtilities.h"
#include "internal/GenDPDEPhysics.h"
#include "internal/GenDPDESweepOrder.h"
#include "internal/GenDPDETypes.h"
#include "internal/ParallelFor.h"
#include "openmm/Vec3.h"
#include <cmath>
#include <cstdint>
#include <vector>

namespace GenDPDEPlugin {

/**
 * What every pair update of one step needs, read once per step: the step, and the integrator's tables by class
 * (GenDPDETypes.h, already updated for this step) with the noise amplitudes derived from them, written into noise
 * (the caller's storage, kept between steps: a step allocates nothing once it has the size). tables and noise must
 * outlive the parameters, which are cheap to copy (one per thread): they hold pointers and numbers only.
 */
struct PairSweepParameters {
    PairSweepParameters(const GenDPDEIntegrator& integrator, const GenDPDEStepTerms& terms, double cutoff, int seed,
                        long long step, const IntegratorTypeTables& tables, std::vector<double>& noise) :
            terms(terms), cutoff(cutoff), stepSize(integrator.getStepSize()), sqrtStepSize(std::sqrt(stepSize)),
            table(&tables.getTable()), numClasses(table->numClasses), particleClass(tables.getParticleClasses().data()),
            seed((std::uint32_t) seed), step((std::uint64_t) step) {
        const int numPairs = numClasses * numClasses;
        noise.resize(2 * numPairs);
        for (int ab = 0; ab < numPairs; ab++) {
            noise[ab] = Physics::gendpdeHeatNoise(table->heatConduction[ab], Physics::Boltzmann);
            noise[numPairs + ab] =
                    Physics::gendpdeBathNoise(table->friction[ab], Physics::Boltzmann, integrator.getTemperature());
        }
        heatNoise = noise.data();
        bathNoise = noise.data() + numPairs;
    }
    /** The class of particle i. */
    int classOf(int i) const { return numClasses == 1 ? 0 : particleClass[i]; }
    GenDPDEStepTerms terms;
    double cutoff, stepSize, sqrtStepSize;
    const TypePairTable* table;   // C_V per class, gamma and kappa per pair of classes (index a*numClasses + b)
    const double* heatNoise;      // alpha = sqrt(2 k_B kappa) per pair of classes
    const double* bathNoise;      // sigma = sqrt(2 gamma k_B T) of the Isothermal mode per pair of classes
    int numClasses;
    const int* particleClass;
    std::uint32_t seed;
    std::uint64_t step;
};

/**
 * What the sweep reads and writes per particle, copied into the sweep order's cell order (GenDPDESweepOrder::
 * getParticlesByCell) for the duration of the sweep: a pair's two particles are then close in memory whatever their
 * indices (a liquid mixes its particles within a few thousand steps; in index order at 256,000 particles nearly
 * every particle a pair reaches is a cache miss). The copies are exact, and the sweep's arithmetic and order do not
 * change: only addresses. Velocities and internal energies go back with scatter().
 */
class SweepLayout {
public:
    /**
     * Copy positions, velocities, internal energies (null: none), inverse masses and classes (null: one class) into
     * cell order, on this many threads; the velocities of particles with mass advanced on the way by forces
     * (kJ/mol/nm) over kickTime (ps), v + F (kickTime / m), as a kick computes it (the step's first half kick: the
     * particles' own velocities stay as they were until scatter()).
     */
    void gather(const GenDPDESweepOrder& order, const std::vector<OpenMM::Vec3>& positions,
                const std::vector<OpenMM::Vec3>& velocities, const std::vector<OpenMM::Vec3>& forces, double kickTime,
                const double* energies, const double* inverseMasses, const int* classes, int numThreads) {
        slots = order.getSlots().data();
        particles = order.getParticlesByCell().data();
        const int n = order.getParticlesByCell().size();
        slotVelocities.resize(n);
        slotInverseMasses.resize(n);
        slotEnergies.resize(energies != nullptr ? n : 0);
        slotClasses.resize(classes != nullptr ? n : 0);
        slotPositions.resize(n);
        OpenMM::Vec3* sx = slotPositions.data();
        const int* particle = particles;
        const OpenMM::Vec3* x = positions.data();
        const OpenMM::Vec3* v = velocities.data();
        const OpenMM::Vec3* f = forces.data();
        OpenMM::Vec3* sv = slotVelocities.data();
        double* se = slotEnergies.data();
        double* sm = slotInverseMasses.data();
        int* sc = slotClasses.data();
        parallelFor(numThreads, n, 4096, [=](int begin, int end) {
            for (int s = begin; s < end; s++) {
                const int i = particle[s];
                sv[s] = inverseMasses[i] != 0.0 ? v[i] + f[i] * (kickTime * inverseMasses[i]) : v[i];
                sm[s] = inverseMasses[i];
                if (energies != nullptr)
                    se[s] = energies[i];
                if (classes != nullptr)
                    sc[s] = classes[i];
                sx[s] = x[i];
            }
        });
    }
    /** Copy the velocities and internal energies (null: none) back to index order. */
    void scatter(std::vector<OpenMM::Vec3>& velocities, double* energies, int numThreads) const {
        const int* particle = particles;
        OpenMM::Vec3* v = velocities.data();
        const OpenMM::Vec3* sv = slotVelocities.data();
        const double* se = slotEnergies.data();
        parallelFor(numThreads, slotVelocities.size(), 4096, [=](int begin, int end) {
            for (int s = begin; s < end; s++) {
                v[particle[s]] = sv[s];
                if (energies != nullptr)
                    energies[particle[s]] = se[s];
            }
        });
    }
    const int* slots = nullptr;       // particle i is at slots[i]
    const int* particles = nullptr;   // slot s holds particle particles[s]
    std::vector<OpenMM::Vec3> slotVelocities, slotPositions;
    std::vector<double> slotEnergies, slotInverseMasses;
    std::vector<int> slotClasses;
};

/**
 * A candidate of the sweep, in sweep order: the slots of its two particles in the sweep's layout (SweepLayout::slots
 * at the order's build), slotI that of the lower index: the particles i < j (SweepLayout::particles of the slots) key
 * the pair's random stream.
 */
struct SweepPair {
    int slotI, slotJ;
};

/**
 * Ask for the memory the sweep reaches soon: the slots of the pair 8 places ahead. The pairs are read in sequence,
 * but the particles they reach are at random in memory; without this, each pair of 256,000 particles waited for main
 * memory. Always inlined: GCC deems a function that only prefetches free of effects and deletes its calls.
 */
__attribute__((always_inline)) inline void prefetchAhead(const SweepPair* pairs, int n, int count,
                                                         const OpenMM::Vec3* velocities, const double* energies,
                                                         const OpenMM::Vec3* positions, const int* particles) {
    if (n + 8 < count) {
        const SweepPair& ahead = pairs[n + 8];
        __builtin_prefetch(&velocities[ahead.slotI]);
        __builtin_prefetch(&velocities[ahead.slotJ]);
        __builtin_prefetch(&positions[ahead.slotI]);
        __builtin_prefetch(&positions[ahead.slotJ]);
        __builtin_prefetch(&particles[ahead.slotI]);
        __builtin_prefetch(&particles[ahead.slotJ]);
        if (energies != nullptr) {
            __builtin_prefetch(&energies[ahead.slotI]);
            __builtin_prefetch(&energies[ahead.slotJ]);
        }
    }
}

/**
 * The sweep's candidates pairs[0..count) in sweep order (GenDPDESweepOrder), each closer than the cutoff at these
 * positions updated by the core's pair step (gendpdeSweepPair, GenDPDESweepPair.h, as on the device and in LAMMPS)
 * with the random stream keyed on (i, j); the others skipped. The geometry: delta = nearestImage(r_i - r_j) from
 * positions (by slot), updated if delta . delta < R^2. In the Isoenergetic mode (p.terms.internalEnergies) full
 * GenDPDE, dissipative and random momenta with sigma^2 = 2 gamma k_B Theta_ij, mechanical heating split equally and
 * heat conduction, at the temperatures the particles have when the pair is reached; otherwise the DPD thermostat of
 * the Isothermal mode, whose heat goes to the bath. The particles' data are by slot (SweepLayout): inverseMasses,
 * velocities, energies (null in the Isothermal mode) and p's classes. Returns the position in pairs of the first pair
 * after which an internal energy is <= 0 (the sweep stops there; the caller restores the state), or -1. particles:
 * the particle of each slot (SweepLayout::particles), for the random streams' keys.
 */
template <class NearestImage>
int sweepPairs(const SweepPair* pairs, int count, NearestImage nearestImage, const OpenMM::Vec3* positions,
               const int* particles, const PairSweepParameters& p, const double* inverseMasses,
               OpenMM::Vec3* velocities, double* energies) {
    const int dissipation = p.terms.dissipation, conduction = p.terms.conduction;
    const int internalEnergies = p.terms.internalEnergies ? 1 : 0;
    const double cutoff2 = p.cutoff * p.cutoff;
    for (int n = 0; n < count; n++) {
        prefetchAhead(pairs, n, count, velocities, energies, positions, particles);
        const SweepPair& pair = pairs[n];
        const int i = pair.slotI, j = pair.slotJ;
        const OpenMM::Vec3 delta = nearestImage(positions[i] - positions[j]);
        const double r2 = delta.dot(delta);
        if (!(r2 < cutoff2))
            continue;
        const double r = std::sqrt(r2);
        const int a = p.classOf(i), b = p.classOf(j), ab = a * p.numClasses + b;
        CounterRandom::PairStream random(p.seed, p.step, particles[i], particles[j]);
        const int failed = Physics::gendpdeSweepPair(
                dissipation, conduction, internalEnergies, delta[0], delta[1], delta[2], r, p.cutoff, inverseMasses[i],
                inverseMasses[j], &velocities[i][0], &velocities[j][0], internalEnergies ? &energies[i] : nullptr,
                internalEnergies ? &energies[j] : nullptr, p.table->heatCapacity[a], p.table->heatCapacity[b],
                p.table->friction[ab], p.table->heatConduction[ab], p.heatNoise[ab], p.bathNoise[ab],
                Physics::Boltzmann, p.stepSize, p.sqrtStepSize, &random);
        if (failed)
            return n;
    }
    return -1;
}

/**
 * The particle whose internal energy failed in this pair (i if eps_i <= 0, else j), with energies and particles by
 * slot.
 */
inline int failedParticle(const SweepPair& pair, const double* energies, const int* particles) {
    return particles[energies[pair.slotI] > 0.0 ? pair.slotJ : pair.slotI];
}

} // namespace GenDPDEPlugin

#endif /*GENDPDE_PAIR_SWEEP_H_*/
