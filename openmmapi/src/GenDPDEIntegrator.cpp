#include "GenDPDEIntegrator.h"
#include "GenDPDEForce.h"
#include "GenDPDEKernels.h"
#include "internal/GenDPDEForceImpl.h"
#include "internal/GenDPDEIntegratorUtilities.h"
#include "internal/GenDPDEPhysics.h"
#include "internal/ParameterChecks.h"
#include "openmm/OpenMMException.h"
#include "openmm/internal/ContextImpl.h"
#include "openmm/serialization/SerializationNode.h"
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <random>
#include <sstream>

using namespace GenDPDEPlugin;
using namespace OpenMM;
using namespace ParameterChecks;

namespace {
const char* integratorName = "GenDPDEIntegrator";
const int checkpointVersion = 1;
}

GenDPDEIntegrator::GenDPDEIntegrator(double stepSize, double friction, double heatConduction, double heatCapacity) :
        cutoff(0.0), temperature(0.0), randomSeed(0), mode(Isoenergetic), temperaturesSet(false) {
    // Validate everything before storing anything.
    requirePositive(integratorName, "step size", stepSize, "ps");
    requireNonNegative(integratorName, "friction", friction, "amu/ps");
    requireNonNegative(integratorName, "heat conduction", heatConduction, "kJ K/(mol ps)");
    requirePositive(integratorName, "heat capacity", heatCapacity, "kJ/(mol K)");
    Integrator::setStepSize(stepSize);
    setConstraintTolerance(1e-5);   // OpenMM's default; the base class leaves it uninitialised
    this->friction = friction;
    this->heatConduction = heatConduction;
    this->heatCapacity = heatCapacity;
}

void GenDPDEIntegrator::setStepSize(double size) {
    requirePositive(integratorName, "step size", size, "ps");
    Integrator::setStepSize(size);
}

double GenDPDEIntegrator::getFriction() const {
    return friction;
}

void GenDPDEIntegrator::setFriction(double friction) {
    requireNonNegative(integratorName, "friction", friction, "amu/ps");
    this->friction = friction;
}

double GenDPDEIntegrator::getHeatConduction() const {
    return heatConduction;
}

void GenDPDEIntegrator::setHeatConduction(double heatConduction) {
    requireNonNegative(integratorName, "heat conduction", heatConduction, "kJ K/(mol ps)");
    this->heatConduction = heatConduction;
}

double GenDPDEIntegrator::getHeatCapacity() const {
    return heatCapacity;
}

void GenDPDEIntegrator::setHeatCapacity(double heatCapacity) {
    requirePositive(integratorName, "heat capacity", heatCapacity, "kJ/(mol K)");
    this->heatCapacity = heatCapacity;
}

double GenDPDEIntegrator::getCutoffDistance() const {
    return cutoff;
}

void GenDPDEIntegrator::setCutoffDistance(double distance) {
    requireNonNegative(integratorName, "cutoff distance", distance, "nm");
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
}

double GenDPDEIntegrator::getTemperature() const {
    return temperature;
}

void GenDPDEIntegrator::setTemperature(double temperature) {
    requirePositive(integratorName, "temperature", temperature, "K");
    this->temperature = temperature;
    temperaturesSet = true;
    initialTemperatures.clear();
    if (context != nullptr) {
        int numParticles = context->getSystem().getNumParticles();
        kernel.getAs<IntegrateGenDPDEStepKernel>().setInternalEnergies(std::vector<double>(numParticles, heatCapacity*temperature));
    }
}

void GenDPDEIntegrator::setParticleTemperatures(const std::vector<double>& temperatures) {
    for (size_t i = 0; i < temperatures.size(); i++)
        requirePositive(integratorName, "temperature of particle " + std::to_string(i), temperatures[i], "K");
    if (context != nullptr) {
        int numParticles = context->getSystem().getNumParticles();
        if ((int) temperatures.size() != numParticles)
            reject(integratorName, "number of particle temperatures", temperatures.size(), "",
                   "the number of particles in the System, " + std::to_string(numParticles));
        std::vector<double> energies(numParticles);
        for (int i = 0; i < numParticles; i++)
            energies[i] = heatCapacity*temperatures[i];
        kernel.getAs<IntegrateGenDPDEStepKernel>().setInternalEnergies(energies);
    }
    else
        initialTemperatures = temperatures;
    temperaturesSet = true;
}

