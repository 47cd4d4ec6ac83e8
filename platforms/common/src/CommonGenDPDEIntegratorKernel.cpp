#include "CommonGenDPDEIntegratorKernel.h"
#include "CommonGenDPDEArguments.h"
#include "CommonGenDPDEKernelSources.h"
#include "internal/BoxGeometry.h"
#include "internal/CounterRandom.h"
#include "internal/FixedOrderSum.h"
#include "internal/GenDPDEIntegratorUtilities.h"
#include "internal/GenDPDEPairSweep.h"
#include "internal/GenDPDEPhysics.h"
#include "internal/GenDPDESweepOrder.h"
#include "openmm/OpenMMException.h"
#include "openmm/common/ContextSelector.h"
#include "openmm/internal/ContextImpl.h"
#include <climits>
#include <cmath>

using namespace GenDPDEPlugin;
using namespace OpenMM;

namespace {

const int noValue = INT_MAX;

/** The arguments of kernels/gendpdeIntegrator.cc's kernels, in the order of their parameters. */
namespace CheckArgument {
enum {Velm, ForceBuffers, AtomIndex, StepSize, MaxDisplacement, Status, Count};
}
namespace KickArgument {
enum {Velm, ForceBuffers, TimeStep, Count};
}
namespace DriftArgument {
enum {Posq, PosqCorrection, Velm, TimeStep, Count};
}
namespace KineticArgument {
enum {Velm, ForceBuffers, HalfStep, Energy, Count};
}
namespace FindPairsArgument {
enum {Cells, Blocks, CellStart, SortedCell, SortedAtom, SortedSlot, Posq, PosqCorrection, BoxA, BoxB, BoxC, Cutoff,
      RankOfBlock, Fill, BlockCount, BlockStart, BlockPairs, Status, Count};
}
namespace OrderArgument {
enum {NumBlocks, BlockStart, BlockPairs, OrderedPairs, Count};
}
namespace SweepArgument {
enum {FirstRank, NumRanks, BlockStart, OrderedPairs, SlotOfAtom, Posq, PosqCorrection, Velm, Energies, BoxA, BoxB,
      BoxC, Parameters, AtomType, PairTable, HeatCapacityTable, NumTypes, Boltzmann, Terms, Seed, StepLow, StepHigh,
      ZigguratX, ZigguratF, ZigguratRatio, Status, Count};
}

} // namespace

