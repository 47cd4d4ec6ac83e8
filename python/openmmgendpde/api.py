# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""The plugin's OpenMM classes: ``GenDPDEForce`` and ``GenDPDEIntegrator`` (the SWIG classes of the C++ API) with
OpenMM's conventions added: arguments accept ``openmm.unit`` quantities, getters return them, per-particle results are
Quantities holding numpy arrays, copies, pickling and ``repr``. Importing this module loads the kernel libraries.

Import the classes from the package (``from openmmgendpde import GenDPDEForce``); the other modules of the package
import them from here, so that nothing imports the package's ``__init__`` in a circle.
"""

import dataclasses as _dataclasses
import glob as _glob
import os as _os

import openmm as _openmm
from openmm import unit as _unit
from openmm import version as _openmm_version

from . import gendpde as _swig
from .internal.wrapping import (
    DIMENSIONLESS,
    NUMBER_DENSITY,
    PRESSURE,
    PRESSURE_PER_KELVIN,
    accept_units,
    add_cast_copy_and_pickle,
    parse_units,
    return_units,
    to_openmm_value,
)

#: The kernels this plugin adds to OpenMM's platforms.
KERNEL_NAMES = ("CalcGenDPDEForce", "IntegrateGenDPDEStep")


def _load_kernel_libraries():
    """`import openmm` loads the kernel libraries from OpenMM's plugin directory, where `pip install` puts them,
    unless OPENMM_PLUGIN_DIR names another directory: then load them from OpenMM's directory by path."""
    if _openmm.Platform.getPlatformByName("Reference").supportsKernels(KERNEL_NAMES):
        return
    plugins = _os.path.join(_openmm_version.openmm_library_path, "plugins")
    for library in sorted(_glob.glob(_os.path.join(plugins, "libOpenMMGenDPDE*.so"))):
        try:
            _openmm.Platform.loadPluginLibrary(library)
        except Exception:  # a GPU platform OpenMM cannot load here (e.g. no CUDA driver): as `import openmm` does
            pass


_load_kernel_libraries()

__all__ = ["GenDPDEForce", "GenDPDEIntegrator"]


def _units_of(arguments):
    """The units of an argument list of accept_units, for the matching getter's return_units."""
    return [argument_unit for _, argument_unit in arguments]


GenDPDEForce = _swig.GenDPDEForce

accept_units(GenDPDEForce, "__init__", [("cutoff", _unit.nanometer)])
accept_units(GenDPDEForce, "setCutoffDistance", [("distance", _unit.nanometer)])
return_units(GenDPDEForce, "getCutoffDistance", _unit.nanometer)
accept_units(GenDPDEForce, "setCutoffScaling", [("scaling", DIMENSIONLESS)])
_TAIT = [("referenceDensity", NUMBER_DENSITY), ("referencePressure", PRESSURE), ("bulkModulus", PRESSURE),
         ("exponent", DIMENSIONLESS)]
accept_units(GenDPDEForce, "setTaitParameters", _TAIT)
return_units(GenDPDEForce, "getTaitParameters", _units_of(_TAIT))
# Particle types are plain ints (setParticleType, getParticleType, getParticleTypes: a dict {particle: type}).
accept_units(GenDPDEForce, "addTypeParameters", [("type", DIMENSIONLESS)] + _TAIT)
accept_units(GenDPDEForce, "setTypeParameters", [("index", DIMENSIONLESS), ("type", DIMENSIONLESS)] + _TAIT)
return_units(GenDPDEForce, "getTypeParameters", [DIMENSIONLESS] + _units_of(_TAIT))
return_units(GenDPDEForce, "getReferenceDensity", NUMBER_DENSITY)
return_units(GenDPDEForce, "getReferencePressure", PRESSURE)
return_units(GenDPDEForce, "getBulkModulus", PRESSURE)
accept_units(GenDPDEForce, "setBackgroundPressure", [("pressure", PRESSURE)])
return_units(GenDPDEForce, "getBackgroundPressure", PRESSURE)
return_units(GenDPDEForce, "getVirial", _unit.kilojoule_per_mole)
return_units(GenDPDEForce, "getPrimitiveDensities", NUMBER_DENSITY)
return_units(GenDPDEForce, "getParticleDensities", NUMBER_DENSITY)
return_units(GenDPDEForce, "getParticleVolumes", _unit.nanometer**3)
return_units(GenDPDEForce, "getParticlePressures", PRESSURE)


def _particle_virials(original):
    def getParticleVirials(self, context):
        return _unit.Quantity(original(self, context).reshape(-1, 3, 3), _unit.kilojoule_per_mole)
    getParticleVirials.__doc__ = (original.__doc__ or "") + (
        "\n\nReturns a Quantity holding an N x 3 x 3 numpy array (kJ/mol): element [i, a, b] is W_i,ab.")
    return getParticleVirials


