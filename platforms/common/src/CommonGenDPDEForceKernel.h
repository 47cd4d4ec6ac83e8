/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
#ifndef COMMON_GENDPDE_FORCE_KERNEL_H_
#define COMMON_GENDPDE_FORCE_KERNEL_H_

#include "CommonGenDPDEArguments.h"
#include "CommonGenDPDECellGrid.h"
#include "CommonGenDPDEForceChecks.h"
#include "CommonGenDPDEProfiler.h"
#include "GenDPDEKernels.h"
#include "internal/GenDPDETypes.h"
#include "openmm/common/ComputeArray.h"
#include "openmm/common/ComputeContext.h"
#include <memory>

namespace GenDPDEPlugin {

/**
 * GenDPDEForce on OpenMM's Common compute platforms (OpenCL, CUDA): the passes of kernels/gendpdeForce.cc over
 * the device cell grid, forces in fixed point, energy in the context's energy buffer, in the context's precision.
 * A particle whose state is invalid (no neighbour under V-A, an overflowing equation of state, a non-finite position)
 * stops the evaluation with the Reference platform's error, naming the particle and the step, or, while a
 * GenDPDEIntegrator's run of steps defers these checks (CommonGenDPDEForceChecks), stops that run on the device. It
 * lends its checks to the integrator kernel (GenDPDEPairSource).
 */
class CommonCalcGenDPDEForceKernel : public CalcGenDPDEForceKernel,
                                     public GenDPDEPairSource,
                                     public CommonGenDPDEForceChecks {
public:
    CommonCalcGenDPDEForceKernel(std::string name, const OpenMM::Platform& platform, OpenMM::ComputeContext& cc) :
            CalcGenDPDEForceKernel(name, platform), cc(cc), profiler(cc, "GenDPDEForce") {}
    ~CommonCalcGenDPDEForceKernel();
    void initialize(const OpenMM::System& system, const GenDPDEForce& force) override;
    double execute(OpenMM::ContextImpl& context, bool includeForces, bool includeEnergy) override;
    void copyParametersToContext(OpenMM::ContextImpl& context, const GenDPDEForce& force) override;
    const GenDPDEObservables& getObservables(OpenMM::ContextImpl& context, bool particleVirials) override;
    GenDPDEPairSource* getPairSource() override { return this; }
    // GenDPDEPairSource: the force's checks, which an integrator's run of steps defers.
    CommonGenDPDEForceChecks* getDeviceChecks() override { return this; }
    bool giveThermalState(IntegrateGenDPDEStepKernel& integratorKernel) override;
    // CommonGenDPDEForceChecks
    void setDeferred(bool deferred) override;
    OpenMM::ArrayInterface& getErrorFlags() override { return errors; }
    void throwErrors(OpenMM::ContextImpl& context, int nonFinite, int invalid, long long step) override;
    OpenMM::ArrayInterface* shareBuild(CommonGenDPDEBuildSource* source, double range) override;

private:
    class ForceInfo;
    class ReorderListener;
    /** Add the arguments every pass begins with (NEIGHBOUR_ARGUMENTS in kernels/gendpdeForce.cc). */
    KernelArguments addNeighbourArguments(OpenMM::ComputeKernel& kernel, const std::string& name);
    /** Make room in the list for this many neighbours per particle, if it has less, at the next evaluation. */
    void growList(int mostNeighbours);
    /** The slot (position in OpenMM's per-atom arrays) of a particle. */
    int slotOf(int particle) const;
    void readParameters(const GenDPDEForce& force);
    /** The setup's stages (CommonGenDPDEForceSetup.cpp): the per-particle arrays and the neighbour list; the V-B
     *  tables; the kernels of the list, of the density pass, of the forces and virials, with their arguments. */
    void allocateArrays(const OpenMM::System& system);
    void uploadVolumeTables();
    void createListKernels(OpenMM::ComputeProgram& program);
    void createSharedListKernel(OpenMM::ComputeProgram& program);
    void createDensityKernel(OpenMM::ComputeProgram& program);
    void createForceKernels(OpenMM::ComputeProgram& program);
    /**
     * Build the grid and run the density pass; throws (after the pass) if a particle's state is invalid, unless the
     * checks are deferred.
     */
    void computeDensities(OpenMM::ContextImpl& context);
    /** The cell grid, the neighbour list (rebuilt if needed) and the density pass, without waiting for the device. */
    void densityPass();
    /** The passes' arguments for cells of this size, starting at cellStart (the own grid's or the shared one's). */
    void setModelArguments(const OpenMM::mm_int4& cells, OpenMM::ArrayInterface& cellStart);
    /** Point the density pass at the integrator's thermal state (laws that depend on temperature). */
    void setThermalArguments(OpenMM::ContextImpl& context);
    /** The per-type tables of the laws from the parameters read last. */
    void uploadTypeTables();
    OpenMM::ComputeContext& cc;
    double cutoff, cutoffScaling;
    std::unique_ptr<ParticleTypeIndex> types; // the particle types, fixed when the Context is created
    std::vector<Physics::LocalEquationOfState> lawByType; // by type index (uploaded: lawParameterTable, lawTable)
    bool dependsOnTemperature = false; // some type's law does (docs/theory.md section 11)
    int estimator; // GenDPDEForce::DensityEstimator (= GENDPDE_ESTIMATOR_*)
    bool periodic;
    bool deferred = false; // the checks are made by an integrator's run of steps (CommonGenDPDEForceChecks)
    std::unique_ptr<CommonGenDPDECellGrid> grid;
    // The neighbour list: each particle's neighbours (slots) within (1 + listSkin) R at its last build, by original
    // index, kept while no particle has moved half the skin; rows by slot.
    OpenMM::ComputeArray listCount, buildPosition, neighbours, rebuild;
    int listCapacity = 0, wantedCapacity = 0; // neighbours held per particle; what the next evaluation makes room for
    std::shared_ptr<bool> needsRebuild; // set by the host: first evaluation, atom reordering, new box or capacity
    OpenMM::Vec3 listBox[3];
    OpenMM::ComputeArray primitiveDensity, volume, pressure, forceCoefficient, particleVirial; // real, cell order
    OpenMM::ComputeArray particleVirialTensor; // real, 9 per particle in cell order (observables only)
    OpenMM::ComputeArray momentForce; // q = 2 pi dV/dG g per particle (real4, cell order; estimators with moments)
    OpenMM::ComputeArray polynomialTable, quadratureTable, errors; // the V-B tables (real); error flags
    OpenMM::ComputeArray atomType, lawParameterTable, taitPowerTable; // type by original index; per type the core's
    OpenMM::ComputeArray lawTable; // parameters (real, coreStride() each) and power; the law (GENDPDE_EOS_*, int)
    // Laws that depend on temperature: C_V theta_i and sigma(n_i) by original index (mixed), for the integrator; a
    // placeholder of one element (and for the integrator's arrays) when no law does.
    OpenMM::ComputeArray thermalEnergyOut, densityEntropyOut, placeholderInt;
    OpenMM::ComputeKernel checkKernel, buildKernel, sharedBuildKernel, densityKernel, forceKernel, virialKernel;
    CommonGenDPDEBuildSource* buildSource = nullptr; // the integrator's, while this force shares its build
    GenDPDEObservables observables;
    CommonGenDPDEProfiler profiler;
};

} // namespace GenDPDEPlugin

#endif /*COMMON_GENDPDE_FORCE_KERNEL_H_*/
