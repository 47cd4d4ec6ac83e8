#include "ReferenceGenDPDEIntegratorKernel.h"
#include "ReferenceGenDPDEForceKernel.h"
#include "ReferenceKernelAccess.h"
#include "internal/BoxGeometry.h"
#include "internal/CounterRandom.h"
#include "internal/GenDPDEForceImpl.h"
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

const std::vector<int>& ReferenceIntegrateGenDPDEStepKernel::sweepOrder(PairView pairs) {
    // The pairs come sorted by i, then j. Within each block of four consecutive particles, their lists of pairs
    // are interleaved (the first pair of each, then the second of each, ...): consecutive updates then rarely
    // share a particle and overlap in the processor instead of waiting on each other, the lists are still read
    // front to back, and the order is a pure function of the set of pairs.
    const int block = 4, numParticles = inverseMasses.size();
    firstPair.assign(numParticles + 1, 0);
    for (const ParticlePair& pair : pairs)
        firstPair[pair.i + 1]++;
    for (int i = 0; i < numParticles; i++)
        firstPair[i + 1] += firstPair[i];
    order.resize(pairs.size());
    size_t next = 0;
    for (int start = 0; start < numParticles; start += block) {
        const int end = std::min(numParticles, start + block);
        int longest = 0;
        for (int i = start; i < end; i++)
            longest = std::max(longest, firstPair[i + 1] - firstPair[i]);
        for (int rank = 0; rank < longest; rank++)
            for (int i = start; i < end; i++)
                if (firstPair[i] + rank < firstPair[i + 1])
                    order[next++] = firstPair[i] + rank;
    }
    return order;
}

bool ReferenceIntegrateGenDPDEStepKernel::sweepIsoenergetic(PairView pairs, std::vector<Vec3>& velocities,
        const GenDPDEIntegrator& integrator, const GenDPDEStepTerms& terms, long long step, int& failedParticle) {
    // docs/theory.md sections 5-7, pair by pair in sweepOrder() at fixed positions: dissipative and random momenta with
    // sigma^2 = 2 gamma k_B Theta_ij (and the Ito term of the friction, see Physics::pairTemperatures), mechanical
    // heating split equally, heat conduction, all with the particles' temperatures when the pair is reached.
    const double dt = integrator.getStepSize(), sqrtDt = std::sqrt(dt);
    const double friction = integrator.getFriction(), heatConduction = integrator.getHeatConduction();
    const double heatCapacity = integrator.getHeatCapacity();
    const double heatNoise = std::sqrt(2.0*Physics::Boltzmann*heatConduction);
    for (int k : sweepOrder(pairs)) {
        const ParticlePair& pair = pairs[k];
        const int i = pair.i, j = pair.j;
        if (pair.r == 0.0 || (inverseMasses[i] == 0.0 && inverseMasses[j] == 0.0))
            continue;
        const double omegaR = Physics::randomWeight(pair.r, cutoff);
        CounterRandom::PairStream random(seed, step, i, j);
        const Physics::PairTemperatures temperatures = Physics::pairTemperatures(internalEnergies[i],
                internalEnergies[j], heatCapacity, Physics::Boltzmann);
        if (terms.dissipation) {
            const double kineticChange = Physics::dissipativePairUpdate(pair.delta*(1.0/pair.r), omegaR,
                    friction*(1.0 + temperatures.frictionFactor), std::sqrt(2.0*friction*temperatures.pairThermalEnergy),
                    dt, sqrtDt, inverseMasses[i], inverseMasses[j], velocities[i], velocities[j], random.normal());
            internalEnergies[i] -= 0.5*kineticChange;
            internalEnergies[j] -= 0.5*kineticChange;
        }
        if (terms.conduction) {
            const double heat = Physics::conductiveHeat(omegaR, heatConduction, heatNoise,
                    temperatures.inverseTemperatureDifference, dt, sqrtDt, random.normal());
            internalEnergies[i] += heat;
            internalEnergies[j] -= heat;
        }
        if (!(internalEnergies[i] > 0.0) || !(internalEnergies[j] > 0.0)) {
            failedParticle = (internalEnergies[i] > 0.0 ? j : i);
            return false;
        }
    }
    return true;
}

