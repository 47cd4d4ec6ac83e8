/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
#include "GenDPDEIntegrator.h"
#include "GenDPDEForce.h"
#include "GenDPDEKernels.h"
#include "internal/BoxGeometry.h"
#include "gendpde/CounterRandom.h"
#include "internal/GenDPDEForceImpl.h"
#include "internal/GenDPDEIntegratorUtilities.h"
#include "internal/GenDPDEPhysics.h"
#include "internal/GenDPDETypes.h"
#include "internal/ParameterChecks.h"
#include "openmm/OpenMMException.h"
#include "openmm/internal/ContextImpl.h"
#include <algorithm>
#include <cstdint>
#include <random>
#include "internal/MessageText.h"

using namespace GenDPDEPlugin;
using namespace OpenMM;
using namespace ParameterChecks;

namespace {
const char* integratorName = "GenDPDEIntegrator";

/** Refuse a list of per-particle values other than one per particle of a System of numParticles. */
void requireOnePerParticle(const std::vector<double>& values, const std::string& count, int numParticles) {
    if ((int) values.size() != numParticles)
        reject(integratorName, count, values.size(), "",
               "the number of particles in the System, " + std::to_string(numParticles));
}

/**
 * Refuse a list of per-particle values (setParticleTemperatures, setInternalEnergies) unless it is not empty, each
 * value (named "<value> of particle i") is in range and, with a Context (numParticles >= 0), there is one per
 * particle: before anything changes.
 */
void requirePerParticleValues(const std::vector<double>& values, const std::string& count, const std::string& value,
                              const Range& range, int numParticles) {
    if (values.empty())
        reject(integratorName, count, 0, "", "one per particle (at least one)");
    for (size_t i = 0; i < values.size(); i++)
        requireInRange(integratorName, value + " of particle " + std::to_string(i), values[i], range);
    if (numParticles >= 0)
        requireOnePerParticle(values, count, numParticles);
}
} // namespace

GenDPDEIntegrator::GenDPDEIntegrator(double stepSize, double friction, double heatConduction, double heatCapacity) :
        cutoff(0.0), temperature(0.0), randomSeed(0), mode(Isoenergetic) {
    // Validate everything before storing anything.
    requireInRange(integratorName, "step size", stepSize, Ranges::stepSize, true);
    requireInRange(integratorName, "friction", friction, Ranges::friction);
    requireInRange(integratorName, "heat conduction", heatConduction, Ranges::heatConduction);
    requireInRange(integratorName, "heat capacity", heatCapacity, Ranges::heatCapacity);
    Integrator::setStepSize(stepSize);
    setConstraintTolerance(1e-5);   // OpenMM's default; the base class leaves it uninitialised
    this->friction = friction;
    this->heatConduction = heatConduction;
    this->heatCapacity = heatCapacity;
}

void GenDPDEIntegrator::setStepSize(double size) {
    requireInRange(integratorName, "step size", size, Ranges::stepSize, true);
    Integrator::setStepSize(size);
}

double GenDPDEIntegrator::getFriction() const {
    return friction;
}

void GenDPDEIntegrator::setFriction(double friction) {
    requireInRange(integratorName, "friction", friction, Ranges::friction);
    this->friction = friction;
}

double GenDPDEIntegrator::getHeatConduction() const {
    return heatConduction;
}

void GenDPDEIntegrator::setHeatConduction(double heatConduction) {
    requireInRange(integratorName, "heat conduction", heatConduction, Ranges::heatConduction);
    this->heatConduction = heatConduction;
}

double GenDPDEIntegrator::getHeatCapacity() const {
    return heatCapacity;
}

void GenDPDEIntegrator::setHeatCapacity(double heatCapacity) {
    requireInRange(integratorName, "heat capacity", heatCapacity, Ranges::heatCapacity);
    this->heatCapacity = heatCapacity;
    applyThermalRule(ThermalEvent::ParametersChanged);
}

double GenDPDEIntegrator::getCutoffDistance() const {
    return cutoff;
}

void GenDPDEIntegrator::setCutoffDistance(double distance) {
    if (distance != 0.0)
        requireInRange(integratorName, "cutoff distance (0, or a range)", distance, Ranges::cutoff);
    cutoff = distance;
}

int GenDPDEIntegrator::getRandomNumberSeed() const {
    return randomSeed;
}

void GenDPDEIntegrator::setRandomNumberSeed(int seed) {
    randomSeed = seed;
}

