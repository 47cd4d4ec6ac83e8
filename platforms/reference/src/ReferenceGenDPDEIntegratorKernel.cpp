/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
#include "ReferenceGenDPDEIntegratorKernel.h"
#include "ReferenceKernelAccess.h"
#include "internal/BoxGeometry.h"
#include "gendpde/CounterRandom.h"
#include "gendpde/GenDPDESweepDefinition.h"
#include "internal/Buffers.h"
#include "internal/FixedOrderSum.h"
#include "internal/ParallelFor.h"
#include "internal/GenDPDEPhysics.h"
#include "openmm/OpenMMException.h"
#include "openmm/internal/ContextImpl.h"
#include <algorithm>
#include <cmath>

using namespace GenDPDEPlugin;
using namespace OpenMM;

void ReferenceIntegrateGenDPDEStepKernel::initialize(ContextImpl& context, const GenDPDEIntegrator& integrator,
                                                     double cutoff, int seed, const std::vector<double>& energies,
                                                     const std::map<int, int>& particleTypes) {
    const System& system = context.getSystem();
    this->cutoff = cutoff;
    this->seed = seed;
    internalEnergies = energies;
    typeTables.reset(
            new IntegratorTypeTables(ParticleTypeIndex(particleTypes, system.getNumParticles(), "GenDPDEIntegrator")));
    inverseMasses.resize(system.getNumParticles());
    for (int i = 0; i < system.getNumParticles(); i++) {
        double mass = system.getParticleMass(i);
        inverseMasses[i] = (mass == 0.0 ? 0.0 : 1.0 / mass);
    }
    if (cutoff > 0.0)
        neighborList.reset(new NeighborList(cutoff, NeighborList::defaultSkinFraction * cutoff,
                                            system.usesPeriodicBoundaryConditions()));
}

GenDPDEThermalState ReferenceIntegrateGenDPDEStepKernel::getThermalState(const GenDPDEIntegrator& integrator) {
    typeTables->update(integrator);   // the heat capacities may have changed since the last step
    GenDPDEThermalState state;
    state.isothermal = (integrator.getMode() == GenDPDEIntegrator::Isothermal);
    state.temperature = integrator.getTemperature();
    state.internalEnergies = internalEnergies.data();
    state.densityEntropies = densityEntropiesKnown ? densityEntropies.data() : nullptr;
    state.particleClass = typeTables->getParticleClasses().data();
    state.classHeatCapacity = typeTables->getTable().heatCapacity.data();
    state.checkStep = GenDPDEIntegratorUtilities::checksStepTemperatures(integrator);
    return state;
}

bool ReferenceIntegrateGenDPDEStepKernel::getSweepBuild(std::vector<Vec3>& positions, Vec3 box[3]) const {
    if (!pendingBuildPositions.empty()) {
        positions = pendingBuildPositions;
        std::copy(pendingBuildBox, pendingBuildBox + 3, box);
        return true;
    }
    if (!orderBuilt)
        return false;
    positions = buildPositions;
    std::copy(buildBox, buildBox + 3, box);
    return true;
}

void ReferenceIntegrateGenDPDEStepKernel::setSweepBuild(const std::vector<Vec3>& positions, const Vec3 box[3]) {
    if (positions.size() != inverseMasses.size())
        throw OpenMMException("GenDPDEIntegrator: the sweep's build positions are for "
                              + std::to_string(positions.size()) + " particles; the System has "
                              + std::to_string(inverseMasses.size()));
    pendingBuildPositions = positions;
    std::copy(box, box + 3, pendingBuildBox);
    orderBuilt = false;
}

void ReferenceIntegrateGenDPDEStepKernel::forgetSweepOrder() {
    pendingBuildPositions.clear();
    orderBuilt = false;
}

bool ReferenceIntegrateGenDPDEStepKernel::orderIsStale(const std::vector<Vec3>& positions, const Vec3 box[3],
                                                       int numThreads) const {
    // The definition's rule (SweepDefinition): a new box, or a particle farther than half the skin from its position
    // at the build.
    if (!orderBuilt || positions.size() != buildPositions.size())
        return true;
    if (neighborList->isPeriodic() && !(box[0] == buildBox[0] && box[1] == buildBox[1] && box[2] == buildBox[2]))
        return true;
    return NeighborList::anyMovedFarther(positions, buildPositions, SweepDefinition::rebuildDisplacement2(cutoff),
                                         numThreads);
}

