/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
#ifndef CPU_GENDPDE_INTEGRATOR_KERNEL_H_
#define CPU_GENDPDE_INTEGRATOR_KERNEL_H_

#include "ReferenceGenDPDEIntegratorKernel.h"

namespace GenDPDEPlugin {

/**
 * The CPU platform's step of GenDPDEIntegrator: Reference's step (same stages, same arithmetic, same results to the
 * last bit) with each stage shared among the platform's threads. The pair sweep follows GenDPDESweepOrder: its
 * colours one after another, the blocks of a colour at the same time (they share no particle), each block's pairs
 * in order by one thread; an internal energy that would become <= 0 is reported for the first failing pair of the
 * sequence, as Reference reports it.
 */
class CpuIntegrateGenDPDEStepKernel : public ReferenceIntegrateGenDPDEStepKernel {
public:
    CpuIntegrateGenDPDEStepKernel(std::string name, const OpenMM::Platform& platform) :
            ReferenceIntegrateGenDPDEStepKernel(name, platform) {}
    double computeKineticEnergy(OpenMM::ContextImpl& context, const GenDPDEIntegrator& integrator) override;

protected:
    int numThreads(OpenMM::ContextImpl& context) const override;
    void checkStepIsStable(OpenMM::ContextImpl& context, double stepSize, double maxDisplacement) override;
    void sweep(OpenMM::ContextImpl& context, PairView pairs, std::vector<OpenMM::Vec3>& velocities,
               const GenDPDEIntegrator& integrator, const GenDPDEStepTerms& terms) override;
    void kick(OpenMM::ContextImpl& context, std::vector<OpenMM::Vec3>& velocities,
              const std::vector<OpenMM::Vec3>& forces, double timeStep) override;
    void drift(OpenMM::ContextImpl& context, std::vector<OpenMM::Vec3>& positions,
               const std::vector<OpenMM::Vec3>& velocities, double timeStep) override;

private:
    /** The sweep of these pairs (pair: their first element; geometry: StoredPairGeometry or SlotPositionGeometry). */
    template <class Pair, class Geometry>
    void sweepBlocks(OpenMM::ContextImpl& context, PairView pairs, const Pair* pair, Geometry geometry,
                     std::vector<OpenMM::Vec3>& velocities, const GenDPDEIntegrator& integrator,
                     const GenDPDEStepTerms& terms, int threads);
    std::vector<int> blockFailure; // per block of the running colour: position of the failing pair, or -1
    std::vector<double> chunkSums;
    std::vector<int> rangeFirstUnstable; // per range of particles: the first unstable one, or -1 (checkStepIsStable)
};

} // namespace GenDPDEPlugin

#endif /*CPU_GENDPDE_INTEGRATOR_KERNEL_H_*/
