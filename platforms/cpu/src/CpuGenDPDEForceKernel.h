#ifndef CPU_GENDPDE_FORCE_KERNEL_H_
#define CPU_GENDPDE_FORCE_KERNEL_H_

#include "ReferenceGenDPDEForceKernel.h"
#include "openmm/internal/ThreadPool.h"
#include <vector>

namespace GenDPDEPlugin {

/**
 * The CPU platform's evaluation of GenDPDEForce (docs/theory.md sections 2-4) on the platform's threads, with the
 * same results as Reference to the last bit, whatever the number of threads:
 *
 * - the neighbor list is the Reference one, built and refreshed in parallel (same candidates, same order);
 * - each particle's candidates (j > i) are evaluated once per step, in parallel over particles: displacement,
 *   distance and weight, zero for a candidate out of range;
 * - every per-particle sum is a gather in the order in which Reference's pair loop adds the terms (the pairs in which
 *   the particle is second, by increasing first particle, then those in which it is first, by increasing second),
 *   so no thread writes what another reads, and the rounding is Reference's;
 * - the energy and the virial are summed in fixed chunks (FixedOrderSum).
 */
class CpuCalcGenDPDEForceKernel : public ReferenceCalcGenDPDEForceKernel {
public:
    CpuCalcGenDPDEForceKernel(std::string name, const OpenMM::Platform& platform) :
            ReferenceCalcGenDPDEForceKernel(name, platform) {
    }
    /**
     * The pairs closer than the cutoff at the positions of the last evaluation, in (i, j) order (the pair list the
     * integrator sweeps), collected from the evaluated candidates on these threads.
     */
    PairView collectPairs(OpenMM::ThreadPool& threads);
protected:
    double computeDensitiesAndEnergy(OpenMM::ContextImpl& context) override;
    double computePairForces(OpenMM::ContextImpl& context, std::vector<OpenMM::Vec3>* forces) override;
private:
    /** Displacement, distance (-1 when out of range) and weight of every candidate (parallel over particles). */
    void evaluateCandidates(OpenMM::ThreadPool& threads);
    std::vector<OpenMM::Vec3> candidateDelta;   // r_i - r_j (nm)
    std::vector<double> candidateDistance;      // r_ij (nm), -1 for a candidate beyond the cutoff
    std::vector<double> candidateWeight;        // w(r_ij) (nm^-3), 0 beyond the cutoff
    std::vector<double> candidateScale;         // (c_i + c_j) w'(r)/r, 0 beyond the cutoff or at r = 0
    std::vector<double> chunkSums;              // partial sums of the energy or the virial (FixedOrderSum chunks)
    std::vector<int> chunkCounts;
    std::vector<ParticlePair> pairs;            // collectPairs()
};

} // namespace GenDPDEPlugin

#endif /*CPU_GENDPDE_FORCE_KERNEL_H_*/
