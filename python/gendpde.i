%module(package="openmmgendpde") gendpde

/* Low-level SWIG bindings of the GenDPDE plugin. Users import the package openmmgendpde, which adds unit handling,
 * cast/isinstance with correct ownership, copy and pickle on top of these classes. */

%import(module="openmm") "OpenMMBaseClasses.i"

%{
#define SWIG_FILE_WITH_INIT
#define NPY_NO_DEPRECATED_API NPY_1_7_API_VERSION
#include <numpy/arrayobject.h>
#include "GenDPDEForce.h"
#include "GenDPDEIntegrator.h"
#include "internal/GenDPDEPhysics.h"
#include "openmm/OpenMMException.h"
#include <cstring>
#include <typeinfo>
%}

%init %{
    import_array();
%}

%include "std_string.i"
%include "typemaps.i"

/* C++ exceptions become openmm.OpenMMException, like OpenMM's own wrappers. */
%exception {
    try {
        $action
    }
    catch (std::exception& e) {
        PyObject* openmmModule = PyImport_ImportModule("openmm");
        PyObject* exceptionType = openmmModule ? PyObject_GetAttrString(openmmModule, "OpenMMException") : NULL;
        PyErr_Clear();
        PyErr_SetString(exceptionType ? exceptionType : PyExc_Exception, e.what());
        Py_XDECREF(exceptionType);
        Py_XDECREF(openmmModule);
        SWIG_fail;
    }
}

/* std::vector<double> results are returned as float64 numpy arrays. */
%typemap(out) std::vector<double> {
    npy_intp size = $1.size();
    $result = PyArray_SimpleNew(1, &size, NPY_DOUBLE);
    if ($result == NULL)
        SWIG_fail;
    if (size > 0)
        std::memcpy(PyArray_DATA((PyArrayObject*) $result), $1.data(), size*sizeof(double));
}

/* Any sequence of numbers (list, tuple, numpy array) is accepted where a const std::vector<double>& is expected. */
%typemap(in) const std::vector<double>& (std::vector<double> values) {
    PyObject* array = PyArray_FROMANY($input, NPY_DOUBLE, 1, 1, NPY_ARRAY_IN_ARRAY);
    if (array == NULL)
        SWIG_exception_fail(SWIG_TypeError, "expected a one-dimensional sequence of numbers");
    double* data = (double*) PyArray_DATA((PyArrayObject*) array);
    values.assign(data, data + PyArray_SIZE((PyArrayObject*) array));
    Py_DECREF(array);
    $1 = &values;
}
%typemap(typecheck, precedence=SWIG_TYPECHECK_DOUBLE_ARRAY) const std::vector<double>& {
    $1 = PySequence_Check($input) || PyArray_Check($input);
}

%apply double& OUTPUT { double& referenceDensity, double& referencePressure, double& bulkModulus, double& exponent };
%apply double& OUTPUT { double& volume, double& derivative, double& value, double& pressure, double& freeEnergy };

%ignore GenDPDEPlugin::GenDPDEForce::createImpl;
%include "GenDPDEForce.h"

%extend GenDPDEPlugin::GenDPDEForce {
    /* The ownership-aware cast() and isinstance() are defined in openmmgendpde/__init__.py on top of these. */
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

%ignore GenDPDEPlugin::GenDPDEIntegrator::initialize;
%ignore GenDPDEPlugin::GenDPDEIntegrator::cleanup;
%ignore GenDPDEPlugin::GenDPDEIntegrator::getKernelNames;
%ignore GenDPDEPlugin::GenDPDEIntegrator::computeKineticEnergy;
%ignore GenDPDEPlugin::GenDPDEIntegrator::kineticEnergyRequiresForce;
%ignore GenDPDEPlugin::GenDPDEIntegrator::getVelocityTimeOffset;
%ignore GenDPDEPlugin::GenDPDEIntegrator::createCheckpoint;
%ignore GenDPDEPlugin::GenDPDEIntegrator::loadCheckpoint;
%ignore GenDPDEPlugin::GenDPDEIntegrator::serializeParameters;
%ignore GenDPDEPlugin::GenDPDEIntegrator::deserializeParameters;
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

/* The pointwise physics of MODEL.md, exactly as the kernels evaluate it (any consistent units). */
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
