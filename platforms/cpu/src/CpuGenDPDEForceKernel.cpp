/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
#include "CpuGenDPDEForceKernel.h"
#include "ReferenceKernelAccess.h"
#include "RowGatherAvx2.h"
#include "internal/Buffers.h"
#include "internal/FixedOrderSum.h"
#include "internal/ParallelFor.h"
#include <algorithm>
#include <climits>
#include <cstdlib>
#include <cstring>
#include <type_traits>

using namespace GenDPDEPlugin;
using namespace OpenMM;

namespace {

/** Rows per range of work (fixed: the ranges do not depend on the number of threads). */
const int rowChunk = 256;

/**
 * From this many particles one thread runs the gathers in cell order too (docs/performance.md, "One thread"): below
 * it, Reference's passes over its (i, j) list are faster (each pair evaluated once, the particles in cache); above
 * it, the particles that list reaches in index order miss the caches (a long run numbers its particles at random in
 * space), and the gathers, which read them in cell order, are faster.
 */
const int oneThreadGathersFrom = 131072;

/**
 * Whether one thread runs the gathers for this many particles: by size, or as GENDPDE_CPU_ONE_THREAD_GATHERS says (1:
 * always, 0: never; read once per process), so that the tests can compare both paths with Reference at any size.
 */
bool oneThreadGathers(size_t numParticles) {
    static const int setting = []() {
        const char* value = std::getenv("GENDPDE_CPU_ONE_THREAD_GATHERS");
        return value == nullptr ? -1 : (std::strcmp(value, "1") == 0 ? 1 : 0);
    }();
    return setting < 0 ? numParticles >= (size_t) oneThreadGathersFrom : setting == 1;
}

/**
 * What a gather along a row needs: the row positions, the rows and Reference's pair arithmetic (the physics core's
 * functions, called as Reference calls them). The displacement of a neighbor j < i is r_i - r_j, the exact negative
 * of the r_j - r_i Reference computes for the pair (j, i) (IEEE subtraction and the nearest-image rounding are odd
 * functions), so the distance, the weight and the force term come out with Reference's bits.
 */
template <class NearestImage>
struct RowGather {
    const Vec3* position;
    const int* rowStart;
    const int* upperStart;
    const int* neighbors;
    NearestImage nearestImage;
    double cutoff2;
    Physics::DensityWeight weight;
    /** r_s - r_t (nearest image) and its squared length. */
    Vec3 displacement(int s, int t, double& r2) const {
        const Vec3 d = nearestImage(position[s] - position[t]);
        r2 = d.dot(d);
        return d;
    }
    /** Whether Reference lists the pair (r^2 < R^2). */
    bool listed(double r2) const { return r2 < cutoff2; }
    /** 1 where a listed pair's weight and its derivative are nonzero (r < R too), else 0: a mask, not a branch. */
    double mask(double r2, double r) const { return (double) (listed(r2) & (r < weight.getCutoff())); }
    /** The pair's w(r), masked: Reference's bits in range, 0 beyond (a product by 1 or 0, no branch). */
    double weightTerm(double r, double in) const { return in * weight.valueInside(r); }
    /** VC: the pair's moment term phi(r) d/r as Reference adds it, masked, 0 beyond range or at r = 0. */
    Vec3 momentTerm(const Vec3& d, double r, double in) const {
        const double positive = (double) (r > 0.0);
        return d * ((in * positive) * Physics::momentWeightOverDistance(r, weight.getInverseCutoff()));
    }
    /** 1 where Reference computes the pair's force (listed, r < R and r > 0), else 0 (in: mask()). */
    double forceMask(double r, double in) const { return in * (double) (r > 0.0); }
    /**
     * The pair's force on s (Physics::pairForce, the core's gendpdePairForce, as Reference calls it) with the mask
     * of forceMask on w'(r), and V-C's moment term (qs, qt; when moments) only where the mask is 1: zero beyond range
     * or at r = 0, where Reference skips the pair (r = 0 is replaced by 1 there, so that the arithmetic stays
     * finite). virial receives its d . F.
     */
    Vec3 pairForce(const Vec3& d, double r, double mask, double coefficientSum, bool moments, const Vec3& qs,
                   const Vec3& qt, double& virial) const {
        return Physics::pairForce(d, r + (1.0 - (double) (r > 0.0)), coefficientSum, mask * weight.derivativeInside(r),
                                  weight.getInverseCutoff(), moments && mask != 0.0, qs, qt, virial);
    }
};

template <class NearestImage>
RowGather<NearestImage> rowGather(const CellOrderedCandidates& layout, NearestImage nearestImage, double cutoff) {
    return {layout.getPositions().data(),
            layout.getRowStart().data(),
            layout.getUpperStart().data(),
            layout.getNeighbors().data(),
            nearestImage,
            cutoff * cutoff,
            Physics::DensityWeight(cutoff)};
}

} // namespace