void ReferenceIntegrateGenDPDEStepKernel::updateSweepOrder(ContextImpl& context, GenDPDEPairSource* pairSource,
                                                           int numThreads) {
    const std::vector<Vec3>& positions = extractPositions(context);
    const Vec3* box = extractBoxVectors(context);
    if (context.getSystem().usesPeriodicBoundaryConditions())
        BoxGeometry::checkCutoffAgainstBox("GenDPDEIntegrator", cutoff, box); // a barostat may have shrunk it
    if (!pendingBuildPositions.empty()) {
        // a checkpoint's build: the order of the uninterrupted run, kept or rebuilt by the rule against its positions
        buildSweepOrder(pendingBuildPositions, pendingBuildBox, nullptr, numThreads);
        pendingBuildPositions.clear();
    }
    if (!orderIsStale(positions, box, numThreads))
        return;
    // The candidates of a GenDPDEForce's list built at exactly these positions and box are the same as our own list's
    // would be (the same class and settings): borrowed, they save a search.
    const NeighborList* list = pairSource != nullptr ? pairSource->getHostNeighborList() : nullptr;
    if (list != nullptr && !list->holdsCandidatesAt(positions, box, *neighborList))
        list = nullptr;
    buildSweepOrder(positions, box, list, numThreads);
}

void ReferenceIntegrateGenDPDEStepKernel::buildSweepOrder(const std::vector<Vec3>& positions, const Vec3 box[3],
                                                          const NeighborList* list, int numThreads) {
    // The candidates in (i, j) order (of the list given, built at these positions, or of our own list built now), the
    // order made from them, and the candidates copied into that order with their slots.
    if (list == nullptr) {
        neighborList->invalidate();
        neighborList->refresh(positions, box, numThreads);
        list = neighborList.get();
    }
    // The candidates in (i, j) order (a build's scratch, as is the order: 12 bytes per pair, freed when the ordered
    // pairs are made), the order made from them, and the candidates copied into that order as pairs of slots.
    const int numParticles = inverseMasses.size();
    const int numCandidates = list->getNumCandidates();
    std::vector<IndexPair> candidates(numCandidates);
    IndexPair* next = candidates.data();
    for (int i = 0; i < numParticles; i++)
        for (int j : list->candidatesOf(i))
            *next++ = {i, j};
    const int* first = candidates.empty() ? nullptr : &candidates[0].i;
    const bool periodic = neighborList->isPeriodic();
    sweepOrder.build(positions, box, periodic, cutoff, numCandidates, first, first != nullptr ? first + 1 : nullptr, 2,
                     numThreads);
    resizeBuffer(orderedPairs, numCandidates);
    SweepPair* ordered = orderedPairs.data();
    const IndexPair* candidate = candidates.data();
    const int* sequence = sweepOrder.getOrder().data();
    const int* slot = sweepOrder.getSlots().data();
    parallelFor(numThreads, numCandidates, 4096, [=](int begin, int end) {
        for (int n = begin; n < end; n++) {
            const IndexPair& pair = candidate[sequence[n]];
            ordered[n] = {slot[pair.i], slot[pair.j]};
        }
    });
    sweepOrder.releaseOrder();
    buildPositions = positions;
    std::copy(box, box + 3, buildBox);
    if (periodic)
        sweepBox = PeriodicBox(box);
    orderBuilt = true;
}

void ReferenceIntegrateGenDPDEStepKernel::kick(ContextImpl& context, std::vector<Vec3>& velocities,
                                               const std::vector<Vec3>& forces, double timeStep) {
    for (size_t i = 0; i < velocities.size(); i++)
        if (inverseMasses[i] != 0.0)
            velocities[i] += forces[i] * (timeStep * inverseMasses[i]);
}