def _law_table():
    """Each law's parameters, in order, with their units, as the C++ table has them (GenDPDEEquationsOfState.h):
    {law: [(name, unit), ...]}."""
    return {law: [(_swig.equationOfStateParameterName(law, k),
                   parse_units(_swig.equationOfStateParameterUnits(law, k)))
                  for k in range(_swig.numEquationOfStateParameters(law))]
            for law in range(_swig.numEquationsOfState())}


# The local equations of state (docs/theory.md section 11): each law's parameters, in order, with their units.
_LAW_PARAMETERS = _law_table()


def law_description(law):
    """(name as the API spells it, whether it takes the Tait parameters n0, pi0, B_T, gamma_T before its own, [(its
    own parameters' names, OpenMM units), ...]) of a GenDPDEForce.EquationOfState value, from the C++ table
    (GenDPDEEquationsOfState.h): what a program that writes the laws for another engine reads."""
    return (_swig.equationOfStateName(int(law)), bool(_swig.equationOfStateExtendsTait(int(law))),
            _LAW_PARAMETERS[int(law)])


def _describe_laws():
    """The laws' parameters for docstrings: "Tait [], TaitThermalExpansion [beta (kJ/mol/nm^3/K, or MPa/K), ...]"."""
    def one(law, k, unit_):
        text = _swig.equationOfStateParameterUnits(law, k) or "dimensionless"
        also = {PRESSURE: ", or MPa", PRESSURE_PER_KELVIN: ", or MPa/K"}.get(unit_, "")
        return f"{_swig.equationOfStateParameterName(law, k)} ({text}{also})"
    return ", ".join(f"{_swig.equationOfStateName(law)} [{', '.join(one(law, k, u) for k, (_, u) in enumerate(names))}]"
                     for law, names in _LAW_PARAMETERS.items())


def _law_parameters(law, parameters, where):
    """A law's parameters as plain numbers in OpenMM units (each may be a Quantity; a per-molecule pressure or
    pressure per kelvin, in MPa or MPa/K, is converted per mole); a law the plugin does not know passes through, for
    the C++ check to refuse it."""
    names = _LAW_PARAMETERS.get(int(law))
    values = list(parameters)
    if names is None or len(values) != len(names):
        return law, values   # refused by the C++ check, which names the law and the parameters it takes
    return law, [to_openmm_value(v, u, f"{where}({name})") for v, (name, u) in zip(values, names)]


def _with_law_units(law, parameters):
    """A getter's parameters of ``law`` as Quantities in OpenMM units."""
    names = _LAW_PARAMETERS.get(int(law), [])
    return [v if u is DIMENSIONLESS else _unit.Quantity(v, u) for v, (_, u) in zip(parameters, names)]


def _wrap_equation_of_state():
    set_law, get_law = GenDPDEForce.setEquationOfState, GenDPDEForce.getEquationOfState
    add_type, set_type, get_type = (GenDPDEForce.addTypeEquationOfState, GenDPDEForce.setTypeEquationOfState,
                                    GenDPDEForce.getTypeEquationOfState)

    def setEquationOfState(self, law, parameters=()):
        return set_law(self, *_law_parameters(law, parameters, "GenDPDEForce.setEquationOfState"))

    def getEquationOfState(self):
        law, parameters = get_law(self)
        return [law, _with_law_units(law, parameters)]

    def addTypeEquationOfState(self, type, law, parameters=()):
        return add_type(self, type, *_law_parameters(law, parameters, "GenDPDEForce.addTypeEquationOfState"))

    def setTypeEquationOfState(self, index, type, law, parameters=()):
        return set_type(self, index, type, *_law_parameters(law, parameters, "GenDPDEForce.setTypeEquationOfState"))

    def getTypeEquationOfState(self, index):
        type_, law, parameters = get_type(self, index)
        return [type_, law, _with_law_units(law, parameters)]

    for function, original in ((setEquationOfState, set_law), (getEquationOfState, get_law),
                               (addTypeEquationOfState, add_type), (setTypeEquationOfState, set_type),
                               (getTypeEquationOfState, get_type)):
        function.__doc__ = (original.__doc__ or "") + (
            "\n\nParameters are plain numbers in OpenMM units or Quantities: " + _describe_laws() + ". "
            "Getters return [law, parameters] or [type, law, parameters], the parameters as Quantities.")
        setattr(GenDPDEForce, function.__name__, function)


_wrap_equation_of_state()
GenDPDEForce.getParticleVirials = _particle_virials(GenDPDEForce.getParticleVirials)
add_cast_copy_and_pickle(GenDPDEForce)

