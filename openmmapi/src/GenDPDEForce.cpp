/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
#include "GenDPDEForce.h"
#include "gendpde/GenDPDEDensityEstimators.h"
#include "gendpde/GenDPDEEquationsOfState.h"
#include "internal/GenDPDEForceImpl.h"
#include "internal/GenDPDEPhysics.h"
#include "internal/GenDPDETypes.h"
#include "internal/LiquidArgon.h"
#include "internal/ParameterChecks.h"
#include "openmm/OpenMMException.h"
#include <string>

using namespace GenDPDEPlugin;
using namespace OpenMM;
using namespace ParameterChecks;

namespace {
// Default Tait parameters: liquid argon (internal/LiquidArgon.h) converted to OpenMM units.
const double argonLength = LiquidArgon::length;                                        // L (nm)
const double argonEnergy = LiquidArgon::energy * 6.02214076e23 / 1000.0;                   // u (kJ/mol)
const double argonPressureUnit = argonEnergy / (argonLength * argonLength * argonLength);   // u/L^3 (kJ/mol/nm^3)
}

GenDPDEForce::GenDPDEForce(double cutoff) :
        cutoffScaling(1.0), backgroundPressure(0.0),
        referenceDensity(LiquidArgon::density / (argonLength * argonLength * argonLength)),
        // pi0* = P0* - n0* T0*
        referencePressure((LiquidArgon::pressure - LiquidArgon::density * LiquidArgon::temperature)
                          * argonPressureUnit),
        bulkModulus(argonPressureUnit
                    / (LiquidArgon::taitExponent * LiquidArgon::compressibility)),   // 1/(gamma_T kappa_T0)
        exponent(LiquidArgon::taitExponent), nonbondedMethod(CutoffPeriodic), estimator(VB), defaultLaw{0, Tait, {}} {
    setCutoffDistance(cutoff);
}

double GenDPDEForce::getCutoffDistance() const {
    return cutoff;
}

void GenDPDEForce::setCutoffDistance(double distance) {
    requireInRange("GenDPDEForce", "cutoff distance", distance, Ranges::cutoff);
    cutoff = distance;
}

GenDPDEForce::NonbondedMethod GenDPDEForce::getNonbondedMethod() const {
    return nonbondedMethod;
}

void GenDPDEForce::setNonbondedMethod(NonbondedMethod method) {
    if (method != CutoffNonPeriodic && method != CutoffPeriodic)
        reject("GenDPDEForce", "nonbonded method", (int) method, "", "CutoffNonPeriodic (0) or CutoffPeriodic (1)");
    nonbondedMethod = method;
}

GenDPDEForce::DensityEstimator GenDPDEForce::getDensityEstimator() const {
    return estimator;
}

void GenDPDEForce::setDensityEstimator(DensityEstimator estimator) {
    if (DensityEstimators::find(estimator) == nullptr)
        reject("GenDPDEForce", "density estimator", (int) estimator, "", DensityEstimators::listOfEstimators());
    this->estimator = estimator;
}

double GenDPDEForce::getCutoffScaling() const {
    return cutoffScaling;
}

void GenDPDEForce::setCutoffScaling(double scaling) {
    requireInRange("GenDPDEForce", "cutoff scaling f_cut", scaling, Ranges::cutoffScaling);
    cutoffScaling = scaling;
}

double GenDPDEForce::getBackgroundPressure() const {
    return backgroundPressure;
}

void GenDPDEForce::setBackgroundPressure(double pressure) {
    requireInRange("GenDPDEForce", "background pressure p_b", pressure, Ranges::backgroundPressure);
    backgroundPressure = pressure;
}

void GenDPDEForce::setTaitParameters(double referenceDensity, double referencePressure, double bulkModulus,
                                     double exponent) {
    // Check all four before changing any.
    requireInRange("GenDPDEForce", "Tait reference density n0", referenceDensity, Ranges::referenceDensity);
    requireInRange("GenDPDEForce", "Tait reference pressure pi0", referencePressure, Ranges::referencePressure);
    requireInRange("GenDPDEForce", "Tait bulk modulus B_T", bulkModulus, Ranges::bulkModulus);
    requireInRange("GenDPDEForce", "Tait exponent gamma_T", exponent, Ranges::taitExponent, true);
    this->referenceDensity = referenceDensity;
    this->referencePressure = referencePressure;
    this->bulkModulus = bulkModulus;
    this->exponent = exponent;
}

