#include "CpuGenDPDEForceKernel.h"
#include "ReferenceKernelAccess.h"
#include "internal/FixedOrderSum.h"
#include "internal/ParallelFor.h"
#include <algorithm>
#include <climits>

using namespace GenDPDEPlugin;
using namespace OpenMM;

namespace {
/** Particles per range of work (fixed: the ranges do not depend on the number of threads). */
const int particleChunk = 256;
}

void CpuCalcGenDPDEForceKernel::evaluateCandidates(ThreadPool& threads) {
    const std::vector<int>& start = neighborList->getCandidateStart();
    const std::vector<int>& candidates = neighborList->getCandidates();
    const int numParticles = start.size() - 1;
    candidateDelta.resize(candidates.size());
    candidateDistance.resize(candidates.size());
    candidateWeight.resize(candidates.size());
    const Physics::DensityWeight weight(cutoff);
    const double cutoff2 = cutoff*cutoff;
    parallelFor(&threads, numParticles, particleChunk, [&](int begin, int end) {
        for (int i = begin; i < end; i++)
            for (int m = start[i]; m < start[i + 1]; m++) {
                const Vec3 d = neighborList->displacement(i, candidates[m]);
                candidateDelta[m] = d;
                if (d.dot(d) < cutoff2) {
                    const double r = std::sqrt(d.dot(d));
                    candidateDistance[m] = r;
                    candidateWeight[m] = weight.value(r);
                }
                else {
                    candidateDistance[m] = -1.0;
                    candidateWeight[m] = 0.0;
                }
            }
    });
}

double CpuCalcGenDPDEForceKernel::computeDensitiesAndEnergy(ContextImpl& context) {
    ThreadPool& threads = platformData(context).threads;
    const std::vector<Vec3>& positions = extractPositions(context);
    const int numParticles = positions.size();
    std::vector<int> firstBad(numRanges(numParticles, particleChunk), -1);
    parallelFor(&threads, numParticles, particleChunk, [&](int begin, int end) {
        firstBad[begin/particleChunk] = firstNonFinitePosition(positions, begin, end);
    });
    const auto bad = std::find_if(firstBad.begin(), firstBad.end(), [](int i) { return i >= 0; });
    checkConfiguration(context, bad == firstBad.end() ? -1 : *bad);
    neighborList->refresh(positions, extractBoxVectors(context), &threads);
    evaluateCandidates(threads);

    // docs/theory.md sections 2-3: n0_i = sum_j w(r_ij), gathered in Reference's order of addition.
    const std::vector<int>& start = neighborList->getCandidateStart();
    const std::vector<int>& lowerStart = neighborList->getLowerStart();
    const std::vector<int>& lower = neighborList->getLowerCandidates();
    parallelFor(&threads, numParticles, particleChunk, [&](int begin, int end) {
        for (int i = begin; i < end; i++) {
            double n0 = 0.0;
            for (int l = lowerStart[i]; l < lowerStart[i + 1]; l++)
                n0 += candidateWeight[lower[l]];
            for (int m = start[i]; m < start[i + 1]; m++)
                n0 += candidateWeight[m];
            primitiveDensity[i] = n0;
        }
    });

    // docs/theory.md sections 2-4: volumes, pressures and free energies; U = sum_i f(n_i) in fixed chunks. The error
    // reported is that of the lowest failing particle, as the sequential loop would report it.
    const ParticleModel model(*this);
    const int numChunks = FixedOrderSum::numChunks(numParticles);
    chunkSums.assign(numChunks, 0.0);
    std::vector<int> failedParticle(numChunks, INT_MAX);
    std::vector<ParticleStatus> failedStatus(numChunks, Valid);
    parallelFor(&threads, numChunks, 1, [&](int chunkBegin, int chunkEnd) {
        for (int c = chunkBegin; c < chunkEnd; c++) {
            double partial = 0.0;
            const int last = std::min(numParticles, (c + 1)*FixedOrderSum::chunkSize);
            for (int i = c*FixedOrderSum::chunkSize; i < last; i++) {
                double freeEnergy;
                const ParticleStatus status = evaluateParticle(i, model, freeEnergy);
                if (status != Valid) {
                    failedParticle[c] = i;
                    failedStatus[c] = status;
                    break;
                }
                partial += freeEnergy;
            }
            chunkSums[c] = partial;
        }
    });
    for (int c = 0; c < numChunks; c++)
        if (failedParticle[c] != INT_MAX)
            throwParticleError(failedStatus[c], failedParticle[c], context);
    return FixedOrderSum::combine(chunkSums);
}

