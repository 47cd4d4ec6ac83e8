/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
#include "CommonGenDPDEBlockSweep.h"
#include "CommonGenDPDEArguments.h"
#include "CommonGenDPDEKernelSources.h"
#include "CommonGenDPDEStatus.h"
#include "gendpde/CounterRandom.h"
#include "gendpde/GenDPDESweepDefinition.h"
#include "internal/BoxGeometry.h"
#include "internal/GenDPDESweepOrder.h"
#include "openmm/OpenMMException.h"
#include <algorithm>
#include <cmath>
#include <cstdlib>

using namespace GenDPDEPlugin;
using namespace OpenMM;

namespace {

const int scanGroupSize = 256;
const int boundsGroupSize = 128;

/** The arguments of kernels/gendpdeSweep.cc's kernels, in the order of their parameters. */
namespace PrepareArgument {
enum {
    FirstStage,
    EndStage,
    AtomUnits,
    CellUnits,
    Posq,
    PosqCorrection,
    AtomIndex,
    BuildPosition,
    BoxA,
    BoxB,
    BoxC,
    Limit2,
    Parity,
    HostBuild,
    HostCapture,
    Flags,
    SlotOfAtom,
    Status,
    ListRebuild,
    ListForced,
    ForceErrors,
    ClearForceErrors,
    Low,
    Extent,
    Cells,
    AtomCell,
    CellCount,
    CellStart,
    CellFill,
    SortedAtom,
    Schedule,
    Count
};
}
namespace BoundsArgument {
enum { Flags, Parity, Status, Posq, PosqCorrection, SlotOfAtom, BuildPosition, Bounds, Count };
}
namespace OrderArgument {
enum {
    Flags,
    Parity,
    StepIndex,
    Cells,
    Blocks,
    CellStart,
    SortedAtom,
    BuildPosition,
    BoxA,
    BoxB,
    BoxC,
    CandidateRange,
    PairCapacity,
    Status,
    Header,
    BlockAtoms,
    PairScratch,
    BlockPairs,
    LevelStart,
    Count
};
}
namespace SweepArgument {
enum {
    FirstColour,
    EndColour,
    Cells,
    Blocks,
    Header,
    BlockAtoms,
    LevelStart,
    BlockPairs,
    PairCapacity,
    CellStart,
    SortedAtom,
    BuildPosition,
    BuildA,
    BuildB,
    BuildC,
    CandidateRange,
    LevelMasks,
    SlotOfAtom,
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
    Schedule,
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
                                                 const std::string& sources, bool periodic, double range,
                                                 int localMemory) :
        cc(cc), profiler(profiler), defines(defines), sources(sources), periodic(periodic), range(range),
        localMemory(localMemory) {
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
    // The build: its flags, positions (by original index), cells; each particle's slot.
    const int numAtoms = cc.getNumAtoms();
    const int mixedSize = mixedIsDouble(cc) ? sizeof(double) : sizeof(float);
    flags.initialize<int>(cc, 4, "gendpdeSweepBuildFlags");
    flags.upload(std::vector<int>(4, 0));
    buildPosition.initialize(cc, numAtoms, 4 * mixedSize, "gendpdeSweepBuildPosition");
    slotOfAtom.initialize<int>(cc, numAtoms, "gendpdeSweepSlotOfAtom");
    atomCell.initialize<int>(cc, numAtoms, "gendpdeSweepAtomCell");
    sortedAtom.initialize<int>(cc, numAtoms, "gendpdeSweepSortedAtom");
    cellCount.initialize<int>(cc, 1, "gendpdeSweepCellCount");
    cellFill.initialize<int>(cc, 1, "gendpdeSweepCellFill");
    cellStart.initialize<int>(cc, 2, "gendpdeSweepCellStart");
    bounds.initialize(cc, 6, mixedSize, "gendpdeSweepBounds");
    levelMasks.initialize<int>(cc, (size_t) numAtoms * levelWords(), "gendpdeSweepLevelMasks");
    header.initialize<mm_int4>(cc, 1, "gendpdeSweepHeader");
    blockAtoms.initialize<int>(cc, 1, "gendpdeSweepAtoms");
    pairScratch.initialize<mm_int2>(cc, 1, "gendpdeSweepScratch");
    blockPairs.initialize<int>(cc, 1, "gendpdeSweepPairs");
    levelStart.initialize<int>(cc, 1, "gendpdeSweepLevels");
    failureParticle.initialize<int>(cc, 1, "gendpdeSweepFailure");
    failureEnergy.initialize(cc, 1, mixedSize, "gendpdeSweepFailureEnergy");
    placeholder.initialize<int>(cc, 2, "gendpdeSweepPlaceholder"); // a force's flags where no force shares
    placeholder.upload(std::vector<int>(2, 0));
    // The tickets of the launches whose stages run in ticket order (kernels/gendpdeSweep.cc, "Stages in one
    // launch"), left so by every launch.
    schedule.initialize<int>(cc, 4, "gendpdeSweepSchedule");
    schedule.upload(std::vector<int>{0, 0, 0, DeviceStatus::NoValue});
    // A developer's setting: a launch per stage (the check, each step of the cells, each colour), as before they
    // shared a launch, to compare the two (devtools/sweep_launch_modes.py).
    launchPerStage = setting("GENDPDE_SWEEP_LAUNCH_PER_STAGE", 0) != 0;
}

int CommonGenDPDEBlockSweep::levelWords() const {
    // The masks of used levels take the space of a particle's position (a mixed4) once its pairs are listed.
    return mixedIsDouble(cc) ? 8 : 4;
}

int CommonGenDPDEBlockSweep::bytesPerParticle() const {
    // orderBlocks: four ints and a mixed4 per particle; sweepBlocks: a mixed4, a mixed and three ints.
    const int mixedSize = mixedIsDouble(cc) ? 8 : 4;
    return std::max(4 * 4 + 4 * mixedSize, 3 * 4 + 5 * mixedSize);
}

int CommonGenDPDEBlockSweep::particleLimit() const {
    // The group's other local arrays take under 1 kB; ranks within a region are 16 bits.
    return std::min(65535, 32 * ((localMemory - 1024) / bytesPerParticle() / 32));
}

void CommonGenDPDEBlockSweep::estimateCapacities(int numParticles, const Vec3* box) {
    // Periodic: the mean number of particles in a region of up to 3x3x3 cells and of candidates in a block of 2x2x2,
    // with room for fluctuations; open boundaries (the occupied cells are not known yet): room for a dense liquid.
    int particles = 256, pairs = 1024;
    if (box != nullptr) {
        const double candidate = SweepDefinition::candidateRange(range);
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
        const double blockPairs =
                blockCells * perCell * (2.0 * M_PI / 3.0) * candidate * candidate * candidate * density;
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
    if (changed && built)
        givenPending = true; // the slabs are new: the same build again, into them
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
    programDefines["SWEEP_LEVEL_WORDS"] = cc.intToString(levelWords());
    ComputeProgram program = cc.compileProgram(sources + CommonGenDPDEKernelSources::GenDPDESweepPair
                                                       + CommonGenDPDEKernelSources::gendpdeSweep,
                                               programDefines);
    prepareKernel = program->createKernel("prepareSweepBuild");
    {
        using namespace PrepareArgument;
        KernelArguments(prepareKernel, "prepareSweepBuild")
                .later(FirstStage)
                .later(EndStage)
                .later(AtomUnits)
                .later(CellUnits)
                .array(Posq, cc.getPosq())
                .array(PosqCorrection, cc.getPosqCorrection())
                .array(AtomIndex, cc.getAtomIndexArray())
                .array(BuildPosition, buildPosition)
                .later(BoxA)
                .later(BoxB)
                .later(BoxC)
                .later(Limit2)
                .later(Parity)
                .later(HostBuild)
                .later(HostCapture)
                .array(Flags, flags)
                .array(SlotOfAtom, slotOfAtom)
                .later(Status)
                .later(ListRebuild)
                .later(ListForced)
                .later(ForceErrors)
                .later(ClearForceErrors)
                .later(Low)
                .later(Extent)
                .later(Cells)
                .array(AtomCell, atomCell)
                .later(CellCount)
                .later(CellStart)
                .later(CellFill)
                .array(SortedAtom, sortedAtom)
                .array(Schedule, schedule)
                .done(Count);
    }
    boundsKernel = program->createKernel("findSweepBounds");
    {
        using namespace BoundsArgument;
        KernelArguments(boundsKernel, "findSweepBounds")
                .array(Flags, flags)
                .later(Parity)
                .later(Status)
                .array(Posq, cc.getPosq())
                .array(PosqCorrection, cc.getPosqCorrection())
                .array(SlotOfAtom, slotOfAtom)
                .array(BuildPosition, buildPosition)
                .array(Bounds, bounds)
                .done(Count);
    }
    orderKernel = program->createKernel("orderBlocks");
    {
        using namespace OrderArgument;
        KernelArguments(orderKernel, "orderBlocks")
                .array(Flags, flags)
                .later(Parity)
                .later(StepIndex)
                .later(Cells)
                .later(Blocks)
                .later(CellStart)
                .array(SortedAtom, sortedAtom)
                .array(BuildPosition, buildPosition)
                .later(BoxA)
                .later(BoxB)
                .later(BoxC)
                .later(CandidateRange)
                .later(PairCapacity)
                .later(Status)
                .later(Header)
                .later(BlockAtoms)
                .later(PairScratch)
                .later(BlockPairs)
                .later(LevelStart)
                .done(Count);
    }
    sweepKernel = program->createKernel("sweepBlocks");
    {
        using namespace SweepArgument;
        KernelArguments(sweepKernel, "sweepBlocks")
                .later(FirstColour)
                .later(EndColour)
                .later(Cells)
                .later(Blocks)
                .later(Header)
                .later(BlockAtoms)
                .later(LevelStart)
                .later(BlockPairs)
                .later(PairCapacity)
                .later(CellStart)
                .array(SortedAtom, sortedAtom)
                .array(BuildPosition, buildPosition)
                .later(BuildA)
                .later(BuildB)
                .later(BuildC)
                .later(CandidateRange)
                .array(LevelMasks, levelMasks)
                .array(SlotOfAtom, slotOfAtom)
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
                .array(Schedule, schedule)
                .done(Count);
    }
    allocatedRanks = -1;
}

void CommonGenDPDEBlockSweep::allocate() {
    // The slabs of every block: its region's particles, its pairs (twice: in (i, j) order, then by level), its levels.
    const size_t ranks = std::max(1, numRanks);
    header.resize(ranks);
    blockAtoms.resize(ranks * maxParticles);
    pairScratch.resize(ranks * pairCapacity);
    blockPairs.resize(ranks * pairCapacity);
    levelStart.resize(ranks * (pairCapacity + 1));
    failureParticle.resize(ranks);
    failureEnergy.resize(ranks);
    allocatedRanks = numRanks;
}

void CommonGenDPDEBlockSweep::setCells(const Vec3& extent) {
    const std::array<int, 3> cells =
            GenDPDESweepOrder::cellCounts(extent, range, periodic); // (cells of the candidate range)
    const long long total = (long long) cells[0] * cells[1] * cells[2];
    if (total > 100000000)
        throw OpenMMException("GenDPDE: the particles span " + std::to_string(total)
                              + " cells of the sweep's candidate range; more than 1e8 cells are not supported on this "
                                "platform (is the system blowing apart?)");
    if (cells == gridCells)
        return;
    gridCells = cells;
    blocks = {(cells[0] + 1) / 2, (cells[1] + 1) / 2, (cells[2] + 1) / 2};
    std::vector<int> rankOfBlock; // (not needed here: the kernels find a rank's block themselves)
    numRanks = GenDPDESweepOrder::blockRanks(blocks, rankOfBlock, groupStart);
    if ((long long) cellCount.getSize() < total || !countersCleared) {
        // The counters start at zero; afterwards the scan and the sort leave them zero (no clearing launches).
        if ((long long) cellCount.getSize() < total) {
            cellCount.resize(total);
            cellFill.resize(total);
            cellStart.resize(total + 1);
        }
        countersCleared = true;
        cc.clearBuffer(cellCount);
        cc.clearBuffer(cellFill);
        profiler.launched();
        profiler.launched();
    }
}

void CommonGenDPDEBlockSweep::setBoxArguments(ComputeKernel& kernel, int index, const Vec3 box[3]) const {
    // w: the inverse of the diagonal element, for the nearest image (as CommonGenDPDECellGrid::setBoxArguments).
    for (int k = 0; k < 3; k++)
        setVector4(kernel, index + k, mixedIsDouble(cc), box[k][0], box[k][1], box[k][2], 1.0 / box[k][k]);
}

void CommonGenDPDEBlockSweep::prepare(int stepIndex, ArrayInterface& status, ArrayInterface* listRebuild,
                                      bool listForced, ArrayInterface* forceErrors) {
    // The build rule (GenDPDESweepDefinition.h): the host asks for a build from the step's positions at the first
    // step and when the box has changed, for one from given positions after setBuild(); the device adds one when a
    // particle has moved too far.
    if (stepIndex == 0)
        lastAskedStep = -1; // a new run of steps
    Vec3 box[3];
    cc.getPeriodicBoxVectors(box[0], box[1], box[2]);
    bool newBox = false;
    if (built && periodic)
        for (int k = 0; k < 3; k++)
            newBox = newBox || box[k] != buildBox[k];
    const bool hostCapture = !built || newBox, hostBuild = givenPending && !hostCapture;
    if (hostCapture || hostBuild) {
        lastAskedStep = stepIndex;
        lastAskedGiven = hostBuild;
    }
    if (hostCapture) {
        for (int k = 0; k < 3; k++)
            buildBox[k] = box[k];
        built = true;
    }
    givenPending = false;
    const int numAtoms = cc.getNumAtoms();
    {
        using namespace PrepareArgument;
        setBoxArguments(prepareKernel, BoxA, box); // (periodic: the build's box, which it is now)
        setMixed(cc, prepareKernel, Limit2, SweepDefinition::rebuildDisplacement2(range));
        prepareKernel->setArg(Parity, parity);
        prepareKernel->setArg(HostBuild, hostBuild ? 1 : 0);
        prepareKernel->setArg(HostCapture, hostCapture ? 1 : 0);
        prepareKernel->setArg(Status, status);
        ArrayInterface* rebuildMark = (listRebuild != nullptr ? listRebuild : sharedListRebuild);
        prepareKernel->setArg(ListRebuild, rebuildMark != nullptr ? *rebuildMark : placeholder);
        prepareKernel->setArg(ListForced, listForced ? 1 : 0);
        prepareKernel->setArg(ForceErrors, forceErrors != nullptr ? *forceErrors : placeholder);
        prepareKernel->setArg(ClearForceErrors, forceErrors != nullptr ? 1 : 0);
    }
    // The stages first .. end - 1 of prepareSweepBuild (0 the check; 1-4 the cells, at a build) in one launch, or
    // in one launch each (GENDPDE_SWEEP_LAUNCH_PER_STAGE).
    auto launchRange = [&](int first, int end, const Vec3& low, const Vec3& extent) {
        using namespace PrepareArgument;
        const mm_int4 cellsArgument = getCellsArgument();
        const int atomUnits =
                std::max(1, std::min((numAtoms + scanGroupSize - 1) / scanGroupSize, cc.getNumThreadBlocks()));
        const int cellUnits =
                std::max(1, std::min((cellsArgument.w + scanGroupSize - 1) / scanGroupSize, cc.getNumThreadBlocks()));
        int units = 0;
        for (int stage = first; stage < end; stage++)
            units += (stage == 2 ? 1 : stage == 4 ? cellUnits : atomUnits);
        prepareKernel->setArg(FirstStage, first);
        prepareKernel->setArg(EndStage, end);
        prepareKernel->setArg(AtomUnits, atomUnits);
        prepareKernel->setArg(CellUnits, cellUnits);
        setMixed4(cc, prepareKernel, Low, low[0], low[1], low[2], 0.0);
        setMixed4(cc, prepareKernel, Extent, extent[0], extent[1], extent[2], 0.0);
        prepareKernel->setArg(Cells, cellsArgument);
        prepareKernel->setArg(CellCount, cellCount);
        prepareKernel->setArg(CellStart, cellStart);
        prepareKernel->setArg(CellFill, cellFill);
        profiler.launch(prepareKernel, scanGroupSize * units, scanGroupSize);
    };
    auto launchStages = [&](int first, int end, const Vec3& low, const Vec3& extent) {
        for (int stage = first; stage < end; stage = (launchPerStage ? stage + 1 : end))
            launchRange(stage, launchPerStage ? stage + 1 : end, low, extent);
    };
    mayBuild = true;
    if (periodic) {
        // The check and, at a build, the cells, in one launch.
        setCells(BoxGeometry::perpendicularWidths(buildBox));
        if (allocatedRanks != numRanks)
            allocate();
        profiler.time("sweep check, cells (if due)", [&]() { launchStages(0, 5, Vec3(), Vec3()); });
    } else {
        // Open boundaries: the cells follow the build positions' bounding box, which the host must read.
        profiler.time("sweep check, cells (if due)", [&]() { launchStages(0, 1, Vec3(), Vec3()); });
        std::vector<int> found;
        profiler.transfer();
        flags.download(found);
        mayBuild = found[2 * parity] != 0;
        if (mayBuild) {
            {
                using namespace BoundsArgument;
                boundsKernel->setArg(Parity, parity);
                boundsKernel->setArg(Status, status);
                profiler.launch(boundsKernel, boundsGroupSize, boundsGroupSize);
            }
            std::vector<double> corners;
            profiler.transfer();
            bounds.download(corners, true);
            const Vec3 low(corners[0], corners[1], corners[2]);
            const Vec3 extent = Vec3(corners[3], corners[4], corners[5]) - low;
            setCells(extent);
            if (allocatedRanks != numRanks)
                allocate();
            profiler.time("sweep check, cells (if due)", [&]() { launchStages(1, 5, low, extent); });
        }
    }
    prepared = true;
}

CommonGenDPDESharedGrid CommonGenDPDEBlockSweep::sharedGrid() {
    CommonGenDPDESharedGrid grid;
    grid.cells = getCellsArgument();
    grid.cellStart = &cellStart;
    grid.sortedAtom = &sortedAtom;
    grid.atomCell = &atomCell;
    grid.buildPosition = &buildPosition;
    grid.slotOfAtom = &slotOfAtom;
    return grid;
}

void CommonGenDPDEBlockSweep::run(const BlockSweepStep& step, ArrayInterface& energies, ArrayInterface& atomType,
                                  ArrayInterface& pairTable, ArrayInterface& heatCapacityTable, int numClasses,
                                  ArrayInterface& status) {
    // The step's check and cells, unless a GenDPDEForce that shares the build launched them for this step.
    if (!prepared)
        prepare(step.stepIndex, status, nullptr, false, nullptr);
    prepared = false;
    Vec3 box[3];
    cc.getPeriodicBoxVectors(box[0], box[1], box[2]);
    const mm_int4 cellsArgument = getCellsArgument();
    const mm_int4 blocksArgument(blocks[0], blocks[1], blocks[2], numRanks);
    const int groupSize = blocksPerGroup * blockThreads;
    if (mayBuild) {
        {
            using namespace OrderArgument;
            orderKernel->setArg(Parity, parity);
            orderKernel->setArg(StepIndex, step.stepIndex);
            orderKernel->setArg(Cells, cellsArgument);
            orderKernel->setArg(Blocks, blocksArgument);
            orderKernel->setArg(CellStart, cellStart);
            setBoxArguments(orderKernel, BoxA, buildBox);
            setMixed(cc, orderKernel, CandidateRange, SweepDefinition::candidateRange(range));
            orderKernel->setArg(PairCapacity, pairCapacity);
            orderKernel->setArg(Status, status);
            orderKernel->setArg(Header, header);
            orderKernel->setArg(BlockAtoms, blockAtoms);
            orderKernel->setArg(PairScratch, pairScratch);
            orderKernel->setArg(BlockPairs, blockPairs);
            orderKernel->setArg(LevelStart, levelStart);
        }
        const int groups = (numRanks + blocksPerGroup - 1) / blocksPerGroup;
        profiler.time("sweep order build (if due)",
                      [&]() { profiler.launch(orderKernel, groups * groupSize, groupSize); });
    }
    {
        using namespace SweepArgument;
        sweepKernel->setArg(Cells, cellsArgument);
        sweepKernel->setArg(Blocks, blocksArgument);
        sweepKernel->setArg(Header, header);
        sweepKernel->setArg(BlockAtoms, blockAtoms);
        sweepKernel->setArg(LevelStart, levelStart);
        sweepKernel->setArg(BlockPairs, blockPairs);
        sweepKernel->setArg(PairCapacity, pairCapacity);
        sweepKernel->setArg(CellStart, cellStart);
        setBoxArguments(sweepKernel, BuildA, buildBox);
        setMixed(cc, sweepKernel, CandidateRange, SweepDefinition::candidateRange(range));
        sweepKernel->setArg(Energies, energies);
        setBoxArguments(sweepKernel, BoxA, box);
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
    profiler.time("sweep (8 colours)", [&]() {
        // One launch for the 8 colours, or one per colour (GENDPDE_SWEEP_LAUNCH_PER_STAGE); a launch's work groups
        // take its units (blocksPerGroup blocks of a colour) in ticket order, however many OpenMM launches.
        const int first = 0, end = (int) groupStart.size() - 1;
        for (int colour = first; colour < end; colour += (launchPerStage ? 1 : std::max(1, end - first))) {
            const int last = (launchPerStage ? colour + 1 : end);
            int units = 0;
            for (int k = colour; k < last; k++)
                units += (groupStart[k + 1] - groupStart[k] + blocksPerGroup - 1) / blocksPerGroup;
            if (units == 0)
                continue;
            sweepKernel->setArg(SweepArgument::FirstColour, colour);
            sweepKernel->setArg(SweepArgument::EndColour, last);
            profiler.launch(sweepKernel, groupSize * units, groupSize);
        }
    });
    parity = 1 - parity;
}

bool CommonGenDPDEBlockSweep::getBuild(std::vector<Vec3>& positions, Vec3 box[3]) const {
    if (!built)
        return false;
    positions.resize(cc.getNumAtoms());
    if (mixedIsDouble(cc)) {
        std::vector<mm_double4> values;
        buildPosition.download(values);
        for (size_t i = 0; i < positions.size(); i++)
            positions[i] = Vec3(values[i].x, values[i].y, values[i].z);
    } else {
        std::vector<mm_float4> values;
        buildPosition.download(values);
        for (size_t i = 0; i < positions.size(); i++)
            positions[i] = Vec3(values[i].x, values[i].y, values[i].z);
    }
    for (int k = 0; k < 3; k++)
        box[k] = buildBox[k];
    return true;
}

void CommonGenDPDEBlockSweep::setBuild(const std::vector<Vec3>& positions, const Vec3 box[3]) {
    if ((int) positions.size() != cc.getNumAtoms())
        throw OpenMMException("GenDPDEIntegrator: the sweep's build positions are for "
                              + std::to_string(positions.size()) + " particles; the System has "
                              + std::to_string(cc.getNumAtoms()));
    if (mixedIsDouble(cc)) {
        std::vector<mm_double4> values(positions.size());
        for (size_t i = 0; i < positions.size(); i++)
            values[i] = mm_double4(positions[i][0], positions[i][1], positions[i][2], 0.0);
        buildPosition.upload(values);
    } else {
        std::vector<mm_float4> values(positions.size());
        for (size_t i = 0; i < positions.size(); i++)
            values[i] = mm_float4((float) positions[i][0], (float) positions[i][1], (float) positions[i][2], 0.0f);
        buildPosition.upload(values);
    }
    for (int k = 0; k < 3; k++)
        buildBox[k] = box[k];
    built = true;
    givenPending = true;
}

void CommonGenDPDEBlockSweep::runHalted(int haltStep, bool orderIncomplete) {
    // The steps from haltStep on did nothing: a build the host asked for then is asked for again; an order left
    // incomplete (too many levels) is built again from its positions.
    prepared = false;
    if (orderIncomplete && built)
        givenPending = true;
    else if (lastAskedStep >= haltStep) {
        if (lastAskedGiven)
            givenPending = true;
        else
            built = false;
    }
    lastAskedStep = -1;
}

void CommonGenDPDEBlockSweep::failure(int rank, int& particle, double& energy) {
    std::vector<int> particles;
    std::vector<double> energies;
    failureParticle.download(particles);
    failureEnergy.download(energies, true);
    particle = particles[rank];
    energy = energies[rank];
}
