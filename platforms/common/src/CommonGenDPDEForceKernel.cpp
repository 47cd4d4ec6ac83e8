/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
/* GenDPDEForce on the GPU platforms: the steps (the density pass, the forces, the checks and their errors, the
 * observables). The setup is in CommonGenDPDEForceSetup.cpp. */

#include "CommonGenDPDEForceArguments.h"
#include "CommonGenDPDEForceKernel.h"
#include "CommonGenDPDEThermalArrays.h"
#include "internal/GenDPDEIntegratorUtilities.h"
#include "CommonGenDPDEArguments.h"
#include "CommonGenDPDEKernelSources.h"
#include "internal/BoxGeometry.h"
#include "internal/FixedOrderSum.h"
#include "gendpde/GenDPDEEquationsOfState.h"
#include "internal/GenDPDEForceErrors.h"
#include "internal/GenDPDEPhysics.h"
#include "openmm/OpenMMException.h"
#include "openmm/common/ComputeForceInfo.h"
#include "openmm/common/ContextSelector.h"
#include "openmm/internal/ContextImpl.h"
#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdlib>

using namespace GenDPDEPlugin;
using namespace GenDPDEPlugin::ForceKernelArguments;
using namespace OpenMM;

CommonCalcGenDPDEForceKernel::~CommonCalcGenDPDEForceKernel() {
    // The list's counters for the profile (GENDPDE_PROFILE): entries and pairs in range at the last build.
    if (!profiler.isEnabled() || !errors.isInitialized())
        return;
    ContextSelector selector(cc);
    std::vector<int> found;
    errors.download(found);
    const double particles = cc.getNumAtoms();
    profiler.note("neighbour list: " + std::to_string(found[5]) + " builds, skin " + std::to_string(listSkin)
                  + " R, capacity " + std::to_string(listCapacity) + "; at the last build "
                  + std::to_string(found[3] / particles) + " entries and " + std::to_string(found[4] / particles)
                  + " neighbours closer than R per particle: "
                  + std::to_string(found[4] > 0 ? 2.0 * found[3] / found[4] : 0.0)
                  + " distances per pair in range and pass");
}

void CommonCalcGenDPDEForceKernel::copyParametersToContext(ContextImpl& context, const GenDPDEForce& force) {
    ContextSelector selector(cc);   // (the tables are uploaded: CUDA needs its context current on this thread)
    readParameters(force);
}

void CommonCalcGenDPDEForceKernel::setModelArguments(const mm_int4& cells, ArrayInterface& cellStart) {
    // The constants of the physics core (gendpdeDensityWeightScales, gendpdeEstimatorConstants), computed on the host.
    const Physics::DensityWeight weight(cutoff);
    const Physics::VolumeEstimator constants(estimator, cutoff, cutoff / cutoffScaling);
    for (ComputeKernel* kernel : {&densityKernel, &forceKernel, &virialKernel}) {
        using namespace NeighbourArgument;
        (*kernel)->setArg(Neighbours, neighbours);
        (*kernel)->setArg(Capacity, listCapacity);
        (*kernel)->setArg(Cells, cells);
        (*kernel)->setArg(CellStart, cellStart);
        grid->setBoxArguments(*kernel, BoxA, false);
    }
    for (auto kernelAndIndex : {std::make_pair(&densityKernel, (int) DensityArgument::Model),
                                std::make_pair(&forceKernel, (int) ForceArgument::Model),
                                std::make_pair(&virialKernel, (int) VirialArgument::Model)})
        setReal4(cc, *kernelAndIndex.first, kernelAndIndex.second, cutoff, weight.getInverseCutoff(),
                 weight.getValueScale(), weight.getDerivativeScale());
    setReal4(cc, densityKernel, DensityArgument::VolumeConstants, constants.getKPerDensity(),
             constants.getVolumeScale(), constants.getDerivativeScale(), 0.0);
    setReal4(cc, densityKernel, DensityArgument::MomentConstants, constants.getMomentScale(),
             constants.getDensitySoftening(), 0.0, 0.0);
    densityKernel->setArg(DensityArgument::Estimator, estimator);
    forceKernel->setArg(ForceArgument::Moments, constants.needsMoments() ? 1 : 0);
    virialKernel->setArg(VirialArgument::Moments, constants.needsMoments() ? 1 : 0);
}