double CpuCalcGenDPDEForceKernel::computePairForces(ContextImpl& context, std::vector<Vec3>* forces) {
    // docs/theory.md section 4, as Reference: the pair coefficients once per candidate, then each particle gathers
    // its force in Reference's order of addition, and its share of the virial (pairs in which it is first).
    ThreadPool& threads = platformData(context).threads;
    const std::vector<int>& start = neighborList->getCandidateStart();
    const std::vector<int>& candidates = neighborList->getCandidates();
    const std::vector<int>& lowerStart = neighborList->getLowerStart();
    const std::vector<int>& lower = neighborList->getLowerCandidates();
    const int numParticles = start.size() - 1;
    const Physics::DensityWeight weight(cutoff);
    candidateScale.resize(candidates.size());
    parallelFor(&threads, numParticles, particleChunk, [&](int begin, int end) {
        for (int i = begin; i < end; i++)
            for (int m = start[i]; m < start[i + 1]; m++) {
                const double r = candidateDistance[m];
                // Out of range (r < 0) or coincident (r = 0): no force.
                candidateScale[m] = r > 0.0 ? (forceCoefficient[i] + forceCoefficient[candidates[m]])
                                              *weight.derivative(r)/r : 0.0;
            }
    });
    parallelFor(&threads, numParticles, particleChunk, [&](int begin, int end) {
        for (int i = begin; i < end; i++) {
            if (forces != nullptr) {
                Vec3& force = (*forces)[i];
                for (int l = lowerStart[i]; l < lowerStart[i + 1]; l++) {
                    const int c = lower[l];
                    if (candidateDistance[c] > 0.0)
                        force -= candidateDelta[c]*candidateScale[c];
                }
                for (int m = start[i]; m < start[i + 1]; m++)
                    if (candidateDistance[m] > 0.0)
                        force += candidateDelta[m]*candidateScale[m];
            }
            double virial = 0.0;
            for (int m = start[i]; m < start[i + 1]; m++)
                if (candidateDistance[m] > 0.0)
                    virial += candidateScale[m]*candidateDistance[m]*candidateDistance[m];
            particleVirial[i] = virial;
        }
    });
    const int numChunks = FixedOrderSum::numChunks(numParticles);
    chunkSums.assign(numChunks, 0.0);
    parallelFor(&threads, numChunks, 1, [&](int chunkBegin, int chunkEnd) {
        for (int c = chunkBegin; c < chunkEnd; c++) {
            double partial = 0.0;
            const int last = std::min(numParticles, (c + 1)*FixedOrderSum::chunkSize);
            for (int i = c*FixedOrderSum::chunkSize; i < last; i++)
                partial += particleVirial[i];
            chunkSums[c] = partial;
        }
    });
    return FixedOrderSum::combine(chunkSums);
}

PairView CpuCalcGenDPDEForceKernel::collectPairs(ThreadPool& threads) {
    // The candidates in range, in candidate order: (i, j) order, as Reference's list.
    const std::vector<int>& start = neighborList->getCandidateStart();
    const std::vector<int>& candidates = neighborList->getCandidates();
    const int numParticles = start.size() - 1;
    const int numChunks = numRanges(numParticles, particleChunk);
    chunkCounts.assign(numChunks + 1, 0);
    parallelFor(&threads, numChunks, 1, [&](int chunkBegin, int chunkEnd) {
        for (int c = chunkBegin; c < chunkEnd; c++) {
            const int first = start[c*particleChunk], last = start[std::min(numParticles, (c + 1)*particleChunk)];
            chunkCounts[c + 1] = std::count_if(candidateDistance.begin() + first, candidateDistance.begin() + last,
                                               [](double r) { return r >= 0.0; });
        }
    });
    for (int c = 0; c < numChunks; c++)
        chunkCounts[c + 1] += chunkCounts[c];
    pairs.resize(chunkCounts[numChunks]);
    parallelFor(&threads, numChunks, 1, [&](int chunkBegin, int chunkEnd) {
        for (int c = chunkBegin; c < chunkEnd; c++) {
            int next = chunkCounts[c];
            const int last = std::min(numParticles, (c + 1)*particleChunk);
            for (int i = c*particleChunk; i < last; i++)
                for (int m = start[i]; m < start[i + 1]; m++)
                    if (candidateDistance[m] >= 0.0) {
                        ParticlePair& pair = pairs[next++];
                        pair.i = i;
                        pair.j = candidates[m];
                        pair.delta = candidateDelta[m];
                        pair.r = candidateDistance[m];
                    }
        }
    });
    return PairView(pairs.data(), pairs.size());
}
