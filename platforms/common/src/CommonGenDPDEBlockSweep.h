/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
#ifndef COMMON_GENDPDE_BLOCK_SWEEP_H_
#define COMMON_GENDPDE_BLOCK_SWEEP_H_

#include "CommonGenDPDECellGrid.h"
#include "CommonGenDPDEProfiler.h"
#include "openmm/common/ComputeArray.h"
#include "openmm/common/ComputeContext.h"
#include "openmm/common/ComputeKernel.h"
#include <array>
#include <map>
#include <string>
#include <vector>

namespace GenDPDEPlugin {

/** What the block sweep's kernels read besides the grid: the integrator's state and constants of one step. */
struct BlockSweepStep {
    double cutoff, stepSize, boltzmann;
    int terms;          // bit 0 dissipation, bit 1 conduction, bit 2 internal energies
    unsigned int seed;
    long long step;     // the Context's step count (the random streams' key)
    int stepIndex;      // the step's index in the current run of steps (the status words' HaltStep)
};

/**
 * The Shardlow sweep of GenDPDEIntegrator on OpenMM's Common platforms (kernels/gendpdeSweep.cc), in the sequence of
 * GenDPDESweepOrder: one launch orders every block's pairs (found among the particles of the block's region staged
 * in local memory, interleaved as on the host, grouped in levels of pairs that share no particle), then one launch
 * per colour sweeps its blocks, one work group per block, level by level. The result is the sequential sweep's to
 * the last bit. Nothing waits for the host.
 *
 * Capacities: a block's region (at most maxParticles particles, a compile-time size of local memory) and its slab of
 * pairs (pairCapacity). A block beyond either is swept by a single thread that streams its pairs from the cell grid:
 * correct, slower. The capacities are first estimated from the density of a periodic box, then raised from what the
 * kernels report (adjustCapacities(), once per run of steps): a larger region recompiles the program.
 */
class CommonGenDPDEBlockSweep {
public:
    /**
     * @param defines   the integrator program's defines (NUM_ATOMS, USE_PERIODIC, STATUS_* ...)
     * @param sources   the device code to compile before gendpdeSweep.cc (physics core, cells, random numbers)
     * @param localMemory  the local memory one work group may use on this platform (bytes)
     */
    CommonGenDPDEBlockSweep(OpenMM::ComputeContext& cc, CommonGenDPDEProfiler& profiler,
                            const std::map<std::string, std::string>& defines, const std::string& sources,
                            int localMemory);
    /**
     * A first guess of the capacities, and the program compiled for them: numParticles particles in this periodic
     * box (nm; null for open boundaries) with this pair range (nm).
     */
    void estimateCapacities(int numParticles, const OpenMM::Vec3* box, double range);
    /**
     * Raise the capacities when blocks were streamed: the largest region (particles) and block (pairs) seen, from
     * the status words. Returns whether anything changed.
     */
    bool adjustCapacities(int mostParticles, int mostPairs);
    /**
     * Order the pairs of every block and sweep them, colour by colour, on this grid (built at these positions).
     * atomType: each particle's class by original index (GenDPDETypes.h), the index into the tables by class.
     */
    void run(CommonGenDPDECellGrid& grid, const BlockSweepStep& step, OpenMM::ArrayInterface& energies,
             OpenMM::ArrayInterface& atomType, OpenMM::ArrayInterface& pairTable,
             OpenMM::ArrayInterface& heatCapacityTable, int numClasses, OpenMM::ArrayInterface& status);
    /** The particle and internal energy reported by the failed block of this rank. */
    void failure(int rank, int& particle, double& energy);
    int getMaxParticles() const { return maxParticles; }
    int getPairCapacity() const { return pairCapacity; }
    /** The number of blocks (ranks) of the last run. */
    int getNumRanks() const { return numRanks; }
    /** The blocks one work group sweeps at once, and the threads of each. */
    int getBlocksPerGroup() const { return blocksPerGroup; }
    int getBlockThreads() const { return blockThreads; }
    /** The largest region the local memory of one work group can hold (particles). */
    int particleLimit() const;

private:
    int bytesPerParticle() const;
    void compile();
    void allocate();
    OpenMM::ComputeContext& cc;
    CommonGenDPDEProfiler& profiler;
    std::map<std::string, std::string> defines;
    std::string sources;
    int localMemory, blockThreads, blocksPerGroup = 1;
    int maxParticles = 0, pairCapacity = 0, numRanks = 0, allocatedRanks = -1;
    std::array<int, 3> gridCells = {0, 0, 0}, blocks = {0, 0, 0};
    std::vector<int> rankOfBlock, groupStart;   // GenDPDESweepOrder::blockRanks of the current grid
    OpenMM::ComputeArray header, blockAtoms, blockSlots, pairScratch, blockPairs, levelStart, failureParticle,
            failureEnergy;
    OpenMM::ComputeKernel orderKernel, sweepKernel;
    OpenMM::ComputeArray zigguratX, zigguratF, zigguratRatio;
};

} // namespace GenDPDEPlugin

#endif /*COMMON_GENDPDE_BLOCK_SWEEP_H_*/