GenDPDEIntegrator::Mode GenDPDEIntegrator::getMode() const {
    return mode;
}

void GenDPDEIntegrator::setMode(Mode mode) {
    if (mode != Isoenergetic && mode != Isothermal && mode != Conservative)
        reject(integratorName, "mode", (int) mode, "", "Isoenergetic (0), Isothermal (1) or Conservative (2)");
    this->mode = mode;
    applyThermalRule(ThermalEvent::ModeChanged);
}

double GenDPDEIntegrator::getTemperature() const {
    return temperature;
}

void GenDPDEIntegrator::setTemperature(double temperature) {
    requireInRange(integratorName, "temperature", temperature, Ranges::temperature);
    this->temperature = temperature;
    applyThermalRule(ThermalEvent::ParametersChanged);   // (the Isothermal mode's forces use it)
}

IntegrateGenDPDEStepKernel& GenDPDEIntegrator::boundKernel() const {
    return const_cast<Kernel&>(kernel).getAs<IntegrateGenDPDEStepKernel>();
}

void GenDPDEIntegrator::setParticleTemperatures(const std::vector<double>& temperatures) {
    requirePerParticleValues(temperatures, "number of particle temperatures", "temperature", Ranges::temperature,
                             context == nullptr ? -1 : context->getSystem().getNumParticles());
    if (context == nullptr) {
        initialTemperatures = temperatures;
        initialEnergies.clear();
        return;
    }
    const std::vector<double> capacity = particleHeatCapacities(context->getSystem(), contextParticleTypes);
    std::vector<double> energies(temperatures.size());
    for (size_t i = 0; i < energies.size(); i++)
        energies[i] = capacity[i] * temperatures[i];
    boundKernel().setInternalEnergies(energies);
    applyThermalRule(ThermalEvent::EnergiesSet);
}

void GenDPDEIntegrator::setInternalEnergies(const std::vector<double>& energies) {
    requirePerParticleValues(energies, "number of internal energies", "internal energy", Ranges::internalEnergy,
                             context == nullptr ? -1 : context->getSystem().getNumParticles());
    if (context == nullptr) {
        initialEnergies = energies;
        initialTemperatures.clear();
        return;
    }
    boundKernel().setInternalEnergies(energies);
    applyThermalRule(ThermalEvent::EnergiesSet);
}

void GenDPDEIntegrator::setInternalEnergiesToTemperature(double temperature, int randomSeed) {
    requireInRange(integratorName, "temperature", temperature, Ranges::temperature);
    if (context == nullptr)
        throw OpenMMException("GenDPDEIntegrator: setInternalEnergiesToTemperature() needs a Context");
    // eps_i ~ Gamma(C_i/k_B + 1, k_B T), each a pure function of (randomSeed, i): the same on every machine.
    const std::vector<double> capacity = particleHeatCapacities(context->getSystem(), contextParticleTypes);
    const double scale = Physics::Boltzmann * temperature;
    std::vector<double> energies(capacity.size());
    for (size_t i = 0; i < energies.size(); i++) {
        CounterRandom::ParticleStream random((std::uint32_t) randomSeed, (std::uint32_t) i);
        energies[i] = scale * random.gamma(capacity[i] / Physics::Boltzmann + 1.0);
    }
    boundKernel().setInternalEnergies(energies);
    applyThermalRule(ThermalEvent::EnergiesSet);
}

std::vector<double> GenDPDEIntegrator::configuredHeatCapacities(int numParticles) const {
    // Types refer to particles not known yet: every particle with a type set is looked up.
    const ParticleTypeIndex types(
            particleTypes, std::max<int>(numParticles, particleTypes.empty() ? 0 : particleTypes.rbegin()->first + 1),
            integratorName);
    return GenDPDEPlugin::particleHeatCapacities(typePairTable(*this, types), types);
}

std::vector<double> GenDPDEIntegrator::getInternalEnergies() const {
    if (context != nullptr)
        return boundKernel().getInternalEnergies();   // (C_V theta_i at the current positions: applyThermalRule)
    if (!initialEnergies.empty())
        return initialEnergies;
    // Before a Context: the configured temperatures times C_V.
    std::vector<double> energies = getParticleTemperatures();
    const std::vector<double> capacity = configuredHeatCapacities(energies.size());
    for (size_t i = 0; i < energies.size(); i++)
        energies[i] *= capacity[i];
    return energies;
}

