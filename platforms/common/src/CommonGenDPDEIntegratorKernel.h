/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
#ifndef COMMON_GENDPDE_INTEGRATOR_KERNEL_H_
#define COMMON_GENDPDE_INTEGRATOR_KERNEL_H_

#include "CommonGenDPDEBlockSweep.h"
#include "CommonGenDPDECellGrid.h"
#include "CommonGenDPDEForceChecks.h"
#include "CommonGenDPDEProfiler.h"
#include "CommonGenDPDEThermalArrays.h"
#include "GenDPDEKernels.h"
#include "internal/GenDPDETypes.h"
#include "openmm/common/ComputeArray.h"
#include "openmm/common/ComputeContext.h"
#include <memory>
#include <vector>

namespace GenDPDEPlugin {

/**
 * GenDPDEIntegrator on OpenMM's Common compute platforms: a step is startStep (the checks, a copy of the state, the
 * first kick; kernels/gendpdeIntegrator.cc), the coloured Shardlow sweep in the order of GenDPDESweepDefinition.h,
 * made once per build (CommonGenDPDEBlockSweep), and finishStep (second kick and drift). Internal energies live on the device in `mixed`
 * precision, indexed by original particle index.
 *
 * A run of steps (GenDPDEIntegrator::step(n), between beginSteps() and finishSteps()) never waits for the device: a
 * step that would be unstable, an internal energy that would become <= 0, or an invalid particle found by the
 * GenDPDEForce whose checks it defers stops the run on the device, every later kernel of the run does nothing, and
 * the host reads the status words after the run (and every pollInterval steps, to stop a long run early), resets
 * the step count and time to the failing step (whose state the device kept, rolling back the step's changes), and
 * throws the Reference platform's error, naming the particle and the step.
 *
 * In a run of steps with a GenDPDEForce of the same pair range (periodic, laws that do not depend on temperature) the
 * two share one build (CommonGenDPDEBuildSource): the force's evaluation of each step launches the sweep's build check
 * and cells, and makes its neighbour list from the order's cells whenever the order is built.
 */
class CommonIntegrateGenDPDEStepKernel : public IntegrateGenDPDEStepKernel, public CommonGenDPDEBuildSource {
public:
    /** @param localMemory  the local memory a work group may use on this device (bytes) */
    CommonIntegrateGenDPDEStepKernel(std::string name, const OpenMM::Platform& platform, OpenMM::ComputeContext& cc,
                                     int localMemory) :
            IntegrateGenDPDEStepKernel(name, platform), cc(cc), localMemory(localMemory),
            profiler(cc, "GenDPDEIntegrator") {}
    void initialize(OpenMM::ContextImpl& context, const GenDPDEIntegrator& integrator, double cutoff, int seed,
                    const std::vector<double>& internalEnergies, const std::map<int, int>& particleTypes) override;
    void beginSteps(OpenMM::ContextImpl& context, const GenDPDEIntegrator& integrator, const GenDPDEStepTerms& terms,
                    GenDPDEPairSource* pairSource) override;
    void execute(OpenMM::ContextImpl& context, const GenDPDEIntegrator& integrator, const GenDPDEStepTerms& terms,
                 GenDPDEPairSource* pairSource) override;
    void finishSteps(OpenMM::ContextImpl& context, const GenDPDEIntegrator& integrator) override;
    bool hasInternalEnergies() const override { return energiesSet; }
    double computeKineticEnergy(OpenMM::ContextImpl& context, const GenDPDEIntegrator& integrator) override;
    const std::vector<double>& getInternalEnergies() const override;
    void setInternalEnergies(const std::vector<double>& internalEnergies) override;
    CommonGenDPDEThermalArrays* getDeviceThermalState(const GenDPDEIntegrator& integrator) override;
    void keepDeviceThermalState(OpenMM::ComputeArray& thermalEnergies, OpenMM::ComputeArray& densityEntropies) override;
    void forgetDensityEntropies() override { entropiesKnown = false; }
    int getSeed() const override { return seed; }
    void setSeed(int seed) override { this->seed = seed; }
    bool getSweepBuild(std::vector<OpenMM::Vec3>& positions, OpenMM::Vec3 box[3]) const override;
    void setSweepBuild(const std::vector<OpenMM::Vec3>& positions, const OpenMM::Vec3 box[3]) override;
    void forgetSweepOrder() override;
    // CommonGenDPDEBuildSource
    CommonGenDPDESharedGrid prepareBuild(OpenMM::ArrayInterface& listRebuild, OpenMM::ArrayInterface& forceErrors,
                                         bool listForced) override;
    /** Steps between two reads of the status words inside a run (so that a failed run stops early). */
    static const int pollInterval = 256;

private:
    /** The sweep's tables by class (and each particle's class), uploaded when the integrator's entries changed. */
    /** initialize()'s stages: the per-particle arrays and status words; the step's kernels with their arguments. */
    void allocateArrays(const std::vector<double>& internalEnergies);
    void createStepKernels(OpenMM::ComputeProgram& program);
    void uploadTypeTables(const GenDPDEIntegrator& integrator, const GenDPDEStepTerms& terms);
    /** Read the status words: adjust the sweep's capacities, and throw the run's failure if it stopped. */
    void readStatus(OpenMM::ContextImpl& context, const GenDPDEIntegrator& integrator);
    /** The run of steps is over: the force's checks are its own again. */
    void endRun();
    void throwUnstable(OpenMM::ContextImpl& context, int particle, double stepSize, long long step);
    OpenMM::ComputeContext& cc;
    int localMemory;
    double cutoff = 0.0;
    int seed = 0;
    bool periodic = false, energiesSet = false;
    // The run of steps: where it started, whether the force's checks are deferred to it, and what it stepped.
    bool inRun = false;
    long long runStartStep = 0;
    double runStartTime = 0.0;
    int stepsSincePoll = 0;
    CommonGenDPDEForceChecks* deferredChecks = nullptr;
    bool sharesBuild = false; // the force of deferredChecks shares the sweep's build in this run
    GenDPDEStepTerms runTerms;
    double runStepSize = 0.0;
    std::unique_ptr<CommonGenDPDEBlockSweep> sweep;
    int streamedBlocks = 0;
    OpenMM::ComputeArray energies, savedEnergies, savedVelm, status, noForceErrors, kinetic;
    std::unique_ptr<IntegratorTypeTables> typeTables; // the particle types given to initialize(), and the tables
    OpenMM::ComputeArray atomType, pairTable, heatCapacityTable; // class by original index; per-class parameters
    std::vector<double> uploadedPairTable, uploadedHeatCapacities;
    OpenMM::ComputeKernel startKernel, finishKernel, kineticKernel, keepKernel;
    mutable std::vector<double> hostEnergies;
    // docs/theory.md section 11: sigma(n_i) at the densities `energies` belong to (mixed, by original index), if known.
    OpenMM::ComputeArray densityEntropies;
    bool entropiesKnown = false, runStartEntropiesKnown = false;
    CommonGenDPDEThermalArrays thermalArrays;
    CommonGenDPDEProfiler profiler;
};

} // namespace GenDPDEPlugin

#endif /*COMMON_GENDPDE_INTEGRATOR_KERNEL_H_*/
