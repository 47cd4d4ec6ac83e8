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
    moment.resize(numParticles);
    momentForce.resize(numParticles);
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
        double G, int type, const ParticleModel& model, ParticleState& state) const {
    // docs/theory.md sections 3-4 (VC: docs/interfaces.md): the volume, the Tait pressure and free energy, and
    // pi_i dV_i/dn0_i (and pi_i dV_i/dG_i).
    if (estimator == GenDPDEForce::VA && n0 == 0.0)
        return NoNeighbor;
    double volume, derivative, momentDerivative = 0.0;
    if (estimator == GenDPDEForce::VC) {
        const Physics::ParticleVolumeVC v = model.volumeVC(n0, G);
        volume = v.volume;
        derivative = v.derivative;
        momentDerivative = v.momentDerivative;
    }
    else {
        const Physics::ParticleVolume v = (estimator == GenDPDEForce::VA ? Physics::volumeVA(n0) : model.volumeVB(n0));
        volume = v.volume;
        derivative = v.derivative;
    }
    model.tait[type].evaluate(1.0/volume, state.pressure, state.freeEnergy);
    if (!(std::isfinite(state.freeEnergy) && std::isfinite(state.pressure)))
        return Overflow;
    state.volume = volume;
    // An isolated particle (VB, VC: n0 = 0) is in no pair; its diverging dV/dn0 must not reach the arrays.
    state.forceCoefficient = (n0 > 0.0 ? state.pressure*derivative : 0.0);
    state.momentCoefficient = state.pressure*momentDerivative;
    return Valid;
}

double ReferenceCalcGenDPDEForceKernel::particleDensity(int i) const {
    const ParticleModel model(*this);
    const double n0 = primitiveDensity[i];
    if (estimator == GenDPDEForce::VC)
        return 1.0/model.volumeVC(n0, moment[i].dot(moment[i])).volume;
    return 1.0/(estimator == GenDPDEForce::VA ? Physics::volumeVA(n0) : model.volumeVB(n0)).volume;
}

void ReferenceCalcGenDPDEForceKernel::throwParticleError(ParticleStatus status, int i, ContextImpl& context) const {
    if (status == NoNeighbor)
        throw OpenMMException(GenDPDEForceErrors::noNeighbor(i, cutoff, context.getStepCount()));
    throw OpenMMException(GenDPDEForceErrors::equationOfStateOverflow(i, particleDensity(i),
            taitByType[types->getParticleTypeIndices()[i]].referenceDensity, context.getStepCount()));
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
    // VC (docs/interfaces.md): the first moments g_i = sum_j phi(r_ij) e_ij.
    if (usesMoments()) {
        const Physics::MomentWeight phi(cutoff);
        std::fill(moment.begin(), moment.end(), Vec3());
        for (const ParticlePair& pair : pairs)
            if (pair.r > 0.0 && pair.r < cutoff) {
                const Vec3 term = pair.delta*phi.valueOverDistanceInside(pair.r);
                moment[pair.i] += term;
                moment[pair.j] -= term;
            }
    }

    // docs/theory.md sections 2-4: volumes, Tait pressures and free energies; U = sum_i f(n_i).
    const ParticleModel model(*this);
    const std::vector<int>& type = types->getParticleTypeIndices();
    FixedOrderSum::Accumulator energy;   // summed as the CPU platform sums it, for the same bits
    for (int i = 0; i < numParticles; i++) {
        ParticleState state;
        const ParticleStatus status = evaluateParticle(primitiveDensity[i], moment[i].dot(moment[i]), type[i], model,
                                                       state);
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
    const Physics::MomentWeight phi(cutoff);
    const bool moments = usesMoments();
    std::fill(particleVirial.begin(), particleVirial.end(), 0.0);
    for (const ParticlePair& pair : neighborList->getPairs()) {
        if (pair.r == 0.0)
            continue;   // coincident particles: counted in the density, no direction, no force
        double scale = (forceCoefficient[pair.i] + forceCoefficient[pair.j])*weight.derivative(pair.r)/pair.r;
        Vec3 force = pair.delta*scale;
        double virial = scale*pair.r*pair.r;
        // (q vanishes for the particles below V-C's threshold, nearly all of a bulk liquid: their pairs add nothing.)
        if (moments && pair.r < cutoff && !(momentForce[pair.i] == Vec3() && momentForce[pair.j] == Vec3())) {
            // VC: H(d) (q_i - q_j), H = phi' e e^T + (phi/r)(I - e e^T) (docs/interfaces.md).
            const Vec3 e = pair.delta*(1.0/pair.r), dq = momentForce[pair.i] - momentForce[pair.j];
            const double along = e.dot(dq);
            force += e*(phi.derivativeInside(pair.r)*along) + (dq - e*along)*phi.valueOverDistanceInside(pair.r);
            virial += pair.r*phi.derivativeInside(pair.r)*along;
        }
        if (forces != nullptr) {
            (*forces)[pair.i] += force;
            (*forces)[pair.j] -= force;
        }
        particleVirial[pair.i] += virial;
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