int ReferenceIntegrateGenDPDEStepKernel::firstUnstableParticle(ContextImpl& context, double stepSize,
                                                               double maxDisplacement, int begin, int end) const {
    // A few flops per particle: the force finite, and the particle not about to move farther than maxDisplacement
    // (GenDPDEStepTerms) with its velocity after the kicks.
    const std::vector<Vec3>& forces = extractForces(context);
    const std::vector<Vec3>& velocities = extractVelocities(context);
    const double limit2 = maxDisplacement * maxDisplacement;
    for (int i = begin; i < end; i++) {
        if (!(std::isfinite(forces[i][0]) && std::isfinite(forces[i][1]) && std::isfinite(forces[i][2])))
            return i;
        const Vec3 displacement = (velocities[i] + forces[i] * (stepSize * inverseMasses[i])) * stepSize;
        if (inverseMasses[i] != 0.0 && !(displacement.dot(displacement) <= limit2))
            return i;
    }
    return -1;
}

void ReferenceIntegrateGenDPDEStepKernel::throwUnstable(ContextImpl& context, int i, double stepSize,
                                                        double maxDisplacement) const {
    throw OpenMMException(GenDPDEIntegratorUtilities::unstableParticleMessage(
            i, extractVelocities(context)[i], extractForces(context)[i], inverseMasses[i], stepSize, maxDisplacement,
            context.getStepCount()));
}

void ReferenceIntegrateGenDPDEStepKernel::checkStepIsStable(ContextImpl& context, double stepSize,
                                                            double maxDisplacement) {
    // One cheap pass before anything changes.
    const int unstable = firstUnstableParticle(context, stepSize, maxDisplacement, 0, inverseMasses.size());
    if (unstable >= 0)
        throwUnstable(context, unstable, stepSize, maxDisplacement);
}

void ReferenceIntegrateGenDPDEStepKernel::sweep(ContextImpl& context, std::vector<Vec3>& velocities,
                                                const GenDPDEIntegrator& integrator, const GenDPDEStepTerms& terms,
                                                GenDPDEPairSource* pairSource) {
    // docs/theory.md sections 5-7, pair by pair at fixed positions, in the order every platform follows: the colours
    // one after another, the blocks of a colour in parallel (on one thread, the whole sequence in one loop, whose
    // prefetches run on across the blocks).
    const int threads = numThreads(context);
    const long long step = context.getStepCount();
    updateSweepOrder(context, pairSource, threads);
    typeTables->update(integrator);
    PairSweepParameters parameters(integrator, terms, cutoff, seed, step, *typeTables, sweepNoise);
    gatherSweepState(context, integrator, parameters, threads);
    const double* inverseMass = layout.slotInverseMasses.data();
    const Vec3* position = layout.slotPositions.data();
    const int* particle = layout.particles;
    Vec3* v = layout.slotVelocities.data();
    double* energy = terms.internalEnergies ? layout.slotEnergies.data() : nullptr;
    const SweepPair* pairs = orderedPairs.data();
    withNearestImage(neighborList->isPeriodic() ? &sweepBox : nullptr, [&](auto nearestImage) {
        if (threads == 1) {
            // If an internal energy would become <= 0, nothing is copied back (the velocities and internal energies
            // stay those before the step; positions have not moved yet), and the error names the particle and the
            // step.
            const int failed = sweepPairs(pairs, orderedPairs.size(), nearestImage, position, particle, parameters,
                                          inverseMass, v, energy);
            if (failed >= 0)
                failSweep(failed, step);
            return;
        }
        const std::vector<int>& groupStart = sweepOrder.getGroupStart();
        const int* blockStart = sweepOrder.getBlockStart().data();
        for (int group = 0; group < sweepOrder.getNumGroups(); group++) {
            const int firstBlock = groupStart[group], numBlocks = groupStart[group + 1] - firstBlock;
            blockFailure.assign(numBlocks, -1);
            int* failure = blockFailure.data();
            parallelFor(threads, numBlocks, 1, [=](int begin, int end) {
                for (int b = firstBlock + begin; b < firstBlock + end; b++) {
                    const int failed = sweepPairs(pairs + blockStart[b], blockStart[b + 1] - blockStart[b],
                                                  nearestImage, position, particle, parameters, inverseMass, v, energy);
                    if (failed >= 0)
                        failure[b - firstBlock] = blockStart[b] + failed;
                }
            });
            // The first failing pair of the sequence: in the first block (of this first failing colour) that failed.
            for (int failed : blockFailure)
                if (failed >= 0)
                    failSweep(failed, step);
        }
    });
    layout.scatter(velocities, terms.internalEnergies ? internalEnergies.data() : nullptr, threads);
}