GenDPDEIntegrator = _swig.GenDPDEIntegrator
_FRICTION = _unit.amu / _unit.picosecond
_HEAT_CONDUCTION = _unit.kilojoule_per_mole * _unit.kelvin / _unit.picosecond
_HEAT_CAPACITY = _unit.kilojoule_per_mole / _unit.kelvin
accept_units(GenDPDEIntegrator, "__init__", [("stepSize", _unit.picosecond), ("friction", _FRICTION),
                                             ("heatConduction", _HEAT_CONDUCTION), ("heatCapacity", _HEAT_CAPACITY)])
accept_units(GenDPDEIntegrator, "setStepSize", [("size", _unit.picosecond)])   # (getStepSize: openmm.Integrator's)
accept_units(GenDPDEIntegrator, "setFriction", [("friction", _FRICTION)])
return_units(GenDPDEIntegrator, "getFriction", _FRICTION)
accept_units(GenDPDEIntegrator, "setHeatConduction", [("heatConduction", _HEAT_CONDUCTION)])
return_units(GenDPDEIntegrator, "getHeatConduction", _HEAT_CONDUCTION)
accept_units(GenDPDEIntegrator, "setHeatCapacity", [("heatCapacity", _HEAT_CAPACITY)])
return_units(GenDPDEIntegrator, "getHeatCapacity", _HEAT_CAPACITY)
_TYPE_HEAT_CAPACITY = [("type", DIMENSIONLESS), ("heatCapacity", _HEAT_CAPACITY)]
accept_units(GenDPDEIntegrator, "addTypeHeatCapacity", _TYPE_HEAT_CAPACITY)
accept_units(GenDPDEIntegrator, "setTypeHeatCapacity", [("index", DIMENSIONLESS)] + _TYPE_HEAT_CAPACITY)
return_units(GenDPDEIntegrator, "getTypeHeatCapacity", _units_of(_TYPE_HEAT_CAPACITY))
_TYPE_PAIR = [("type1", DIMENSIONLESS), ("type2", DIMENSIONLESS), ("friction", _FRICTION),
              ("heatConduction", _HEAT_CONDUCTION)]
accept_units(GenDPDEIntegrator, "addTypePair", _TYPE_PAIR)
accept_units(GenDPDEIntegrator, "setTypePairParameters", [("index", DIMENSIONLESS)] + _TYPE_PAIR)
return_units(GenDPDEIntegrator, "getTypePairParameters", _units_of(_TYPE_PAIR))
accept_units(GenDPDEIntegrator, "setCutoffDistance", [("distance", _unit.nanometer)])
return_units(GenDPDEIntegrator, "getCutoffDistance", _unit.nanometer)
accept_units(GenDPDEIntegrator, "setTemperature", [("temperature", _unit.kelvin)])
return_units(GenDPDEIntegrator, "getTemperature", _unit.kelvin)
accept_units(GenDPDEIntegrator, "setParticleTemperatures", [("temperatures", _unit.kelvin)])
accept_units(GenDPDEIntegrator, "setInternalEnergies", [("energies", _unit.kilojoule_per_mole)])
accept_units(GenDPDEIntegrator, "setInternalEnergiesToTemperature", [("temperature", _unit.kelvin),
                                                                    ("randomSeed", DIMENSIONLESS)])
return_units(GenDPDEIntegrator, "getConservedEnergy", _unit.kilojoule_per_mole)
return_units(GenDPDEIntegrator, "getParticleTemperatures", _unit.kelvin)
return_units(GenDPDEIntegrator, "getInternalEnergies", _unit.kilojoule_per_mole)
add_cast_copy_and_pickle(GenDPDEIntegrator)


@_dataclasses.dataclass(frozen=True)
class DensityEstimator:
    """One density estimator as the C++ table describes it (GenDPDEDensityEstimators.h): its
    GenDPDEForce.DensityEstimator value, name ('VB'), description, whether f_cut changes it, whether it reads the
    first moments (V-C), and what a suggested time step is multiplied by for it."""
    value: int
    name: str
    description: str
    reads_cutoff_scaling: bool
    needs_moments: bool
    stable_step_factor: float

    @classmethod
    def of(cls, value):
        """The table's entry of a GenDPDEForce.DensityEstimator value (OpenMMException if there is none)."""
        value = int(value)
        return cls(value, _swig.densityEstimatorName(value), _swig.densityEstimatorDescription(value),
                   bool(_swig.densityEstimatorReadsCutoffScaling(value)),
                   bool(_swig.densityEstimatorNeedsMoments(value)), _swig.densityEstimatorStableStepFactor(value))


#: The density estimators in GenDPDEForce.DensityEstimator order, from the C++ table: an estimator added there is
#: known here (to the commands' choices, the model files, repr) without another list.
ESTIMATORS = tuple(DensityEstimator.of(value) for value in range(_swig.numDensityEstimators()))

#: The density estimators, GenDPDEForce's enum value -> name ('VA', 'VB', ...), from ESTIMATORS.
ESTIMATOR_NAMES = {estimator.value: estimator.name for estimator in ESTIMATORS}


