/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
#include "ReferenceGenDPDEForceKernel.h"
#include "ReferenceKernelAccess.h"
#include "internal/BoxGeometry.h"
#include "internal/FixedOrderSum.h"
#include "internal/GenDPDEForceErrors.h"
#include "internal/GenDPDEIntegratorUtilities.h"
#include "internal/GenDPDEPhysics.h"
#include "openmm/OpenMMException.h"

using namespace GenDPDEPlugin;
using namespace OpenMM;

void ReferenceCalcGenDPDEForceKernel::initialize(const System& system, const GenDPDEForce& force) {
    cutoff = force.getCutoffDistance();
    periodic = force.usesPeriodicBoundaryConditions();
    neighborList.reset(new NeighborList(cutoff, NeighborList::defaultSkinFraction * cutoff, periodic));
    numParticles = system.getNumParticles();
    types.reset(new ParticleTypeIndex(force.getParticleTypes(), numParticles, "GenDPDEForce"));
    readParameters(force);
}

ReferenceCalcGenDPDEForceKernel::ParticleModel::ParticleModel(const ReferenceCalcGenDPDEForceKernel& kernel,
                                                              ContextImpl& context) :
        estimator(kernel.estimator, kernel.cutoff, kernel.cutoff / kernel.cutoffScaling), laws(&kernel.lawByType),
        thermal({false, 0.0, nullptr, nullptr, nullptr, nullptr, false}) {
    if (kernel.dependsOnTemperature)
        thermal = GenDPDEIntegratorUtilities::thermalState(context);
}

void ReferenceCalcGenDPDEForceKernel::copyParametersToContext(ContextImpl& context, const GenDPDEForce& force) {
    readParameters(force);
}

void ReferenceCalcGenDPDEForceKernel::readParameters(const GenDPDEForce& force) {
    GenDPDEForceErrors::checkUnchangeableParameters(force, cutoff, periodic, *types);
    std::vector<Physics::LocalEquationOfState> laws = equationsOfStateByType(force, *types);   // checked first
    estimator = (int) force.getDensityEstimator();
    lawByType = laws;
    dependsOnTemperature = force.dependsOnTemperature();
    thermalEnergy.assign(dependsOnTemperature ? numParticles : 0, 0.0);
    densityEntropy.assign(thermalEnergy.size(), 0.0);
    // V-C's moments (48 bytes per particle) only while the estimator uses them
    moment.assign(usesMoments() ? numParticles : 0, Vec3());
    momentForce.assign(moment.size(), Vec3());
    cutoffScaling = force.getCutoffScaling();
    observablesValid = false;
}

void ReferenceCalcGenDPDEForceKernel::checkConfiguration(ContextImpl& context, int firstBadParticle) const {
    const std::vector<Vec3>& positions = extractPositions(context);
    if (firstBadParticle >= 0)
        throw OpenMMException(GenDPDEForceErrors::nonFinitePosition(firstBadParticle, positions[firstBadParticle],
                                                                    context.getStepCount()));
    if (periodic)
        BoxGeometry::checkCutoffAgainstBox("GenDPDEForce", cutoff, extractBoxVectors(context));
}

int ReferenceCalcGenDPDEForceKernel::firstNonFinitePosition(const std::vector<Vec3>& positions, int begin, int end) {
    for (int i = begin; i < end; i++)
        if (!(std::isfinite(positions[i][0]) && std::isfinite(positions[i][1]) && std::isfinite(positions[i][2])))
            return i;
    return -1;
}

void ReferenceCalcGenDPDEForceKernel::throwParticleError(int status, int i, double volume, ContextImpl& context) const {
    if (status == GENDPDE_PARTICLE_NO_NEIGHBOR)
        throw OpenMMException(GenDPDEForceErrors::noNeighbor(i, cutoff, context.getStepCount()));
    if (status == GENDPDE_PARTICLE_OUTSIDE_DOMAIN)
        throw OpenMMException(GenDPDEForceErrors::outsideDomain(
                i, 1.0 / volume, lawByType[types->getParticleTypeIndices()[i]], context.getStepCount()));
    if (status == GENDPDE_PARTICLE_TEMPERATURE_JUMP) {
        // theta where the integrator kept the state (the last step's positions) and here (storeParticle())
        const GenDPDEThermalState thermal = GenDPDEIntegratorUtilities::thermalState(context);
        const double capacity = thermal.classHeatCapacity[thermal.particleClass[i]];
        throw OpenMMException(GenDPDEForceErrors::temperatureJump(i, thermal.internalEnergies[i] / capacity,
                                                                  thermalEnergy[i] / capacity, 1.0 / volume,
                                                                  context.getStepCount()));
    }
    throw OpenMMException(GenDPDEForceErrors::equationOfStateOverflow(
            i, 1.0 / volume, lawByType[types->getParticleTypeIndices()[i]], context.getStepCount()));
}

