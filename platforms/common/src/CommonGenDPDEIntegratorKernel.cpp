/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
#include "CommonGenDPDEIntegratorKernel.h"
#include "CommonGenDPDEArguments.h"
#include "CommonGenDPDEKernelSources.h"
#include "CommonGenDPDEStatus.h"
#include "internal/BoxGeometry.h"
#include "internal/FixedOrderSum.h"
#include "internal/GenDPDEIntegratorUtilities.h"
#include "internal/GenDPDEPairSweep.h"
#include "internal/GenDPDEPhysics.h"
#include "openmm/OpenMMException.h"
#include "openmm/common/ContextSelector.h"
#include "openmm/internal/ContextImpl.h"
#include <cmath>
#include <cstdlib>
#include <string>

using namespace GenDPDEPlugin;
using namespace OpenMM;

namespace {

/** The arguments of kernels/gendpdeIntegrator.cc's kernels, in the order of their parameters. */
namespace StartArgument {
enum {
    Velm,
    ForceBuffers,
    AtomIndex,
    StepSize,
    MaxDisplacement,
    KickStep,
    StepIndex,
    Status,
    CheckForce,
    ForceErrors,
    SavedVelm,
    SaveEnergies,
    Energies,
    SavedEnergies,
    Count
};
}
namespace FinishArgument {
enum {
    Velm,
    ForceBuffers,
    Posq,
    PosqCorrection,
    KickStep,
    DriftStep,
    Status,
    SavedVelm,
    RestoreEnergies,
    Energies,
    SavedEnergies,
    Count
};
}
namespace KineticArgument {
enum { Velm, ForceBuffers, HalfStep, Energy, Count };
}
namespace KeepArgument {
enum { ThermalEnergy, DensityEntropy, Energies, Entropies, Status, CheckForce, ForceErrors, Count };
}

/** The status words as a run starts: nothing failed (the counters are kept). */
void resetStatusWords(std::vector<int>& words) {
    using namespace DeviceStatus;
    words[Halted] = Running;
    words[HaltStep] = 0;
    words[Unstable] = NoValue;
    words[FailedRank] = NoValue;
    words[ForceNonFinite] = NoValue;
    words[ForceInvalid] = NoValue;
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
    allocateArrays(internalEnergies);

    // Per-type parameters (GenDPDETypes.h): each particle's class by original index, the tables by class, all
    // uploaded by uploadTypeTables() (their sizes follow the integrator's entries).
    typeTables.reset(new IntegratorTypeTables(
            ParticleTypeIndex(particleTypes, context.getSystem().getNumParticles(), "GenDPDEIntegrator")));
    const int mixedSize = mixedIsDouble(cc) ? sizeof(double) : sizeof(float);
    atomType.initialize<int>(cc, cc.getNumAtoms(), "gendpdeAtomType");
    pairTable.initialize(cc, 1, 4 * mixedSize, "gendpdePairTable");
    heatCapacityTable.initialize(cc, 1, mixedSize, "gendpdeHeatCapacityTable");

    std::map<std::string, std::string> defines = CommonGenDPDECellGrid::programDefines(cc, periodic);
    for (const auto& define : DeviceStatus::defines())
        defines[define.first] = define.second;
    if (cc.getSupportsDoublePrecision())
        defines["GENDPDE_DOUBLE_RANDOM"] = "1";
    const std::string sources = CommonGenDPDEKernelSources::physicsCore("mixed")
            + CommonGenDPDEKernelSources::gendpdeCells + CommonGenDPDEKernelSources::gendpdeRandom
            + CommonGenDPDEKernelSources::gendpdeStatus;
    ComputeProgram program = cc.compileProgram(sources + CommonGenDPDEKernelSources::gendpdeIntegrator, defines);
    createStepKernels(program);
    if (cutoff > 0.0) {
        sweep.reset(new CommonGenDPDEBlockSweep(cc, profiler, defines, sources, periodic, cutoff, localMemory));
        Vec3 box[3];
        context.getSystem().getDefaultPeriodicBoxVectors(box[0], box[1], box[2]);
        sweep->estimateCapacities(context.getSystem().getNumParticles(), periodic ? box : nullptr);
    }
}

void CommonIntegrateGenDPDEStepKernel::allocateArrays(const std::vector<double>& internalEnergies) {
    // The internal energies and their saved copies, the status words, the kinetic energies.
    const int numAtoms = cc.getNumAtoms();
    const int mixedSize = mixedIsDouble(cc) ? sizeof(double) : sizeof(float);
    energies.initialize(cc, numAtoms, mixedSize, "gendpdeInternalEnergies");
    densityEntropies.initialize(cc, numAtoms, mixedSize, "gendpdeDensityEntropies");
    savedEnergies.initialize(cc, numAtoms, mixedSize, "gendpdeSavedInternalEnergies");
    savedVelm.initialize(cc, cc.getVelm().getSize(), cc.getVelm().getElementSize(), "gendpdeSavedVelm");
    kinetic.initialize(cc, numAtoms, mixedSize, "gendpdeKineticEnergy");
    std::vector<int> words(DeviceStatus::Size, 0);
    resetStatusWords(words);
    status.initialize<int>(cc, words.size(), "gendpdeStepStatus");
    status.upload(words);
    noForceErrors.initialize<int>(cc, 2, "gendpdeNoForceErrors");
    noForceErrors.upload(std::vector<int>(2, DeviceStatus::NoValue));
    setInternalEnergies(internalEnergies);
}

void CommonIntegrateGenDPDEStepKernel::createStepKernels(ComputeProgram& program) {
    // The kernels of the step (kernels/gendpdeIntegrator.cc) with their arguments.
    startKernel = program->createKernel("startStep");
    {
        using namespace StartArgument;
        KernelArguments(startKernel, "startStep")
                .array(Velm, cc.getVelm())
                .array(ForceBuffers, cc.getLongForceBuffer())
                .array(AtomIndex, cc.getAtomIndexArray())
                .later(StepSize)
                .later(MaxDisplacement)
                .later(KickStep)
                .later(StepIndex)
                .array(Status, status)
                .later(CheckForce)
                .later(ForceErrors)
                .array(SavedVelm, savedVelm)
                .later(SaveEnergies)
                .array(Energies, energies)
                .array(SavedEnergies, savedEnergies)
                .done(Count);
    }
    finishKernel = program->createKernel("finishStep");
    {
        using namespace FinishArgument;
        KernelArguments(finishKernel, "finishStep")
                .array(Velm, cc.getVelm())
                .array(ForceBuffers, cc.getLongForceBuffer())
                .array(Posq, cc.getPosq())
                .array(PosqCorrection, cc.getPosqCorrection())
                .later(KickStep)
                .later(DriftStep)
                .array(Status, status)
                .array(SavedVelm, savedVelm)
                .later(RestoreEnergies)
                .array(Energies, energies)
                .array(SavedEnergies, savedEnergies)
                .done(Count);
    }
    keepKernel = program->createKernel("keepThermalState");
    KernelArguments(keepKernel, "keepThermalState")
            .later(KeepArgument::ThermalEnergy)
            .later(KeepArgument::DensityEntropy)
            .array(KeepArgument::Energies, energies)
            .array(KeepArgument::Entropies, densityEntropies)
            .array(KeepArgument::Status, status)
            .later(KeepArgument::CheckForce)
            .later(KeepArgument::ForceErrors)
            .done(KeepArgument::Count);
    kineticKernel = program->createKernel("kineticEnergies");
    KernelArguments(kineticKernel, "kineticEnergies")
            .array(KineticArgument::Velm, cc.getVelm())
            .array(KineticArgument::ForceBuffers, cc.getLongForceBuffer())
            .later(KineticArgument::HalfStep)
            .array(KineticArgument::Energy, kinetic)
            .done(KineticArgument::Count);
}

const std::vector<double>& CommonIntegrateGenDPDEStepKernel::getInternalEnergies() const {
    ContextSelector selector(cc);
    energies.download(hostEnergies, true);
    return hostEnergies;
}

void CommonIntegrateGenDPDEStepKernel::setInternalEnergies(const std::vector<double>& internalEnergies) {
    ContextSelector selector(cc);
    if ((int) internalEnergies.size() != cc.getNumAtoms())
        throw OpenMMException("GenDPDEIntegrator: " + std::to_string(internalEnergies.size())
                              + " internal energies "
                                "for "
                              + std::to_string(cc.getNumAtoms()) + " particles");
    energies.upload(internalEnergies, true);
    energiesSet = !internalEnergies.empty() && internalEnergies[0] != 0.0;
    entropiesKnown = false;
}

CommonGenDPDEThermalArrays* CommonIntegrateGenDPDEStepKernel::getDeviceThermalState(
        const GenDPDEIntegrator& integrator) {
    ContextSelector selector(cc);
    // The classes and heat capacities as the sweep reads them (they may have changed since the last run of steps).
    uploadTypeTables(integrator, GenDPDEIntegratorUtilities::stepTerms(integrator, cutoff));
    thermalArrays = {integrator.getMode() == GenDPDEIntegrator::Isothermal,
                     integrator.getTemperature(),
                     &energies,
                     &densityEntropies,
                     entropiesKnown,
                     &atomType,
                     &heatCapacityTable,
                     GenDPDEIntegratorUtilities::checksStepTemperatures(integrator)};
    return &thermalArrays;
}

void CommonIntegrateGenDPDEStepKernel::keepDeviceThermalState(ComputeArray& thermalEnergies, ComputeArray& entropies) {
    ContextSelector selector(cc);
    if (!inRun) {   // (outside a run the force has checked its evaluation already)
        thermalEnergies.copyTo(energies);
        entropies.copyTo(densityEntropies);
    } else {
        using namespace KeepArgument;
        keepKernel->setArg(ThermalEnergy, thermalEnergies);
        keepKernel->setArg(DensityEntropy, entropies);
        keepKernel->setArg(CheckForce, deferredChecks != nullptr ? 1 : 0);
        keepKernel->setArg(ForceErrors, deferredChecks != nullptr ? deferredChecks->getErrorFlags() : noForceErrors);
        profiler.launch(keepKernel, cc.getNumAtoms());
    }
    entropiesKnown = true;
}

void CommonIntegrateGenDPDEStepKernel::throwUnstable(ContextImpl& context, int particle, double stepSize,
                                                     long long step) {
    std::vector<Vec3> forces, velocities;
    context.getForces(forces);
    context.getVelocities(velocities);
    // The forces are fixed point (2^-32 kJ/mol/nm, range +-2^31): a component that was not finite converts to the end
    // of the range, -2^31 kJ/mol/nm, plus whatever the other forces add (the host platforms see the NaN itself). A
    // component within 2^24 of the end is reported as not finite, in their words: no force that large can be summed
    // on the device without overflowing.
    for (int c = 0; c < 3; c++)
        if (std::fabs(forces[particle][c]) > 2147483648.0 - 16777216.0)
            forces[particle][c] = std::nan("");
    throw OpenMMException(GenDPDEIntegratorUtilities::unstableParticleMessage(
            particle, velocities[particle], forces[particle], 1.0 / context.getSystem().getParticleMass(particle),
            stepSize, runTerms.maxDisplacement, step));
}

void CommonIntegrateGenDPDEStepKernel::uploadTypeTables(const GenDPDEIntegrator& integrator,
                                                        const GenDPDEStepTerms& terms) {
    // The integrator's parameters may change between runs of steps; the tables are uploaded when they do.
    if (typeTables->update(integrator)) {
        std::vector<int> particleClass = typeTables->getParticleClasses();
        particleClass.resize(cc.getNumAtoms(), 0); // padding atoms
        atomType.upload(particleClass);
    }
    std::vector<double> noise;
    const PairSweepParameters p(integrator, terms, cutoff, seed, 0, *typeTables, noise); // as the host's sweep
    std::vector<double> pairParameters;
    for (int ab = 0; ab < p.numClasses * p.numClasses; ab++)
        pairParameters.insert(pairParameters.end(),
                              {p.table->friction[ab], p.table->heatConduction[ab], p.heatNoise[ab], p.bathNoise[ab]});
    const std::vector<double>& capacity = p.table->heatCapacity;
    if (pairParameters != uploadedPairTable || capacity != uploadedHeatCapacities) {
        pairTable.resize(p.numClasses * p.numClasses);
        heatCapacityTable.resize(p.numClasses);
        uploadValues(pairTable, pairParameters, mixedIsDouble(cc));
        uploadValues(heatCapacityTable, capacity, mixedIsDouble(cc));
        uploadedPairTable = pairParameters;
        uploadedHeatCapacities = capacity;
    }
}

void CommonIntegrateGenDPDEStepKernel::beginSteps(ContextImpl& context, const GenDPDEIntegrator& integrator,
                                                  const GenDPDEStepTerms& terms, GenDPDEPairSource* pairSource) {
    ContextSelector selector(cc);
    inRun = true;
    runStartStep = cc.getStepCount();
    runStartTime = cc.getTime();
    runTerms = terms;
    runStepSize = integrator.getStepSize();
    runStartEntropiesKnown = entropiesKnown;
    stepsSincePoll = 0;
    if (terms.pairSweep)
        uploadTypeTables(integrator, terms);
    // The GenDPDEForce whose pairs the sweep reuses has its checks made by startStep, on the device.
    deferredChecks = (pairSource != nullptr ? pairSource->getDeviceChecks() : nullptr);
    if (deferredChecks != nullptr)
        deferredChecks->setDeferred(true);
    // One build for the force's list and the sweep's order, where the force can share it.
    if (sweep != nullptr)
        sweep->beginRun();
    sharesBuild = false;
    const char* apart = std::getenv("GENDPDE_NO_SHARED_BUILD"); // (a developer's setting: set, not "" or "0")
    const bool keepApart = apart != nullptr && std::string(apart) != "" && std::string(apart) != "0";
    if (deferredChecks != nullptr && sweep != nullptr && terms.pairSweep && !keepApart) {
        ArrayInterface* listRebuild = deferredChecks->shareBuild(this, cutoff);
        sharesBuild = (listRebuild != nullptr);
        sweep->setSharedList(listRebuild);
    }
}

CommonGenDPDESharedGrid CommonIntegrateGenDPDEStepKernel::prepareBuild(ArrayInterface& listRebuild,
                                                                       ArrayInterface& forceErrors, bool listForced) {
    sweep->prepare((int) (cc.getStepCount() - runStartStep), status, &listRebuild, listForced, &forceErrors);
    return sweep->sharedGrid();
}

void CommonIntegrateGenDPDEStepKernel::execute(ContextImpl& context, const GenDPDEIntegrator& integrator,
                                               const GenDPDEStepTerms& terms, GenDPDEPairSource* pairSource) {
    // docs/theory.md section 6: half kick, pair sweep at fixed positions, half kick, drift; without pair terms,
    // velocity Verlet (leapfrog form: one full kick).
    ContextSelector selector(cc);
    if (!inRun) {
        // A step on its own: a run of one.
        beginSteps(context, integrator, terms, pairSource);
        try {
            execute(context, integrator, terms, pairSource);
        } catch (...) {
            finishSteps(context, integrator);
            throw;
        }
        finishSteps(context, integrator);
        return;
    }
    const double dt = integrator.getStepSize();
    const int numAtoms = cc.getNumAtoms();
    const int stepIndex = (int) (cc.getStepCount() - runStartStep);
    ArrayInterface& forceErrors = (deferredChecks != nullptr ? deferredChecks->getErrorFlags() : noForceErrors);
    const bool saveEnergies = terms.pairSweep && terms.internalEnergies;
    {
        using namespace StartArgument;
        setMixed(cc, startKernel, StepSize, dt);
        setMixed(cc, startKernel, MaxDisplacement, terms.maxDisplacement);
        setMixed(cc, startKernel, KickStep, terms.pairSweep ? 0.5 * dt : dt);
        startKernel->setArg(StepIndex, stepIndex);
        startKernel->setArg(CheckForce, deferredChecks != nullptr ? 1 : 0);
        startKernel->setArg(ForceErrors, forceErrors);
        startKernel->setArg(SaveEnergies, saveEnergies ? 1 : 0);
    }
    profiler.time("step check, first kick", [&]() { profiler.launch(startKernel, numAtoms); });
    if (terms.pairSweep) {
        if (periodic) {
            Vec3 box[3];
            cc.getPeriodicBoxVectors(box[0], box[1], box[2]);
            BoxGeometry::checkCutoffAgainstBox("GenDPDEIntegrator", cutoff, box); // a barostat may have shrunk it
        }
        BlockSweepStep step;
        step.cutoff = cutoff;
        step.stepSize = dt;
        step.boltzmann = Physics::Boltzmann;
        step.terms = (terms.dissipation ? 1 : 0) | (terms.conduction ? 2 : 0) | (terms.internalEnergies ? 4 : 0);
        step.seed = (unsigned int) seed;
        step.step = cc.getStepCount();
        step.stepIndex = stepIndex;
        sweep->run(step, energies, atomType, pairTable, heatCapacityTable, typeTables->getTable().numClasses, status);
    }
    {
        using namespace FinishArgument;
        setMixed(cc, finishKernel, KickStep, terms.pairSweep ? 0.5 * dt : 0.0);
        setMixed(cc, finishKernel, DriftStep, dt);
        finishKernel->setArg(RestoreEnergies, saveEnergies ? 1 : 0);
    }
    profiler.time("second kick, drift", [&]() { profiler.launch(finishKernel, numAtoms); });
    profiler.countStep();
    cc.setTime(cc.getTime() + dt);
    cc.setStepCount(cc.getStepCount() + 1);
    cc.reorderAtoms();
    if (++stepsSincePoll >= pollInterval) {
        stepsSincePoll = 0;
        readStatus(context, integrator);
    }
}

void CommonIntegrateGenDPDEStepKernel::finishSteps(ContextImpl& context, const GenDPDEIntegrator& integrator) {
    if (!inRun)
        return;
    ContextSelector selector(cc);
    endRun();
    readStatus(context, integrator);
}

void CommonIntegrateGenDPDEStepKernel::endRun() {
    inRun = false;
    if (sharesBuild) {
        deferredChecks->shareBuild(nullptr, 0.0);
        sweep->setSharedList(nullptr);
        sharesBuild = false;
    }
    if (deferredChecks != nullptr)
        deferredChecks->setDeferred(false);
}

void CommonIntegrateGenDPDEStepKernel::readStatus(ContextImpl& context, const GenDPDEIntegrator& integrator) {
    using namespace DeviceStatus;
    std::vector<int> words;
    profiler.transfer();
    status.download(words);
    profiler.setCounters(words[MostParticles], words[MostPairs], words[Streamed],
                         std::vector<int>(&words[Levels], &words[Levels] + 8),
                         sweep != nullptr ? sweep->getNumRanks() : 0, words[Builds]);
    if (sweep != nullptr && words[Streamed] > streamedBlocks) {
        // Blocks beyond the capacities were streamed (correct, slower): make room for what was seen.
        streamedBlocks = words[Streamed];
        sweep->adjustCapacities(words[MostParticles], words[MostPairs]);
    }
    if (words[Halted] == Running)
        return;
    // The run stopped at step runStartStep + HaltStep, in the state of before that step: the Context goes back there.
    const std::vector<int> found = words;
    resetStatusWords(words);
    status.upload(words);
    const long long step = runStartStep + found[HaltStep];
    if (sweep != nullptr)
        sweep->runHalted(found[HaltStep], found[Halted] == HaltLevels);
    double time = runStartTime;
    for (int k = 0; k < found[HaltStep]; k++)
        time += runStepSize; // as the steps added it
    cc.setStepCount(step);
    cc.setTime(time);
    endRun(); // (a no-op when the run has ended already)
    if (found[Halted] == HaltForce && found[HaltStep] == 0)
        entropiesKnown = runStartEntropiesKnown; // the run's first evaluation failed: its state was not kept
    if (found[Halted] == HaltForce)
        deferredChecks->throwErrors(context, found[ForceNonFinite], found[ForceInvalid], step);
    if (found[Halted] == HaltUnstable)
        throwUnstable(context, found[Unstable], runStepSize, step);
    if (found[Halted] == HaltLevels)
        throw OpenMMException("GenDPDEIntegrator: at step " + std::to_string(step)
                              + " a block of the sweep's order needs more than " + std::to_string(sweep->levelLimit())
                              + " levels, the limit of this platform (" + context.getPlatform().getName()
                              + ", this precision); the particles are packed more densely than the sweep supports");
    int particle;
    double energy;
    sweep->failure(found[FailedRank], particle, energy);
    throw OpenMMException(GenDPDEIntegratorUtilities::nonPositiveEnergyMessage(particle, energy, step));
}

double CommonIntegrateGenDPDEStepKernel::computeKineticEnergy(ContextImpl& context,
                                                              const GenDPDEIntegrator& integrator) {
    ContextSelector selector(cc);
    setMixed(cc, kineticKernel, KineticArgument::HalfStep, 0.5 * integrator.getStepSize());
    profiler.launch(kineticKernel, cc.getNumAtoms());
    std::vector<double> perSlot;
    kinetic.download(perSlot, true);
    const std::vector<int>& atomIndex = cc.getAtomIndex();
    std::vector<double> perAtom(perSlot.size());
    for (size_t slot = 0; slot < perSlot.size(); slot++)
        perAtom[atomIndex[slot]] = perSlot[slot];
    FixedOrderSum::Accumulator sum; // summed in particle order, as the host platforms sum it
    for (double e : perAtom)
        sum.add(e);
    return sum.sum();
}

bool CommonIntegrateGenDPDEStepKernel::getSweepBuild(std::vector<Vec3>& positions, Vec3 box[3]) const {
    ContextSelector selector(cc);
    return sweep != nullptr && sweep->getBuild(positions, box);
}

void CommonIntegrateGenDPDEStepKernel::setSweepBuild(const std::vector<Vec3>& positions, const Vec3 box[3]) {
    ContextSelector selector(cc);
    if (sweep != nullptr)
        sweep->setBuild(positions, box);
}

void CommonIntegrateGenDPDEStepKernel::forgetSweepOrder() {
    if (sweep != nullptr)
        sweep->forget();
}