void ReferenceIntegrateGenDPDEStepKernel::sweepIsothermal(PairView pairs, std::vector<Vec3>& velocities,
        const GenDPDEIntegrator& integrator, long long step) {
    // The classic DPD thermostat: sigma^2 = 2 gamma k_B T with the bath temperature; the heat goes to the bath.
    const double dt = integrator.getStepSize(), sqrtDt = std::sqrt(dt);
    const double friction = integrator.getFriction();
    const double noiseAmplitude = std::sqrt(2.0*friction*Physics::Boltzmann*integrator.getTemperature());
    for (int k : sweepOrder(pairs)) {
        const ParticlePair& pair = pairs[k];
        const int i = pair.i, j = pair.j;
        if (pair.r == 0.0 || (inverseMasses[i] == 0.0 && inverseMasses[j] == 0.0))
            continue;
        CounterRandom::PairStream random(seed, step, i, j);
        Physics::dissipativePairUpdate(pair.delta*(1.0/pair.r), Physics::randomWeight(pair.r, cutoff), friction,
                                       noiseAmplitude, dt,
                                       sqrtDt, inverseMasses[i], inverseMasses[j], velocities[i], velocities[j],
                                       random.normal());
    }
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
            std::ostringstream message;
            message << "GenDPDEIntegrator: the force on particle " << i << " is not finite (" << forces[i][0] << ", "
                    << forces[i][1] << ", " << forces[i][2] << ") at step " << context.getStepCount()
                    << "; the step was not applied";
            throw OpenMMException(message.str());
        }
        const Vec3 displacement = (velocities[i] + forces[i]*(stepSize*inverseMasses[i]))*stepSize;
        const double distance2 = displacement.dot(displacement);
        if (inverseMasses[i] != 0.0 && !(distance2 <= limit2)) {
            std::ostringstream message;
            message.precision(6);
            message << "GenDPDEIntegrator: particle " << i << " would move " << std::sqrt(distance2) << " nm in one "
                    << "step, more than the pair range " << maxDisplacement << " nm, at step " << context.getStepCount()
                    << ": the simulation has become unstable (reduce the step size); the step was not applied";
            throw OpenMMException(message.str());
        }
    }
}

void ReferenceIntegrateGenDPDEStepKernel::sweepIsoenergeticOrRollBack(PairView pairs, std::vector<Vec3>& velocities,
        const GenDPDEIntegrator& integrator, const GenDPDEStepTerms& terms, long long step) {
    // If an internal energy would become <= 0, the velocities and internal energies go back to what execute() saved
    // before the step (positions have not moved yet), and the error names the particle and the step.
    int failed = -1;
    if (sweepIsoenergetic(pairs, velocities, integrator, terms, step, failed))
        return;
    const double value = internalEnergies[failed];
    velocities = savedVelocities;
    internalEnergies = savedInternalEnergies;
    std::ostringstream message;
    message.precision(6);
    message << "GenDPDEIntegrator: the internal energy of particle " << failed << " would become " << value
            << " kJ/mol (<= 0) at step " << step << "; the step was not applied. Reduce the step size or "
            << "increase the heat capacity (the relative fluctuations of eps_i scale like sqrt(k_B/C_V))";
    throw OpenMMException(message.str());
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
        const long long step = context.getStepCount();
        if (terms.internalEnergies) {
            savedVelocities = velocities;
            savedInternalEnergies = internalEnergies;
        }
        kick(velocities, forces, 0.5*dt);
        PairView pairs = currentPairs(context, pairListSource);
        if (terms.internalEnergies)
            sweepIsoenergeticOrRollBack(pairs, velocities, integrator, terms, step);
        else
            sweepIsothermal(pairs, velocities, integrator, step);
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