void CommonIntegrateGenDPDEStepKernel::initialize(ContextImpl& context, const GenDPDEIntegrator& integrator,
                                                  double cutoff, int seed, const std::vector<double>& internalEnergies,
                                                  const std::map<int, int>& particleTypes) {
    cc.initializeContexts();
    ContextSelector selector(cc);
    this->cutoff = cutoff;
    this->seed = seed;
    periodic = context.getSystem().usesPeriodicBoundaryConditions();
    const int numAtoms = cc.getNumAtoms();
    const int mixedSize = mixedIsDouble(cc) ? sizeof(double) : sizeof(float);
    energies.initialize(cc, numAtoms, mixedSize, "gendpdeInternalEnergies");
    savedEnergies.initialize(cc, numAtoms, mixedSize, "gendpdeSavedInternalEnergies");
    savedVelm.initialize(cc, cc.getVelm().getSize(), cc.getVelm().getElementSize(), "gendpdeSavedVelm");
    kinetic.initialize(cc, numAtoms, mixedSize, "gendpdeKineticEnergy");
    slotOfAtom.initialize<int>(cc, numAtoms, "gendpdeSlotOfAtom");
    status.initialize<int>(cc, 4, "gendpdeStepStatus");
    setInternalEnergies(internalEnergies);

    // The ziggurat of CounterRandom, from the host's table (double where the device has it).
    const CounterRandom::ZigguratTable& table = CounterRandom::ZigguratTable::get();
    const bool doubleRandom = cc.getSupportsDoublePrecision();
    const int randomSize = doubleRandom ? sizeof(double) : sizeof(float);
    zigguratX.initialize(cc, 257, randomSize, "gendpdeZigguratX");
    zigguratF.initialize(cc, 257, randomSize, "gendpdeZigguratF");
    zigguratRatio.initialize(cc, 256, randomSize, "gendpdeZigguratRatio");
    zigguratX.upload(std::vector<double>(table.x, table.x + 257), true);
    zigguratF.upload(std::vector<double>(table.f, table.f + 257), true);
    zigguratRatio.upload(std::vector<double>(table.ratio, table.ratio + 256), true);

    // Per-type parameters (GenDPDETypes.h): each particle's type index by original index; the tables by type.
    types.reset(new ParticleTypeIndex(particleTypes, context.getSystem().getNumParticles(), "GenDPDEIntegrator"));
    const int numTypes = types->getNumTypes();
    std::vector<int> typeIndex = types->getParticleTypeIndices();
    typeIndex.resize(numAtoms, 0);   // padding atoms
    atomType.initialize<int>(cc, numAtoms, "gendpdeAtomType");
    atomType.upload(typeIndex);
    pairTable.initialize(cc, numTypes*numTypes, 4*mixedSize, "gendpdePairTable");
    heatCapacityTable.initialize(cc, numTypes, mixedSize, "gendpdeHeatCapacityTable");

    rankOfBlockArray.initialize<int>(cc, 1, "gendpdeRankOfBlock");
    blockCount.initialize<int>(cc, 1, "gendpdeBlockCount");
    blockStart.initialize<int>(cc, 2, "gendpdeBlockStart");
    blockPairs.initialize<mm_int2>(cc, 1, "gendpdeBlockPairs");
    orderedPairs.initialize<mm_int2>(cc, 1, "gendpdeOrderedPairs");

    grid.reset(new CommonGenDPDECellGrid(cc, periodic, cutoff > 0.0 ? cutoff : 1.0));
    std::map<std::string, std::string> defines = grid->defines();
    if (doubleRandom)
        defines["GENDPDE_DOUBLE_RANDOM"] = "1";
    ComputeProgram program = cc.compileProgram(CommonGenDPDEKernelSources::physicsCore("mixed")
            + CommonGenDPDEKernelSources::gendpdeCells + CommonGenDPDEKernelSources::gendpdeRandom
            + CommonGenDPDEKernelSources::gendpdeIntegrator, defines);
    grid->createKernels(program);
    resetKernel = program->createKernel("resetStatus");
    resetKernel->addArg(status);
    checkKernel = program->createKernel("checkStep");
    {
        using namespace CheckArgument;
        KernelArguments(checkKernel, "checkStep").array(Velm, cc.getVelm()).array(ForceBuffers, cc.getLongForceBuffer())
                .array(AtomIndex, cc.getAtomIndexArray()).later(StepSize).later(MaxDisplacement)
                .array(Status, status).done(Count);
    }
    kickKernel = program->createKernel("kick");
    KernelArguments(kickKernel, "kick").array(KickArgument::Velm, cc.getVelm())
            .array(KickArgument::ForceBuffers, cc.getLongForceBuffer()).later(KickArgument::TimeStep)
            .done(KickArgument::Count);
    driftKernel = program->createKernel("drift");
    KernelArguments(driftKernel, "drift").array(DriftArgument::Posq, cc.getPosq())
            .array(DriftArgument::PosqCorrection, cc.getPosqCorrection()).array(DriftArgument::Velm, cc.getVelm())
            .later(DriftArgument::TimeStep).done(DriftArgument::Count);
    kineticKernel = program->createKernel("kineticEnergies");
    KernelArguments(kineticKernel, "kineticEnergies").array(KineticArgument::Velm, cc.getVelm())
            .array(KineticArgument::ForceBuffers, cc.getLongForceBuffer()).later(KineticArgument::HalfStep)
            .array(KineticArgument::Energy, kinetic).done(KineticArgument::Count);
    invertKernel = program->createKernel("invertAtomIndex");
    invertKernel->addArg(cc.getAtomIndexArray());
    invertKernel->addArg(slotOfAtom);
    findPairsKernel = program->createKernel("findBlockPairs");
    boundGrid = grid.get();
    {
        using namespace FindPairsArgument;
        KernelArguments(findPairsKernel, "findBlockPairs").later(Cells).later(Blocks)
                .array(CellStart, grid->cellStart).array(SortedCell, grid->sortedCell)
                .array(SortedAtom, grid->sortedAtom).array(SortedSlot, grid->sortedSlot).array(Posq, cc.getPosq())
                .array(PosqCorrection, cc.getPosqCorrection()).later(BoxA).later(BoxB).later(BoxC).later(Cutoff)
                .array(RankOfBlock, rankOfBlockArray).later(Fill).array(BlockCount, blockCount)
                .array(BlockStart, blockStart).array(BlockPairs, blockPairs).array(Status, status).done(Count);
    }
    orderKernel = program->createKernel("orderBlockPairs");
    KernelArguments(orderKernel, "orderBlockPairs").later(OrderArgument::NumBlocks)
            .array(OrderArgument::BlockStart, blockStart).array(OrderArgument::BlockPairs, blockPairs)
            .array(OrderArgument::OrderedPairs, orderedPairs).done(OrderArgument::Count);
    sweepKernel = program->createKernel("sweepColour");
    {
        using namespace SweepArgument;
        KernelArguments(sweepKernel, "sweepColour").later(FirstRank).later(NumRanks).array(BlockStart, blockStart)
                .array(OrderedPairs, orderedPairs).array(SlotOfAtom, slotOfAtom).array(Posq, cc.getPosq())
                .array(PosqCorrection, cc.getPosqCorrection()).array(Velm, cc.getVelm()).array(Energies, energies)
                .later(BoxA).later(BoxB).later(BoxC).later(Parameters).array(AtomType, atomType)
                .array(PairTable, pairTable).array(HeatCapacityTable, heatCapacityTable).value(NumTypes, numTypes)
                .later(Boltzmann).later(Terms).later(Seed).later(StepLow).later(StepHigh)
                .array(ZigguratX, zigguratX).array(ZigguratF, zigguratF).array(ZigguratRatio, zigguratRatio)
                .array(Status, status).done(Count);
    }
}