template <class Body>
void CpuCalcGenDPDEForceKernel::withRowGather(Body body) {
    withNearestImage(neighborList->isPeriodic() ? &neighborList->getBox() : nullptr,
                     [&](auto nearestImage) { body(rowGather(layout, nearestImage, cutoff)); });
}

const RowGatherAvx2::Rows* CpuCalcGenDPDEForceKernel::vectorRowsOrNull() {
    const PeriodicBox& box = neighborList->getBox();
    if (!RowGatherAvx2::enabled() || (neighborList->isPeriodic() && box.isTriclinic()) || usesMoments())
        return nullptr;   // (the moments of estimators that read them are gathered by the scalar loops)
    const Physics::DensityWeight weight(cutoff);
    RowGatherAvx2::Rows& rows = *vectorRows;
    rows.position = layout.getPositions().data();
    rows.rowStart = layout.getRowStart().data();
    rows.upperStart = layout.getUpperStart().data();
    rows.neighbors = layout.getNeighbors().data();
    rows.periodic = neighborList->isPeriodic();
    for (int k = 0; k < 3; k++) {
        rows.boxLength[k] = rows.periodic ? box.getVectors()[k][k] : 0.0;
        rows.inverseBoxLength[k] = rows.periodic ? box.getInverseDiagonal()[k] : 0.0;
    }
    rows.cutoff = cutoff;
    rows.cutoff2 = cutoff * cutoff;
    rows.inverseCutoff = weight.getInverseCutoff();
    rows.valueScale = weight.getValueScale();
    rows.derivativeScale = weight.getDerivativeScale();
    return &rows;
}

double CpuCalcGenDPDEForceKernel::computeDensitiesAndEnergy(ContextImpl& context) {
    const int threads = extractNumThreads(context);
    sequential = (threads == 1) && !oneThreadGathers(extractPositions(context).size());
    if (sequential)
        return ReferenceCalcGenDPDEForceKernel::computeDensitiesAndEnergy(context);
    const int numParticles = extractPositions(context).size();
    const int numRangesOfRows = numRanges(numParticles, rowChunk);
    refreshRows(context, threads);

    // docs/theory.md sections 2-4: n0_i = sum_j w(r_ij) along the row, then the particle's volume, pressure and free
    // energy, all in row order (threads writing particle arrays at random would share cache lines). A step needs of
    // each particle's state only its force coefficient and free energy; the whole state is kept (and copied into the
    // per-particle arrays) where the observables ask for it or a law that depends on temperature keeps its thermal
    // state. The error reported is that of the lowest failing particle, as the sequential loop would report it.
    const int* particleOf = layout.getParticle().data();
    const bool keepStates = observablesAsked || dependsOnTemperature;
    rowDensity.resize(numParticles);
    rowState.resize(keepStates ? numParticles : 0);
    rowCoefficient.resize(numParticles);
    rowFreeEnergy.resize(numParticles);
    double* density = rowDensity.data();
    Physics::ParticleState* keptState = rowState.data();
    double* coefficient = rowCoefficient.data();
    double* freeEnergy = rowFreeEnergy.data();
    const bool moments = usesMoments();
    rowMoment.resize(moments ? numParticles : 0);
    rowMomentForce.resize(moments ? numParticles : 0);
    Vec3* momentOf = rowMoment.data();
    Vec3* momentForceOf = rowMomentForce.data();
    const ParticleModel model(*this, context);
    const int* typeOf = types->getParticleTypeIndices().data();
    const RowGatherAvx2::Rows* vectorRows = vectorRowsOrNull();
    rangeFailures.assign(numRangesOfRows, RangeFailure());
    RangeFailure* failure = rangeFailures.data();
    withRowGather([&](auto gather) {
        parallelFor(threads, numParticles, rowChunk, [=](int begin, int end) {
            if (vectorRows != nullptr)
                RowGatherAvx2::densities(*vectorRows, begin, end, density);
            else
                for (int s = begin; s < end; s++) {
                    double n0 = 0.0;
                    Vec3 g;
                    for (int m = gather.rowStart[s]; m < gather.rowStart[s + 1]; m++) {
                        double r2;
                        const Vec3 d = gather.displacement(s, gather.neighbors[m], r2);
                        const double r = std::sqrt(r2);
                        const double in = gather.mask(r2, r);
                        n0 += gather.weightTerm(r, in);
                        if (moments)
                            g += gather.momentTerm(d, r, in);
                    }
                    density[s] = n0;
                    if (moments)
                        momentOf[s] = g;
                }
            for (int s = begin; s < end; s++) {
                const int i = particleOf[s];
                const double G = moments ? momentOf[s].dot(momentOf[s]) : 0.0;
                Physics::ParticleState state;
                const int particleStatus = model.particleState(i, typeOf[i], density[s], G, state);
                if (moments)
                    momentForceOf[s] = momentOf[s] * state.momentForceScale; // as storeParticle()
                if (particleStatus != GENDPDE_PARTICLE_VALID && i < failure[begin / rowChunk].particle)
                    failure[begin / rowChunk] = {i, particleStatus, state.volume};
                coefficient[s] = state.forceCoefficient;
                freeEnergy[s] = state.freeEnergy;
                if (keepStates)
                    keptState[s] = state;
            }
        });
    });
    const int* rowOf = layout.getRow().data();
    storeRowStates(threads, numParticles);
    const auto lowest =
            std::min_element(rangeFailures.begin(), rangeFailures.end(),
                             [](const RangeFailure& a, const RangeFailure& b) { return a.particle < b.particle; });
    if (lowest->particle != INT_MAX)
        throwParticleError(lowest->status, lowest->particle, lowest->volume, context);
    // U = sum_i f(n_i)
    return FixedOrderSum::parallelSum(
            threads, numParticles, [freeEnergy, rowOf](int i) { return freeEnergy[rowOf[i]]; }, chunkSums);
}

