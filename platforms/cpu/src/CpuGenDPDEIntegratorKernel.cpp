/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
#include "CpuGenDPDEIntegratorKernel.h"
#include "ReferenceKernelAccess.h"
#include "internal/BoxGeometry.h"
#include "internal/FixedOrderSum.h"
#include "internal/ParallelFor.h"
#include <algorithm>

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

double CpuIntegrateGenDPDEStepKernel::computeKineticEnergy(ContextImpl& context, const GenDPDEIntegrator& integrator) {
    const std::vector<Vec3>& velocities = extractVelocities(context);
    const std::vector<Vec3>& forces = extractForces(context);
    const double halfStep = 0.5 * integrator.getStepSize();
    return FixedOrderSum::parallelSum(
            extractNumThreads(context), velocities.size(),
            [&](int i) { return kineticEnergy(i, velocities, forces, halfStep); }, chunkSums);
}