const std::vector<double>& CommonIntegrateGenDPDEStepKernel::getInternalEnergies() const {
    ContextSelector selector(cc);
    energies.download(hostEnergies, true);
    return hostEnergies;
}

void CommonIntegrateGenDPDEStepKernel::setInternalEnergies(const std::vector<double>& internalEnergies) {
    ContextSelector selector(cc);
    if ((int) internalEnergies.size() != cc.getNumAtoms())
        throw OpenMMException("GenDPDEIntegrator: " + std::to_string(internalEnergies.size()) + " internal energies "
                              "for " + std::to_string(cc.getNumAtoms()) + " particles");
    energies.upload(internalEnergies, true);
}

void CommonIntegrateGenDPDEStepKernel::throwUnstable(ContextImpl& context, int particle, double stepSize,
                                                     double maxDisplacement) {
    std::vector<Vec3> forces, velocities;
    context.getForces(forces);
    context.getVelocities(velocities);
    throw OpenMMException(GenDPDEIntegratorUtilities::unstableParticleMessage(particle, velocities[particle],
            forces[particle], 1.0/context.getSystem().getParticleMass(particle), stepSize, maxDisplacement,
            cc.getStepCount()));
}

void CommonIntegrateGenDPDEStepKernel::preparePairs(ContextImpl& context, const GenDPDEIntegrator& integrator,
                                                    const GenDPDEStepTerms& terms, GenDPDEPairSource* pairSource) {
    // The step check, and the pairs counted per block; then one download tells both (nothing has changed yet).
    const int numAtoms = cc.getNumAtoms();
    setMixed(cc, checkKernel, CheckArgument::StepSize, integrator.getStepSize());
    setMixed(cc, checkKernel, CheckArgument::MaxDisplacement, terms.maxDisplacement);
    profiler.time("step check", [&]() {
        resetKernel->execute(1);
        checkKernel->execute(numAtoms);
    });
    if (terms.pairSweep) {
        if (periodic) {
            Vec3 box[3];
            cc.getPeriodicBoxVectors(box[0], box[1], box[2]);
            BoxGeometry::checkCutoffAgainstBox("GenDPDEIntegrator", cutoff, box);   // a barostat may have shrunk it
        }
        // The cells of the force just evaluated at these positions with this range, if its source lends them (the
        // same grid as GenDPDESweepOrder's: it depends only on positions, box and range); else the integrator's own.
        CommonGenDPDECellGrid* cellGrid = pairSource != nullptr ? pairSource->getDeviceCellGrid() : nullptr;
        if (cellGrid == nullptr || !pairSource->holdsPairsFor(cutoff, cc.getStepCount())) {
            cellGrid = grid.get();
            profiler.time("cell grid (own)", [&]() { grid->build(); });
        }
        if (cellGrid != boundGrid) {
            using namespace FindPairsArgument;
            findPairsKernel->setArg(CellStart, cellGrid->cellStart);
            findPairsKernel->setArg(SortedCell, cellGrid->sortedCell);
            findPairsKernel->setArg(SortedAtom, cellGrid->sortedAtom);
            findPairsKernel->setArg(SortedSlot, cellGrid->sortedSlot);
            boundGrid = cellGrid;
        }
        const std::array<int, 3>& cells = cellGrid->getNumCells();
        if (cells != blockGridCells) {
            blockGridCells = cells;
            const std::array<int, 3> blocks = {(cells[0] + 1)/2, (cells[1] + 1)/2, (cells[2] + 1)/2};
            const int numRanks = GenDPDESweepOrder::blockRanks(blocks, rankOfBlock, groupStart);
            rankOfBlockArray.resize(numRanks);
            rankOfBlockArray.upload(rankOfBlock);
            blockCount.resize(numRanks);
            blockStart.resize(numRanks + 1);
            findPairsKernel->setArg(FindPairsArgument::Blocks, mm_int4(blocks[0], blocks[1], blocks[2], numRanks));
        }
        findPairsKernel->setArg(FindPairsArgument::Cells, cellGrid->getCellsArgument());
        grid->setBoxArguments(findPairsKernel, FindPairsArgument::BoxA, true);
        setMixed(cc, findPairsKernel, FindPairsArgument::Cutoff, cutoff);
        findPairsKernel->setArg(FindPairsArgument::Fill, 0);
        profiler.time("pairs: count per block", [&]() {
            cc.clearBuffer(blockCount);
            findPairsKernel->execute(numAtoms);
            grid->exclusiveScan(blockCount, blockStart, (int) blockCount.getSize(), status, 1);
        });
    }
    std::vector<int> found;
    status.download(found);
    if (found[0] != noValue)
        throwUnstable(context, found[0], integrator.getStepSize(), terms.maxDisplacement);
    if (!terms.pairSweep)
        return;
    if (found[3] != 0)
        throw OpenMMException("GenDPDEIntegrator: " + std::to_string(found[3]) + " pairs in range lie in cells that "
                              "are not adjacent at step " + std::to_string(cc.getStepCount())
                              + " (an internal error of the cell grid)");
    const int numPairs = found[1];
    if ((int) blockPairs.getSize() < numPairs) {
        blockPairs.resize((int) (1.2*numPairs) + 1);
        orderedPairs.resize(blockPairs.getSize());
    }
    findPairsKernel->setArg(FindPairsArgument::Fill, 1);
    orderKernel->setArg(OrderArgument::NumBlocks, (int) blockCount.getSize());
    profiler.time("pairs: list per block", [&]() {
        cc.clearBuffer(blockCount);
        findPairsKernel->execute(numAtoms);
    });
    profiler.time("pairs: sort, interleave", [&]() {
        orderKernel->execute((int) blockCount.getSize());
        invertKernel->execute(numAtoms);
    });
}

