#include "ReferenceGenDPDEIntegratorKernel.h"
#include "ReferenceGenDPDEForceKernel.h"
#include "ReferenceKernelAccess.h"
#include "internal/BoxGeometry.h"
#include "internal/CounterRandom.h"
#include "internal/GenDPDEForceImpl.h"
#include "internal/GenDPDEPairSweep.h"
#include "internal/GenDPDEPhysics.h"
#include "openmm/OpenMMException.h"
#include "openmm/internal/ContextImpl.h"
#include <algorithm>
#include <cmath>
#include <sstream>

using namespace GenDPDEPlugin;
using namespace OpenMM;

void ReferenceIntegrateGenDPDEStepKernel::initialize(ContextImpl& context, const GenDPDEIntegrator& integrator,
                                                     double cutoff, int seed, const std::vector<double>& energies) {
    const System& system = context.getSystem();
    this->cutoff = cutoff;
    this->seed = seed;
    internalEnergies = energies;
    inverseMasses.resize(system.getNumParticles());
    for (int i = 0; i < system.getNumParticles(); i++) {
        double mass = system.getParticleMass(i);
        inverseMasses[i] = (mass == 0.0 ? 0.0 : 1.0/mass);
    }
    if (cutoff > 0.0)
        neighborList.reset(new NeighborList(cutoff, NeighborList::defaultSkinFraction*cutoff, system.usesPeriodicBoundaryConditions()));
}

PairView ReferenceIntegrateGenDPDEStepKernel::currentPairs(ContextImpl& context, GenDPDEForceImpl* pairListSource) {
    // The source, if any, was evaluated at the current positions just before this step (see execute()).
    if (pairListSource != nullptr)
        return dynamic_cast<ReferenceCalcGenDPDEForceKernel&>(pairListSource->getKernel().getImpl())
                .getNeighborList().getPairs();
    const Vec3* box = extractBoxVectors(context);
    if (context.getSystem().usesPeriodicBoundaryConditions())
        BoxGeometry::checkCutoffAgainstBox("GenDPDEIntegrator", cutoff, box);   // a barostat may have shrunk it
    return neighborList->update(extractPositions(context), box);
}

void ReferenceIntegrateGenDPDEStepKernel::kick(std::vector<Vec3>& velocities, const std::vector<Vec3>& forces,
                                               double timeStep) const {
    for (size_t i = 0; i < velocities.size(); i++)
        if (inverseMasses[i] != 0.0)
            velocities[i] += forces[i]*(timeStep*inverseMasses[i]);
}

void ReferenceIntegrateGenDPDEStepKernel::checkStepIsStable(ContextImpl& context, double stepSize,
                                                            double maxDisplacement) const {
    // One cheap pass (a few flops per particle) before anything changes: every force finite, and no particle
    // about to move farther than maxDisplacement (GenDPDEStepTerms) with its velocity after the kicks.
    const std::vector<Vec3>& forces = extractForces(context);
    const std::vector<Vec3>& velocities = extractVelocities(context);
    const double limit2 = maxDisplacement*maxDisplacement;
    for (size_t i = 0; i < forces.size(); i++) {
        if (!(std::isfinite(forces[i][0]) && std::isfinite(forces[i][1]) && std::isfinite(forces[i][2]))) {
            throw OpenMMException(GenDPDEIntegratorUtilities::nonFiniteForceMessage(i, forces[i],
                                                                                   context.getStepCount()));
        }
        const Vec3 displacement = (velocities[i] + forces[i]*(stepSize*inverseMasses[i]))*stepSize;
        const double distance2 = displacement.dot(displacement);
        if (inverseMasses[i] != 0.0 && !(distance2 <= limit2)) {
            throw OpenMMException(GenDPDEIntegratorUtilities::unstableStepMessage(i, std::sqrt(distance2),
                                                                                 maxDisplacement, context.getStepCount()));
        }
    }
}