void CommonCalcGenDPDEForceKernel::setThermalArguments(ContextImpl& context) {
    using namespace DensityArgument;
    const GenDPDEIntegrator* integrator;
    IntegrateGenDPDEStepKernel& holder = GenDPDEIntegratorUtilities::thermalStateHolder(context, integrator);
    CommonGenDPDEThermalArrays* state = holder.getDeviceThermalState(*integrator);
    if (state == nullptr)
        throw OpenMMException("GenDPDEForce: the GenDPDEIntegrator's kernel does not hold its thermal state on the "
                              "device");
    densityKernel->setArg(Thermal, 1);
    densityKernel->setArg(Isothermal, state->isothermal ? 1 : 0);
    setReal(cc, densityKernel, Temperature, state->temperature);
    densityKernel->setArg(EntropyKnown, state->entropiesKnown ? 1 : 0);
    densityKernel->setArg(CheckStep, state->checkStep ? 1 : 0);
    densityKernel->setArg(StoredEnergy, *state->internalEnergies);
    densityKernel->setArg(StoredEntropy, *state->densityEntropies);
    densityKernel->setArg(ParticleClass, *state->particleClass);
    densityKernel->setArg(ClassHeatCapacity, *state->classHeatCapacity);
}

bool CommonCalcGenDPDEForceKernel::giveThermalState(IntegrateGenDPDEStepKernel& integratorKernel) {
    if (dependsOnTemperature)
        integratorKernel.keepDeviceThermalState(thermalEnergyOut, densityEntropyOut);
    return dependsOnTemperature;
}

void CommonCalcGenDPDEForceKernel::computeDensities(ContextImpl& context) {
    if (dependsOnTemperature)
        setThermalArguments(context);
    densityPass();
    if (deferred)
        return; // the integrator's run checks the flags on the device
    std::vector<int> found;
    profiler.transfer();
    errors.download(found);
    growList(found[2]);
    if (found[0] != noValue || found[1] != noValue)
        throwErrors(context, found[0], found[1], cc.getStepCount());
}

void CommonCalcGenDPDEForceKernel::densityPass() {
    Vec3 box[3];
    cc.getPeriodicBoxVectors(box[0], box[1], box[2]);
    if (periodic) {
        BoxGeometry::checkCutoffAgainstBox("GenDPDEForce", cutoff, box);
        if (box[0] != listBox[0] || box[1] != listBox[1] || box[2] != listBox[2])
            *needsRebuild = true; // (a barostat) the list's positions and images belong to another box
    }
    if (wantedCapacity > listCapacity) {
        listCapacity = wantedCapacity;
        neighbours.resize((size_t) cc.getNumAtoms() * listCapacity);
        *needsRebuild = true;
    }
    profiler.countStep();
    const bool forced = *needsRebuild;
    if (buildSource != nullptr) {
        // A build shared with the integrator's sweep: its check (by the order's rule) marks the list too, and the
        // list is made from the order's cells (the integrator's profile counts the check and the cells).
        const CommonGenDPDESharedGrid shared = buildSource->prepareBuild(rebuild, errors, forced);
        setModelArguments(shared.cells, *shared.cellStart);
        {
            using namespace SharedBuildArgument;
            sharedBuildKernel->setArg(Cells, shared.cells);
            sharedBuildKernel->setArg(CellStart, *shared.cellStart);
            sharedBuildKernel->setArg(OrderAtom, *shared.sortedAtom);
            sharedBuildKernel->setArg(AtomCell, *shared.atomCell);
            sharedBuildKernel->setArg(SlotOfAtom, *shared.slotOfAtom);
            sharedBuildKernel->setArg(OrderPosition, *shared.buildPosition);
            grid->setBoxArguments(sharedBuildKernel, BoxA, false);
            setReal(cc, sharedBuildKernel, Cutoff, cutoff);
            setReal(cc, sharedBuildKernel, ListRange, (1 + listSkin) * cutoff);
            sharedBuildKernel->setArg(Capacity, listCapacity);
            sharedBuildKernel->setArg(Neighbours, neighbours);
        }
        profiler.time("neighbour list build (if due)", [&]() { profiler.launch(sharedBuildKernel, cc.getNumAtoms()); });
    } else {
        // The list's check marks a build on the device; the grid (periodic) and the list are built only then.
        setReal(cc, checkKernel, CheckArgument::MaxDrift, 0.5 * listSkin * cutoff);
        profiler.time("neighbour list check", [&]() {
            checkKernel->setArg(CheckArgument::ForceRebuild, forced ? 1 : 0);
            profiler.launch(checkKernel, cc.getNumAtoms());
        });
        profiler.time("cell grid (at list builds)", [&]() { grid->build(rebuild, forced); });
        setModelArguments(grid->getCellsArgument(), grid->cellStart); // (the cells of this build)
        {
            using namespace BuildArgument;
            buildKernel->setArg(Cells, grid->getCellsArgument());
            grid->setBoxArguments(buildKernel, BoxA, false);
            setReal(cc, buildKernel, Cutoff, cutoff);
            setReal(cc, buildKernel, ListRange, (1 + listSkin) * cutoff);
            buildKernel->setArg(Capacity, listCapacity);
            buildKernel->setArg(Neighbours, neighbours);
        }
        profiler.time("neighbour list build (if due)", [&]() { profiler.launch(buildKernel, cc.getNumAtoms()); });
    }
    *needsRebuild = false;
    for (int k = 0; k < 3; k++)
        listBox[k] = box[k];
    profiler.time("densities, particle state", [&]() { profiler.launch(densityKernel, cc.getNumAtoms()); });
}