void CommonIntegrateGenDPDEStepKernel::sweep(ContextImpl& context, const GenDPDEIntegrator& integrator,
                                             const GenDPDEStepTerms& terms) {
    const long long step = cc.getStepCount();
    const PairSweepParameters p(integrator, terms, cutoff, seed, step, *types);   // as the host platforms' sweep
    grid->setBoxArguments(sweepKernel, SweepArgument::BoxA, true);
    setMixed4(cc, sweepKernel, SweepArgument::Parameters, cutoff, p.stepSize, p.sqrtStepSize, 0.0);
    // The type tables: the integrator's parameters may change between steps, so they are uploaded when they do.
    std::vector<double> pairParameters;
    for (int ab = 0; ab < p.numTypes*p.numTypes; ab++)
        pairParameters.insert(pairParameters.end(), {p.table.friction[ab], p.table.heatConduction[ab],
                                                     p.heatNoise[ab], p.bathNoise[ab]});
    const std::vector<double>& capacity = p.table.heatCapacity;
    if (pairParameters != uploadedPairTable || capacity != uploadedHeatCapacities) {
        uploadValues(pairTable, pairParameters, mixedIsDouble(cc));
        uploadValues(heatCapacityTable, capacity, mixedIsDouble(cc));
        uploadedPairTable = pairParameters;
        uploadedHeatCapacities = capacity;
    }
    setMixed(cc, sweepKernel, SweepArgument::Boltzmann, Physics::Boltzmann);
    sweepKernel->setArg(SweepArgument::Terms, (terms.dissipation ? 1 : 0) | (terms.conduction ? 2 : 0)
                                              | (terms.internalEnergies ? 4 : 0));
    sweepKernel->setArg(SweepArgument::Seed, p.seed);
    sweepKernel->setArg(SweepArgument::StepLow, (unsigned int) p.step);
    sweepKernel->setArg(SweepArgument::StepHigh, (unsigned int) (p.step >> 32));
    profiler.time("sweep (8 colours)", [&]() {
        for (int colour = 0; colour + 1 < (int) groupStart.size(); colour++) {
            const int numRanks = groupStart[colour + 1] - groupStart[colour];
            if (numRanks == 0)
                continue;
            sweepKernel->setArg(SweepArgument::FirstRank, groupStart[colour]);
            sweepKernel->setArg(SweepArgument::NumRanks, numRanks);
            sweepKernel->execute(numRanks, 64);
        }
    });
    if (!terms.internalEnergies)
        return;
    std::vector<int> found;
    status.download(found);
    if (found[2] == noValue)
        return;
    // Roll back to the state before the step and name the particle, as the Reference platform does.
    std::vector<mm_int2> pairs;
    orderedPairs.download(pairs);
    std::vector<double> failed;
    energies.download(failed, true);
    const mm_int2 pair = pairs[found[2]];
    const int particle = (failed[pair.x] > 0.0 ? pair.y : pair.x);
    savedVelm.copyTo(cc.getVelm());
    savedEnergies.copyTo(energies);
    throw OpenMMException(GenDPDEIntegratorUtilities::nonPositiveEnergyMessage(particle, failed[particle], step));
}

