/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
%module(package="openmmgendpde") gendpde

/* Low-level SWIG bindings of the GenDPDE plugin, built on OpenMM's own SWIG interface so that the proxies subclass
 * openmm.Force and openmm.Integrator and share the type table of the openmm module (which requires the SWIG
 * version that built the openmm wheel). Users import the package openmmgendpde, which adds unit handling,
 * cast/isinstance with correct ownership, copy and pickle on top of these classes. Docstrings come from the C++
 * headers (swig -doxygen). */

/* As in OpenMM's own module: a number argument takes anything that converts to one (numpy scalars of any type,
 * 0-d arrays); an integer argument takes only integral values. */
%begin %{
#define SWIG_PYTHON_CAST_MODE
%}

/* OpenMM's typemaps (swig/typemaps.i) ask whether numpy can be used; this module imports numpy at load time. */
%header %{
static int isNumpyAvailable() {
    return 1;
}
%}

%import(module="openmm") "swig/OpenMMSwigHeaders.i"
%include "swig/typemaps.i"
%include "typemaps.i"   /* SWIG's own: double& OUTPUT */
%include "std_string.i"

%{
#define SWIG_FILE_WITH_INIT
#define NPY_NO_DEPRECATED_API NPY_1_7_API_VERSION
#include <numpy/arrayobject.h>
#include "OpenMM.h"
#include "OpenMMAmoeba.h"
#include "OpenMMDrude.h"
#include "openmm/RPMDIntegrator.h"
#include "openmm/RPMDMonteCarloBarostat.h"
#include "GenDPDEForce.h"
#include "GenDPDEIntegrator.h"
#include "gendpde/GenDPDEDensityEstimators.h"
#include "gendpde/GenDPDEEquationsOfState.h"
#include "gendpde/GenDPDESweepDefinition.h"
#include "internal/GenDPDEPhysics.h"
#include "internal/GenDPDETypes.h"
#include "internal/LiquidArgon.h"
#include <cstring>
%}

%init %{
    import_array();
%}

/* C++ exceptions become openmm.OpenMMException, as in OpenMM's own wrappers. */
%{
static void setOpenMMException(const char* message) {
    PyObject* module = PyImport_AddModule("openmm");   /* borrowed; openmm is imported before this module */
    PyObject* type = module ? PyObject_GetAttrString(module, "OpenMMException") : NULL;
    PyErr_Clear();
    PyErr_SetString(type ? type : PyExc_Exception, message);
    Py_XDECREF(type);
}
%}
%exception {
    try {
        $action
    }
    catch (std::exception& e) {
        setOpenMMException(e.what());
        SWIG_fail;
    }
}

/* Long calls release the GIL, as OpenMM's do, so that other Python threads (a second Context, a progress bar)
 * run meanwhile. Nothing in them calls back into Python. */
%define RELEASE_GIL(function)
%exception function {
    PyThreadState* savedThreadState = PyEval_SaveThread();
    try {
        $action
    }
    catch (std::exception& e) {
        PyEval_RestoreThread(savedThreadState);
        setOpenMMException(e.what());
        SWIG_fail;
    }
    PyEval_RestoreThread(savedThreadState);
}
%enddef
RELEASE_GIL(GenDPDEPlugin::GenDPDEIntegrator::step)
RELEASE_GIL(GenDPDEPlugin::GenDPDEIntegrator::getConservedEnergy)
RELEASE_GIL(GenDPDEPlugin::GenDPDEIntegrator::setInternalEnergiesToTemperature)
RELEASE_GIL(GenDPDEPlugin::GenDPDEForce::getPrimitiveDensities)
RELEASE_GIL(GenDPDEPlugin::GenDPDEForce::getParticleDensities)
RELEASE_GIL(GenDPDEPlugin::GenDPDEForce::getParticleVolumes)
RELEASE_GIL(GenDPDEPlugin::GenDPDEForce::getParticlePressures)
RELEASE_GIL(GenDPDEPlugin::GenDPDEForce::getVirial)
RELEASE_GIL(GenDPDEPlugin::GenDPDEForce::getParticleVirials)
RELEASE_GIL(GenDPDEPlugin::GenDPDEForce::updateParametersInContext)