void CommonCalcGenDPDEForceKernel::setDeferred(bool deferred) {
    if (this->deferred && !deferred) {
        // The end of an integrator's run of steps: the list's largest count, read once per run.
        ContextSelector selector(cc);
        std::vector<int> found;
        profiler.transfer();
        errors.download(found);
        growList(found[2]);
    }
    this->deferred = deferred;
}

ArrayInterface* CommonCalcGenDPDEForceKernel::shareBuild(CommonGenDPDEBuildSource* source, double range) {
    // Either way the list is built again at the next evaluation: from the shared cells, or from its own grid
    // (the shared list's rows belong to the order's build, whose cells the own grid does not hold).
    if (source == nullptr) {
        if (buildSource != nullptr)
            *needsRebuild = true;
        buildSource = nullptr;
        return nullptr;
    }
    if (!periodic || dependsOnTemperature || range != cutoff)
        return nullptr;
    buildSource = source;
    *needsRebuild = true;
    return &rebuild;
}

void CommonCalcGenDPDEForceKernel::growList(int mostNeighbours) {
    // Some particles had more neighbours than the list holds (they used the cells): room for them at the start of
    // the next evaluation (this one's passes may still read the list).
    if (mostNeighbours > listCapacity && wantedCapacity != INT_MIN)
        wantedCapacity = std::max(wantedCapacity, roundUp(1.25 * mostNeighbours, 8));
}