void CpuCalcGenDPDEForceKernel::refreshRows(ContextImpl& context, int threads) {
    // The positions checked (the first non-finite one is reported), the neighbour list refreshed and the rows laid
    // out for this evaluation.
    const std::vector<Vec3>& positions = extractPositions(context);
    const int numParticles = positions.size();
    const int numRangesOfRows = numRanges(numParticles, rowChunk);
    std::vector<int>& firstBad = rangeFirstBad;
    firstBad.assign(numRangesOfRows, -1);
    parallelFor(threads, numParticles, rowChunk, [&](int begin, int end) {
        firstBad[begin / rowChunk] = firstNonFinitePosition(positions, begin, end);
    });
    const auto bad = std::find_if(firstBad.begin(), firstBad.end(), [](int i) { return i >= 0; });
    checkConfiguration(context, bad == firstBad.end() ? -1 : *bad);
    neighborList->refresh(positions, extractBoxVectors(context), threads);
    layout.update(*neighborList, threads);
}

void CpuCalcGenDPDEForceKernel::storeRowStates(int threads, int numParticles) {
    // The per-particle arrays in particle order where they are read, each thread writing its own range: all of them
    // for the observables, else a law's thermal state.
    const int* rowOf = layout.getRow().data();
    const double* density = rowDensity.data();
    const Physics::ParticleState* keptState = rowState.data();
    const Vec3* momentOf = rowMoment.data();
    const bool moments = usesMoments();
    if (observablesAsked) {
        sizeParticleArrays();
        parallelFor(threads, numParticles, rowChunk, [=](int begin, int end) {
            for (int i = begin; i < end; i++) {
                primitiveDensity[i] = density[rowOf[i]];
                if (moments)
                    moment[i] = momentOf[rowOf[i]];
                storeParticle(i, keptState[rowOf[i]]);
            }
        });
    } else if (dependsOnTemperature) {
        parallelFor(threads, numParticles, rowChunk, [=](int begin, int end) {
            for (int i = begin; i < end; i++)
                storeThermalState(i, keptState[rowOf[i]]);
        });
    }
}