std::vector<double> GenDPDEIntegrator::getParticleTemperatures() const {
    if (context == nullptr) {
        if (!initialTemperatures.empty())
            return initialTemperatures;
        if (!initialEnergies.empty()) {
            std::vector<double> temperatures = initialEnergies;
            const std::vector<double> capacity = configuredHeatCapacities(temperatures.size());
            for (size_t i = 0; i < temperatures.size(); i++)
                temperatures[i] /= capacity[i];
            return temperatures;
        }
        MessageText message;
        message.precision(12);
        message << "GenDPDEIntegrator: the particle temperatures are not known one by one before a Context exists "
                << "(the number of particles is not known yet): ";
        if (temperature > 0.0)
            message << "every particle will start at the bath temperature, " << temperature << " K";
        else
            message << "none are set; call setParticleTemperatures() or setInternalEnergies(), or setTemperature() "
                    << "to start every particle at the bath temperature";
        throw OpenMMException(message.str());
    }
    std::vector<double> temperatures = boundKernel().getInternalEnergies();
    const std::vector<double> capacity = particleHeatCapacities(context->getSystem(), contextParticleTypes);
    for (size_t i = 0; i < temperatures.size(); i++)
        temperatures[i] /= capacity[i];
    return temperatures;
}

int GenDPDEIntegrator::getSeedInUse() const {
    if (context == nullptr)
        throw OpenMMException("GenDPDEIntegrator: the seed in use is only defined once a Context has been created");
    return kernel.getAs<const IntegrateGenDPDEStepKernel>().getSeed();
}

void GenDPDEIntegrator::checkSystem(const System& system) const {
    if (system.getNumConstraints() > 0)
        throw OpenMMException("GenDPDEIntegrator: constraints are not supported; the System has "
                              + std::to_string(system.getNumConstraints()));
    for (int i = 0; i < system.getNumParticles(); i++) {
        if (system.isVirtualSite(i))
            throw OpenMMException("GenDPDEIntegrator: virtual sites are not supported; particle " + std::to_string(i)
                                  + " is one (the pair forces of a massless site cannot be distributed to its "
                                    "parents without breaking the conservation of momentum and energy)");
        requireInRange(integratorName, "mass of particle " + std::to_string(i), system.getParticleMass(i),
                       Ranges::mass);
    }
}

std::vector<double> GenDPDEIntegrator::initialInternalEnergies(const System& system,
                                                               const std::map<int, int>& types) const {
    // docs/integrator.md, "Temperatures and internal energies": the internal energies or temperatures set before the
    // Context, else the bath temperature for every particle, else none (all zero: an Isoenergetic step then asks for
    // them).
    const int numParticles = system.getNumParticles();
    if (!initialEnergies.empty()) {
        requireOnePerParticle(initialEnergies, "number of internal energies", numParticles);
        return initialEnergies;
    }
    if (!initialTemperatures.empty())
        requireOnePerParticle(initialTemperatures, "number of particle temperatures", numParticles);
    const std::vector<double> capacity = particleHeatCapacities(system, types);
    std::vector<double> energies(numParticles);
    for (int i = 0; i < numParticles; i++)
        energies[i] = capacity[i] * (initialTemperatures.empty() ? temperature : initialTemperatures[i]);
    return energies;
}

void GenDPDEIntegrator::initialize(ContextImpl& contextRef) {
    if (owner != nullptr && &contextRef.getOwner() != owner)
        throw OpenMMException("This Integrator is already bound to a context");
    const System& system = contextRef.getSystem();
    checkSystem(system);
    const double range = GenDPDEIntegratorUtilities::pairRange(system, *this);
    if (range > 0.0 && system.usesPeriodicBoundaryConditions()) {
        Vec3 box[3];
        system.getDefaultPeriodicBoxVectors(box[0], box[1], box[2]);
        BoxGeometry::checkCutoffAgainstBox(integratorName, range, box);
    }
    // The types (the integrator's or the GenDPDEForce's), and every type named by an entry, are checked here, before
    // anything is bound.
    const std::map<int, int> types = GenDPDEIntegratorUtilities::particleTypes(system, *this);
    const ParticleTypeIndex typeIndex(types, system.getNumParticles(), integratorName);
    typePairTable(*this, typeIndex);
    const int thermalForceIndex = GenDPDEIntegratorUtilities::checkThermalForces(system, *this);
    const std::vector<double> energies = initialInternalEnergies(system, types);
    int seed = randomSeed;
    if (seed == 0) {
        std::random_device device;
        while (seed == 0)
            seed = (int) device();
    }
    kernel = contextRef.getPlatform().createKernel(IntegrateGenDPDEStepKernel::Name(), contextRef);
    kernel.getAs<IntegrateGenDPDEStepKernel>().initialize(contextRef, *this, range, seed, energies, types);
    pairRange = range;
    boundCutoff = cutoff;
    contextParticleTypes = types;
    typesChangedWhileBound = false;
    contextTypes = typeIndex.getTypes();
    // (the Forces' Impls are made and initialized before the integrator, in the order of the System's Forces)
    thermalForce = thermalForceIndex >= 0
            ? dynamic_cast<const GenDPDEForceImpl*>(contextRef.getForceImpls()[thermalForceIndex])
            : nullptr;
    entropyState = EntropyState::Unknown;
    positionsSet = false;
    stoppedBy.clear(); // a new Context state (reinitialize() without preserving the state)
    refusedPositions.clear();
    collectNonPeriodicBonds(contextRef);
    energyMark = EnergyMark();
    lawUpdatesSeen = 0;
    forcesCurrent = false;
    context = &contextRef;
    owner = &contextRef.getOwner();
}