def estimator_value(estimator):
    """GenDPDEForce.VA, VB, ... from a name ('VA', 'vb', ...) or the enum value itself (ESTIMATOR_NAMES); ValueError
    naming the estimator and those allowed."""
    values = {name: value for value, name in ESTIMATOR_NAMES.items()}
    listed = ", ".join(f"'{name}'" for name in values)
    if isinstance(estimator, str):
        if estimator.upper() not in values:
            raise ValueError(f"estimator must be one of {listed}, not '{estimator}'")
        return values[estimator.upper()]
    if estimator not in ESTIMATOR_NAMES:
        raise ValueError(f"estimator must be GenDPDEForce.{', '.join(values)}, not {estimator}")
    return estimator


def estimator_of(estimator):
    """The DensityEstimator (ESTIMATORS) of a name or a GenDPDEForce.DensityEstimator value (estimator_value)."""
    return ESTIMATORS[estimator_value(estimator)]


def estimators_reading_cutoff_scaling():
    """The names of the estimators that f_cut changes (the table's reads_cutoff_scaling): those tune-fcut tunes."""
    return [estimator.name for estimator in ESTIMATORS if estimator.reads_cutoff_scaling]


@_dataclasses.dataclass(frozen=True)
class Law:
    """One local equation of state as the C++ table describes it (GenDPDEEquationsOfState.h): its
    GenDPDEForce.EquationOfState value, name ('TaitThermalExpansion'), whether it takes the Tait parameters n0, pi0,
    B_T, gamma_T before its own, and its own parameters ((name, OpenMM unit), ...) in the order setEquationOfState
    takes them, each with its allowed range (minimum, maximum) in that unit."""
    value: int
    name: str
    extends_tait: bool
    parameters: tuple
    ranges: tuple

    @property
    def parameter_names(self):
        return tuple(name for name, _ in self.parameters)

    @classmethod
    def of(cls, value):
        """The table's entry of a GenDPDEForce.EquationOfState value (OpenMMException if there is none)."""
        value = int(value)
        name, extends_tait, parameters = law_description(value)
        ranges = tuple(tuple(_swig.equationOfStateParameterRange(value, k)) for k in range(len(parameters)))
        return cls(value, name, extends_tait, tuple(parameters), ranges)


#: The local equations of state in GenDPDEForce.EquationOfState order, from the C++ table: a law added there is known
#: here (to the model files, the mapping of a fluid, the calibration) without another list.
LAWS = tuple(Law.of(value) for value in range(_swig.numEquationsOfState()))

#: The laws, GenDPDEForce's enum value -> name, from LAWS.
LAW_NAMES = {law.value: law.name for law in LAWS}


def law_value(law):
    """A GenDPDEForce.EquationOfState value from its name (as LAW_NAMES spells it) or the value itself; ValueError
    naming the law and those allowed."""
    values = {name: value for value, name in LAW_NAMES.items()}
    if isinstance(law, str):
        if law not in values:
            raise ValueError(f"equation of state must be one of {', '.join(map(repr, values))}, not {law!r}")
        return values[law]
    if isinstance(law, bool) or law not in LAW_NAMES:
        raise ValueError(f"equation of state must be GenDPDEForce.{', GenDPDEForce.'.join(values)}, not {law!r}")
    return int(law)


def _force_repr(self):
    estimator = ESTIMATOR_NAMES[self.getDensityEstimator()]
    method = "CutoffPeriodic" if self.usesPeriodicBoundaryConditions() else "CutoffNonPeriodic"
    n0, pi0, bulk, gamma = self.getTaitParameters()
    return (f"<GenDPDEForce cutoff={self.getCutoffDistance().value_in_unit(_unit.nanometer):g} nm, {method}, "
            f"estimator={estimator}, cutoffScaling={self.getCutoffScaling():g}, "
            f"Tait(n0={n0.value_in_unit(NUMBER_DENSITY):g} nm^-3, pi0={pi0.value_in_unit(PRESSURE):g}, "
            f"B_T={bulk.value_in_unit(PRESSURE):g} kJ/mol/nm^3, gamma_T={gamma:g})>")


GenDPDEForce.__repr__ = _force_repr


_MODE_NAMES = {GenDPDEIntegrator.Isoenergetic: "Isoenergetic", GenDPDEIntegrator.Isothermal: "Isothermal",
               GenDPDEIntegrator.Conservative: "Conservative"}


def _integrator_repr(self):
    mode = _MODE_NAMES[self.getMode()]
    return (f"<GenDPDEIntegrator {mode}, stepSize={self.getStepSize()}, friction={self.getFriction()}, "
            f"heatConduction={self.getHeatConduction()}, heatCapacity={self.getHeatCapacity()}>")


GenDPDEIntegrator.__repr__ = _integrator_repr
