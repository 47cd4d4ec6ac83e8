#include "ReferenceGenDPDEForceKernel.h"
#include "ReferenceKernelAccess.h"
#include "internal/BoxGeometry.h"
#include "internal/FixedOrderSum.h"
#include "internal/GenDPDEForceErrors.h"
#include "internal/GenDPDEPhysics.h"
#include "openmm/OpenMMException.h"

using namespace GenDPDEPlugin;
using namespace OpenMM;

void ReferenceCalcGenDPDEForceKernel::initialize(const System& system, const GenDPDEForce& force) {
    cutoff = force.getCutoffDistance();
    periodic = force.usesPeriodicBoundaryConditions();
    neighborList.reset(new NeighborList(cutoff, NeighborList::defaultSkinFraction*cutoff, periodic));
    int numParticles = system.getNumParticles();
    primitiveDensity.resize(numParticles);
    volume.resize(numParticles);
    pressure.resize(numParticles);
    forceCoefficient.resize(numParticles);
    particleVirial.resize(numParticles);
    types.reset(new ParticleTypeIndex(force.getParticleTypes(), numParticles, "GenDPDEForce"));
    readParameters(force);
}

void ReferenceCalcGenDPDEForceKernel::copyParametersToContext(ContextImpl& context, const GenDPDEForce& force) {
    readParameters(force);
}

void ReferenceCalcGenDPDEForceKernel::readParameters(const GenDPDEForce& force) {
    GenDPDEForceErrors::checkUnchangeableParameters(force, cutoff, periodic, *types);
    std::vector<TaitParameters> tait = taitParametersByType(force, *types);   // checked before anything changes
    estimator = force.getDensityEstimator();
    cutoffScaling = force.getCutoffScaling();
    taitByType = tait;
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

ReferenceCalcGenDPDEForceKernel::ParticleStatus ReferenceCalcGenDPDEForceKernel::evaluateParticle(double n0,
        int type, const ParticleModel& model, ParticleState& state) const {
    // docs/theory.md sections 3-4: the volume, the Tait pressure and free energy, and pi_i dV_i/dn0_i.
    if (estimator == GenDPDEForce::VA && n0 == 0.0)
        return NoNeighbor;
    const Physics::ParticleVolume v = (estimator == GenDPDEForce::VA ? Physics::volumeVA(n0) : model.volumeVB(n0));
    model.tait[type].evaluate(1.0/v.volume, state.pressure, state.freeEnergy);
    if (!(std::isfinite(state.freeEnergy) && std::isfinite(state.pressure)))
        return Overflow;
    state.volume = v.volume;
    // An isolated particle (VB, n0 = 0) is in no pair; its diverging dV/dn0 must not reach the arrays.
    state.forceCoefficient = (n0 > 0.0 ? state.pressure*v.derivative : 0.0);
    return Valid;
}

void ReferenceCalcGenDPDEForceKernel::throwParticleError(ParticleStatus status, int i, ContextImpl& context) const {
    if (status == NoNeighbor)
        throw OpenMMException(GenDPDEForceErrors::noNeighbor(i, cutoff, context.getStepCount()));
    throw OpenMMException(GenDPDEForceErrors::equationOfStateOverflow(i, primitiveDensity[i], estimator,
            cutoff/cutoffScaling, taitByType[types->getParticleTypeIndices()[i]].referenceDensity,
            context.getStepCount()));
}

double ReferenceCalcGenDPDEForceKernel::computeDensitiesAndEnergy(ContextImpl& context) {
    const std::vector<Vec3>& positions = extractPositions(context);
    const int numParticles = positions.size();
    checkConfiguration(context, firstNonFinitePosition(positions, 0, numParticles));
    const PairView pairs = neighborList->update(positions, extractBoxVectors(context));

    // docs/theory.md sections 2-3: primitive densities n0_i = sum_j w(r_ij).
    const Physics::DensityWeight weight(cutoff);
    std::fill(primitiveDensity.begin(), primitiveDensity.end(), 0.0);
    for (const ParticlePair& pair : pairs) {
        double w = weight.value(pair.r);
        primitiveDensity[pair.i] += w;
        primitiveDensity[pair.j] += w;
    }

    // docs/theory.md sections 2-4: volumes, Tait pressures and free energies; U = sum_i f(n_i).
    const ParticleModel model(*this);
    const std::vector<int>& type = types->getParticleTypeIndices();
    FixedOrderSum::Accumulator energy;   // summed as the CPU platform sums it, for the same bits
    for (int i = 0; i < numParticles; i++) {
        ParticleState state;
        const ParticleStatus status = evaluateParticle(primitiveDensity[i], type[i], model, state);
        if (status != Valid)
            throwParticleError(status, i, context);
        storeParticle(i, state);
        energy.add(state.freeEnergy);
    }
    return energy.sum();
}

double ReferenceCalcGenDPDEForceKernel::computePairForces(ContextImpl& context, std::vector<Vec3>* forces) {
    // docs/theory.md section 4: F_i = sum_j [pi_i V'_i + pi_j V'_j] w'(r_ij) e_ij; W = sum_{i<j} r_ij . F_ij, summed
    // per first particle, then over particles in the fixed order (as the CPU platform does).
    const Physics::DensityWeight weight(cutoff);
    std::fill(particleVirial.begin(), particleVirial.end(), 0.0);
    for (const ParticlePair& pair : neighborList->getPairs()) {
        if (pair.r == 0.0)
            continue;   // coincident particles: counted in the density, no direction, no force
        double scale = (forceCoefficient[pair.i] + forceCoefficient[pair.j])*weight.derivative(pair.r)/pair.r;
        if (forces != nullptr) {
            Vec3 force = pair.delta*scale;
            (*forces)[pair.i] += force;
            (*forces)[pair.j] -= force;
        }
        particleVirial[pair.i] += scale*pair.r*pair.r;
    }
    FixedOrderSum::Accumulator virial;
    for (double w : particleVirial)
        virial.add(w);
    return virial.sum();
}

double ReferenceCalcGenDPDEForceKernel::execute(ContextImpl& context, bool includeForces, bool includeEnergy) {
    double energy = computeDensitiesAndEnergy(context);
    if (includeForces)
        computePairForces(context, &extractForces(context));
    return energy;
}

const GenDPDEObservables& ReferenceCalcGenDPDEForceKernel::getObservables(ContextImpl& context) {
    const std::vector<Vec3>& positions = extractPositions(context);
    Vec3* box = extractBoxVectors(context);
    if (observablesValid && positions == observedPositions && box[0] == observedBox[0] && box[1] == observedBox[1]
            && box[2] == observedBox[2])
        return observables;
    computeDensitiesAndEnergy(context);
    observables.virial = computePairForces(context, nullptr);
    observables.primitiveDensities = primitiveDensity;
    observables.volumes = volume;
    observables.pressures = pressure;
    observables.densities.resize(volume.size());
    for (size_t i = 0; i < volume.size(); i++)
        observables.densities[i] = 1.0/volume[i];
    observedPositions = positions;
    for (int k = 0; k < 3; k++)
        observedBox[k] = box[k];
    observablesValid = true;
    return observables;
}