void ReferenceIntegrateGenDPDEStepKernel::gatherSweepState(ContextImpl& context, const GenDPDEIntegrator& integrator,
                                                           PairSweepParameters& parameters, int numThreads) {
    const bool classes = parameters.numClasses > 1;
    layout.gather(sweepOrder, extractPositions(context), extractVelocities(context), extractForces(context),
                  0.5 * integrator.getStepSize(), parameters.terms.internalEnergies ? internalEnergies.data() : nullptr,
                  inverseMasses.data(), classes ? parameters.particleClass : nullptr, numThreads);
    if (classes)
        parameters.particleClass = layout.slotClasses.data();
}

void ReferenceIntegrateGenDPDEStepKernel::failSweep(int failed, long long step) {
    const int particle = failedParticle(orderedPairs[failed], layout.slotEnergies.data(), layout.particles);
    const double value = layout.slotEnergies[layout.slots[particle]];
    throw OpenMMException(GenDPDEIntegratorUtilities::nonPositiveEnergyMessage(particle, value, step));
}

void ReferenceIntegrateGenDPDEStepKernel::drift(ContextImpl& context, std::vector<Vec3>& positions,
                                                const std::vector<Vec3>& velocities, double timeStep) {
    for (size_t i = 0; i < positions.size(); i++)
        if (inverseMasses[i] != 0.0)
            positions[i] += velocities[i] * timeStep;
}

void ReferenceIntegrateGenDPDEStepKernel::execute(ContextImpl& context, const GenDPDEIntegrator& integrator,
                                                  const GenDPDEStepTerms& terms, GenDPDEPairSource* pairSource) {
    // docs/theory.md section 6: half kick, pair sweep at fixed positions, half kick, drift; without pair terms,
    // velocity Verlet (leapfrog form: one full kick).
    checkStepIsStable(context, integrator.getStepSize(), terms.maxDisplacement);
    std::vector<Vec3>& velocities = extractVelocities(context);
    const std::vector<Vec3>& forces = extractForces(context);
    const double dt = integrator.getStepSize();
    if (!terms.pairSweep)
        kick(context, velocities, forces, dt);
    else {
        // (the first half kick inside the sweep, on the sweep's copies: a failed sweep leaves the state untouched)
        sweep(context, velocities, integrator, terms, pairSource);
        kick(context, velocities, forces, 0.5 * dt);
    }
    drift(context, extractPositions(context), velocities, dt);
    ReferencePlatform::PlatformData& data = platformData(context);
    data.time += dt;
    data.stepCount++;
}

double ReferenceIntegrateGenDPDEStepKernel::kineticEnergy(int i, const std::vector<Vec3>& velocities,
                                                          const std::vector<Vec3>& forces, double halfStep) const {
    // Velocities are half a step behind the positions: K at the current time uses v + (dt/2) F/m.
    if (inverseMasses[i] == 0.0)
        return 0.0;
    const Vec3 v = velocities[i] + forces[i] * (halfStep * inverseMasses[i]);
    return 0.5 * v.dot(v) / inverseMasses[i];
}

double ReferenceIntegrateGenDPDEStepKernel::computeKineticEnergy(ContextImpl& context,
                                                                 const GenDPDEIntegrator& integrator) {
    const std::vector<Vec3>& velocities = extractVelocities(context);
    const std::vector<Vec3>& forces = extractForces(context);
    const double halfStep = 0.5 * integrator.getStepSize();
    FixedOrderSum::Accumulator energy; // summed as the CPU platform sums it, for the same bits
    for (size_t i = 0; i < velocities.size(); i++)
        energy.add(kineticEnergy(i, velocities, forces, halfStep));
    return energy.sum();
}
