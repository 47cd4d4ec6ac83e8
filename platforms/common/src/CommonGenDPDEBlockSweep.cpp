/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
#include "CommonGenDPDEBlockSweep.h"
#include "CommonGenDPDEArguments.h"
#include "CommonGenDPDEKernelSources.h"
#include "internal/BoxGeometry.h"
#include "gendpde/CounterRandom.h"
#include "internal/GenDPDESweepOrder.h"
#include "openmm/OpenMMException.h"
#include <algorithm>
#include <cmath>
#include <cstdlib>

using namespace GenDPDEPlugin;
using namespace OpenMM;

namespace {

/** The arguments of kernels/gendpdeSweep.cc's kernels, in the order of their parameters. */
namespace OrderArgument {
enum {
    Cells,
    Blocks,
    CellStart,
    SortedAtom,
    SortedSlot,
    Posq,
    PosqCorrection,
    BoxA,
    BoxB,
    BoxC,
    Cutoff,
    PairCapacity,
    Status,
    Header,
    BlockAtoms,
    BlockSlots,
    PairScratch,
    BlockPairs,
    LevelStart,
    Count
};
}
namespace SweepArgument {
enum {
    FirstRank,
    NumRanks,
    Cells,
    Blocks,
    Header,
    BlockAtoms,
    BlockSlots,
    LevelStart,
    BlockPairs,
    PairCapacity,
    CellStart,
    SortedAtom,
    SortedSlot,
    Posq,
    PosqCorrection,
    Velm,
    Energies,
    BoxA,
    BoxB,
    BoxC,
    Parameters,
    AtomType,
    PairTable,
    HeatCapacityTable,
    NumClasses,
    Terms,
    Seed,
    StepLow,
    StepHigh,
    StepIndex,
    ZigguratX,
    ZigguratF,
    ZigguratRatio,
    Status,
    Failure,
    FailureEnergy,
    Count
};
}

int roundUp(double value, int multiple) {
    return multiple * (int) std::ceil(value / multiple);
}

/** A developer's setting from the environment (tests force small capacities and several blocks per group). */
int setting(const char* name, int otherwise) {
    const char* value = std::getenv(name);
    return value == nullptr || *value == '\0' ? otherwise : std::atoi(value);
}

} // namespace

CommonGenDPDEBlockSweep::CommonGenDPDEBlockSweep(ComputeContext& cc, CommonGenDPDEProfiler& profiler,
                                                 const std::map<std::string, std::string>& defines,
                                                 const std::string& sources, int localMemory) :
        cc(cc), profiler(profiler), defines(defines), sources(sources), localMemory(localMemory) {
    // One block per group where threads of a warp do not run in step (CPUs); else several blocks of one warp each,
    // as many as local memory holds, since OpenMM launches a bounded number of groups.
    blockThreads = setting("GENDPDE_SWEEP_BLOCK_THREADS", cc.getSIMDWidth() >= 32 ? cc.getSIMDWidth() : 64);
    // The ziggurat of CounterRandom, from the host's table (double where the device has it).
    const CounterRandom::ZigguratTable& table = CounterRandom::ZigguratTable::get();
    const int randomSize = cc.getSupportsDoublePrecision() ? sizeof(double) : sizeof(float);
    zigguratX.initialize(cc, 257, randomSize, "gendpdeZigguratX");
    zigguratF.initialize(cc, 257, randomSize, "gendpdeZigguratF");
    zigguratRatio.initialize(cc, 256, randomSize, "gendpdeZigguratRatio");
    zigguratX.upload(std::vector<double>(table.x, table.x + 257), true);
    zigguratF.upload(std::vector<double>(table.f, table.f + 257), true);
    zigguratRatio.upload(std::vector<double>(table.ratio, table.ratio + 256), true);
    header.initialize<mm_int4>(cc, 1, "gendpdeSweepHeader");
    blockAtoms.initialize<int>(cc, 1, "gendpdeSweepAtoms");
    blockSlots.initialize<int>(cc, 1, "gendpdeSweepSlots");
    pairScratch.initialize<mm_int2>(cc, 1, "gendpdeSweepScratch");
    blockPairs.initialize<mm_int2>(cc, 1, "gendpdeSweepPairs");
    levelStart.initialize<int>(cc, 1, "gendpdeSweepLevels");
    failureParticle.initialize<int>(cc, 1, "gendpdeSweepFailure");
    failureEnergy.initialize(cc, 1, mixedIsDouble(cc) ? sizeof(double) : sizeof(float), "gendpdeSweepFailureEnergy");
}