void GenDPDEForce::getTaitParameters(double& referenceDensity, double& referencePressure, double& bulkModulus,
                                     double& exponent) const {
    referenceDensity = this->referenceDensity;
    referencePressure = this->referencePressure;
    bulkModulus = this->bulkModulus;
    exponent = this->exponent;
}

double GenDPDEForce::getReferenceDensity() const {
    return referenceDensity;
}

double GenDPDEForce::getReferencePressure() const {
    return referencePressure;
}

double GenDPDEForce::getBulkModulus() const {
    return bulkModulus;
}

double GenDPDEForce::getTaitExponent() const {
    return exponent;
}

void GenDPDEForce::setParticleType(int index, int type) {
    setParticleTypeIn(particleTypes, "GenDPDEForce", index, type);
}

int GenDPDEForce::getParticleType(int index) const {
    return particleTypeIn(particleTypes, index);
}

const std::map<int, int>& GenDPDEForce::getParticleTypes() const {
    return particleTypes;
}

void GenDPDEForce::checkTypeEntry(int index, int type, double referenceDensity, double referencePressure,
                                  double bulkModulus, double exponent) const {
    const std::string entry =
            "GenDPDEForce type parameters " + std::to_string(index) + " (type " + std::to_string(type) + ")";
    requireInRange(entry, "Tait reference density n0", referenceDensity, Ranges::referenceDensity);
    requireInRange(entry, "Tait reference pressure pi0", referencePressure, Ranges::referencePressure);
    requireInRange(entry, "Tait bulk modulus B_T", bulkModulus, Ranges::bulkModulus);
    requireInRange(entry, "Tait exponent gamma_T", exponent, Ranges::taitExponent, true);
    for (int other = 0; other < (int) typeParameters.size(); other++)
        if (other != index && typeParameters[other].type == type)
            throw OpenMMException(entry + ": type " + std::to_string(type) + " already has parameters (entry "
                                  + std::to_string(other) + "); change that entry with setTypeParameters()");
}

int GenDPDEForce::addTypeParameters(int type, double referenceDensity, double referencePressure, double bulkModulus,
                                    double exponent) {
    checkTypeEntry(typeParameters.size(), type, referenceDensity, referencePressure, bulkModulus, exponent);
    typeParameters.push_back({type, referenceDensity, referencePressure, bulkModulus, exponent});
    return typeParameters.size() - 1;
}

int GenDPDEForce::getNumTypeParameters() const {
    return typeParameters.size();
}

void GenDPDEForce::getTypeParameters(int index, int& type, double& referenceDensity, double& referencePressure,
                                     double& bulkModulus, double& exponent) const {
    requireIndex("GenDPDEForce", "type parameters index", index, typeParameters.size());
    const TypeEntry& entry = typeParameters[index];
    type = entry.type;
    referenceDensity = entry.referenceDensity;
    referencePressure = entry.referencePressure;
    bulkModulus = entry.bulkModulus;
    exponent = entry.exponent;
}

void GenDPDEForce::setTypeParameters(int index, int type, double referenceDensity, double referencePressure,
                                     double bulkModulus, double exponent) {
    requireIndex("GenDPDEForce", "type parameters index", index, typeParameters.size());
    checkTypeEntry(index, type, referenceDensity, referencePressure, bulkModulus, exponent);
    typeParameters[index] = {type, referenceDensity, referencePressure, bulkModulus, exponent};
}

void GenDPDEForce::checkLaw(const std::string& entry, EquationOfState law, const std::vector<double>& parameters) {
    // The parameters each law takes, with their ranges: the table of GenDPDEEquationsOfState.h.
    const EquationsOfState::Law* description = EquationsOfState::find((int) law);
    if (description == nullptr)
        reject(entry, "equation of state", (int) law, "", EquationsOfState::listOfLaws());
    if ((int) parameters.size() != description->numParameters) {
        const std::string list = EquationsOfState::listOfParameters(*description);
        throw OpenMMException(entry + ": the " + description->name + " equation of state takes "
                              + std::to_string(description->numParameters) + " parameters"
                              + (list.empty() ? "" : " (" + list + ")") + ", not " + std::to_string(parameters.size()));
    }
    for (int k = 0; k < description->numParameters; k++) {
        const EquationsOfState::Parameter& parameter = description->parameters[k];
        requireInRange(entry, parameter.description, parameters[k], parameter.range, parameter.excludeMinimum);
    }
}

void GenDPDEForce::setEquationOfState(EquationOfState law, const std::vector<double>& parameters) {
    checkLaw("GenDPDEForce", law, parameters);
    defaultLaw = {0, law, parameters};
}

