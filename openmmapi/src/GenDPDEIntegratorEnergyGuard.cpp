/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
/* GenDPDEIntegrator's energy guard (docs/integrator.md, "Simulations that go bad"). The Isoenergetic and Conservative
 * modes conserve E = K + U + sum eps: the sweep exactly, velocity Verlet to O(dt^2) while the step resolves the
 * forces. A step too large for them (a background pressure or an equation of state too stiff for it) breaks that
 * silently: the per-step checks see no particle cross its neighbourhood while the energy runs away (and may come
 * back: a look every 1000 steps can miss it). So E is compared every energyGuardSteps (100) steps; the look costs one
 * evaluation with energies, ~0.5% of the steps. A stable run drifts by far less than 1% of the energy the mode moves
 * over 1000 steps (the criterion of calibration.stability); a drift of energyGuardLimit (10%) of it between two looks
 * is a run that is no longer integrated, and it stops. */

#include "GenDPDEIntegrator.h"
#include "internal/GenDPDEPhysics.h"
#include "internal/MessageText.h"
#include "openmm/OpenMMException.h"
#include "openmm/internal/ContextImpl.h"
#include <algorithm>
#include <cmath>
#include <vector>

using namespace GenDPDEPlugin;
using namespace OpenMM;

double GenDPDEIntegrator::movedEnergy(const EnergyParts& parts) const {
    return parts.kinetic + (mode == Isoenergetic ? parts.internal : 0.0);
}

void GenDPDEIntegrator::markEnergy(const EnergyParts& parts) {
    energyMark.conserved = parts.kinetic + parts.potential + parts.internal;
    energyMark.moved = movedEnergy(parts);
    energyMark.step = energyMark.evaluated = context->getStepCount();
    energyMark.set = true;
}

bool GenDPDEIntegrator::energyGuardMayEvaluate() const {
    // One evaluation per energyGuardSteps steps at most, however often the Context changes from outside (a parameter
    // set before every step(1) would otherwise cost an evaluation a step).
    // (a step count set back, e.g. by an earlier checkpoint, allows one at once)
    const long long since = context->getStepCount() - energyMark.evaluated;
    return since < 0 || since >= energyGuardSteps;
}

void GenDPDEIntegrator::startEnergyGuard() {
    if (!energyMark.set && energyGuardMayEvaluate())
        markEnergy(energyParts());
}

int GenDPDEIntegrator::energyGuardRun(int remaining) const {
    // Up to the next look (a mark's), or the next evaluation allowed (no mark): at fixed step counts.
    const long long next = std::min(energyMark.evaluated, context->getStepCount()) + energyGuardSteps;
    return (int) std::min<long long>(remaining, std::max<long long>(1, next - context->getStepCount()));
}

void GenDPDEIntegrator::checkEnergyDrift() {
    if (!energyGuardMayEvaluate())
        return;
    if (!energyMark.set) { // the Context changed, or a Force moved the particles (a barostat): a new mark
        markEnergy(energyParts());
        return;
    }
    const long long step = context->getStepCount();
    const EnergyParts parts = energyParts();
    const double conserved = parts.kinetic + parts.potential + parts.internal;
    const double moved = movedEnergy(parts);
    // (a floor of k_B x 1 K per particle, for a system at rest, whose E moves by rounding alone)
    const double scale =
            std::max({energyMark.moved, moved, Physics::Boltzmann * context->getSystem().getNumParticles()});
    const double drift = conserved - energyMark.conserved;
    if (!(std::fabs(drift) <= energyGuardLimit * scale)) {
        // The particle with the largest kinetic energy, where the runaway shows.
        std::vector<Vec3> velocities;
        context->getVelocities(velocities);
        const System& system = context->getSystem();
        int hottest = 0;
        double largest = -1.0;
        for (int i = 0; i < system.getNumParticles(); i++) {
            const double kinetic = 0.5 * system.getParticleMass(i) * velocities[i].dot(velocities[i]);
            if (kinetic > largest) {
                largest = kinetic;
                hottest = i;
            }
        }
        MessageText message;
        message.precision(6);
        message << "GenDPDEIntegrator: the conserved energy K + U + sum eps changed by " << drift << " kJ/mol between "
                << "step " << energyMark.step << " and step " << step << ", more than " << energyGuardLimit * 100
                << "% of the energy the "
                << (mode == Isoenergetic ? "Isoenergetic mode moves (K + sum eps, " : "Conservative mode moves (K, ")
                << scale << " kJ/mol): the dynamics is no longer being integrated (the step size is too large for the "
                << "forces, e.g. a background pressure or an equation of state too stiff for it); particle " << hottest
                << " has the largest kinetic energy, " << largest << " kJ/mol";
        energyMark.set = false;
        throw OpenMMException(stopRun(message.str()));
    }
    markEnergy(parts);
}
