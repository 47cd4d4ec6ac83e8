/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
#ifndef COMMON_GENDPDE_BLOCK_SWEEP_H_
#define COMMON_GENDPDE_BLOCK_SWEEP_H_

#include "CommonGenDPDECellGrid.h"
#include "CommonGenDPDEForceChecks.h"
#include "CommonGenDPDEProfiler.h"
#include "openmm/common/ComputeArray.h"
#include "openmm/common/ComputeContext.h"
#include "openmm/common/ComputeKernel.h"
#include <array>
#include <map>
#include <string>
#include <vector>

namespace GenDPDEPlugin {

/** What the block sweep's kernels read: the integrator's state and constants of one step. */
struct BlockSweepStep {
    double cutoff, stepSize, boltzmann;
    int terms;          // bit 0 dissipation, bit 1 conduction, bit 2 internal energies
    unsigned int seed;
    long long step;     // the Context's step count (the random streams' key)
    int stepIndex;      // the step's index in the current run of steps (the status words' HaltStep)
};

/**
 * The Shardlow sweep of GenDPDEIntegrator on OpenMM's Common platforms (kernels/gendpdeSweep.cc), in the order of
 * GenDPDESweepDefinition.h: made once per build on the device and kept between builds. Every step one launch checks
 * whether a build is due (a particle farther than the skin's half from its build position) and, at a build, makes
 * the build's cells; one launch orders each block's candidate pairs in (i, j) order grouped in the greedy levels (at
 * a build; otherwise it returns at once, on the device); one launch sweeps the 8 colours, level by level, updating
 * the candidates closer than R. The stages of a launch run in ticket order (a stage's units after every unit of the
 * stages before it: kernels/gendpdeSweep.cc), or in a launch each with GENDPDE_SWEEP_LAUNCH_PER_STAGE. Nothing waits
 * for the host but, with open boundaries, the build flag and the build's bounding box. The result is the sequential
 * sweep's to the last bit. A GenDPDEForce of the same pair range shares the build during a run of steps (prepare():
 * the check and the cells, launched before its evaluation of the step; its neighbour list is made from these cells at
 * each build).
 *
 * Capacities: a block's region (at most maxParticles particles, a compile-time size of local memory) and its slab of
 * pairs (pairCapacity). A block beyond either is swept by a single thread that finds its candidates and levels again
 * from the build's cells at every step: correct, slower. The capacities are first estimated from the density of a
 * periodic box, then raised from what the kernels report (adjustCapacities(), once per run of steps): a larger region
 * recompiles the program, and the order is then built again from the same build positions.
 */
class CommonGenDPDEBlockSweep {
public:
    /**
     * @param defines   the integrator program's defines (NUM_ATOMS, USE_PERIODIC, STATUS_* ...)
     * @param sources   the device code to compile before gendpdeSweep.cc (physics core, cells, random numbers, status)
     * @param periodic  whether the system is periodic
     * @param range     the pair range R (nm)
     * @param localMemory  the local memory one work group may use on this platform (bytes)
     */
    CommonGenDPDEBlockSweep(OpenMM::ComputeContext& cc, CommonGenDPDEProfiler& profiler,
                            const std::map<std::string, std::string>& defines, const std::string& sources,
                            bool periodic, double range, int localMemory);
    /**
     * A first guess of the capacities, and the program compiled for them: numParticles particles in this periodic
     * box (nm; null for open boundaries).
     */
    void estimateCapacities(int numParticles, const OpenMM::Vec3* box);
    /**
     * Raise the capacities when blocks were streamed: the largest region (particles) and block (pairs) seen, from
     * the status words. Returns whether anything changed (the next step then builds the order again from the same
     * build positions and box).
     */
    bool adjustCapacities(int mostParticles, int mostPairs);
    /**
     * The first part of a step, at its positions: the build check and, where a build is due, the build's cells. A
     * GenDPDEForce that shares the build calls it (through the integrator kernel, CommonGenDPDEBuildSource) before
     * its evaluation of the step, with its list's rebuild mark (set where the order is built, or if listForced) and
     * its error flags (cleared); otherwise run() does, marking the shared list (setSharedList) if there is one.
     */
    void prepare(int stepIndex, OpenMM::ArrayInterface& status, OpenMM::ArrayInterface* listRebuild, bool listForced,
                 OpenMM::ArrayInterface* forceErrors);
    /** The cells of the last build, for a force that shares it. */
    CommonGenDPDESharedGrid sharedGrid();
    /** The rebuild mark of the list of a force that shares the builds during this run of steps, or null. */
    void setSharedList(OpenMM::ArrayInterface* listRebuild) { sharedListRebuild = listRebuild; }
    /**
     * One step's sweep: prepare() unless done for this step, build the order if the build rule asks (or build
     * positions were given), then sweep the pairs of the order closer than R, colour by colour, at the current
     * positions. atomType: each particle's class by original index (GenDPDETypes.h), the index into the tables by
     * class.
     */
    void run(const BlockSweepStep& step, OpenMM::ArrayInterface& energies, OpenMM::ArrayInterface& atomType,
             OpenMM::ArrayInterface& pairTable, OpenMM::ArrayInterface& heatCapacityTable, int numClasses,
             OpenMM::ArrayInterface& status);
    /**
     * The positions (nm, by original index) and box vectors (nm) of the last build, or of the given build not made
     * yet; false if there is none.
     */
    bool getBuild(std::vector<OpenMM::Vec3>& positions, OpenMM::Vec3 box[3]) const;
    /**
     * The next step builds the order from these positions (nm, by original index) and box vectors (nm) instead of its
     * own, then applies the build rule against them.
     */
    void setBuild(const std::vector<OpenMM::Vec3>& positions, const OpenMM::Vec3 box[3]);
    /** Forget the order: the next step builds it at its own positions. */
    void forget() {
        built = false;
        givenPending = false;
        prepared = false;
    }
    /** A new run of steps: no step is prepared yet. */
    void beginRun() { prepared = false; }
    /**
     * The run stopped at step haltStep of the run (its state rolled back): a build the host asked for at that step or
     * later is asked for again; orderIncomplete: the run stopped because a block had more levels than levelLimit()
     * (its order is built again from the same positions next time).
     */
    void runHalted(int haltStep, bool orderIncomplete);
    /** The particle and internal energy reported by the failed block of this rank. */
    void failure(int rank, int& particle, double& energy);
    int getMaxParticles() const { return maxParticles; }
    int getPairCapacity() const { return pairCapacity; }
    /** The number of blocks (ranks) of the last build. */
    int getNumRanks() const { return numRanks; }
    /** The blocks one work group sweeps at once, and the threads of each. */
    int getBlocksPerGroup() const { return blocksPerGroup; }
    int getBlockThreads() const { return blockThreads; }
    /** The largest region the local memory of one work group can hold (particles). */
    int particleLimit() const;
    /** The most levels a block may have on this device (the masks of used levels: 32 bits per word). */
    int levelLimit() const { return 32 * levelWords(); }

private:
    int bytesPerParticle() const;
    int levelWords() const;
    void compile();
    void allocate();
    /** The cells of a build in this box (periodic) or over these bounds (open), and the blocks' ranks. */
    void setCells(const OpenMM::Vec3& extent);
    void setBoxArguments(OpenMM::ComputeKernel& kernel, int index, const OpenMM::Vec3 box[3]) const;
    OpenMM::mm_int4 getCellsArgument() const {
        return OpenMM::mm_int4(gridCells[0], gridCells[1], gridCells[2], gridCells[0] * gridCells[1] * gridCells[2]);
    }
    OpenMM::ComputeContext& cc;
    CommonGenDPDEProfiler& profiler;
    std::map<std::string, std::string> defines;
    std::string sources;
    bool periodic;
    double range;
    int localMemory, blockThreads, blocksPerGroup = 1;
    int maxParticles = 0, pairCapacity = 0, numRanks = 0, allocatedRanks = -1;
    // The build: whether one was made (or given), its box, whether the given positions wait for the next step, the
    // step of the run at which the host last asked for one (and whether it was a given build); the parity of the
    // step (which pair of build flags it uses).
    bool built = false, givenPending = false, lastAskedGiven = false;
    bool countersCleared = false; // cellCount and cellFill hold zeros (kept so by the kernels that use them)
    int lastAskedStep = -1, parity = 0;
    bool prepared = false, mayBuild = false; // prepare() ran for the coming run(); whether that step may build
    OpenMM::ArrayInterface* sharedListRebuild = nullptr;
    OpenMM::ComputeArray placeholder;
    OpenMM::Vec3 buildBox[3], buildLow, buildExtent;
    std::array<int, 3> gridCells = {0, 0, 0}, blocks = {0, 0, 0};
    std::vector<int> groupStart; // the first rank of each colour (GenDPDESweepOrder::blockRanks), and the end
    OpenMM::ComputeArray flags, buildPosition, slotOfAtom, atomCell, cellCount, cellFill, cellStart, sortedAtom, bounds,
            levelMasks;
    OpenMM::ComputeArray header, blockAtoms, pairScratch, blockPairs, levelStart, failureParticle, failureEnergy;
    OpenMM::ComputeArray schedule; // the tickets of the sweep's launch (kernels/gendpdeSweep.cc)
    bool launchPerStage = false;   // GENDPDE_SWEEP_LAUNCH_PER_STAGE: a launch per stage of a step (as before)
    OpenMM::ComputeKernel prepareKernel, boundsKernel, orderKernel, sweepKernel;
    OpenMM::ComputeArray zigguratX, zigguratF, zigguratRatio;
};

} // namespace GenDPDEPlugin

#endif /*COMMON_GENDPDE_BLOCK_SWEEP_H_*/