int CommonGenDPDEBlockSweep::bytesPerParticle() const {
    // orderBlocks: six ints and a mixed4 per particle; sweepBlocks: a mixed4, a mixed and three ints.
    const int mixedSize = mixedIsDouble(cc) ? 8 : 4;
    return std::max(6 * 4 + 4 * mixedSize, 3 * 4 + 5 * mixedSize);
}

int CommonGenDPDEBlockSweep::particleLimit() const {
    // The group's other local arrays take under 1 kB.
    return std::min(65535, 32 * ((localMemory - 1024) / bytesPerParticle() / 32));
}

void CommonGenDPDEBlockSweep::estimateCapacities(int numParticles, const Vec3* box, double range) {
    // Periodic: the mean number of particles in a region of up to 3x3x3 cells and of pairs in a block of 2x2x2, with
    // room for fluctuations; open boundaries (the occupied cells are not known yet): room for a dense liquid.
    int particles = 256, pairs = 1024;
    if (box != nullptr) {
        const std::array<int, 3> cells =
                GenDPDESweepOrder::cellCounts(BoxGeometry::perpendicularWidths(box), range, true);
        const double perCell = numParticles / (double) (cells[0] * cells[1] * cells[2]);
        const double density = numParticles / (box[0][0] * box[1][1] * box[2][2]);
        int regionCells = 1, blockCells = 1;
        for (int k = 0; k < 3; k++) {
            regionCells *= std::min(3, cells[k]);
            blockCells *= std::min(2, cells[k]);
        }
        const double region = regionCells * perCell;
        const double blockPairs = blockCells * perCell * (2.0 * M_PI / 3.0) * range * range * range * density;
        particles = roundUp(1.2 * region + 5 * std::sqrt(region) + 16, 32);
        pairs = roundUp(1.3 * blockPairs + 8 * std::sqrt(blockPairs) + 64, 64);
    }
    maxParticles = std::max(32, std::min(setting("GENDPDE_SWEEP_MAX_PARTICLES", particles), particleLimit()));
    pairCapacity = std::max(1, setting("GENDPDE_SWEEP_PAIR_CAPACITY", pairs));
    compile();
}

bool CommonGenDPDEBlockSweep::adjustCapacities(int mostParticles, int mostPairs) {
    bool changed = false;
    if (mostPairs > pairCapacity && std::getenv("GENDPDE_SWEEP_PAIR_CAPACITY") == nullptr) {
        pairCapacity = roundUp(1.25 * mostPairs, 64);
        allocatedRanks = -1; // reallocate the slabs
        changed = true;
    }
    const int particles = std::min(particleLimit(), roundUp(1.25 * mostParticles, 32));
    if (mostParticles > maxParticles && particles > maxParticles
        && std::getenv("GENDPDE_SWEEP_MAX_PARTICLES") == nullptr) {
        maxParticles = particles;
        allocatedRanks = -1;
        compile();
        changed = true;
    }
    return changed;
}