/* std::vector<double> results are returned as float64 numpy arrays. (Arguments use OpenMM's typemap, which takes
 * lists, tuples and numpy arrays of any numeric type.) */
%typemap(out) std::vector<double> {
    npy_intp size = $1.size();
    $result = PyArray_SimpleNew(1, &size, NPY_DOUBLE);
    if ($result == NULL)
        SWIG_fail;
    if (size > 0)
        std::memcpy(PyArray_DATA((PyArrayObject*) $result), $1.data(), size*sizeof(double));
}

/* Getters with output arguments return a list of them, as OpenMM's own wrappers do (e.g.
 * DPDIntegrator.getTypePairParameters). Only reference parameters match, so the setters' value parameters of the
 * same names are untouched. */
%apply double& OUTPUT { double& referenceDensity, double& referencePressure, double& bulkModulus, double& exponent };
%apply int& OUTPUT { int& type, int& type1, int& type2 };
%apply double& OUTPUT { double& heatCapacity, double& friction, double& heatConduction };
%apply double& OUTPUT { double& volume, double& derivative, double& value, double& pressure, double& freeEnergy };
%apply double& OUTPUT { double& momentDerivative, double& energy, double& entropy, double& pressureAtZero,
                        double& thermalPressure, double& forceCoefficient, double& momentForceScale,
                        double& thermalEnergy, double& densityEntropy, double& minimum, double& maximum };
%apply int& OUTPUT { int& status };

/* The equation-of-state getters (getEquationOfState, getTypeEquationOfState) return the law as an int (the enum's
 * value, GenDPDEForce.TaitThermalExpansion...) and the parameters as a list of floats. */
%typemap(in, numinputs=0) GenDPDEPlugin::GenDPDEForce::EquationOfState& law (GenDPDEPlugin::GenDPDEForce::EquationOfState temp) {
    $1 = &temp;
}
%typemap(argout) GenDPDEPlugin::GenDPDEForce::EquationOfState& law {
    %append_output(PyLong_FromLong((long) *$1));
}
%typemap(in, numinputs=0) std::vector<double>& parameters (std::vector<double> temp) {
    $1 = &temp;
}
/* (SWIG would match the setters' const std::vector<double>& parameters to the typemaps above, qualifiers stripped:
 * theirs take any sequence of numbers and return nothing.) */
%typemap(in) const std::vector<double>& parameters (std::vector<double> temp) {
    PyObject* sequence = PySequence_Fast($input, "parameters: expected a sequence of numbers");
    if (sequence == NULL)
        SWIG_fail;
    for (Py_ssize_t k = 0; k < PySequence_Fast_GET_SIZE(sequence); k++) {
        const double value = PyFloat_AsDouble(PySequence_Fast_GET_ITEM(sequence, k));
        if (PyErr_Occurred()) {
            Py_DECREF(sequence);
            SWIG_fail;
        }
        temp.push_back(value);
    }
    Py_DECREF(sequence);
    $1 = &temp;
}
%typemap(typecheck) const std::vector<double>& parameters {
    $1 = PySequence_Check($input) ? 1 : 0;
}
%typemap(argout) const std::vector<double>& parameters ""
%typemap(argout) std::vector<double>& parameters {
    PyObject* list = PyList_New($1->size());
    if (list == NULL)
        SWIG_fail;
    for (size_t k = 0; k < $1->size(); k++)
        PyList_SET_ITEM(list, k, PyFloat_FromDouble((*$1)[k]));
    %append_output(list);
}

/* Particle types (getParticleTypes) become a dict {particle index: type}, a copy. */
%typemap(out) const std::map<int, int>& {
    $result = PyDict_New();
    if ($result == NULL)
        SWIG_fail;
    for (std::map<int, int>::const_iterator entry = $1->begin(); entry != $1->end(); ++entry) {
        PyObject* key = PyLong_FromLong(entry->first);
        PyObject* value = PyLong_FromLong(entry->second);
        int status = (key != NULL && value != NULL) ? PyDict_SetItem($result, key, value) : -1;
        Py_XDECREF(key);
        Py_XDECREF(value);
        if (status < 0) {
            Py_CLEAR($result);
            SWIG_fail;
        }
    }
}