void ReferenceIntegrateGenDPDEStepKernel::sweep(ContextImpl& context, PairView pairs, std::vector<Vec3>& velocities,
        const GenDPDEIntegrator& integrator, const GenDPDEStepTerms& terms) {
    // docs/theory.md sections 5-7, pair by pair at fixed positions, in the order every platform follows.
    static_assert(sizeof(ParticlePair) % sizeof(int) == 0, "the sweep order reads i and j with an int stride");
    const long long step = context.getStepCount();
    const int stride = sizeof(ParticlePair)/sizeof(int);
    const bool anyPairs = pairs.size() > 0;
    sweepOrder.build(extractPositions(context), extractBoxVectors(context),
                     context.getSystem().usesPeriodicBoundaryConditions(), cutoff, pairs.size(),
                     anyPairs ? &pairs.begin()->i : nullptr, anyPairs ? &pairs.begin()->j : nullptr, stride);
    const std::vector<int>& order = sweepOrder.getOrder();
    const PairSweepParameters parameters(integrator, terms, cutoff, seed, step);
    if (!terms.internalEnergies) {
        sweepIsothermal(pairs.begin(), order.data(), order.size(), parameters, inverseMasses.data(), velocities.data());
        return;
    }
    // If an internal energy would become <= 0, the velocities and internal energies go back to what execute() saved
    // before the step (positions have not moved yet), and the error names the particle and the step.
    const int failed = sweepIsoenergetic(pairs.begin(), order.data(), order.size(), parameters, inverseMasses.data(),
                                         velocities.data(), internalEnergies.data());
    if (failed < 0)
        return;
    const int particle = failedParticle(pairs.begin(), order.data(), failed, internalEnergies.data());
    const double value = internalEnergies[particle];
    velocities = savedVelocities;
    internalEnergies = savedInternalEnergies;
    throw OpenMMException(GenDPDEIntegratorUtilities::nonPositiveEnergyMessage(particle, value, step));
}

void ReferenceIntegrateGenDPDEStepKernel::execute(ContextImpl& context, const GenDPDEIntegrator& integrator,
                                                  const GenDPDEStepTerms& terms, GenDPDEForceImpl* pairListSource) {
    // docs/theory.md section 6: half kick, pair sweep at fixed positions, half kick, drift; without pair terms,
    // velocity Verlet (leapfrog form: one full kick).
    checkStepIsStable(context, integrator.getStepSize(), terms.maxDisplacement);
    std::vector<Vec3>& velocities = extractVelocities(context);
    const std::vector<Vec3>& forces = extractForces(context);
    const double dt = integrator.getStepSize();
    if (!terms.pairSweep)
        kick(velocities, forces, dt);
    else {
        if (terms.internalEnergies) {
            savedVelocities = velocities;
            savedInternalEnergies = internalEnergies;
        }
        kick(velocities, forces, 0.5*dt);
        sweep(context, currentPairs(context, pairListSource), velocities, integrator, terms);
        kick(velocities, forces, 0.5*dt);
    }
    std::vector<Vec3>& positions = extractPositions(context);
    for (size_t i = 0; i < positions.size(); i++)
        if (inverseMasses[i] != 0.0)
            positions[i] += velocities[i]*dt;
    ReferencePlatform::PlatformData& data = platformData(context);
    data.time += dt;
    data.stepCount++;
}

double ReferenceIntegrateGenDPDEStepKernel::computeKineticEnergy(ContextImpl& context, const GenDPDEIntegrator& integrator) {
    // Velocities are half a step behind the positions: K at the current time uses v + (dt/2) F/m.
    const std::vector<Vec3>& velocities = extractVelocities(context);
    const std::vector<Vec3>& forces = extractForces(context);
    const double halfStep = 0.5*integrator.getStepSize();
    double energy = 0.0;
    for (size_t i = 0; i < velocities.size(); i++)
        if (inverseMasses[i] != 0.0) {
            Vec3 v = velocities[i] + forces[i]*(halfStep*inverseMasses[i]);
            energy += 0.5*v.dot(v)/inverseMasses[i];
        }
    return energy;
}
