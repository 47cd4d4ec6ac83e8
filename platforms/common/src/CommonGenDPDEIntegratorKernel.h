#ifndef COMMON_GENDPDE_INTEGRATOR_KERNEL_H_
#define COMMON_GENDPDE_INTEGRATOR_KERNEL_H_

#include "CommonGenDPDECellGrid.h"
#include "CommonGenDPDEProfiler.h"
#include "GenDPDEKernels.h"
#include "internal/GenDPDETypes.h"
#include "openmm/common/ComputeArray.h"
#include "openmm/common/ComputeContext.h"
#include <memory>
#include <vector>

namespace GenDPDEPlugin {

/**
 * GenDPDEIntegrator on OpenMM's Common compute platforms (kernels/gendpdeIntegrator.cc): half kick, the coloured
 * Shardlow sweep in GenDPDESweepOrder's sequence (the pairs found and ordered on the device, one launch per colour,
 * one thread per block), half kick, drift. Internal energies live on the device in `mixed` precision, indexed by
 * original particle index. A step that would be unstable is refused before anything changes; a sweep after which an
 * internal energy is <= 0 is rolled back (velocities and internal energies) and reported, naming particle and step.
 */
class CommonIntegrateGenDPDEStepKernel : public IntegrateGenDPDEStepKernel {
public:
    CommonIntegrateGenDPDEStepKernel(std::string name, const OpenMM::Platform& platform, OpenMM::ComputeContext& cc) :
            IntegrateGenDPDEStepKernel(name, platform), cc(cc), profiler(cc, "GenDPDEIntegrator") {
    }
    void initialize(OpenMM::ContextImpl& context, const GenDPDEIntegrator& integrator, double cutoff, int seed,
                    const std::vector<double>& internalEnergies, const std::map<int, int>& particleTypes) override;
    void execute(OpenMM::ContextImpl& context, const GenDPDEIntegrator& integrator, const GenDPDEStepTerms& terms,
                 GenDPDEPairSource* pairSource) override;
    double computeKineticEnergy(OpenMM::ContextImpl& context, const GenDPDEIntegrator& integrator) override;
    const std::vector<double>& getInternalEnergies() const override;
    void setInternalEnergies(const std::vector<double>& internalEnergies) override;
    int getSeed() const override {
        return seed;
    }
    void setSeed(int seed) override {
        this->seed = seed;
    }
private:
    /** Find and order the pairs (after the step check); throws, changing nothing, if the step is unstable. */
    void preparePairs(OpenMM::ContextImpl& context, const GenDPDEIntegrator& integrator,
                      const GenDPDEStepTerms& terms, GenDPDEPairSource* pairSource);
    /** The sweep, colour by colour; rolls back and throws if an internal energy became <= 0. */
    void sweep(OpenMM::ContextImpl& context, const GenDPDEIntegrator& integrator, const GenDPDEStepTerms& terms);
    void throwUnstable(OpenMM::ContextImpl& context, int particle, double stepSize, double maxDisplacement);
    OpenMM::ComputeContext& cc;
    double cutoff = 0.0;
    int seed = 0;
    bool periodic = false;
    std::unique_ptr<CommonGenDPDECellGrid> grid;   // own cells, when no force's can be reused
    CommonGenDPDECellGrid* boundGrid = nullptr;     // the grid whose arrays findPairsKernel reads
    std::vector<int> rankOfBlock, groupStart;   // each block's rank in the sweep; each colour's first rank
    std::array<int, 3> blockGridCells = {0, 0, 0};
    OpenMM::ComputeArray energies, savedEnergies, savedVelm, slotOfAtom, status, kinetic;
    OpenMM::ComputeArray zigguratX, zigguratF, zigguratRatio;
    std::unique_ptr<ParticleTypeIndex> types;   // the particle types given to initialize()
    OpenMM::ComputeArray atomType, pairTable, heatCapacityTable;   // type by original index; per-type parameters
    std::vector<double> uploadedPairTable, uploadedHeatCapacities;
    OpenMM::ComputeArray rankOfBlockArray, blockCount, blockStart, blockPairs, orderedPairs;
    OpenMM::ComputeKernel resetKernel, checkKernel, kickKernel, driftKernel, kineticKernel, invertKernel;
    OpenMM::ComputeKernel findPairsKernel, orderKernel, sweepKernel;
    mutable std::vector<double> hostEnergies;
    CommonGenDPDEProfiler profiler;
};

} // namespace GenDPDEPlugin

#endif /*COMMON_GENDPDE_INTEGRATOR_KERNEL_H_*/
