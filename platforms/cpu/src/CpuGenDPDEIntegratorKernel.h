/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
#ifndef CPU_GENDPDE_INTEGRATOR_KERNEL_H_
#define CPU_GENDPDE_INTEGRATOR_KERNEL_H_

#include "ReferenceGenDPDEIntegratorKernel.h"

namespace GenDPDEPlugin {

/**
 * The CPU platform's step of GenDPDEIntegrator: Reference's step (same stages, same arithmetic, same results to the
 * last bit) with each stage shared among the platform's threads (the sweep: Reference's, whose blocks of a colour run
 * at the same time on the platform's threads).
 */
class CpuIntegrateGenDPDEStepKernel : public ReferenceIntegrateGenDPDEStepKernel {
public:
    CpuIntegrateGenDPDEStepKernel(std::string name, const OpenMM::Platform& platform) :
            ReferenceIntegrateGenDPDEStepKernel(name, platform) {}
    double computeKineticEnergy(OpenMM::ContextImpl& context, const GenDPDEIntegrator& integrator) override;

protected:
    int numThreads(OpenMM::ContextImpl& context) const override;
    void checkStepIsStable(OpenMM::ContextImpl& context, double stepSize, double maxDisplacement) override;
    void kick(OpenMM::ContextImpl& context, std::vector<OpenMM::Vec3>& velocities,
              const std::vector<OpenMM::Vec3>& forces, double timeStep) override;
    void drift(OpenMM::ContextImpl& context, std::vector<OpenMM::Vec3>& positions,
               const std::vector<OpenMM::Vec3>& velocities, double timeStep) override;

private:
    std::vector<double> chunkSums;
    std::vector<int> rangeFirstUnstable; // per range of particles: the first unstable one, or -1 (checkStepIsStable)
};

} // namespace GenDPDEPlugin

#endif /*CPU_GENDPDE_INTEGRATOR_KERNEL_H_*/