void GenDPDEIntegrator::setInternalEnergiesToTemperature(double temperature, int randomSeed) {
    requirePositive(integratorName, "temperature", temperature, "K");
    if (context == nullptr)
        throw OpenMMException("GenDPDEIntegrator: setInternalEnergiesToTemperature() needs a Context");
    std::mt19937 generator(randomSeed);
    std::gamma_distribution<double> gamma(heatCapacity/Physics::Boltzmann + 1.0, Physics::Boltzmann*temperature);
    std::vector<double> energies(context->getSystem().getNumParticles());
    for (double& e : energies)
        e = gamma(generator);
    kernel.getAs<IntegrateGenDPDEStepKernel>().setInternalEnergies(energies);
    temperaturesSet = true;
}

std::vector<double> GenDPDEIntegrator::getInternalEnergies() const {
    if (context != nullptr)
        return kernel.getAs<const IntegrateGenDPDEStepKernel>().getInternalEnergies();
    std::vector<double> energies(initialTemperatures.size());
    for (size_t i = 0; i < energies.size(); i++)
        energies[i] = heatCapacity*initialTemperatures[i];
    return energies;
}

std::vector<double> GenDPDEIntegrator::getParticleTemperatures() const {
    if (context == nullptr)
        return initialTemperatures;
    std::vector<double> temperatures = getInternalEnergies();
    for (double& t : temperatures)
        t /= heatCapacity;
    return temperatures;
}

int GenDPDEIntegrator::getSeedInUse() const {
    if (context == nullptr)
        throw OpenMMException("GenDPDEIntegrator: the seed in use is only defined once a Context has been created");
    return kernel.getAs<const IntegrateGenDPDEStepKernel>().getSeed();
}

void GenDPDEIntegrator::initialize(ContextImpl& contextRef) {
    const System& system = contextRef.getSystem();
    if (system.getNumConstraints() > 0)
        throw OpenMMException("GenDPDEIntegrator: constraints are not supported; the System has "
                              + std::to_string(system.getNumConstraints()));
    const int numParticles = system.getNumParticles();

    const double range = GenDPDEIntegratorUtilities::pairRange(system, *this);
    if (range > 0.0 && system.usesPeriodicBoundaryConditions()) {
        Vec3 box[3];
        system.getDefaultPeriodicBoxVectors(box[0], box[1], box[2]);
        GenDPDEForceImpl::checkCutoffAgainstBox(range, box);
    }
    if (!initialTemperatures.empty() && (int) initialTemperatures.size() != numParticles)
        reject(integratorName, "number of particle temperatures", initialTemperatures.size(), "",
               "the number of particles in the System, " + std::to_string(numParticles));
    std::vector<double> energies(numParticles, heatCapacity*temperature);
    for (size_t i = 0; i < initialTemperatures.size(); i++)
        energies[i] = heatCapacity*initialTemperatures[i];
    int seed = randomSeed;
    if (seed == 0) {
        std::random_device device;
        while (seed == 0)
            seed = (int) device();
    }
    kernel = contextRef.getPlatform().createKernel(IntegrateGenDPDEStepKernel::Name(), contextRef);
    kernel.getAs<IntegrateGenDPDEStepKernel>().initialize(contextRef, *this, range, seed, energies);
    pairRange = range;
    context = &contextRef;
    owner = &contextRef.getOwner();
}

void GenDPDEIntegrator::cleanup() {
    kernel = Kernel();   // the internal energies belong to the Context; what the user set is kept
}

std::vector<std::string> GenDPDEIntegrator::getKernelNames() {
    return {IntegrateGenDPDEStepKernel::Name()};
}

void GenDPDEIntegrator::requireTemperatures() const {
    if (mode == Isoenergetic && !temperaturesSet)
        throw OpenMMException("GenDPDEIntegrator: the particle temperatures are not set; call setTemperature() or "
                              "setParticleTemperatures() before stepping in Isoenergetic mode");
    if (mode == Isothermal && !(temperature > 0.0))
        throw OpenMMException("GenDPDEIntegrator: the Isothermal mode needs a temperature > 0; call setTemperature()");
}

void GenDPDEIntegrator::step(int steps) {
    if (context == nullptr)
        throw OpenMMException("GenDPDEIntegrator: this integrator is not bound to a Context");
    requireTemperatures();
    const GenDPDEStepTerms terms = GenDPDEIntegratorUtilities::stepTerms(*this);
    if (terms.pairSweep && pairRange == 0.0)
        throw OpenMMException("GenDPDEIntegrator: no cutoff distance for the pair terms: the System has no "
                              "GenDPDEForce; call setCutoffDistance()");
    for (int i = 0; i < steps; i++) {
        context->updateContextState();
        context->calcForcesAndEnergy(true, false, getIntegrationForceGroups());
        // The forces of the integration groups were evaluated just now: a GenDPDEForce among them has its pairs.
        GenDPDEForceImpl* pairListSource = terms.pairSweep
                ? GenDPDEIntegratorUtilities::findPairListSource(*context, *this, pairRange) : nullptr;
        kernel.getAs<IntegrateGenDPDEStepKernel>().execute(*context, *this, terms, pairListSource);
    }
}

