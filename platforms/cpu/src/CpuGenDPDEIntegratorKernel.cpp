/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
#include "CpuGenDPDEIntegratorKernel.h"
#include "ReferenceKernelAccess.h"
#include "internal/BoxGeometry.h"
#include "internal/FixedOrderSum.h"
#include "internal/GenDPDEPairSweep.h"
#include "internal/ParallelFor.h"
#include <algorithm>
#include <type_traits>

using namespace GenDPDEPlugin;
using namespace OpenMM;

namespace {
/** Particles per range of work (fixed: the ranges do not depend on the number of threads). */
const int particleChunk = 1024;
}

int CpuIntegrateGenDPDEStepKernel::numThreads(ContextImpl& context) const {
    return extractNumThreads(context);
}

void CpuIntegrateGenDPDEStepKernel::checkStepIsStable(ContextImpl& context, double stepSize, double maxDisplacement) {
    const int numParticles = inverseMasses.size();
    std::vector<int>& firstUnstable = rangeFirstUnstable;
    firstUnstable.assign(numRanges(numParticles, particleChunk), -1);
    parallelFor(extractNumThreads(context), numParticles, particleChunk, [&](int begin, int end) {
        firstUnstable[begin / particleChunk] = firstUnstableParticle(context, stepSize, maxDisplacement, begin, end);
    });
    for (int i : firstUnstable)
        if (i >= 0)
            throwUnstable(context, i, stepSize, maxDisplacement);   // the lowest, as Reference reports it
}

void CpuIntegrateGenDPDEStepKernel::kick(ContextImpl& context, std::vector<Vec3>& velocities,
                                         const std::vector<Vec3>& forces, double timeStep) {
    Vec3* v = velocities.data();
    const Vec3* f = forces.data();
    const double* inverseMass = inverseMasses.data();
    parallelFor(extractNumThreads(context), velocities.size(), particleChunk, [=](int begin, int end) {
        for (int i = begin; i < end; i++)
            if (inverseMass[i] != 0.0)
                v[i] += f[i] * (timeStep * inverseMass[i]);
    });
}

void CpuIntegrateGenDPDEStepKernel::drift(ContextImpl& context, std::vector<Vec3>& positions,
                                          const std::vector<Vec3>& velocities, double timeStep) {
    Vec3* x = positions.data();
    const Vec3* v = velocities.data();
    const double* inverseMass = inverseMasses.data();
    parallelFor(extractNumThreads(context), positions.size(), particleChunk, [=](int begin, int end) {
        for (int i = begin; i < end; i++)
            if (inverseMass[i] != 0.0)
                x[i] += v[i] * timeStep;
    });
}

void CpuIntegrateGenDPDEStepKernel::sweep(ContextImpl& context, PairView pairs, std::vector<Vec3>& velocities,
                                          const GenDPDEIntegrator& integrator, const GenDPDEStepTerms& terms) {
    // docs/theory.md section 6: the colours one after another, the blocks of a colour in parallel; on one thread with
    // Reference's list, Reference's sweep (the same sequence in one loop, whose prefetches run on across the blocks).
    const int threads = extractNumThreads(context);
    if (!pairs.holdsIndexPairs()) {
        if (threads == 1) {
            ReferenceIntegrateGenDPDEStepKernel::sweep(context, pairs, velocities, integrator, terms);
            return;
        }
        sweepBlocks(context, pairs, pairs.begin(), StoredPairGeometry(), velocities, integrator, terms, threads);
        return;
    }
    // The force's IndexPairs: their geometry from the positions they were found at, with the gathers' nearest image.
    withNearestImage(pairs.getBox(), [&](auto nearestImage) {
        sweepBlocks(context, pairs, pairs.getIndexPairs(),
                    SlotPositionGeometry<decltype(nearestImage)>{nullptr, nearestImage}, velocities, integrator, terms,
                    threads);
    });
}

template <class Pair, class Geometry>
void CpuIntegrateGenDPDEStepKernel::sweepBlocks(ContextImpl& context, PairView pairs, const Pair* pair,
                                                Geometry geometry, std::vector<Vec3>& velocities,
                                                const GenDPDEIntegrator& integrator, const GenDPDEStepTerms& terms,
                                                int threads) {
    const long long step = context.getStepCount();
    buildSweepOrder(context, pairs, threads);
    const int* order = sweepOrder.getOrder().data();
    const std::vector<int>& groupStart = sweepOrder.getGroupStart();
    const int* blockStart = sweepOrder.getBlockStart().data();
    typeTables->update(integrator);
    PairSweepParameters parameters(integrator, terms, cutoff, seed, step, *typeTables, sweepNoise);
    gatherSweepState(context, integrator, parameters, threads, pairs.getPositions());
    if constexpr (!std::is_same<Geometry, StoredPairGeometry>::value)
        geometry.slotPosition = layout.slotPositions.data();
    const int* slot = layout.slots;
    const double* inverseMass = layout.slotInverseMasses.data();
    Vec3* v = layout.slotVelocities.data();
    double* energy = terms.internalEnergies ? layout.slotEnergies.data() : nullptr;
    for (int group = 0; group < sweepOrder.getNumGroups(); group++) {
        const int firstBlock = groupStart[group], numBlocks = groupStart[group + 1] - firstBlock;
        blockFailure.assign(numBlocks, -1);
        int* failure = blockFailure.data();
        parallelFor(threads, numBlocks, 1, [=](int begin, int end) {
            for (int b = firstBlock + begin; b < firstBlock + end; b++) {
                const int* blockOrder = order + blockStart[b];
                const int count = blockStart[b + 1] - blockStart[b];
                const int failed =
                        sweepPairs(pair, geometry, blockOrder, count, parameters, slot, inverseMass, v, energy);
                if (failed >= 0)
                    failure[b - firstBlock] = blockStart[b] + failed;
            }
        });
        // The first failing pair of the sequence: in the first block (of this first failing colour) that failed.
        for (int failed : blockFailure)
            if (failed >= 0)
                failSweep(pairs, sweepOrder.getOrder(), failed, step);
    }
    layout.scatter(velocities, terms.internalEnergies ? internalEnergies.data() : nullptr, threads);
}

double CpuIntegrateGenDPDEStepKernel::computeKineticEnergy(ContextImpl& context, const GenDPDEIntegrator& integrator) {
    const std::vector<Vec3>& velocities = extractVelocities(context);
    const std::vector<Vec3>& forces = extractForces(context);
    const double halfStep = 0.5 * integrator.getStepSize();
    return FixedOrderSum::parallelSum(
            extractNumThreads(context), velocities.size(),
            [&](int i) { return kineticEnergy(i, velocities, forces, halfStep); }, chunkSums);
}
