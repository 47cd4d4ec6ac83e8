/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
#ifndef CPU_GENDPDE_FORCE_KERNEL_H_
#define CPU_GENDPDE_FORCE_KERNEL_H_

#include "CellOrderedCandidates.h"
#include "ReferenceGenDPDEForceKernel.h"
#include "RowGatherAvx2.h"
#include <climits>
#include <memory>
#include <vector>

namespace GenDPDEPlugin {

/**
 * The CPU platform's evaluation of GenDPDEForce (docs/theory.md sections 2-4) on the platform's threads, with the
 * same results as Reference to the last bit, whatever the number of threads:
 *
 * - the neighbor list is the Reference one, built and refreshed in parallel (same candidates, same order), its
 *   candidates laid out as full rows in cell order (CellOrderedCandidates), so that the gathers stay in cache;
 * - every per-particle sum is a gather along the particle's row, in the order in which Reference's pair loop adds
 *   the terms (the pairs in which the particle is second, by increasing first particle, then those in which it is
 *   first, by increasing second), each pair term recomputed from the positions with the physics core's functions,
 *   as Reference calls them; no thread writes what another reads, no pair array is stored, and the rounding is
 *   Reference's;
 * - the energy and the virial are summed in fixed chunks (FixedOrderSum).
 *
 * On one thread and below 131,072 particles it runs Reference's passes instead (the same results by construction):
 * the gathers evaluate each pair from both of its particles, which pays only when threads share the work or when the
 * particles no longer fit in the caches (docs/performance.md, "One thread").
 */
class CpuCalcGenDPDEForceKernel : public ReferenceCalcGenDPDEForceKernel {
public:
    CpuCalcGenDPDEForceKernel(std::string name, const OpenMM::Platform& platform) :
            ReferenceCalcGenDPDEForceKernel(name, platform) {}

protected:
    double computeDensitiesAndEnergy(OpenMM::ContextImpl& context) override;
    double computePairForces(OpenMM::ContextImpl& context, std::vector<OpenMM::Vec3>* forces,
                             std::vector<double>* particleVirials) override;

private:
    /** computeDensitiesAndEnergy()'s first and last stages: the positions checked, the neighbour list refreshed and
     *  the rows laid out; the rows' states copied to the per-particle arrays that are read (observables, thermal
     *  state). */
    void refreshRows(OpenMM::ContextImpl& context, int threads);
    void storeRowStates(int threads, int numParticles);
    /** body(gather) with the RowGather (CpuGenDPDEForceKernel.cpp) for this box: open, rectangular or triclinic. */
    template <class Body>
    void withRowGather(Body body);
    /** The AVX2 gathers' input for this evaluation, or null where they do not apply (no AVX2, triclinic box, VC). */
    const RowGatherAvx2::Rows* vectorRowsOrNull();
    std::unique_ptr<RowGatherAvx2::Rows> vectorRows{new RowGatherAvx2::Rows()};
    bool sequential = false; // whether the last evaluation ran Reference's passes (one thread, small systems)
    CellOrderedCandidates layout; // the neighbor list's candidates as full rows in cell order
    // Per row: what the passes find, before it is copied to the particle arrays.
    std::vector<double> rowDensity, rowCoefficient, rowFreeEnergy, rowVirial;
    std::vector<OpenMM::Vec3> rowMoment, rowMomentForce; // VC: g and q = 2 pi dV/dG g per row
    std::vector<Physics::ParticleState> rowState; // where the whole state is kept (computeDensitiesAndEnergy)
    std::vector<OpenMM::Vec3> rowForce;
    std::vector<Physics::Tensor> rowVirialTensor; // each row's virial tensor, when the observables ask for them
    std::vector<double> chunkSums; // partial sums of the energy or the virial (FixedOrderSum chunks)
    // Per range of rows, kept so that a step allocates nothing: the first particle with a position that is not finite,
    // and the lowest particle whose state failed (its status and volume, for the error).
    struct RangeFailure {
        int particle = INT_MAX;
        int status = GENDPDE_PARTICLE_VALID;
        double volume = 0.0;
    };
    std::vector<int> rangeFirstBad;
    std::vector<RangeFailure> rangeFailures;
};

} // namespace GenDPDEPlugin

#endif /*CPU_GENDPDE_FORCE_KERNEL_H_*/