double GenDPDEIntegrator::computeKineticEnergy() {
    return kernel.getAs<IntegrateGenDPDEStepKernel>().computeKineticEnergy(*context, *this);
}

double GenDPDEIntegrator::getConservedEnergy() {
    if (context == nullptr)
        throw OpenMMException("GenDPDEIntegrator: this integrator is not bound to a Context");
    double potential = context->calcForcesAndEnergy(true, true, getIntegrationForceGroups());
    double kinetic = computeKineticEnergy();
    double internal = 0.0;
    for (double e : kernel.getAs<IntegrateGenDPDEStepKernel>().getInternalEnergies())
        internal += e;
    return kinetic + potential + internal;
}

// Checkpoints: version, seed in use, temperaturesSet, then the internal energies (binary, exact).
void GenDPDEIntegrator::createCheckpoint(std::ostream& stream) const {
    const IntegrateGenDPDEStepKernel& k = kernel.getAs<const IntegrateGenDPDEStepKernel>();
    const std::vector<double>& energies = k.getInternalEnergies();
    int version = checkpointVersion, seed = k.getSeed(), count = energies.size();
    char set = temperaturesSet;
    stream.write((char*) &version, sizeof(int));
    stream.write((char*) &seed, sizeof(int));
    stream.write(&set, 1);
    stream.write((char*) &count, sizeof(int));
    stream.write((char*) energies.data(), sizeof(double)*count);
}

void GenDPDEIntegrator::loadCheckpoint(std::istream& stream) {
    int version, seed, count;
    char set;
    stream.read((char*) &version, sizeof(int));
    if (version != checkpointVersion)
        throw OpenMMException("GenDPDEIntegrator: this checkpoint holds integrator data of version "
                              + std::to_string(version) + "; this build reads version " + std::to_string(checkpointVersion));
    stream.read((char*) &seed, sizeof(int));
    stream.read(&set, 1);
    stream.read((char*) &count, sizeof(int));
    if (count != context->getSystem().getNumParticles())
        throw OpenMMException("GenDPDEIntegrator: the checkpoint holds " + std::to_string(count)
                              + " internal energies, the System has " + std::to_string(context->getSystem().getNumParticles()) + " particles");
    std::vector<double> energies(count);
    stream.read((char*) energies.data(), sizeof(double)*count);
    IntegrateGenDPDEStepKernel& k = kernel.getAs<IntegrateGenDPDEStepKernel>();
    k.setSeed(seed);
    k.setInternalEnergies(energies);
    temperaturesSet = set;
}

// States (getState(getIntegratorParameters=True), Simulation.saveState): the internal energies as exact hex floats.
void GenDPDEIntegrator::serializeParameters(SerializationNode& node) const {
    const IntegrateGenDPDEStepKernel& k = kernel.getAs<const IntegrateGenDPDEStepKernel>();
    std::string text;
    char buffer[40];
    for (double e : k.getInternalEnergies()) {
        std::snprintf(buffer, sizeof(buffer), "%a ", e);
        text += buffer;
    }
    node.setIntProperty("GenDPDEIntegratorVersion", 1);
    node.setIntProperty("seedInUse", k.getSeed());
    node.setBoolProperty("temperaturesSet", temperaturesSet);
    node.setStringProperty("internalEnergies", text);
}

void GenDPDEIntegrator::deserializeParameters(const SerializationNode& node) {
    if (!node.hasProperty("internalEnergies"))
        throw OpenMMException("GenDPDEIntegrator: the State does not hold GenDPDEIntegrator parameters (it was saved "
                              "with another integrator, or without getIntegratorParameters=True)");
    std::vector<double> energies;
    const std::string& text = node.getStringProperty("internalEnergies");
    const char* cursor = text.c_str();
    char* end;
    for (double value = std::strtod(cursor, &end); end != cursor; value = std::strtod(cursor, &end)) {
        energies.push_back(value);
        cursor = end;
    }
    int numParticles = context->getSystem().getNumParticles();
    if ((int) energies.size() != numParticles)
        throw OpenMMException("GenDPDEIntegrator: the State holds " + std::to_string(energies.size())
                              + " internal energies, the System has " + std::to_string(numParticles) + " particles");
    IntegrateGenDPDEStepKernel& k = kernel.getAs<IntegrateGenDPDEStepKernel>();
    k.setSeed(node.getIntProperty("seedInUse"));
    k.setInternalEnergies(energies);
    temperaturesSet = node.getBoolProperty("temperaturesSet");
}
