#include "CpuGenDPDEForceKernel.h"
#include "ReferenceKernelAccess.h"
#include "RowGatherAvx2.h"
#include "internal/FixedOrderSum.h"
#include "internal/ParallelFor.h"
#include <algorithm>
#include <climits>

using namespace GenDPDEPlugin;
using namespace OpenMM;

namespace {

/** Slots per range of work (fixed: the ranges do not depend on the number of threads). */
const int slotChunk = 256;

/**
 * What a gather along a row needs: the slot positions, the rows and Reference's pair arithmetic. The displacement of
 * a neighbor j < i is r_i - r_j, the exact negative of the r_j - r_i Reference computes for the pair (j, i) (IEEE
 * subtraction and the nearest-image rounding are odd functions), so the distance, the weight and the force term
 * come out with Reference's bits.
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
    Physics::MomentWeight moment;
    /** r_s - r_t (nearest image) and its squared length. */
    Vec3 displacement(int s, int t, double& r2) const {
        const Vec3 d = nearestImage(position[s] - position[t]);
        r2 = d.dot(d);
        return d;
    }
    /** Whether Reference lists the pair (r^2 < R^2). */
    bool listed(double r2) const {
        return r2 < cutoff2;
    }
    /** 1 where a listed pair's weight and its derivative are nonzero (r < R too), else 0: a mask, not a branch. */
    double mask(double r2, double r) const {
        return (double) (listed(r2) & (r < weight.getCutoff()));
    }
    /** The pair's w(r), masked: Reference's bits in range, 0 beyond (a product by 1 or 0, no branch). */
    double weightTerm(double r, double in) const {
        return in*weight.valueInside(r);
    }
    /** VC: the pair's moment term phi(r) d/r as Reference adds it, masked, 0 beyond range or at r = 0. */
    Vec3 momentTerm(const Vec3& d, double r, double in) const {
        const double positive = (double) (r > 0.0);
        return d*((in*positive)*moment.valueOverDistanceInside(r));
    }
    /**
     * VC: the pair's force H(d) (q_s - q_t) as Reference computes it (e = d/r, H = phi' e e^T + (phi/r)(I - e e^T)),
     * masked; along receives e.(q_s - q_t).
     */
    Vec3 momentForce(const Vec3& d, double r, double in, const Vec3& dq, double& along) const {
        const double positive = (double) (r > 0.0), safe = r + (1.0 - positive);
        const Vec3 e = d*(1.0/safe);
        along = e.dot(dq);
        return (e*(moment.derivativeInside(r)*along) + (dq - e*along)*moment.valueOverDistanceInside(r))*(in*positive);
    }
    /**
     * The pair's force scale (c_s + c_t) w'(r)/r, masked, 0 beyond range or at r = 0 (where Reference skips the
     * pair); r = 0 is replaced by 1 in the division so that the product stays finite.
     */
    double forceScale(double r, double in, double coefficientSum) const {
        const double positive = (double) (r > 0.0);
        return (in*positive)*(coefficientSum*weight.derivativeInside(r)/(r + (1.0 - positive)));
    }
};

template <class NearestImage>
RowGather<NearestImage> rowGather(const CellOrderedCandidates& layout, NearestImage nearestImage, double cutoff) {
    return {layout.getPositions().data(), layout.getRowStart().data(), layout.getUpperStart().data(),
            layout.getNeighbors().data(), nearestImage, cutoff*cutoff, Physics::DensityWeight(cutoff),
            Physics::MomentWeight(cutoff)};
}

} // namespace

template <class Body>
void CpuCalcGenDPDEForceKernel::withRowGather(Body body) {
    // The nearest-image rule chosen once per pass, not once per pair.
    const PeriodicBox box = neighborList->getBox();
    if (!neighborList->isPeriodic())
        body(rowGather(layout, [](const Vec3& d) { return d; }, cutoff));
    else if (box.isTriclinic())
        body(rowGather(layout, [box](const Vec3& d) { return box.nearestImageTriclinic(d); }, cutoff));
    else
        body(rowGather(layout, [box](const Vec3& d) { return box.nearestImageRectangular(d); }, cutoff));
}

const RowGatherAvx2::Rows* CpuCalcGenDPDEForceKernel::vectorRowsOrNull() {
    const PeriodicBox& box = neighborList->getBox();
    if (!RowGatherAvx2::enabled() || (neighborList->isPeriodic() && box.isTriclinic()) || usesMoments())
        return nullptr;   // (VC's moments are gathered by the scalar loops)
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
    rows.cutoff2 = cutoff*cutoff;
    rows.inverseCutoff = weight.getInverseCutoff();
    rows.valueScale = weight.getValueScale();
    rows.derivativeScale = weight.getDerivativeScale();
    return &rows;
}