void GenDPDEIntegrator::cleanup() {
    kernel = Kernel(); // the internal energies belong to the Context; what the user set is kept
}

std::vector<std::string> GenDPDEIntegrator::getKernelNames() {
    return {IntegrateGenDPDEStepKernel::Name()};
}

void GenDPDEIntegrator::requireTemperatures() const {
    if (mode == Isoenergetic && !boundKernel().hasInternalEnergies()) // all zero: never set (see the header)
        throw OpenMMException("GenDPDEIntegrator: the particle temperatures are not set; call setTemperature() "
                              "before creating the Context, or setParticleTemperatures(), setInternalEnergies() or "
                              "setInternalEnergiesToTemperature(), before stepping in Isoenergetic mode");
    if (mode == Isothermal && !(temperature > 0.0))
        throw OpenMMException("GenDPDEIntegrator: the Isothermal mode needs a temperature > 0; call setTemperature()");
}

void GenDPDEIntegrator::step(int steps) {
    if (context == nullptr)
        throw OpenMMException("GenDPDEIntegrator: this integrator is not bound to a Context");
    requireRunNotStopped("step");
    if (!refusedPositions.empty())
        throw OpenMMException("GenDPDEIntegrator: cannot step from the positions set: " + refusedPositions);
    requireTemperatures();
    requireBoundTypes();
    if (cutoff != boundCutoff) {
        MessageText message;
        message.precision(12);
        message << "GenDPDEIntegrator: the cutoff distance was changed to " << cutoff << " nm after the Context was "
                << "created (it runs with " << boundCutoff << (boundCutoff == 0.0 ? ", the GenDPDEForce's" : " nm")
                << "); the cutoff is read when the Context is created: call Context.reinitialize(preserveState=True) "
                << "to apply it, or set it back";
        throw OpenMMException(message.str());
    }
    const GenDPDEStepTerms terms = GenDPDEIntegratorUtilities::stepTerms(*this, pairRange);
    if (terms.pairSweep && pairRange == 0.0)
        throw OpenMMException("GenDPDEIntegrator: no cutoff distance for the pair terms: the System has no "
                              "GenDPDEForce; call setCutoffDistance()");
    // The forces of the integration groups are evaluated right before each step: a GenDPDEForce among them has
    // the pairs of that step.
    GenDPDEPairSource* pairSource =
            terms.pairSweep ? GenDPDEIntegratorUtilities::findPairSource(*context, *this, pairRange) : nullptr;
    // The energy guard (GenDPDEIntegratorEnergyGuard.cpp) looks at the conserved energy every energyGuardSteps steps
    // after its mark, however the steps are split into calls.
    const bool guarded = mode != Isothermal;
    if (guarded)
        startEnergyGuard();
    for (int done = 0; done < steps;) {
        const int run = guarded ? energyGuardRun(steps - done) : steps - done;
        runSteps(run, terms, pairSource);
        done += run;
        if (guarded)
            checkEnergyDrift();
    }
}

