#ifndef COMMON_GENDPDE_FORCE_KERNEL_H_
#define COMMON_GENDPDE_FORCE_KERNEL_H_

#include "CommonGenDPDECellGrid.h"
#include "CommonGenDPDEProfiler.h"
#include "GenDPDEKernels.h"
#include "internal/GenDPDETypes.h"
#include "openmm/common/ComputeArray.h"
#include "openmm/common/ComputeContext.h"
#include <memory>

namespace GenDPDEPlugin {

/**
 * GenDPDEForce on OpenMM's Common compute platforms (OpenCL, CUDA): the two passes of kernels/gendpdeForce.cc over
 * the device cell grid, forces in fixed point, energy in the context's energy buffer, in the context's precision.
 * A particle whose state is invalid (no neighbour under V-A, an overflowing equation of state, a non-finite position)
 * stops the evaluation with the Reference platform's error, naming the particle and the step.
 */
class CommonCalcGenDPDEForceKernel : public CalcGenDPDEForceKernel {
public:
    CommonCalcGenDPDEForceKernel(std::string name, const OpenMM::Platform& platform, OpenMM::ComputeContext& cc) :
            CalcGenDPDEForceKernel(name, platform), cc(cc), profiler(cc, "GenDPDEForce") {
    }
    void initialize(const OpenMM::System& system, const GenDPDEForce& force) override;
    double execute(OpenMM::ContextImpl& context, bool includeForces, bool includeEnergy) override;
    void copyParametersToContext(OpenMM::ContextImpl& context, const GenDPDEForce& force) override;
    const GenDPDEObservables& getObservables(OpenMM::ContextImpl& context) override;
    /** The cell grid of the last evaluation (the integrator's sweep reuses it at the same positions). */
    CommonGenDPDECellGrid& getCellGrid() {
        return *grid;
    }
private:
    class ForceInfo;
    void readParameters(const GenDPDEForce& force);
    /** Build the grid and run the density pass; throws (after the pass) if a particle's state is invalid. */
    void computeDensities(OpenMM::ContextImpl& context);
    /** The force pass: forces into the force buffer and/or each particle's half virial. */
    void computeForces(bool includeForces, bool includeVirial);
    void setModelArguments();
    /** The per-type Tait tables from the parameters read last. */
    void uploadTypeTables();
    OpenMM::ComputeContext& cc;
    double cutoff, cutoffScaling;
    std::unique_ptr<ParticleTypeIndex> types;   // the particle types, fixed when the Context is created
    std::vector<TaitParameters> taitByType;    // by type index
    GenDPDEForce::DensityEstimator estimator;
    bool periodic;
    std::unique_ptr<CommonGenDPDECellGrid> grid;
    OpenMM::ComputeArray primitiveDensity, volume, pressure, forceCoefficient, particleVirial;   // real, cell order
    OpenMM::ComputeArray momentForce;   // V-C: q = 2 pi dV/dG g per particle (real4, cell order)
    OpenMM::ComputeArray vbCoefficients, vbQuadrature, errors;
    OpenMM::ComputeArray atomType, taitTable, taitPowerTable;   // type by original index; per-type Tait parameters
    OpenMM::ComputeKernel resetErrorsKernel, densityKernel, forceKernel;
    GenDPDEObservables observables;
    CommonGenDPDEProfiler profiler;
};

} // namespace GenDPDEPlugin

#endif /*COMMON_GENDPDE_FORCE_KERNEL_H_*/