double CpuCalcGenDPDEForceKernel::computeDensitiesAndEnergy(ContextImpl& context) {
    const int threads = extractNumThreads(context);
    const std::vector<Vec3>& positions = extractPositions(context);
    const int numParticles = positions.size();
    std::vector<int> firstBad(numRanges(numParticles, slotChunk), -1);
    parallelFor(threads, numParticles, slotChunk, [&](int begin, int end) {
        firstBad[begin/slotChunk] = firstNonFinitePosition(positions, begin, end);
    });
    const auto bad = std::find_if(firstBad.begin(), firstBad.end(), [](int i) { return i >= 0; });
    checkConfiguration(context, bad == firstBad.end() ? -1 : *bad);
    neighborList->refresh(positions, extractBoxVectors(context), threads);
    layout.update(*neighborList, threads);

    // docs/theory.md sections 2-4: n0_i = sum_j w(r_ij) along the row, then the particle's volume, pressure and free
    // energy, all in slot order (threads writing particle arrays at random would share cache lines). The error
    // reported is that of the lowest failing particle, as the sequential loop would report it.
    const int* particleOf = layout.getParticle().data();
    slotDensity.resize(numParticles);
    slotState.resize(numParticles);
    slotCoefficient.resize(numParticles);
    double* density = slotDensity.data();
    ParticleState* state = slotState.data();
    double* coefficient = slotCoefficient.data();
    const bool moments = usesMoments();
    slotMoment.resize(moments ? numParticles : 0);
    slotMomentForce.resize(moments ? numParticles : 0);
    Vec3* momentOf = slotMoment.data();
    Vec3* momentForceOf = slotMomentForce.data();
    listedFlags.resize(layout.getNeighbors().size());
    char* listed = listedFlags.data();
    const ParticleModel model(*this);
    const int* typeOf = types->getParticleTypeIndices().data();
    const RowGatherAvx2::Rows* vectorRows = vectorRowsOrNull();
    std::vector<int> failedParticle(numRanges(numParticles, slotChunk), INT_MAX);
    std::vector<ParticleStatus> failedStatus(failedParticle.size(), Valid);
    int* failed = failedParticle.data();
    ParticleStatus* status = failedStatus.data();
    withRowGather([&](auto gather) {
        parallelFor(threads, numParticles, slotChunk, [=](int begin, int end) {
            if (vectorRows != nullptr)
                RowGatherAvx2::densities(*vectorRows, begin, end, density, listed);
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
                        listed[m] = gather.listed(r2);   // read by collectPairs()
                    }
                    density[s] = n0;
                    if (moments)
                        momentOf[s] = g;
                }
            for (int s = begin; s < end; s++) {
                const double n0 = density[s];
                const int i = particleOf[s];
                const double G = moments ? momentOf[s].dot(momentOf[s]) : 0.0;
                const ParticleStatus particleStatus = evaluateParticle(n0, G, typeOf[i], model, state[s]);
                if (moments)
                    momentForceOf[s] = momentOf[s]*(2.0*state[s].momentCoefficient);   // as storeParticle()
                if (particleStatus != Valid && i < failed[begin/slotChunk]) {
                    failed[begin/slotChunk] = i;
                    status[begin/slotChunk] = particleStatus;
                }
                coefficient[s] = state[s].forceCoefficient;
            }
        });
    });
    // The per-particle arrays in particle order, each thread writing its own range.
    const int* slotOf = layout.getSlot().data();
    parallelFor(threads, numParticles, slotChunk, [=](int begin, int end) {
        for (int i = begin; i < end; i++) {
            primitiveDensity[i] = density[slotOf[i]];
            if (moments)
                moment[i] = momentOf[slotOf[i]];
            storeParticle(i, state[slotOf[i]]);
        }
    });
    const auto lowest = std::min_element(failedParticle.begin(), failedParticle.end());
    if (*lowest != INT_MAX)
        throwParticleError(failedStatus[lowest - failedParticle.begin()], *lowest, context);
    // U = sum_i f(n_i)
    return FixedOrderSum::parallelSum(threads, numParticles,
                                      [state, slotOf](int i) { return state[slotOf[i]].freeEnergy; }, chunkSums);
}

