#include "CpuGenDPDEIntegratorKernel.h"
#include "CpuGenDPDEForceKernel.h"
#include "ReferenceKernelAccess.h"
#include "internal/BoxGeometry.h"
#include "internal/FixedOrderSum.h"
#include "internal/GenDPDEForceImpl.h"
#include "internal/GenDPDEPairSweep.h"
#include "internal/ParallelFor.h"
#include <algorithm>

using namespace GenDPDEPlugin;
using namespace OpenMM;

namespace {
/** Particles per range of work (fixed: the ranges do not depend on the number of threads). */
const int particleChunk = 1024;
}

PairView CpuIntegrateGenDPDEStepKernel::currentPairs(ContextImpl& context, GenDPDEForceImpl* pairListSource) {
    // The source, if any, was evaluated at the current positions just before this step (see execute()).
    ThreadPool& threads = platformData(context).threads;
    if (pairListSource != nullptr)
        return dynamic_cast<CpuCalcGenDPDEForceKernel&>(pairListSource->getKernel().getImpl()).collectPairs(threads);
    const Vec3* box = extractBoxVectors(context);
    if (context.getSystem().usesPeriodicBoundaryConditions())
        BoxGeometry::checkCutoffAgainstBox("GenDPDEIntegrator", cutoff, box);   // a barostat may have shrunk it
    return neighborList->update(extractPositions(context), box, &threads);
}

void CpuIntegrateGenDPDEStepKernel::checkStepIsStable(ContextImpl& context, double stepSize, double maxDisplacement) {
    const int numParticles = inverseMasses.size();
    std::vector<int> firstUnstable(numRanges(numParticles, particleChunk), -1);
    parallelFor(&platformData(context).threads, numParticles, particleChunk, [&](int begin, int end) {
        firstUnstable[begin/particleChunk] = firstUnstableParticle(context, stepSize, maxDisplacement, begin, end);
    });
    for (int i : firstUnstable)
        if (i >= 0)
            throwUnstable(context, i, stepSize, maxDisplacement);   // the lowest, as Reference reports it
}

void CpuIntegrateGenDPDEStepKernel::kick(ContextImpl& context, std::vector<Vec3>& velocities,
                                         const std::vector<Vec3>& forces, double timeStep) {
    parallelFor(&platformData(context).threads, velocities.size(), particleChunk, [&](int begin, int end) {
        for (int i = begin; i < end; i++)
            if (inverseMasses[i] != 0.0)
                velocities[i] += forces[i]*(timeStep*inverseMasses[i]);
    });
}

void CpuIntegrateGenDPDEStepKernel::drift(ContextImpl& context, std::vector<Vec3>& positions,
                                          const std::vector<Vec3>& velocities, double timeStep) {
    parallelFor(&platformData(context).threads, positions.size(), particleChunk, [&](int begin, int end) {
        for (int i = begin; i < end; i++)
            if (inverseMasses[i] != 0.0)
                positions[i] += velocities[i]*timeStep;
    });
}

void CpuIntegrateGenDPDEStepKernel::sweep(ContextImpl& context, PairView pairs, std::vector<Vec3>& velocities,
                                          const GenDPDEIntegrator& integrator, const GenDPDEStepTerms& terms) {
    // docs/theory.md section 6: the colours one after another, the blocks of a colour in parallel.
    ThreadPool& threads = platformData(context).threads;
    const long long step = context.getStepCount();
    const int stride = sizeof(ParticlePair)/sizeof(int);
    const bool anyPairs = pairs.size() > 0;
    sweepOrder.build(extractPositions(context), extractBoxVectors(context),
                     context.getSystem().usesPeriodicBoundaryConditions(), cutoff, pairs.size(),
                     anyPairs ? &pairs.begin()->i : nullptr, anyPairs ? &pairs.begin()->j : nullptr, stride, &threads);
    const std::vector<int>& order = sweepOrder.getOrder();
    const std::vector<int>& groupStart = sweepOrder.getGroupStart();
    const std::vector<int>& blockStart = sweepOrder.getBlockStart();
    const PairSweepParameters parameters(integrator, terms, cutoff, seed, step);
    for (int group = 0; group < sweepOrder.getNumGroups(); group++) {
        const int firstBlock = groupStart[group], numBlocks = groupStart[group + 1] - firstBlock;
        blockFailure.assign(numBlocks, -1);
        parallelFor(&threads, numBlocks, 1, [&](int begin, int end) {
            for (int b = firstBlock + begin; b < firstBlock + end; b++) {
                const int* blockOrder = order.data() + blockStart[b];
                const int count = blockStart[b + 1] - blockStart[b];
                if (!terms.internalEnergies)
                    sweepIsothermal(pairs.begin(), blockOrder, count, parameters, inverseMasses.data(),
                                    velocities.data());
                else {
                    const int failed = sweepIsoenergetic(pairs.begin(), blockOrder, count, parameters,
                                                         inverseMasses.data(), velocities.data(),
                                                         internalEnergies.data());
                    if (failed >= 0)
                        blockFailure[b - firstBlock] = blockStart[b] + failed;
                }
            }
        });
        // The first failing pair of the sequence: in the first block (of this first failing colour) that failed.
        for (int failed : blockFailure)
            if (failed >= 0)
                failSweep(pairs, order, failed, velocities, step);
    }
}

double CpuIntegrateGenDPDEStepKernel::computeKineticEnergy(ContextImpl& context, const GenDPDEIntegrator& integrator) {
    const std::vector<Vec3>& velocities = extractVelocities(context);
    const std::vector<Vec3>& forces = extractForces(context);
    const double halfStep = 0.5*integrator.getStepSize();
    const int numParticles = velocities.size();
    const int numChunks = FixedOrderSum::numChunks(numParticles);
    chunkSums.assign(numChunks, 0.0);
    parallelFor(&platformData(context).threads, numChunks, 1, [&](int chunkBegin, int chunkEnd) {
        for (int c = chunkBegin; c < chunkEnd; c++) {
            double partial = 0.0;
            const int last = std::min(numParticles, (c + 1)*FixedOrderSum::chunkSize);
            for (int i = c*FixedOrderSum::chunkSize; i < last; i++)
                partial += kineticEnergy(i, velocities, forces, halfStep);
            chunkSums[c] = partial;
        }
    });
    return FixedOrderSum::combine(chunkSums);
}