double ReferenceCalcGenDPDEForceKernel::computeDensitiesAndEnergy(ContextImpl& context) {
    const std::vector<Vec3>& positions = extractPositions(context);
    const int numParticles = positions.size();
    checkConfiguration(context, firstNonFinitePosition(positions, 0, numParticles));
    const PairView pairs = neighborList->update(positions, extractBoxVectors(context));

    // docs/theory.md sections 2-3: primitive densities n0_i = sum_j w(r_ij).
    const Physics::DensityWeight weight(cutoff);
    sizeParticleArrays();
    std::fill(primitiveDensity.begin(), primitiveDensity.end(), 0.0);
    for (const ParticlePair& pair : pairs) {
        double w = weight.value(pair.r);
        primitiveDensity[pair.i] += w;
        primitiveDensity[pair.j] += w;
    }
    // docs/theory.md section 3 (V-C): the first moments g_i = sum_j phi(r_ij) e_ij.
    if (usesMoments()) {
        std::fill(moment.begin(), moment.end(), Vec3());
        for (const ParticlePair& pair : pairs)
            if (pair.r > 0.0 && pair.r < cutoff) {
                const Vec3 term = pair.delta * Physics::momentWeightOverDistance(pair.r, weight.getInverseCutoff());
                moment[pair.i] += term;
                moment[pair.j] -= term;
            }
    }

    // docs/theory.md sections 3-4: volumes, Tait pressures and free energies; U = sum_i f(n_i).
    const ParticleModel model(*this, context);
    const std::vector<int>& type = types->getParticleTypeIndices();
    const bool moments = usesMoments();
    FixedOrderSum::Accumulator energy;   // summed as the CPU platform sums it, for the same bits
    for (int i = 0; i < numParticles; i++) {
        Physics::ParticleState state;
        const int status =
                model.particleState(i, type[i], primitiveDensity[i], moments ? moment[i].dot(moment[i]) : 0.0, state);
        storeParticle(i, state);
        if (status != GENDPDE_PARTICLE_VALID)
            throwParticleError(status, i, state.volume, context);
        energy.add(state.freeEnergy);
    }
    return energy.sum();
}

double ReferenceCalcGenDPDEForceKernel::computePairForces(ContextImpl& context, std::vector<Vec3>* forces,
                                                          std::vector<double>* particleVirials) {
    // docs/theory.md section 4: F_i = sum_j [pi_i V'_i + pi_j V'_j] w'(r_ij) e_ij (+ V-C's moment term);
    // W = sum_{i<j} r_ij . F_ij, summed per first particle, then over particles in the fixed order (as the CPU platform
    // does); the particles' virial tensors, when asked for, get half of each of their pairs' F r^T in a pass of their
    // own (a step does not pay for them).
    const Physics::DensityWeight weight(cutoff);
    const bool moments = usesMoments();
    const Vec3 noMoment;
    // The force on pair.i from pair.j (pair.r > 0; the core's gendpdePairForce); virial receives pair.delta . F. A
    // pair whose r^2 < R^2 rounds to r = R has w'(r) = 0 (DensityWeight::derivative) and no moment term.
    auto pairForce = [&](const ParticlePair& pair, double& virial) {
        return Physics::pairForce(pair.delta, pair.r, forceCoefficient[pair.i] + forceCoefficient[pair.j],
                                  weight.derivative(pair.r), weight.getInverseCutoff(), moments && pair.r < cutoff,
                                  moments ? momentForce[pair.i] : noMoment, moments ? momentForce[pair.j] : noMoment,
                                  virial);
    };
    particleVirial.assign(numParticles, 0.0);
    for (const ParticlePair& pair : neighborList->getPairs()) {
        if (pair.r == 0.0)
            continue; // coincident particles: counted in the density, no direction, no force
        double virial;
        const Vec3 force = pairForce(pair, virial);
        if (forces != nullptr) {
            (*forces)[pair.i] += force;
            (*forces)[pair.j] -= force;
        }
        particleVirial[pair.i] += virial;
    }
    if (particleVirials != nullptr) {
        std::vector<Physics::Tensor> tensors(particleVirial.size());
        for (const ParticlePair& pair : neighborList->getPairs()) {
            if (pair.r == 0.0)
                continue;
            double virial;
            const Vec3 force = pairForce(pair, virial);
            Physics::addHalfPairVirial(force, pair.delta, tensors[pair.i]);
            Physics::addHalfPairVirial(force, pair.delta, tensors[pair.j]);
        }
        particleVirials->resize(9 * tensors.size());
        for (size_t i = 0; i < tensors.size(); i++)
            std::copy(tensors[i].element, tensors[i].element + 9, particleVirials->data() + 9 * i);
    }
    FixedOrderSum::Accumulator virial;
    for (double w : particleVirial)
        virial.add(w);
    return virial.sum();
}

double ReferenceCalcGenDPDEForceKernel::execute(ContextImpl& context, bool includeForces, bool includeEnergy) {
    double energy = computeDensitiesAndEnergy(context);
    if (includeForces)
        computePairForces(context, &extractForces(context), nullptr);
    return energy;
}

const GenDPDEObservables& ReferenceCalcGenDPDEForceKernel::getObservables(ContextImpl& context, bool particleVirials) {
    const std::vector<Vec3>& positions = extractPositions(context);
    Vec3* box = extractBoxVectors(context);
    // (With a law that depends on temperature they also depend on the integrator's state: always computed.)
    if (observablesValid && !dependsOnTemperature && (observedVirials || !particleVirials)
        && positions == observedPositions && box[0] == observedBox[0] && box[1] == observedBox[1]
        && box[2] == observedBox[2])
        return observables;
    observablesAsked = true;
    try {
        computeDensitiesAndEnergy(context);
    } catch (...) {
        observablesAsked = false;
        throw;
    }
    observablesAsked = false;
    observables.virial = computePairForces(context, nullptr, particleVirials ? &observables.particleVirials : nullptr);
    if (!particleVirials)
        observables.particleVirials.clear();
    observables.primitiveDensities = primitiveDensity;
    observables.volumes = volume;
    observables.pressures = pressure;
    observables.densities.resize(volume.size());
    for (size_t i = 0; i < volume.size(); i++)
        observables.densities[i] = 1.0 / volume[i];
    observedPositions = positions;
    for (int k = 0; k < 3; k++)
        observedBox[k] = box[k];
    observablesValid = true;
    observedVirials = particleVirials;
    return observables;
}