double CpuCalcGenDPDEForceKernel::computePairForces(ContextImpl& context, std::vector<Vec3>* forces) {
    // docs/theory.md section 4, as Reference: each particle gathers its force along its row, and its share of the
    // virial from the pairs in which it is first (the upper part of the row).
    const int threads = extractNumThreads(context);
    const int numSlots = layout.getNumSlots();
    const int* particleOf = layout.getParticle().data();
    const double* coefficient = slotCoefficient.data();
    const bool moments = usesMoments();
    const Vec3* momentForce = slotMomentForce.data();
    slotForce.resize(numSlots);
    slotVirial.resize(numSlots);
    Vec3* slotF = slotForce.data();
    double* slotW = slotVirial.data();
    const Vec3* initialForce = forces != nullptr ? forces->data() : nullptr;
    const RowGatherAvx2::Rows* vectorRows = vectorRowsOrNull();
    withRowGather([&](auto gather) {
        parallelFor(threads, numSlots, slotChunk, [=](int begin, int end) {
            // Added to the force already there, term by term, as Reference adds them.
            for (int s = begin; s < end; s++)
                slotF[s] = initialForce != nullptr ? initialForce[particleOf[s]] : Vec3();
            if (vectorRows != nullptr) {
                RowGatherAvx2::forces(*vectorRows, coefficient, begin, end, slotF, slotW);
                return;
            }
            for (int s = begin; s < end; s++) {
                Vec3 f = slotF[s];
                double sum = 0.0;
                // The pairs (j, i), then (i, j): the virial counts the second kind only. VC adds H(d) (q_s - q_t)
                // to each pair's force before it is added, as Reference does.
                for (int m = gather.rowStart[s]; m < gather.rowStart[s + 1]; m++) {
                    const int t = gather.neighbors[m];
                    double r2;
                    const Vec3 d = gather.displacement(s, t, r2);
                    const double r = std::sqrt(r2);
                    const double in = gather.mask(r2, r);
                    const double scale = gather.forceScale(r, in, coefficient[s] + coefficient[t]);
                    Vec3 term = d*scale;
                    double virial = scale*r*r;
                    // (q vanishes below V-C's threshold, for nearly all of a bulk liquid: nothing to add then.)
                    if (moments && !(momentForce[s] == Vec3() && momentForce[t] == Vec3())) {
                        double along;
                        term += gather.momentForce(d, r, in, momentForce[s] - momentForce[t], along);
                        virial += (r*gather.moment.derivativeInside(r)*along)*(in*(double) (r > 0.0));
                    }
                    f += term;
                    if (m >= gather.upperStart[s])
                        sum += virial;
                }
                slotF[s] = f;
                slotW[s] = sum;
            }
        });
    });
    // Back to particle order, each thread writing its own range.
    const int* slotOf = layout.getSlot().data();
    double* virial = particleVirial.data();
    Vec3* force = forces != nullptr ? forces->data() : nullptr;
    parallelFor(threads, numSlots, slotChunk, [=](int begin, int end) {
        for (int i = begin; i < end; i++) {
            virial[i] = slotW[slotOf[i]];
            if (force != nullptr)
                force[i] = slotF[slotOf[i]];
        }
    });
    return FixedOrderSum::parallelSum(threads, numSlots, [virial](int i) { return virial[i]; }, chunkSums);
}

PairView CpuCalcGenDPDEForceKernel::collectPairs(int threads) {
    // The entries the last density pass marked in the upper parts of the rows; the rows by increasing first particle
    // give the pairs in (i, j) order, as Reference's list. Rows are read in slot order (in memory order): each row's
    // count, then each row's first position (a prefix sum in particle order), then each row writes its pairs there.
    const int numParticles = layout.getNumSlots();
    const int numChunks = numRanges(numParticles, slotChunk);
    const int* particleOf = layout.getParticle().data();
    const int* slotOf = layout.getSlot().data();
    const int* rowStart = layout.getRowStart().data();
    const int* upperStart = layout.getUpperStart().data();
    const char* listed = listedFlags.data();
    slotPairStart.resize(numParticles);
    int* pairStart = slotPairStart.data();
    parallelFor(threads, numParticles, slotChunk, [=](int begin, int end) {
        for (int s = begin; s < end; s++) {
            int count = 0;
            for (int m = upperStart[s]; m < rowStart[s + 1]; m++)
                count += listed[m];
            pairStart[s] = count;
        }
    });
    pairOffset.assign(numChunks + 1, 0);
    int* offset = pairOffset.data();
    parallelFor(threads, numChunks, 1, [=](int chunkBegin, int chunkEnd) {
        for (int c = chunkBegin; c < chunkEnd; c++) {
            int total = 0;
            for (int i = c*slotChunk; i < std::min(numParticles, (c + 1)*slotChunk); i++)
                total += pairStart[slotOf[i]];
            offset[c + 1] = total;
        }
    });
    for (int c = 0; c < numChunks; c++)
        pairOffset[c + 1] += pairOffset[c];
    parallelFor(threads, numChunks, 1, [=](int chunkBegin, int chunkEnd) {
        for (int c = chunkBegin; c < chunkEnd; c++) {
            int next = offset[c];
            for (int i = c*slotChunk; i < std::min(numParticles, (c + 1)*slotChunk); i++) {
                const int count = pairStart[slotOf[i]];
                pairStart[slotOf[i]] = next;
                next += count;
            }
        }
    });
    pairs.resize(pairOffset[numChunks]);
    ParticlePair* pair = pairs.data();
    withRowGather([&](auto gather) {
        parallelFor(threads, numParticles, slotChunk, [=](int begin, int end) {
            for (int s = begin; s < end; s++) {
                ParticlePair* next = pair + pairStart[s];
                for (int m = gather.upperStart[s]; m < gather.rowStart[s + 1]; m++)
                    if (listed[m]) {
                        double r2;
                        const Vec3 d = gather.displacement(s, gather.neighbors[m], r2);
                        *next++ = {particleOf[s], particleOf[gather.neighbors[m]], d, std::sqrt(r2)};
                    }
            }
        });
    });
    return PairView(pairs.data(), pairs.size());
}