void CommonGenDPDEBlockSweep::compile() {
    blocksPerGroup = std::max(1,
                              std::min(setting("GENDPDE_SWEEP_BLOCKS_PER_GROUP", cc.getSIMDWidth() >= 32 ? 4 : 1),
                                       (localMemory - 1024) / (bytesPerParticle() * maxParticles)));
    std::map<std::string, std::string> programDefines = defines;
    programDefines["SWEEP_MAX_PARTICLES"] = cc.intToString(maxParticles);
    programDefines["SWEEP_BLOCKS_PER_GROUP"] = cc.intToString(blocksPerGroup);
    programDefines["SWEEP_BLOCK_THREADS"] = cc.intToString(blockThreads);
    ComputeProgram program = cc.compileProgram(sources + CommonGenDPDEKernelSources::GenDPDESweepPair
                                                       + CommonGenDPDEKernelSources::gendpdeSweep,
                                               programDefines);
    orderKernel = program->createKernel("orderBlocks");
    {
        using namespace OrderArgument;
        KernelArguments(orderKernel, "orderBlocks")
                .later(Cells)
                .later(Blocks)
                .later(CellStart)
                .later(SortedAtom)
                .later(SortedSlot)
                .array(Posq, cc.getPosq())
                .array(PosqCorrection, cc.getPosqCorrection())
                .later(BoxA)
                .later(BoxB)
                .later(BoxC)
                .later(Cutoff)
                .later(PairCapacity)
                .later(Status)
                .later(Header)
                .later(BlockAtoms)
                .later(BlockSlots)
                .later(PairScratch)
                .later(BlockPairs)
                .later(LevelStart)
                .done(Count);
    }
    sweepKernel = program->createKernel("sweepBlocks");
    {
        using namespace SweepArgument;
        KernelArguments(sweepKernel, "sweepBlocks")
                .later(FirstRank)
                .later(NumRanks)
                .later(Cells)
                .later(Blocks)
                .later(Header)
                .later(BlockAtoms)
                .later(BlockSlots)
                .later(LevelStart)
                .later(BlockPairs)
                .later(PairCapacity)
                .later(CellStart)
                .later(SortedAtom)
                .later(SortedSlot)
                .array(Posq, cc.getPosq())
                .array(PosqCorrection, cc.getPosqCorrection())
                .array(Velm, cc.getVelm())
                .later(Energies)
                .later(BoxA)
                .later(BoxB)
                .later(BoxC)
                .later(Parameters)
                .later(AtomType)
                .later(PairTable)
                .later(HeatCapacityTable)
                .later(NumClasses)
                .later(Terms)
                .later(Seed)
                .later(StepLow)
                .later(StepHigh)
                .later(StepIndex)
                .array(ZigguratX, zigguratX)
                .array(ZigguratF, zigguratF)
                .array(ZigguratRatio, zigguratRatio)
                .later(Status)
                .later(Failure)
                .later(FailureEnergy)
                .done(Count);
    }
    allocatedRanks = -1;
}

void CommonGenDPDEBlockSweep::allocate() {
    // The slabs of every block: its region's particles, its pairs (twice: the sequence, then by level), its levels.
    const size_t ranks = std::max(1, numRanks);
    header.resize(ranks);
    blockAtoms.resize(ranks * maxParticles);
    blockSlots.resize(ranks * maxParticles);
    pairScratch.resize(ranks * pairCapacity);
    blockPairs.resize(ranks * pairCapacity);
    levelStart.resize(ranks * (pairCapacity + 1));
    failureParticle.resize(ranks);
    failureEnergy.resize(ranks);
    allocatedRanks = numRanks;
}