double CpuCalcGenDPDEForceKernel::computePairForces(ContextImpl& context, std::vector<Vec3>* forces,
                                                    std::vector<double>* particleVirials) {
    if (sequential)
        return ReferenceCalcGenDPDEForceKernel::computePairForces(context, forces, particleVirials);
    // docs/theory.md section 4, as Reference: each particle gathers its force along its row, its share of the virial
    // from the pairs in which it is first (the upper part of the row) and, if asked, half of each pair's virial
    // tensor (the scalar gathers then, which the observables alone ask for).
    const int threads = extractNumThreads(context);
    const int numRows = layout.getNumRows();
    const int* particleOf = layout.getParticle().data();
    const double* coefficient = rowCoefficient.data();
    const bool moments = usesMoments();
    const Vec3* momentForce = rowMomentForce.data();
    rowForce.resize(numRows);
    rowVirial.resize(numRows);
    if (particleVirials != nullptr)
        rowVirialTensor.resize(numRows);
    Vec3* rowF = rowForce.data();
    double* rowW = rowVirial.data();
    Physics::Tensor* rowTensor = particleVirials != nullptr ? rowVirialTensor.data() : nullptr;
    const Vec3* initialForce = forces != nullptr ? forces->data() : nullptr;
    const RowGatherAvx2::Rows* vectorRows = particleVirials == nullptr ? vectorRowsOrNull() : nullptr;
    // The scalar gathers, with the tensors (withTensors true: the observables' pass) or without them (a step's, which
    // must not pay for them): chosen at compile time.
    auto gatherRows = [&](auto gather, auto withTensors, int begin, int end) {
        for (int s = begin; s < end; s++) {
            Vec3 f = rowF[s];
            double sum = 0.0;
            Physics::Tensor tensor;
            // The pairs (j, i), then (i, j): the virial counts the second kind only. VC adds H(d) (q_s - q_t) to
            // each pair's force before it is added, as Reference does.
            const Vec3 noMoment;
            const Vec3& qs = moments ? momentForce[s] : noMoment;
            for (int m = gather.rowStart[s]; m < gather.rowStart[s + 1]; m++) {
                const int t = gather.neighbors[m];
                double r2;
                const Vec3 d = gather.displacement(s, t, r2);
                const double r = std::sqrt(r2);
                const double mask = gather.forceMask(r, gather.mask(r2, r));
                double virial;
                const Vec3 term = gather.pairForce(d, r, mask, coefficient[s] + coefficient[t], moments, qs,
                                                   moments ? momentForce[t] : noMoment, virial);
                f += term;
                if (m >= gather.upperStart[s])
                    sum += virial;
                if constexpr (decltype(withTensors)::value)
                    if (mask != 0.0) // the pairs Reference visits
                        Physics::addHalfPairVirial(term, d, tensor);
            }
            rowF[s] = f;
            rowW[s] = sum;
            if constexpr (decltype(withTensors)::value)
                rowTensor[s] = tensor;
        }
    };
    withRowGather([&](auto gather) {
        parallelFor(threads, numRows, rowChunk, [=](int begin, int end) {
            // Added to the force already there, term by term, as Reference adds them.
            for (int s = begin; s < end; s++)
                rowF[s] = initialForce != nullptr ? initialForce[particleOf[s]] : Vec3();
            if (vectorRows != nullptr)
                RowGatherAvx2::forces(*vectorRows, coefficient, begin, end, rowF, rowW);
            else if (rowTensor != nullptr)
                gatherRows(gather, std::true_type(), begin, end);
            else
                gatherRows(gather, std::false_type(), begin, end);
        });
    });
    // The forces back to particle order, each thread writing its own range.
    const int* rowOf = layout.getRow().data();
    if (forces != nullptr) {
        Vec3* force = forces->data();
        parallelFor(threads, numRows, rowChunk, [=](int begin, int end) {
            for (int i = begin; i < end; i++)
                force[i] = rowF[rowOf[i]];
        });
    }
    if (particleVirials != nullptr) {
        particleVirials->resize(9 * numRows);
        double* tensorOut = particleVirials->data();
        parallelFor(threads, numRows, rowChunk, [=](int begin, int end) {
            for (int i = begin; i < end; i++)
                std::copy(rowTensor[rowOf[i]].element, rowTensor[rowOf[i]].element + 9, tensorOut + 9 * i);
        });
    }
    // W summed over the particles in index order, as Reference sums it
    return FixedOrderSum::parallelSum(threads, numRows, [rowW, rowOf](int i) { return rowW[rowOf[i]]; }, chunkSums);
}
