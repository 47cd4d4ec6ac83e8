/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
#include "ReferenceGenDPDEIntegratorKernel.h"
#include "ReferenceKernelAccess.h"
#include "internal/BoxGeometry.h"
#include "gendpde/CounterRandom.h"
#include "internal/FixedOrderSum.h"
#include "internal/GenDPDEPhysics.h"
#include "openmm/OpenMMException.h"
#include "openmm/internal/ContextImpl.h"
#include <algorithm>
#include <cmath>

using namespace GenDPDEPlugin;
using namespace OpenMM;

void ReferenceIntegrateGenDPDEStepKernel::initialize(ContextImpl& context, const GenDPDEIntegrator& integrator,
                                                     double cutoff, int seed, const std::vector<double>& energies,
                                                     const std::map<int, int>& particleTypes) {
    const System& system = context.getSystem();
    this->cutoff = cutoff;
    this->seed = seed;
    internalEnergies = energies;
    typeTables.reset(
            new IntegratorTypeTables(ParticleTypeIndex(particleTypes, system.getNumParticles(), "GenDPDEIntegrator")));
    inverseMasses.resize(system.getNumParticles());
    for (int i = 0; i < system.getNumParticles(); i++) {
        double mass = system.getParticleMass(i);
        inverseMasses[i] = (mass == 0.0 ? 0.0 : 1.0 / mass);
    }
    if (cutoff > 0.0)
        neighborList.reset(new NeighborList(cutoff, NeighborList::defaultSkinFraction * cutoff,
                                            system.usesPeriodicBoundaryConditions()));
}

GenDPDEThermalState ReferenceIntegrateGenDPDEStepKernel::getThermalState(const GenDPDEIntegrator& integrator) {
    typeTables->update(integrator);   // the heat capacities may have changed since the last step
    GenDPDEThermalState state;
    state.isothermal = (integrator.getMode() == GenDPDEIntegrator::Isothermal);
    state.temperature = integrator.getTemperature();
    state.internalEnergies = internalEnergies.data();
    state.densityEntropies = densityEntropiesKnown ? densityEntropies.data() : nullptr;
    state.particleClass = typeTables->getParticleClasses().data();
    state.classHeatCapacity = typeTables->getTable().heatCapacity.data();
    state.checkStep = GenDPDEIntegratorUtilities::checksStepTemperatures(integrator);
    return state;
}

PairView ReferenceIntegrateGenDPDEStepKernel::currentPairs(ContextImpl& context, GenDPDEPairSource* pairSource,
                                                           int numThreads) {
    // The source, if any, was evaluated at the current positions just before this step (see execute()).
    GenDPDEHostPairList* list = pairSource != nullptr ? pairSource->getHostPairList() : nullptr;
    if (list != nullptr && pairSource->holdsPairsFor(cutoff, context.getStepCount()))
        return list->getPairs(numThreads);
    const Vec3* box = extractBoxVectors(context);
    if (context.getSystem().usesPeriodicBoundaryConditions())
        BoxGeometry::checkCutoffAgainstBox("GenDPDEIntegrator", cutoff, box);   // a barostat may have shrunk it
    return neighborList->update(extractPositions(context), box, numThreads);
}

void ReferenceIntegrateGenDPDEStepKernel::kick(ContextImpl& context, std::vector<Vec3>& velocities,
                                               const std::vector<Vec3>& forces, double timeStep) {
    for (size_t i = 0; i < velocities.size(); i++)
        if (inverseMasses[i] != 0.0)
            velocities[i] += forces[i] * (timeStep * inverseMasses[i]);
}

int ReferenceIntegrateGenDPDEStepKernel::firstUnstableParticle(ContextImpl& context, double stepSize,
                                                               double maxDisplacement, int begin, int end) const {
    // A few flops per particle: the force finite, and the particle not about to move farther than maxDisplacement
    // (GenDPDEStepTerms) with its velocity after the kicks.
    const std::vector<Vec3>& forces = extractForces(context);
    const std::vector<Vec3>& velocities = extractVelocities(context);
    const double limit2 = maxDisplacement * maxDisplacement;
    for (int i = begin; i < end; i++) {
        if (!(std::isfinite(forces[i][0]) && std::isfinite(forces[i][1]) && std::isfinite(forces[i][2])))
            return i;
        const Vec3 displacement = (velocities[i] + forces[i] * (stepSize * inverseMasses[i])) * stepSize;
        if (inverseMasses[i] != 0.0 && !(displacement.dot(displacement) <= limit2))
            return i;
    }
    return -1;
}

void ReferenceIntegrateGenDPDEStepKernel::throwUnstable(ContextImpl& context, int i, double stepSize,
                                                        double maxDisplacement) const {
    throw OpenMMException(GenDPDEIntegratorUtilities::unstableParticleMessage(
            i, extractVelocities(context)[i], extractForces(context)[i], inverseMasses[i], stepSize, maxDisplacement,
            context.getStepCount()));
}

void ReferenceIntegrateGenDPDEStepKernel::checkStepIsStable(ContextImpl& context, double stepSize,
                                                            double maxDisplacement) {
    // One cheap pass before anything changes.
    const int unstable = firstUnstableParticle(context, stepSize, maxDisplacement, 0, inverseMasses.size());
    if (unstable >= 0)
        throwUnstable(context, unstable, stepSize, maxDisplacement);
}