void GenDPDEIntegrator::runSteps(int steps, const GenDPDEStepTerms& terms, GenDPDEPairSource* pairSource) {
    IntegrateGenDPDEStepKernel& stepKernel = boundKernel();
    stepKernel.beginSteps(*context, *this, terms, pairSource);
    // With a law that depends on temperature, every step starts from the thermal state of its positions, fixed before
    // a Force (a barostat) may move them, so that a move keeps exactly what applyThermalRule says; that evaluation
    // serves the step unless the Force moved the particles or evaluated them elsewhere.
    const bool keepsThermalState = thermalForce != nullptr && mode != Isothermal;
    try {
        try {
            for (int i = 0; i < steps; i++) {
                if (keepsThermalState && !forcesAreCurrent()) {
                    evaluateStepForces(entropyState == EntropyState::Earlier); // (the drift of the step before)
                    rememberForces();
                }
                if (context->updateContextState()) // a Force moved the particles (a barostat) or its parameters
                    applyThermalRule(ThermalEvent::PositionsMovedByForce);
                if (!forcesAreCurrent())
                    evaluateStepForces(entropyState == EntropyState::Earlier);
                forcesCurrent = false;
                stepKernel.execute(*context, *this, terms, pairSource);
                if (entropyState == EntropyState::Current)
                    entropyState = EntropyState::Earlier; // the drift: the entropies belong to the last positions
            }
        } catch (...) {
            stepKernel.finishSteps(*context, *this); // a failure the device found earlier is the one to report
            throw;
        }
        stepKernel.finishSteps(*context, *this);
        if (steps > 0 && keepsThermalState) {
            // The thermal state at the positions the steps reached (outside step(), eps_i is C_V theta_i at the
            // current positions: applyThermalRule); its forces serve the next step.
            evaluateStepForces(true);
            rememberForces();
        }
    } catch (const OpenMMException& error) {
        std::string failure = error.what();
        try {
            requireFinitePositions(); // (OpenMM's own check may have seen it first, naming neither particle nor step)
        } catch (const OpenMMException& nonFinite) {
            failure = nonFinite.what();
        }
        throw OpenMMException(stopRun(failure));
    }
}

std::string GenDPDEIntegrator::stopRun(const std::string& failure) {
    stoppedBy = failure;
    return failure + GenDPDEIntegratorUtilities::stoppedRunAdvice;
}

void GenDPDEIntegrator::requireRunNotStopped(const std::string& what) const {
    if (!stoppedBy.empty())
        throw OpenMMException("GenDPDEIntegrator: cannot " + what + ": the run stopped (" + stoppedBy + ")"
                              + GenDPDEIntegratorUtilities::stoppedRunAdvice);
}

double GenDPDEIntegrator::computeKineticEnergy() {
    return boundKernel().computeKineticEnergy(*context, *this);
}

double GenDPDEIntegrator::getConservedEnergy() {
    if (context == nullptr)
        throw OpenMMException("GenDPDEIntegrator: this integrator is not bound to a Context");
    const EnergyParts parts = energyParts();
    return parts.kinetic + parts.potential + parts.internal;
}

GenDPDEIntegrator::EnergyParts GenDPDEIntegrator::energyParts() {
    const bool forcesWereCurrent = forcesAreCurrent();
    EnergyParts parts;
    parts.potential = context->calcForcesAndEnergy(true, true, getIntegrationForceGroups());
    if (forcesWereCurrent)
        rememberForces(); // the same forces again: the next step still needs no evaluation
    parts.kinetic = computeKineticEnergy();
    for (double e : boundKernel().getInternalEnergies())
        parts.internal += e;
    return parts;
}

void GenDPDEIntegrator::checkInternalEnergies(const std::vector<double>& energies, const std::string& source) const {
    // The internal-energy state is either set (every eps_i finite, within Ranges::internalEnergy) or not set yet
    // (every eps_i zero); anything else is corrupt.
    const int numParticles = context->getSystem().getNumParticles();
    if ((int) energies.size() != numParticles)
        throw OpenMMException("GenDPDEIntegrator: " + source + " holds " + std::to_string(energies.size())
                              + " internal energies, the System has " + std::to_string(numParticles) + " particles");
    const bool unset = !energies.empty() && energies[0] == 0.0;
    for (int i = 0; i < numParticles; i++)
        if (unset ? energies[i] != 0.0
                  : !(energies[i] >= Ranges::internalEnergy.minimum && energies[i] <= Ranges::internalEnergy.maximum)) {
            MessageText message;
            message.precision(17);
            message << "GenDPDEIntegrator: " << source << " is corrupt: the internal energy of particle " << i << " is "
                    << energies[i] << " kJ/mol; each must be finite and in [" << Ranges::internalEnergy.minimum << ", "
                    << Ranges::internalEnergy.maximum << "] kJ/mol (or all zero, not set)";
            throw OpenMMException(message.str());
        }
}
