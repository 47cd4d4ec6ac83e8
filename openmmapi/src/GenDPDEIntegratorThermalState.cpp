/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
/* GenDPDEIntegrator and the particles' thermal state when a GenDPDEForce's equation of state depends on temperature
 * (docs/theory.md section 11; the rule in docs/integrator.md, "The particles' thermal state: one rule").
 *
 * The kernel holds eps_i and, when known, sigma_i, the value of sigma(n) at the density eps_i belongs to: together the
 * particle's entropy. A force evaluation reads them and finds each particle's thermal energy at the current positions,
 * C_V theta_i = eps_i exp(-(sigma(n_i) - sigma_i)/C_V); keeping that state (keepThermalState) fixes the entropies at
 * the current positions. Everything that changes the Context reaches applyThermalRule() as an event, and the rule
 * keeps one invariant: outside step(), eps_i is C_V theta_i at the current positions. So reading the state (getters,
 * checkpoints, States, the conserved energy, the force's observables) needs no evaluation and changes nothing. */

#include "GenDPDEIntegrator.h"
#include "GenDPDEKernels.h"
#include "internal/GenDPDEForceImpl.h"
#include "internal/GenDPDEIntegratorUtilities.h"
#include "openmm/OpenMMException.h"
#include "openmm/internal/ContextImpl.h"

using namespace GenDPDEPlugin;
using namespace OpenMM;

void GenDPDEIntegrator::stateChanged(State::DataType changed) {
    if (context == nullptr)
        return;
    forcesCurrent = false;
    energyMark.set = false; // the conserved energy changed from outside the dynamics: the guard marks it again
    if (changed == State::Positions) {
        checkSetPositions();
        applyThermalRule(ThermalEvent::PositionsSet);
    } else if (changed == State::Energy) {
        // A Force's parameters changed (ContextImpl::systemChanged), or a checkpoint was loaded: the rule applies if
        // they were the laws of the particles' state.
        if (thermalForce != nullptr && thermalForce->getNumParameterUpdates() != lawUpdatesSeen) {
            lawUpdatesSeen = thermalForce->getNumParameterUpdates();
            applyThermalRule(ThermalEvent::LawChanged);
        }
    }
}

void GenDPDEIntegrator::applyThermalRule(ThermalEvent event) {
    forcesCurrent = false; // every event changes the forces or what they act on
    energyMark.set = false; // and may change the conserved energy: the guard marks it again
    if (context == nullptr || thermalForce == nullptr || event == ThermalEvent::ParametersChanged)
        return;
    IntegrateGenDPDEStepKernel& k = boundKernel();
    auto forget = [&]() { // eps_i stays: C_V theta_i at the current positions, the entropies not fixed
        k.forgetDensityEntropies();
        entropyState = EntropyState::Unknown;
    };
    if (mode == Isothermal) {
        // The particles' own state is frozen (the force uses the bath temperature): they keep their temperatures.
        forget();
        if (event == ThermalEvent::PositionsSet)
            positionsSet = true;
        return;
    }
    const bool keepEntropies = adiabaticPositionChanges;
    switch (event) {
        case ThermalEvent::PositionsSet:
            positionsSet = true;
            if (!keepEntropies)
                forget(); // each particle keeps its temperature at the new positions
            else {
                // each keeps its entropy (or, never fixed, its temperature: the first positions)
                if (entropyState == EntropyState::Current)
                    entropyState = EntropyState::Earlier;
                settleThermalState();
            }
            break;
        case ThermalEvent::PositionsMovedByForce:
            // Inside step(), right before the step's evaluation, which fixes the state at the new positions.
            if (!keepEntropies)
                forget();
            else if (entropyState == EntropyState::Current)
                entropyState = EntropyState::Earlier;
            break;
        case ThermalEvent::EnergiesSet:
        case ThermalEvent::LawChanged:
            // Temperatures just set, or a new law at the same positions: each particle has its temperature here (eps_i
            // is C_V theta_i at the current positions); with adiabatic moves its entropy is fixed now.
            forget();
            if (keepEntropies)
                settleThermalState();
            break;
        case ThermalEvent::AdiabaticChanged:
        case ThermalEvent::ModeChanged:
            // Adiabatic moves need the entropies fixed at the current positions (from now on, or since the Isothermal
            // mode froze the state); otherwise nothing changes.
            if (keepEntropies && entropyState == EntropyState::Unknown)
                settleThermalState();
            break;
        case ThermalEvent::ParametersChanged:
            break;
    }
}

void GenDPDEIntegrator::settleThermalState() {
    if (!positionsSet || !boundKernel().hasInternalEnergies())
        return; // nothing to fix the entropies at yet: the temperatures hold at the first positions set
    try {
        evaluateStepForces(false); // (a move from outside the dynamics may change the temperatures by any factor)
    } catch (const OpenMMException&) {
        return; // positions where the force cannot be evaluated: the state stays, and the next step says why
    }
    rememberForces();
}

void GenDPDEIntegrator::evaluateStepForces(bool checkStep) {
    checkingStepTemperatures = checkStep && thermalForce != nullptr;
    try {
        context->calcForcesAndEnergy(true, false, getIntegrationForceGroups());
    } catch (...) {
        checkingStepTemperatures = false;
        throw;
    }
    checkingStepTemperatures = false;
    if (thermalForce == nullptr)
        return;
    // eps_i at the densities of these positions (docs/theory.md section 11), or, in the Isothermal mode, forgotten
    GenDPDEIntegratorUtilities::keepThermalState(*context, *this, boundKernel());
    entropyState = (mode == Isothermal ? EntropyState::Unknown : EntropyState::Current);
}

bool GenDPDEIntegrator::forcesAreCurrent() const {
    if (!forcesCurrent || context->getLastForceGroups() != getIntegrationForceGroups())
        return false;
    if (thermalForce == nullptr || thermalForce->getNumEvaluations() != forcesEvaluation)
        return false; // another evaluation (a barostat's trial) replaced the force's pairs and thermal state
    Vec3 box[3];
    context->getPeriodicBoxVectors(box[0], box[1], box[2]); // (setting the box alone tells no integrator)
    return box[0] == forcesBox[0] && box[1] == forcesBox[1] && box[2] == forcesBox[2];
}

void GenDPDEIntegrator::rememberForces() {
    if (thermalForce == nullptr || mode == Isothermal)
        return;
    forcesCurrent = true;
    forcesEvaluation = thermalForce->getNumEvaluations();
    context->getPeriodicBoxVectors(forcesBox[0], forcesBox[1], forcesBox[2]);
}

void GenDPDEIntegrator::setAdiabaticPositionChanges(bool adiabatic) {
    adiabaticPositionChanges = adiabatic;
    applyThermalRule(ThermalEvent::AdiabaticChanged);
}

bool GenDPDEIntegrator::getAdiabaticPositionChanges() const {
    return adiabaticPositionChanges;
}
