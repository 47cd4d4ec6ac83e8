#include "CommonGenDPDEIntegratorKernel.h"
#include "CommonGenDPDEArguments.h"
#include "CommonGenDPDEForceKernel.h"
#include "CommonGenDPDEKernelSources.h"
#include "internal/GenDPDEForceImpl.h"
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
}

void CommonIntegrateGenDPDEStepKernel::initialize(ContextImpl& context, const GenDPDEIntegrator& integrator,
                                                  double cutoff, int seed, const std::vector<double>& internalEnergies) {
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
    types.reset(new ParticleTypeIndex(integrator.getParticleTypes(), context.getSystem().getNumParticles(),
                                      "GenDPDEIntegrator"));
    const int numTypes = types->getNumTypes();
    std::vector<int> typeIndex = types->getParticleTypeIndices();
    typeIndex.resize(numAtoms, 0);   // padding atoms
    atomType.initialize<int>(cc, numAtoms, "gendpdeAtomType");
    atomType.upload(typeIndex);
    pairTable.initialize(cc, numTypes*numTypes, 4*mixedSize, "gendpdePairTable");
    heatCapacityTable.initialize(cc, numTypes, mixedSize, "gendpdeHeatCapacityTable");

    blockSlotArray.initialize<int>(cc, 1, "gendpdeSlotOfBlock");
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
    checkKernel->addArg(cc.getVelm());
    checkKernel->addArg(cc.getLongForceBuffer());
    checkKernel->addArg(cc.getAtomIndexArray());
    checkKernel->addArg();   // step size
    checkKernel->addArg();   // largest displacement
    checkKernel->addArg(status);
    kickKernel = program->createKernel("kick");
    kickKernel->addArg(cc.getVelm());
    kickKernel->addArg(cc.getLongForceBuffer());
    kickKernel->addArg();   // time step
    driftKernel = program->createKernel("drift");
    driftKernel->addArg(cc.getPosq());
    driftKernel->addArg(cc.getPosqCorrection());
    driftKernel->addArg(cc.getVelm());
    driftKernel->addArg();   // time step
    kineticKernel = program->createKernel("kineticEnergies");
    kineticKernel->addArg(cc.getVelm());
    kineticKernel->addArg(cc.getLongForceBuffer());
    kineticKernel->addArg();   // half step
    kineticKernel->addArg(kinetic);
    invertKernel = program->createKernel("invertAtomIndex");
    invertKernel->addArg(cc.getAtomIndexArray());
    invertKernel->addArg(slotOfAtom);
    findPairsKernel = program->createKernel("findBlockPairs");
    findPairsKernel->addArg();   // cells
    findPairsKernel->addArg();   // blocks
    findPairsKernel->addArg(grid->cellStart);
    findPairsKernel->addArg(grid->sortedCell);
    findPairsKernel->addArg(grid->sortedAtom);
    findPairsKernel->addArg(grid->sortedSlot);
    boundGrid = grid.get();
    findPairsKernel->addArg(cc.getPosq());
    findPairsKernel->addArg(cc.getPosqCorrection());
    for (int i = 0; i < 4; i++)
        findPairsKernel->addArg();   // box (3), cutoff
    findPairsKernel->addArg(blockSlotArray);
    findPairsKernel->addArg();   // fill
    findPairsKernel->addArg(blockCount);
    findPairsKernel->addArg(blockStart);
    findPairsKernel->addArg(blockPairs);
    findPairsKernel->addArg(status);
    orderKernel = program->createKernel("orderBlockPairs");
    orderKernel->addArg();   // number of slots
    orderKernel->addArg(blockStart);
    orderKernel->addArg(blockPairs);
    orderKernel->addArg(orderedPairs);
    sweepKernel = program->createKernel("sweepColour");
    sweepKernel->addArg();   // first slot
    sweepKernel->addArg();   // number of slots
    sweepKernel->addArg(blockStart);
    sweepKernel->addArg(orderedPairs);
    sweepKernel->addArg(slotOfAtom);
    sweepKernel->addArg(cc.getPosq());
    sweepKernel->addArg(cc.getPosqCorrection());
    sweepKernel->addArg(cc.getVelm());
    sweepKernel->addArg(energies);
    for (int i = 0; i < 4; i++)
        sweepKernel->addArg();   // box (3), parameters
    sweepKernel->addArg(atomType);
    sweepKernel->addArg(pairTable);
    sweepKernel->addArg(heatCapacityTable);
    sweepKernel->addArg(numTypes);
    for (int i = 0; i < 5; i++)
        sweepKernel->addArg();   // boltzmann, terms, seed, step (2)
    sweepKernel->addArg(zigguratX);
    sweepKernel->addArg(zigguratF);
    sweepKernel->addArg(zigguratRatio);
    sweepKernel->addArg(status);
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
                                                    const GenDPDEStepTerms& terms, GenDPDEForceImpl* pairListSource) {
    // The step check, and the pairs counted per block; then one download tells both (nothing has changed yet).
    const int numAtoms = cc.getNumAtoms();
    setMixed(cc, checkKernel, 3, integrator.getStepSize());
    setMixed(cc, checkKernel, 4, terms.maxDisplacement);
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
        // The cells of the force just evaluated at these positions with this range, if there is one (the same
        // grid as GenDPDESweepOrder's: it depends only on positions, box and range); else the integrator's own.
        CommonGenDPDECellGrid* cellGrid = grid.get();
        if (pairListSource != nullptr)
            cellGrid = &dynamic_cast<CommonCalcGenDPDEForceKernel&>(pairListSource->getKernel().getImpl()).getCellGrid();
        else
            profiler.time("cell grid (own)", [&]() { grid->build(); });
        if (cellGrid != boundGrid) {
            findPairsKernel->setArg(2, cellGrid->cellStart);
            findPairsKernel->setArg(3, cellGrid->sortedCell);
            findPairsKernel->setArg(4, cellGrid->sortedAtom);
            findPairsKernel->setArg(5, cellGrid->sortedSlot);
            boundGrid = cellGrid;
        }
        const std::array<int, 3>& cells = cellGrid->getNumCells();
        if (cells != blockGridCells) {
            blockGridCells = cells;
            const std::array<int, 3> blocks = {(cells[0] + 1)/2, (cells[1] + 1)/2, (cells[2] + 1)/2};
            const int numSlots = GenDPDESweepOrder::blockSlots(blocks, slotOfBlock, groupStart);
            blockSlotArray.resize(numSlots);
            blockSlotArray.upload(slotOfBlock);
            blockCount.resize(numSlots);
            blockStart.resize(numSlots + 1);
            findPairsKernel->setArg(1, mm_int4(blocks[0], blocks[1], blocks[2], numSlots));
        }
        findPairsKernel->setArg(0, cellGrid->getCellsArgument());
        grid->setBoxArguments(findPairsKernel, 8, true);
        setMixed(cc, findPairsKernel, 11, cutoff);
        findPairsKernel->setArg(13, 0);
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
    findPairsKernel->setArg(13, 1);
    orderKernel->setArg(0, (int) blockCount.getSize());
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
    grid->setBoxArguments(sweepKernel, 9, true);
    setMixed4(cc, sweepKernel, 12, cutoff, p.stepSize, p.sqrtStepSize, 0.0);
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
    setMixed(cc, sweepKernel, 17, Physics::Boltzmann);
    sweepKernel->setArg(18, (terms.dissipation ? 1 : 0) | (terms.conduction ? 2 : 0)
                            | (terms.internalEnergies ? 4 : 0));
    sweepKernel->setArg(19, p.seed);
    sweepKernel->setArg(20, (unsigned int) p.step);
    sweepKernel->setArg(21, (unsigned int) (p.step >> 32));
    profiler.time("sweep (8 colours)", [&]() {
        for (int colour = 0; colour + 1 < (int) groupStart.size(); colour++) {
            const int numSlots = groupStart[colour + 1] - groupStart[colour];
            if (numSlots == 0)
                continue;
            sweepKernel->setArg(0, groupStart[colour]);
            sweepKernel->setArg(1, numSlots);
            sweepKernel->execute(numSlots, 64);
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
                                               const GenDPDEStepTerms& terms, GenDPDEForceImpl* pairListSource) {
    // docs/theory.md section 6: half kick, pair sweep at fixed positions, half kick, drift; without pair terms,
    // velocity Verlet (leapfrog form: one full kick).
    ContextSelector selector(cc);
    preparePairs(context, integrator, terms, pairListSource);
    const double dt = integrator.getStepSize();
    const int numAtoms = cc.getNumAtoms();
    if (!terms.pairSweep) {
        setMixed(cc, kickKernel, 2, dt);
        profiler.time("kicks, drift", [&]() { kickKernel->execute(numAtoms); });
    }
    else {
        if (terms.internalEnergies) {
            cc.getVelm().copyTo(savedVelm);
            energies.copyTo(savedEnergies);
        }
        setMixed(cc, kickKernel, 2, 0.5*dt);
        profiler.time("kicks, drift", [&]() { kickKernel->execute(numAtoms); });
        sweep(context, integrator, terms);
        profiler.time("kicks, drift", [&]() { kickKernel->execute(numAtoms); });
    }
    setMixed(cc, driftKernel, 3, dt);
    profiler.time("kicks, drift", [&]() { driftKernel->execute(numAtoms); });
    cc.setTime(cc.getTime() + dt);
    cc.setStepCount(cc.getStepCount() + 1);
    cc.reorderAtoms();
}

double CommonIntegrateGenDPDEStepKernel::computeKineticEnergy(ContextImpl& context,
                                                              const GenDPDEIntegrator& integrator) {
    ContextSelector selector(cc);
    setMixed(cc, kineticKernel, 2, 0.5*integrator.getStepSize());
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