void CommonGenDPDEBlockSweep::run(CommonGenDPDECellGrid& grid, const BlockSweepStep& step, ArrayInterface& energies,
                                  ArrayInterface& atomType, ArrayInterface& pairTable,
                                  ArrayInterface& heatCapacityTable, int numClasses, ArrayInterface& status) {
    const std::array<int, 3>& cells = grid.getNumCells();
    if (cells != gridCells) {
        gridCells = cells;
        blocks = {(cells[0] + 1) / 2, (cells[1] + 1) / 2, (cells[2] + 1) / 2};
        numRanks = GenDPDESweepOrder::blockRanks(blocks, rankOfBlock, groupStart);
    }
    if (allocatedRanks != numRanks)
        allocate();
    const mm_int4 cellsArgument = grid.getCellsArgument();
    const mm_int4 blocksArgument(blocks[0], blocks[1], blocks[2], numRanks);
    {
        using namespace OrderArgument;
        orderKernel->setArg(Cells, cellsArgument);
        orderKernel->setArg(Blocks, blocksArgument);
        orderKernel->setArg(CellStart, grid.cellStart);
        orderKernel->setArg(SortedAtom, grid.sortedAtom);
        orderKernel->setArg(SortedSlot, grid.sortedSlot);
        grid.setBoxArguments(orderKernel, BoxA, true);
        setMixed(cc, orderKernel, Cutoff, step.cutoff);
        orderKernel->setArg(PairCapacity, pairCapacity);
        orderKernel->setArg(Status, status);
        orderKernel->setArg(Header, header);
        orderKernel->setArg(BlockAtoms, blockAtoms);
        orderKernel->setArg(BlockSlots, blockSlots);
        orderKernel->setArg(PairScratch, pairScratch);
        orderKernel->setArg(BlockPairs, blockPairs);
        orderKernel->setArg(LevelStart, levelStart);
    }
    {
        using namespace SweepArgument;
        sweepKernel->setArg(Cells, cellsArgument);
        sweepKernel->setArg(Blocks, blocksArgument);
        sweepKernel->setArg(Header, header);
        sweepKernel->setArg(BlockAtoms, blockAtoms);
        sweepKernel->setArg(BlockSlots, blockSlots);
        sweepKernel->setArg(LevelStart, levelStart);
        sweepKernel->setArg(BlockPairs, blockPairs);
        sweepKernel->setArg(PairCapacity, pairCapacity);
        sweepKernel->setArg(CellStart, grid.cellStart);
        sweepKernel->setArg(SortedAtom, grid.sortedAtom);
        sweepKernel->setArg(SortedSlot, grid.sortedSlot);
        sweepKernel->setArg(Energies, energies);
        grid.setBoxArguments(sweepKernel, BoxA, true);
        setMixed4(cc, sweepKernel, Parameters, step.cutoff, step.stepSize, std::sqrt(step.stepSize), step.boltzmann);
        sweepKernel->setArg(AtomType, atomType);
        sweepKernel->setArg(PairTable, pairTable);
        sweepKernel->setArg(HeatCapacityTable, heatCapacityTable);
        sweepKernel->setArg(NumClasses, numClasses);
        sweepKernel->setArg(Terms, step.terms);
        sweepKernel->setArg(Seed, step.seed);
        sweepKernel->setArg(StepLow, (unsigned int) step.step);
        sweepKernel->setArg(StepHigh, (unsigned int) ((unsigned long long) step.step >> 32));
        sweepKernel->setArg(StepIndex, step.stepIndex);
        sweepKernel->setArg(Status, status);
        sweepKernel->setArg(Failure, failureParticle);
        sweepKernel->setArg(FailureEnergy, failureEnergy);
    }
    const int groupSize = blocksPerGroup * blockThreads;
    const int groups = (numRanks + blocksPerGroup - 1) / blocksPerGroup;
    profiler.time("sweep order (all blocks)", [&]() { profiler.launch(orderKernel, groups * groupSize, groupSize); });
    profiler.time("sweep (8 colours)", [&]() {
        for (int colour = 0; colour + 1 < (int) groupStart.size(); colour++) {
            const int ranks = groupStart[colour + 1] - groupStart[colour];
            if (ranks == 0)
                continue;
            sweepKernel->setArg(SweepArgument::FirstRank, groupStart[colour]);
            sweepKernel->setArg(SweepArgument::NumRanks, ranks);
            profiler.launch(sweepKernel, groupSize * ((ranks + blocksPerGroup - 1) / blocksPerGroup), groupSize);
        }
    });
}

void CommonGenDPDEBlockSweep::failure(int rank, int& particle, double& energy) {
    std::vector<int> particles;
    std::vector<double> energies;
    failureParticle.download(particles);
    failureEnergy.download(energies, true);
    particle = particles[rank];
    energy = energies[rank];
}