void GenDPDEForce::getEquationOfState(EquationOfState& law, std::vector<double>& parameters) const {
    law = defaultLaw.law;
    parameters = defaultLaw.parameters;
}

void GenDPDEForce::checkTypeLaw(int index, int type, EquationOfState law, const std::vector<double>& parameters) const {
    const std::string entry =
            "GenDPDEForce type equation of state " + std::to_string(index) + " (type " + std::to_string(type) + ")";
    checkLaw(entry, law, parameters);
    for (int other = 0; other < (int) typeLaws.size(); other++)
        if (other != index && typeLaws[other].type == type)
            throw OpenMMException(entry + ": type " + std::to_string(type) + " already has an equation of state (entry "
                                  + std::to_string(other) + "); change that entry with setTypeEquationOfState()");
}

int GenDPDEForce::addTypeEquationOfState(int type, EquationOfState law, const std::vector<double>& parameters) {
    checkTypeLaw(typeLaws.size(), type, law, parameters);
    typeLaws.push_back({type, law, parameters});
    return typeLaws.size() - 1;
}

int GenDPDEForce::getNumTypeEquationsOfState() const {
    return typeLaws.size();
}

void GenDPDEForce::getTypeEquationOfState(int index, int& type, EquationOfState& law,
                                          std::vector<double>& parameters) const {
    requireIndex("GenDPDEForce", "type equation of state index", index, typeLaws.size());
    type = typeLaws[index].type;
    law = typeLaws[index].law;
    parameters = typeLaws[index].parameters;
}

void GenDPDEForce::setTypeEquationOfState(int index, int type, EquationOfState law,
                                          const std::vector<double>& parameters) {
    requireIndex("GenDPDEForce", "type equation of state index", index, typeLaws.size());
    checkTypeLaw(index, type, law, parameters);
    typeLaws[index] = {type, law, parameters};
}

bool GenDPDEForce::dependsOnTemperature() const {
    if (Physics::gendpdeLawDependsOnTemperature(EquationsOfState::laws[defaultLaw.law].coreId))
        return true;
    for (const LawEntry& entry : typeLaws)
        if (Physics::gendpdeLawDependsOnTemperature(EquationsOfState::laws[entry.law].coreId))
            return true;
    return false;
}

bool GenDPDEForce::usesPeriodicBoundaryConditions() const {
    return nonbondedMethod == CutoffPeriodic;
}

ForceImpl* GenDPDEForce::createImpl() const {
    return new GenDPDEForceImpl(*this);
}

GenDPDEForceImpl& GenDPDEForce::getImpl(Context& context) const {
    // The impl belongs to the Context, which the caller passes as non-const; evaluating observables updates caches.
    return const_cast<GenDPDEForceImpl&>(dynamic_cast<const GenDPDEForceImpl&>(getImplInContext(context)));
}

void GenDPDEForce::updateParametersInContext(Context& context) {
    getImpl(context).updateParametersInContext(getContextImpl(context));
}

const GenDPDEObservables& GenDPDEForce::observablesInContext(Context& context, bool particleVirials) const {
    return getImpl(context).getObservables(const_cast<GenDPDEForce*>(this)->getContextImpl(context), particleVirials);
}

std::vector<double> GenDPDEForce::getPrimitiveDensities(Context& context) const {
    return observablesInContext(context).primitiveDensities;
}

std::vector<double> GenDPDEForce::getParticleDensities(Context& context) const {
    return observablesInContext(context).densities;
}

std::vector<double> GenDPDEForce::getParticleVolumes(Context& context) const {
    return observablesInContext(context).volumes;
}

std::vector<double> GenDPDEForce::getParticlePressures(Context& context) const {
    return observablesInContext(context).pressures;
}

double GenDPDEForce::getVirial(Context& context) const {
    ContextImpl& impl = const_cast<GenDPDEForce*>(this)->getContextImpl(context);
    return observablesInContext(context).virial + getImpl(context).backgroundVirial(impl);
}

std::vector<double> GenDPDEForce::getParticleVirials(Context& context) const {
    std::vector<double> virials = observablesInContext(context, true).particleVirials;
    const int numParticles = virials.size() / 9;
    if (numParticles > 0) {
        // The box term -p_b V_box on the diagonal of the system's tensor, shared equally.
        ContextImpl& impl = const_cast<GenDPDEForce*>(this)->getContextImpl(context);
        const double share = getImpl(context).backgroundVirial(impl) / (3.0 * numParticles);
        if (share != 0)
            for (int i = 0; i < numParticles; i++)
                for (int a = 0; a < 3; a++)
                    virials[9 * i + 4 * a] += share;
    }
    return virials;
}