%ignore GenDPDEPlugin::GenDPDEForce::createImpl;
%include "GenDPDEForce.h"

%extend GenDPDEPlugin::GenDPDEForce {
    /* The ownership-aware cast() and isinstance() are defined in openmmgendpde/_wrapping.py on top of these. */
    static GenDPDEPlugin::GenDPDEForce& _downcast(OpenMM::Force& force) {
        GenDPDEPlugin::GenDPDEForce* result = dynamic_cast<GenDPDEPlugin::GenDPDEForce*>(&force);
        if (result == NULL)
            throw OpenMM::OpenMMException("GenDPDEForce.cast: the Force is not a GenDPDEForce");
        return *result;
    }
    static bool _isinstance(OpenMM::Force& force) {
        return dynamic_cast<GenDPDEPlugin::GenDPDEForce*>(&force) != NULL;
    }
}

%include "GenDPDEIntegrator.h"

%extend GenDPDEPlugin::GenDPDEIntegrator {
    static GenDPDEPlugin::GenDPDEIntegrator& _downcast(OpenMM::Integrator& integrator) {
        GenDPDEPlugin::GenDPDEIntegrator* result = dynamic_cast<GenDPDEPlugin::GenDPDEIntegrator*>(&integrator);
        if (result == NULL)
            throw OpenMM::OpenMMException("GenDPDEIntegrator.cast: the Integrator is not a GenDPDEIntegrator");
        return *result;
    }
    static bool _isinstance(OpenMM::Integrator& integrator) {
        return dynamic_cast<GenDPDEPlugin::GenDPDEIntegrator*>(&integrator) != NULL;
    }
}

/* The liquid-argon model's numbers (one home, read by openmmgendpde.presets). */
%include "internal/LiquidArgon.h"

/* The pointwise physics of docs/theory.md, exactly as the kernels evaluate it (any consistent units). */
%inline %{
namespace GenDPDEPlugin {
/** V-A volume and dV/dn0 for primitive density n0 > 0: returns (V, dV/dn0). */
void particleVolumeVA(double primitiveDensity, double& volume, double& derivative) {
    if (!(primitiveDensity > 0.0))
        throw OpenMM::OpenMMException("particleVolumeVA: primitive density must be > 0");
    Physics::ParticleVolume v = Physics::volumeVA(primitiveDensity);
    volume = v.volume;
    derivative = v.derivative;
}
/** V-B volume and dV/dn0 for primitive density n0 >= 0 and reduced range Rt = R/f_cut: returns (V, dV/dn0). */
void particleVolumeVB(double primitiveDensity, double reducedRange, double& volume, double& derivative) {
    if (!(primitiveDensity >= 0.0) || !(reducedRange > 0.0))
        throw OpenMM::OpenMMException("particleVolumeVB: need primitive density >= 0 and reduced range > 0");
    Physics::ParticleVolume v = Physics::volumeVB(primitiveDensity, reducedRange);
    volume = v.volume;
    derivative = v.derivative;
}
/** The density weight w(r) and its derivative w'(r) for cutoff R: returns (w, w'). */
void densityWeight(double r, double cutoff, double& value, double& derivative) {
    Physics::DensityWeight weight(cutoff);
    value = weight.value(r);
    derivative = weight.derivative(r);
}
/** The dimensionless V-B integrals of k = (2 pi/15) Rt^3 n0 >= 0: returns (I, J) with V = 4 pi Rt^3 I and
 *  dV/dn0 = -(8 pi^2/15) Rt^6 J. */
void volumeIntegralsVB(double k, double& value, double& derivative) {
    if (!(k >= 0.0))
        throw OpenMM::OpenMMException("volumeIntegralsVB: k must be >= 0");
    Physics::VolumeIntegralsVB integrals = Physics::volumeIntegralsVB(k);
    value = integrals.I;
    derivative = integrals.J;
}
/** Tait pressure pi(n) and free energy per particle f(n): returns (pi, f). */
void taitEquationOfState(double density, double referenceDensity, double referencePressure, double bulkModulus,
                         double exponent, double& pressure, double& freeEnergy) {
    Physics::TaitEquationOfState(referenceDensity, referencePressure, bulkModulus, exponent).evaluate(density, pressure, freeEnergy);
}
}
%}