void ReferenceIntegrateGenDPDEStepKernel::sweep(ContextImpl& context, PairView pairs, std::vector<Vec3>& velocities,
                                                const GenDPDEIntegrator& integrator, const GenDPDEStepTerms& terms) {
    // docs/theory.md sections 5-7, pair by pair at fixed positions, in the order every platform follows.
    if (pairs.holdsIndexPairs())   // (the CPU platform sweeps its IndexPairs itself)
        throw OpenMMException("GenDPDEIntegrator: internal error: Reference's sweep was given pairs without geometry");
    const long long step = context.getStepCount();
    buildSweepOrder(context, pairs, 1);
    const std::vector<int>& order = sweepOrder.getOrder();
    typeTables->update(integrator);
    PairSweepParameters parameters(integrator, terms, cutoff, seed, step, *typeTables, sweepNoise);
    gatherSweepState(context, integrator, parameters, 1);
    // If an internal energy would become <= 0, nothing is copied back (the velocities and internal energies stay
    // those before the step; positions have not moved yet), and the error names the particle and the step.
    const int failed = sweepPairs(pairs.begin(), StoredPairGeometry(), order.data(), order.size(), parameters,
                                  layout.slots, layout.slotInverseMasses.data(), layout.slotVelocities.data(),
                                  terms.internalEnergies ? layout.slotEnergies.data() : nullptr);
    if (failed >= 0)
        failSweep(pairs, order, failed, step);
    layout.scatter(velocities, terms.internalEnergies ? internalEnergies.data() : nullptr, 1);
}

void ReferenceIntegrateGenDPDEStepKernel::buildSweepOrder(ContextImpl& context, PairView pairs, int numThreads) {
    const int stride = pairs.indexStride();
    const int* first = pairs.size() > 0 ? pairs.firstIndices() : nullptr; // (each pair's j follows its i)
    sweepOrder.build(extractPositions(context), extractBoxVectors(context),
                     context.getSystem().usesPeriodicBoundaryConditions(), cutoff, pairs.size(), first,
                     first != nullptr ? first + 1 : nullptr, stride, numThreads, pairs.getRowPairStart());
}

void ReferenceIntegrateGenDPDEStepKernel::gatherSweepState(ContextImpl& context, const GenDPDEIntegrator& integrator,
                                                           PairSweepParameters& parameters, int numThreads,
                                                           const Vec3* positions) {
    const bool classes = parameters.numClasses > 1;
    layout.gather(sweepOrder, extractVelocities(context), extractForces(context), 0.5 * integrator.getStepSize(),
                  parameters.terms.internalEnergies ? internalEnergies.data() : nullptr, inverseMasses.data(),
                  classes ? parameters.particleClass : nullptr, numThreads, positions);
    if (classes)
        parameters.particleClass = layout.slotClasses.data();
}

void ReferenceIntegrateGenDPDEStepKernel::failSweep(PairView pairs, const std::vector<int>& order, int failed,
                                                    long long step) {
    const int particle = pairs.holdsIndexPairs()
            ? failedParticle(pairs.getIndexPairs(), order.data(), failed, layout.slots, layout.slotEnergies.data())
            : failedParticle(pairs.begin(), order.data(), failed, layout.slots, layout.slotEnergies.data());
    const double value = layout.slotEnergies[layout.slots[particle]];
    throw OpenMMException(GenDPDEIntegratorUtilities::nonPositiveEnergyMessage(particle, value, step));
}

void ReferenceIntegrateGenDPDEStepKernel::drift(ContextImpl& context, std::vector<Vec3>& positions,
                                                const std::vector<Vec3>& velocities, double timeStep) {
    for (size_t i = 0; i < positions.size(); i++)
        if (inverseMasses[i] != 0.0)
            positions[i] += velocities[i] * timeStep;
}

void ReferenceIntegrateGenDPDEStepKernel::execute(ContextImpl& context, const GenDPDEIntegrator& integrator,
                                                  const GenDPDEStepTerms& terms, GenDPDEPairSource* pairSource) {
    // docs/theory.md section 6: half kick, pair sweep at fixed positions, half kick, drift; without pair terms,
    // velocity Verlet (leapfrog form: one full kick).
    checkStepIsStable(context, integrator.getStepSize(), terms.maxDisplacement);
    std::vector<Vec3>& velocities = extractVelocities(context);
    const std::vector<Vec3>& forces = extractForces(context);
    const double dt = integrator.getStepSize();
    if (!terms.pairSweep)
        kick(context, velocities, forces, dt);
    else {
        // (the first half kick inside the sweep, on the sweep's copies: a failed sweep leaves the state untouched)
        sweep(context, currentPairs(context, pairSource, numThreads(context)), velocities, integrator, terms);
        kick(context, velocities, forces, 0.5 * dt);
    }
    drift(context, extractPositions(context), velocities, dt);
    ReferencePlatform::PlatformData& data = platformData(context);
    data.time += dt;
    data.stepCount++;
}

double ReferenceIntegrateGenDPDEStepKernel::kineticEnergy(int i, const std::vector<Vec3>& velocities,
                                                          const std::vector<Vec3>& forces, double halfStep) const {
    // Velocities are half a step behind the positions: K at the current time uses v + (dt/2) F/m.
    if (inverseMasses[i] == 0.0)
        return 0.0;
    const Vec3 v = velocities[i] + forces[i] * (halfStep * inverseMasses[i]);
    return 0.5 * v.dot(v) / inverseMasses[i];
}

double ReferenceIntegrateGenDPDEStepKernel::computeKineticEnergy(ContextImpl& context,
                                                                 const GenDPDEIntegrator& integrator) {
    const std::vector<Vec3>& velocities = extractVelocities(context);
    const std::vector<Vec3>& forces = extractForces(context);
    const double halfStep = 0.5 * integrator.getStepSize();
    FixedOrderSum::Accumulator energy; // summed as the CPU platform sums it, for the same bits
    for (size_t i = 0; i < velocities.size(); i++)
        energy.add(kineticEnergy(i, velocities, forces, halfStep));
    return energy.sum();
}