void CommonCalcGenDPDEForceKernel::throwErrors(ContextImpl& context, int nonFinite, int invalid, long long step) {
    // The first particle in index order whose position, then whose state, is bad (as the Reference platform checks).
    std::vector<Vec3> positions;
    context.getPositions(positions);
    for (int i = 0; i < (int) positions.size(); i++)
        if (!(std::isfinite(positions[i][0]) && std::isfinite(positions[i][1]) && std::isfinite(positions[i][2])))
            throw OpenMMException(GenDPDEForceErrors::nonFinitePosition(i, positions[i], step));
    if (invalid == noValue)
        throw OpenMMException("GenDPDEForce: a particle's position is not finite at step " + std::to_string(step)
                              + " (particle " + std::to_string(nonFinite) + ")");
    const int particle = invalid / GENDPDE_PARTICLE_STATUSES, status = invalid % GENDPDE_PARTICLE_STATUSES;
    if (status == GENDPDE_PARTICLE_NO_NEIGHBOR)
        throw OpenMMException(GenDPDEForceErrors::noNeighbor(particle, cutoff, step));
    const Physics::LocalEquationOfState& law = lawByType[types->getParticleTypeIndices()[particle]];
    shareBuild(nullptr, 0.0); // (the pass below is not a step's: its own check and grid)
    // The density of the particle at these positions (the flags came from an evaluation at them; the atoms may have
    // been reordered since, so the pass runs again).
    densityPass();
    std::vector<double> volumes;
    volume.download(volumes, true);
    const double density = 1.0 / volumes[slotOf(particle)];
    if (status == GENDPDE_PARTICLE_OUTSIDE_DOMAIN)
        throw OpenMMException(GenDPDEForceErrors::outsideDomain(particle, density, law, step));
    if (status == GENDPDE_PARTICLE_TEMPERATURE_JUMP) {
        // theta where the integrator kept the state (the last step's positions; it kept none from the failed
        // evaluation) and here
        const GenDPDEIntegrator* integrator;
        CommonGenDPDEThermalArrays* state =
                GenDPDEIntegratorUtilities::thermalStateHolder(context, integrator).getDeviceThermalState(*integrator);
        std::vector<double> stored, found, capacity;
        std::vector<int> particleClass;
        state->internalEnergies->download(stored, true);
        thermalEnergyOut.download(found, true);
        state->classHeatCapacity->download(capacity, true);
        state->particleClass->download(particleClass);
        const double c = capacity[particleClass[particle]];
        throw OpenMMException(GenDPDEForceErrors::temperatureJump(particle, stored[particle] / c, found[particle] / c,
                                                                  density, step));
    }
    throw OpenMMException(GenDPDEForceErrors::equationOfStateOverflow(particle, density, law, step));
}

int CommonCalcGenDPDEForceKernel::slotOf(int particle) const {
    const std::vector<int>& atomIndex = cc.getAtomIndex();
    return (int) (std::find(atomIndex.begin(), atomIndex.end(), particle) - atomIndex.begin());
}

double CommonCalcGenDPDEForceKernel::execute(ContextImpl& context, bool includeForces, bool includeEnergy) {
    ContextSelector selector(cc);
    computeDensities(context);
    if (includeForces)
        profiler.time("forces", [&]() { profiler.launch(forceKernel, cc.getNumAtoms()); });
    return 0.0; // the energy is in the context's energy buffer
}

const GenDPDEObservables& CommonCalcGenDPDEForceKernel::getObservables(ContextImpl& context, bool particleVirials) {
    ContextSelector selector(cc);
    computeDensities(context);
    virialKernel->setArg(VirialArgument::Tensors, particleVirials ? 1 : 0);
    profiler.time("virials", [&]() { profiler.launch(virialKernel, cc.getNumAtoms()); });
    std::vector<double> n0, v, pi, w, tensors;
    primitiveDensity.download(n0, true);
    volume.download(v, true);
    pressure.download(pi, true);
    particleVirial.download(w, true);
    if (particleVirials)
        particleVirialTensor.download(tensors, true);
    const int numAtoms = cc.getNumAtoms();
    observables.primitiveDensities.resize(numAtoms);
    observables.volumes.resize(numAtoms);
    observables.densities.resize(numAtoms);
    observables.pressures.resize(numAtoms);
    observables.particleVirials.assign(particleVirials ? 9 * numAtoms : 0, 0.0);
    std::vector<double> virial(numAtoms);
    const std::vector<int>& atomIndex = cc.getAtomIndex(); // the values are by slot
    for (int slot = 0; slot < numAtoms; slot++) {
        const int i = atomIndex[slot];
        observables.primitiveDensities[i] = n0[slot];
        observables.volumes[i] = v[slot];
        observables.densities[i] = 1.0 / v[slot];
        observables.pressures[i] = pi[slot];
        virial[i] = w[slot];
        if (particleVirials)
            std::copy(&tensors[9 * slot], &tensors[9 * slot] + 9, &observables.particleVirials[9 * i]);
    }
    FixedOrderSum::Accumulator sum;
    for (double value : virial)
        sum.add(value);
    observables.virial = sum.sum();
    return observables;
}