/* The local equations of state, as the table of GenDPDEEquationsOfState.h describes them (openmmgendpde reads its
 * parameters' names and units from here), and the core's per-particle functions for every estimator and law. */
%{
namespace {
const GenDPDEPlugin::EquationsOfState::Law& requireLaw(int law) {
    const GenDPDEPlugin::EquationsOfState::Law* found = GenDPDEPlugin::EquationsOfState::find(law);
    if (found == nullptr)
        throw OpenMM::OpenMMException("equation of state " + std::to_string(law) + " is not one; it must be "
                                      + GenDPDEPlugin::EquationsOfState::listOfLaws());
    return *found;
}
const GenDPDEPlugin::DensityEstimators::Estimator& requireEstimator(int estimator) {
    const GenDPDEPlugin::DensityEstimators::Estimator* found = GenDPDEPlugin::DensityEstimators::find(estimator);
    if (found == nullptr)
        throw OpenMM::OpenMMException("density estimator " + std::to_string(estimator) + " is not one; it must be "
                                      + GenDPDEPlugin::DensityEstimators::listOfEstimators());
    return *found;
}
const GenDPDEPlugin::EquationsOfState::Parameter& requireParameter(int law, int index) {
    const GenDPDEPlugin::EquationsOfState::Law& found = requireLaw(law);
    if (index < 0 || index >= found.numParameters)
        throw OpenMM::OpenMMException(std::string("the ") + found.name + " equation of state has no parameter "
                                      + std::to_string(index) + " (it takes " + std::to_string(found.numParameters)
                                      + ")");
    return found.parameters[index];
}
/** Refuse what GenDPDEForce's setters refuse (a law, its parameters, the Tait parameters, p_b). */
void checkedLaw(int law, const std::vector<double>& parameters, double referenceDensity, double referencePressure,
                double bulkModulus, double exponent, double backgroundPressure) {
    GenDPDEPlugin::GenDPDEForce check(1.0);
    check.setTaitParameters(referenceDensity, referencePressure, bulkModulus, exponent);
    check.setEquationOfState((GenDPDEPlugin::GenDPDEForce::EquationOfState) law, parameters);
    check.setBackgroundPressure(backgroundPressure);
}
}
%}
%inline %{
namespace GenDPDEPlugin {
/** The number of equations of state (GenDPDEForce.EquationOfState values 0 .. n-1). */
int numEquationsOfState() {
    return EquationsOfState::numLaws;
}
/** The name of an equation of state as the API spells it ("TaitThermalExpansion"). */
const char* equationOfStateName(int law) {
    return requireLaw(law).name;
}
/** Whether an equation of state extends the Tait law (it takes the type's n0, pi0, B_T, gamma_T before its own). */
bool equationOfStateExtendsTait(int law) {
    return requireLaw(law).extendsTait;
}
/** The number of parameters an equation of state takes (setEquationOfState). */
int numEquationOfStateParameters(int law) {
    return requireLaw(law).numParameters;
}
/** A parameter's short name ("beta"). */
const char* equationOfStateParameterName(int law, int index) {
    return requireParameter(law, index).name;
}
/** A parameter's description, as messages name it ("thermal pressure coefficient beta"). */
const char* equationOfStateParameterDescription(int law, int index) {
    return requireParameter(law, index).description;
}
/** A parameter's OpenMM units as text ("kJ/mol/nm^3/K"; "" if dimensionless). */
const char* equationOfStateParameterUnits(int law, int index) {
    return requireParameter(law, index).range.units;
}
/** A parameter's allowed range (in its units): returns (minimum, maximum); see also the minimum's exclusion. */
void equationOfStateParameterRange(int law, int index, double& minimum, double& maximum) {
    minimum = requireParameter(law, index).range.minimum;
    maximum = requireParameter(law, index).range.maximum;
}
/** Whether a parameter's minimum itself is refused. */
bool equationOfStateParameterExcludesMinimum(int law, int index) {
    return requireParameter(law, index).excludeMinimum;
}
/** The number of sweep cells along one direction of this extent for this pair range (periodic or not), as every
 *  engine computes them (GenDPDESweepDefinition.h). */
int sweepCellCount(double extent, double range, bool periodic) {
    if (!(extent > 0.0) || !(range > 0.0))
        throw OpenMM::OpenMMException("sweepCellCount: the extent and the range must be > 0");
    return SweepDefinition::cellCount(extent, range, periodic);
}
/** The reach of the sweep's candidate pairs for this pair range, (1 + skin fraction) R = 1.1 R: the sweep's cells
 *  are at least this wide (GenDPDESweepDefinition.h). */
double sweepCandidateRange(double range) {
    if (!(range > 0.0))
        throw OpenMM::OpenMMException("sweepCandidateRange: the range must be > 0");
    return SweepDefinition::candidateRange(range);
}
/** The fewest sweep cells per direction that a sweep split across subdomains (the LAMMPS fix) takes. */
int sweepMinCellsAcrossSubdomains() {
    return SweepDefinition::minCellsAcrossSubdomains;
}
/** The ghost cutoff a sweep split across subdomains (the LAMMPS fix) needs for a periodic box of these widths, pair
 *  range and neighbour skin (GenDPDESweepDefinition.h): 1.5 widths of the widest sweep cell plus the skin. */
double sweepGhostCutoff(double widthX, double widthY, double widthZ, double range, double skin) {
    if (!(widthX > 0.0 && widthY > 0.0 && widthZ > 0.0 && range > 0.0 && skin >= 0.0))
        throw OpenMM::OpenMMException("sweepGhostCutoff: the widths and the range must be > 0, the skin >= 0");
    const double widths[3] = {widthX, widthY, widthZ};
    return SweepDefinition::ghostCutoff(widths, range, skin);
}
/** The number of density estimators (GenDPDEForce.DensityEstimator values 0 .. n-1; GenDPDEDensityEstimators.h). */
int numDensityEstimators() {
    return DensityEstimators::numEstimators;
}
/** The name of a density estimator as the API spells it ("VB"). */
const char* densityEstimatorName(int estimator) {
    return requireEstimator(estimator).name;
}
/** A density estimator's description, for help and messages ("partition of unity"). */
const char* densityEstimatorDescription(int estimator) {
    return requireEstimator(estimator).description;
}
/** Whether the cutoff scaling f_cut changes a density estimator (Rt = R/f_cut; V-A ignores it). */
bool densityEstimatorReadsCutoffScaling(int estimator) {
    return requireEstimator(estimator).readsCutoffScaling;
}
/** Whether a density estimator reads the first moments of the neighbourhoods (V-C). */
bool densityEstimatorNeedsMoments(int estimator) {
    return requireEstimator(estimator).needsMoments;
}
/** What a suggested time step is multiplied by for this estimator (V-C: 0.1; GenDPDEDensityEstimators.h says why). */
double densityEstimatorStableStepFactor(int estimator) {
    return requireEstimator(estimator).stableStepFactor;
}
/** V, dV/dn0 and dV/dG of any estimator (GenDPDEForce.VA, VB, VC) at primitive density n0 >= 0 and squared moment G
 *  (V-C), for cutoff R and cutoff scaling f_cut (Rt = R/f_cut): returns (V, dV/dn0, dV/dG). */
void particleVolume(int estimator, double primitiveDensity, double squaredMoment, double cutoff,
                    double cutoffScaling, double& volume, double& derivative, double& momentDerivative) {
    if (DensityEstimators::find(estimator) == nullptr || !(primitiveDensity >= 0.0)
            || !(squaredMoment >= 0.0) || !(cutoff > 0.0) || !(cutoffScaling >= 1.0))
        throw OpenMM::OpenMMException("particleVolume: need an estimator (" + DensityEstimators::listOfEstimators()
                                      + "), primitive density >= 0, squared moment >= 0, cutoff > 0 and cutoff "
                                      "scaling >= 1");
    const Physics::ParticleVolumeAndMoment v = Physics::VolumeEstimator(estimator, cutoff, cutoff/cutoffScaling)(
            primitiveDensity, squaredMoment);
    volume = v.volume;
    derivative = v.derivative;
    momentDerivative = v.momentDerivative;
}
/** The law's (GenDPDEForce.EquationOfState) parts at density n: returns (status, e, sigma, pressureAtZero,
 *  thermalPressure) with pi = pressureAtZero + theta thermalPressure (gendpdeLocalEquationOfState). parameters as
 *  setEquationOfState takes them (checked), tait the type's n0, pi0, B_T, gamma_T, p_b the background pressure. */
void localEquationOfState(int law, const std::vector<double>& parameters, double referenceDensity,
                          double referencePressure, double bulkModulus, double exponent, double backgroundPressure,
                          double density, int& status, double& energy, double& entropy, double& pressureAtZero,
                          double& thermalPressure) {
    checkedLaw(law, parameters, referenceDensity, referencePressure, bulkModulus, exponent, backgroundPressure);
    const Physics::LocalEquationOfState eos = packEquationOfState((GenDPDEForce::EquationOfState) law, parameters,
            {referenceDensity, referencePressure, bulkModulus, exponent}, backgroundPressure);
    status = Physics::gendpdeLocalEquationOfState(eos.law, density, eos.parameter.data(), eos.integerPower, &energy,
                                                  &entropy, &pressureAtZero, &thermalPressure);
}
/** Everything a particle contributes to the force (gendpdeParticleState), for any estimator and law: returns (status,
 *  V, pi, its term of U, pi dV/dn0, 2 pi dV/dG, C theta, sigma). The law as localEquationOfState; the thermal state
 *  (laws that depend on temperature): isothermal with temperature, else storedEnergy eps_i with storedEntropy if
 *  entropyKnown, and heatCapacity C_V. */
void particleState(int estimator, double cutoff, double cutoffScaling, double primitiveDensity,
                   double squaredMoment, int law, const std::vector<double>& parameters, double referenceDensity,
                   double referencePressure, double bulkModulus, double exponent, double backgroundPressure,
                   bool isothermal, double temperature, double storedEnergy, double storedEntropy, bool entropyKnown,
                   double heatCapacity, int& status, double& volume, double& pressure, double& energy,
                   double& forceCoefficient, double& momentForceScale, double& thermalEnergy,
                   double& densityEntropy) {
    double ignored;
    particleVolume(estimator, primitiveDensity, squaredMoment, cutoff, cutoffScaling, ignored, ignored, ignored);
    checkedLaw(law, parameters, referenceDensity, referencePressure, bulkModulus, exponent, backgroundPressure);
    const Physics::LocalEquationOfState eos = packEquationOfState((GenDPDEForce::EquationOfState) law, parameters,
            {referenceDensity, referencePressure, bulkModulus, exponent}, backgroundPressure);
    Physics::ParticleState state;
    status = Physics::particleState(Physics::VolumeEstimator(estimator, cutoff, cutoff/cutoffScaling), eos,
            primitiveDensity, squaredMoment, {isothermal, temperature, storedEnergy, storedEntropy, entropyKnown,
            heatCapacity, false}, state);
    volume = state.volume;
    pressure = state.pressure;
    energy = state.freeEnergy;
    forceCoefficient = state.forceCoefficient;
    momentForceScale = state.momentForceScale;
    thermalEnergy = state.thermalEnergy;
    densityEntropy = state.densityEntropy;
}
}
%}

/* What gendpdeParticleState and gendpdeLocalEquationOfState return (GENDPDE_PARTICLE_*). */
%constant int PARTICLE_VALID = GENDPDE_PARTICLE_VALID;
%constant int PARTICLE_NO_NEIGHBOR = GENDPDE_PARTICLE_NO_NEIGHBOR;
%constant int PARTICLE_OVERFLOW = GENDPDE_PARTICLE_OVERFLOW;
%constant int PARTICLE_OUTSIDE_DOMAIN = GENDPDE_PARTICLE_OUTSIDE_DOMAIN;
%constant int PARTICLE_TEMPERATURE_JUMP = GENDPDE_PARTICLE_TEMPERATURE_JUMP;