void CommonIntegrateGenDPDEStepKernel::execute(ContextImpl& context, const GenDPDEIntegrator& integrator,
                                               const GenDPDEStepTerms& terms, GenDPDEPairSource* pairSource) {
    // docs/theory.md section 6: half kick, pair sweep at fixed positions, half kick, drift; without pair terms,
    // velocity Verlet (leapfrog form: one full kick).
    ContextSelector selector(cc);
    preparePairs(context, integrator, terms, pairSource);
    const double dt = integrator.getStepSize();
    const int numAtoms = cc.getNumAtoms();
    if (!terms.pairSweep) {
        setMixed(cc, kickKernel, KickArgument::TimeStep, dt);
        profiler.time("kicks, drift", [&]() { kickKernel->execute(numAtoms); });
    }
    else {
        if (terms.internalEnergies) {
            cc.getVelm().copyTo(savedVelm);
            energies.copyTo(savedEnergies);
        }
        setMixed(cc, kickKernel, KickArgument::TimeStep, 0.5*dt);
        profiler.time("kicks, drift", [&]() { kickKernel->execute(numAtoms); });
        sweep(context, integrator, terms);
        profiler.time("kicks, drift", [&]() { kickKernel->execute(numAtoms); });
    }
    setMixed(cc, driftKernel, DriftArgument::TimeStep, dt);
    profiler.time("kicks, drift", [&]() { driftKernel->execute(numAtoms); });
    cc.setTime(cc.getTime() + dt);
    cc.setStepCount(cc.getStepCount() + 1);
    cc.reorderAtoms();
}

double CommonIntegrateGenDPDEStepKernel::computeKineticEnergy(ContextImpl& context,
                                                              const GenDPDEIntegrator& integrator) {
    ContextSelector selector(cc);
    setMixed(cc, kineticKernel, KineticArgument::HalfStep, 0.5*integrator.getStepSize());
    kineticKernel->execute(cc.getNumAtoms());
    std::vector<double> perSlot;
    kinetic.download(perSlot, true);
    const std::vector<int>& atomIndex = cc.getAtomIndex();
    std::vector<double> perAtom(perSlot.size());
    for (size_t slot = 0; slot < perSlot.size(); slot++)
        perAtom[atomIndex[slot]] = perSlot[slot];
    FixedOrderSum::Accumulator sum;   // summed in particle order, as the host platforms sum it
    for (double e : perAtom)
        sum.add(e);
    return sum.sum();
}
