# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""Fluids and calibrated models as files (TOML or JSON), so that any fluid can be set up without writing Python and a
calibrated model can be built again (docs/fluids.md, "Fluid files").

A fluid file holds the properties of a Fluid, each a string "value unit" in the syntax of pint (the units library
of the scientific Python stack: "997.05 kg/m^3", "0.4525e-9 1/Pa", "74.44 J/(mol K)", "0.89 mPa s",
"0.6065 W/(m K)", "18.015 g/mol"; per molecule or per mole, as a Fluid takes them), except heat_capacity, which may
also be a plain number in k_B per molecule, and tait_exponent and bulk_modulus_derivative ((dK_T/dP)_T: gamma_T is
it where given, properties.Fluid), plain numbers; self_diffusion (m^2/s),
speed_of_sound (m/s) and surface_tension (N/m, liquid-vapour) are optional, properties the model is not fitted to
that calibrate (surface_tension: slab) measures back:

    name = "liquid methanol, 298.15 K, 0.1 MPa"
    temperature = "298.15 K"
    ...

A model file (``save_parameters``) holds the fluid in a table [fluid] (SI units) and every parameter of the model
in a table [parameters] (plain numbers in OpenMM units, written so that they read back to the last bit):
``load_parameters`` returns the same GenDPDEParameters, whose ``liquid()`` builds the same System. ``load_fluid``
reads either kind.
"""

import json
import math
import numbers
import os
import re

import openmm
import tomllib
from openmm import unit

from ..api import ESTIMATOR_NAMES, LAW_NAMES, LAWS, GenDPDEForce, law_value
from ..internal.files import atomic_write
from .fluid import (
    ARGON,
    ARGON_EXPANDING,
    PROPERTY_UNITS,
    SUPERCRITICAL_ARGON,
    WATER,
    Fluid,
    GenDPDEParameters,
    _in_openmm,
    amount_power,
)

#: The format key of the model files this version writes. Format 3 records the equation of state as any law of the
#: table with its parameters by name (equation_of_state_parameters); format 2 recorded the estimator that f_cut was
#: tuned for and the law, Tait or the thermal Tait law (its two parameters as thermal_pressure and
#: thermal_reference_temperature); format 1 neither (its estimator unknown, None). All three are read.
MODEL_FORMAT = "openmmgendpde-model-3"
#: Every format this version reads, oldest first.
MODEL_FORMATS = ("openmmgendpde-model-1", "openmmgendpde-model-2", MODEL_FORMAT)
#: The parameters of a model file that are names, not numbers, and the names each allows (the core's tables).
_NAMED_PARAMETERS = {"estimator": tuple(ESTIMATOR_NAMES.values()), "equation_of_state": tuple(LAW_NAMES.values())}
#: The table of a format-3 file that holds the law's parameters by the names of the table of laws.
_LAW_PARAMETERS = "equation_of_state_parameters"
#: The names formats 1 and 2 gave the two parameters of their one law with parameters (beta and theta0).
_OLD_LAW_PARAMETERS = ("thermal_pressure", "thermal_reference_temperature")

#: The properties of a Fluid with a unit, and the SI unit a model file writes each in (pint syntax, openmm.unit).
_SI_UNITS = {
    "temperature": ("K", unit.kelvin),
    "pressure": ("Pa", unit.pascal),
    "mass_density": ("kg/m^3", unit.kilogram / unit.meter**3),
    "compressibility": ("1/Pa", unit.pascal**-1),
    "heat_capacity": ("J/(mol K)", unit.joule / (unit.mole * unit.kelvin)),
    "shear_viscosity": ("Pa s", unit.pascal * unit.second),
    "thermal_conductivity": ("W/(m K)", unit.watt / (unit.meter * unit.kelvin)),
    "molar_mass": ("g/mol", unit.gram / unit.mole),
}
#: Optional properties (not fitted; measured back beside the targets) and their SI units.
_OPTIONAL_UNITS = {"self_diffusion": ("m^2/s", unit.meter**2 / unit.second),
                   "speed_of_sound": ("m/s", unit.meter / unit.second),
                   "surface_tension": ("N/m", unit.newton / unit.meter),
                   "thermal_expansion": ("1/K", unit.kelvin**-1)}   # (if given, the law is TaitThermalExpansion)
#: pint's base units and openmm.unit's.
_BASE_UNITS = {"kilogram": unit.kilogram, "meter": unit.meter, "second": unit.second, "mole": unit.mole,
               "kelvin": unit.kelvin}
#: The numbers of GenDPDEParameters that a model file may hold but need not (None: absent).
_OPTIONAL_PARAMETERS = ["background_pressure"]
#: The numbers of GenDPDEParameters that a model file holds, in order (the fluid, the law and the optional ones aside).
_PARAMETERS = ["molecules_per_particle", "mass", "temperature", "density", "reference_pressure", "bulk_modulus",
               "tait_exponent", "cutoff", "neighbors", "cutoff_scaling", "friction", "heat_conduction", "heat_capacity"]


#: One quantity: a number (digits, an optional decimal point and exponent; no nan or inf) then its unit.
_QUANTITY = re.compile(r"\s*([+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?)\s*(.*?)\s*")
_EXAMPLES = "e.g. '298.15 K', '0.1 MPa', '997.05 kg/m^3'"


def quantity(text, name="quantity"):
    """An openmm.unit Quantity (SI base units) from a string "value unit": one number followed by a unit in pint's
    syntax (no expression: '298.15 K + 5 K' and '2 * 150 K' are refused); ValueError naming ``name``, the text and
    what is allowed if it cannot be read or has a unit that is not made of kg, m, s, mol and K."""
    import pint  # imported here: only the file readers need it
    registry = _registry(pint)
    if not isinstance(text, str):
        raise ValueError(f"{name} = {text!r} is not allowed; it must be a string 'value unit', {_EXAMPLES}")
    match = _QUANTITY.fullmatch(text)
    if match is None:
        raise ValueError(f"{name} = {text!r} is not allowed; it must be one number followed by its unit (no "
                         f"expression), {_EXAMPLES}")
    try:
        parsed = (float(match.group(1)) * registry.Unit(match.group(2))).to_base_units()
    except Exception as error:   # pint raises several kinds; all mean the same to a user
        raise ValueError(f"{name} = {text!r} cannot be read as 'value unit' ({type(error).__name__}: "
                         f"{' '.join(str(error).split())}); it must be one number followed by its unit (no "
                         f"expression; K, not degC), {_EXAMPLES}") from None
    magnitude = parsed.magnitude
    if not (isinstance(magnitude, numbers.Real) and math.isfinite(magnitude)):
        raise ValueError(f"{name} = {text!r} is not allowed; its value must be a finite number")
    result = (float(magnitude) + 0.0) * unit.dimensionless   # (+ 0.0: -0.0 reads as 0.0; its sign means nothing)
    for base, exponent in parsed.unit_items():
        if base not in _BASE_UNITS:
            raise ValueError(f"{name} = {text!r} is not allowed; its unit may use only mass, length, time, amount "
                             f"of substance and temperature (found {base})")
        result = result * _BASE_UNITS[base] ** exponent
    return result


_REGISTRY = []


def _registry(pint):
    if not _REGISTRY:
        _REGISTRY.append(pint.UnitRegistry())
    return _REGISTRY[0]


def _read(path):
    """The table in a TOML (.toml) or JSON (.json) file."""
    extension = os.path.splitext(path)[1].lower()
    try:
        if extension == ".toml":
            with open(path, "rb") as stream:
                return tomllib.load(stream)
        if extension == ".json":
            with open(path, encoding="utf-8") as stream:
                return json.load(stream)
    except (tomllib.TOMLDecodeError, json.JSONDecodeError) as error:
        raise ValueError(f"{path}: not a valid {extension[1:].upper()} file: {error}") from None
    except UnicodeDecodeError as error:   # (TOML and JSON files are UTF-8 text)
        raise ValueError(f"{path}: not a valid {extension[1:].upper()} file: it must be UTF-8 text (byte "
                         f"{error.object[error.start:error.start + 1]!r} at offset {error.start} is not)") from None
    raise ValueError(f"{path}: a fluid file must be .toml or .json")


def fluid_from_table(table, source="fluid"):
    """A Fluid from a table (dict) of a fluid file; ValueError naming ``source`` and the bad entry."""
    if not isinstance(table, dict):
        raise ValueError(f"{source}: expected a table of properties, got {type(table).__name__}")
    known = set(_SI_UNITS) | set(_OPTIONAL_UNITS) | {"name", "tait_exponent", "bulk_modulus_derivative"}
    unknown = sorted(set(table) - known)
    if unknown:
        raise ValueError(f"{source}: unknown entries {unknown}; a fluid has {sorted(known)}")
    missing = sorted(set(_SI_UNITS) - set(table) | ({"name"} - set(table)))
    if missing:
        raise ValueError(f"{source}: missing {missing}")
    values = {"name": str(table["name"])}
    units = dict(_SI_UNITS, **_OPTIONAL_UNITS)
    try:
        for name in [name for name in units if name in table]:
            given = table[name]
            if name == "heat_capacity" and isinstance(given, numbers.Real) and not isinstance(given, bool):
                values[name] = float(given)   # in k_B per molecule
            else:
                values[name] = quantity(given, name)
                try:
                    _in_openmm(values[name], PROPERTY_UNITS[name], name)
                except ValueError:
                    molar = amount_power(PROPERTY_UNITS[name]) != 0
                    raise ValueError(f"{name} = {given!r} is not allowed; its unit must be compatible with "
                                     f"{units[name][0]}" + (" (per molecule or per mole)" if molar else
                                                            " (not per mole: the property is not molar)")) from None
        for name in ("tait_exponent", "bulk_modulus_derivative"):
            if name in table:
                exponent = table[name]
                if isinstance(exponent, bool) or not isinstance(exponent, numbers.Real):
                    raise ValueError(f"{name} = {exponent!r} is not allowed; it must be a number > 1")
                values[name] = float(exponent)
        return Fluid(**values)
    except ValueError as error:
        raise ValueError(f"{source}: {error}") from None


def load_fluid(path):
    """The Fluid of a fluid file, or of the [fluid] table of a model file (save_parameters)."""
    table = _read(path)
    if "format" in table:
        _check_model(table, path)
        return fluid_from_table(table["fluid"], f"{path} [fluid]")
    return fluid_from_table(table, path)


def fluid_table(fluid):
    """A Fluid as the table of a fluid file: each property as 'value unit' in SI (per mole where molar)."""
    table = {"name": fluid.name}
    for name, (text, target) in dict(_SI_UNITS, **_OPTIONAL_UNITS).items():
        given = getattr(fluid, name)
        if given is None:
            continue
        if name == "heat_capacity" and not unit.is_quantity(given):
            table[name] = float(given)
        else:
            table[name] = f"{_in_si(given, name, target)!r} {text}"
    table["tait_exponent"] = float(fluid.tait_exponent)
    if fluid.bulk_modulus_derivative is not None:
        table["bulk_modulus_derivative"] = float(fluid.bulk_modulus_derivative)
    return table


def _in_si(given, name, target):
    """A Fluid's property ``name`` (checked as Fluid checks it: _in_openmm into its OpenMM unit) in the SI unit
    ``target``, made per molecule where the OpenMM unit is per mole and the SI one is not (Pa, 1/Pa, W/(m K))."""
    openmm_unit = PROPERTY_UNITS[name]
    value = _in_openmm(given, openmm_unit, name) * openmm_unit
    return (value * unit.AVOGADRO_CONSTANT_NA ** (amount_power(openmm_unit) - amount_power(target))).value_in_unit(
        target)


def save_parameters(parameters, path, comment=None):
    """Write a model file (TOML or JSON by the extension of ``path``): the fluid and every parameter, so that
    load_parameters(path) returns the same parameters. ``comment``: lines written at the top of a TOML file (e.g.
    how the model was calibrated)."""
    model = {name: float(getattr(parameters, name)) for name in _PARAMETERS}
    for name in _OPTIONAL_PARAMETERS:
        if getattr(parameters, name) is not None:
            model[name] = float(getattr(parameters, name))
    if parameters.estimator is not None:
        model["estimator"] = parameters.estimator
    model["equation_of_state"] = parameters.equation_of_state
    model[_LAW_PARAMETERS] = dict(zip(LAWS[parameters.law].parameter_names, parameters.law_parameters))
    extension = os.path.splitext(path)[1].lower()
    if extension == ".json":
        with atomic_write(path) as stream:
            json.dump({"format": MODEL_FORMAT, "fluid": fluid_table(parameters.fluid), "parameters": model},
                      stream, indent=1)
        return
    if extension != ".toml":
        raise ValueError(f"{path}: a model file must be .toml or .json")
    lines = [f"# {line}" for line in (comment or "").splitlines()]
    lines += [f'format = "{MODEL_FORMAT}"', "", "# The fluid (SI units; the targets of the model).", "[fluid]"]
    lines += [f"{name} = {_toml_value(value)}" for name, value in fluid_table(parameters.fluid).items()]
    lines += ["", "# The model (OpenMM units: nm, amu, ps, kJ/mol, K; see GenDPDEParameters).", "[parameters]"]
    lines += [f"{name} = {_toml_value(value)}" for name, value in model.items()]
    with atomic_write(path) as stream:   # (a model file is complete or absent, never half written)
        stream.write("\n".join(lines) + "\n")


def _toml_value(value):
    if isinstance(value, dict):   # (an inline table of numbers)
        return "{" + ", ".join(f"{name} = {value!r}" for name, value in value.items()) + "}"
    return json.dumps(value) if isinstance(value, str) else repr(value)


def _check_model(table, path):
    given = table.get("format") if isinstance(table, dict) else None
    if given not in MODEL_FORMATS:
        raise ValueError(f"{path}: format = {given!r} is not a model file this version reads "
                         f"({' or '.join(map(repr, MODEL_FORMATS))})")
    for key in ("fluid", "parameters"):
        if not isinstance(table.get(key), dict):
            raise ValueError(f"{path}: a model file needs a table [{key}]")


def load_parameters(path):
    """The GenDPDEParameters of a model file written by save_parameters (any format of MODEL_FORMATS); ValueError
    naming what is wrong."""
    table = _read(path)
    _check_model(table, path)
    fluid = fluid_from_table(table["fluid"], f"{path} [fluid]")
    given, version = table["parameters"], MODEL_FORMATS.index(table["format"])
    where = f"{path} [parameters]"
    law_keys = {0: list(_OLD_LAW_PARAMETERS), 1: list(_NAMED_PARAMETERS) + list(_OLD_LAW_PARAMETERS),
                2: list(_NAMED_PARAMETERS) + [_LAW_PARAMETERS]}[version]
    missing = sorted(set(_PARAMETERS) - set(given))
    unknown = sorted(set(given) - set(_PARAMETERS) - set(_OPTIONAL_PARAMETERS) - set(law_keys))
    if missing or unknown:
        raise ValueError(f"{where}: " + "; ".join(
            part for part in (f"missing {missing}" if missing else "", f"unknown {unknown}" if unknown else "")
            if part))
    values = {name: _number(given, name, where) for name in _PARAMETERS + _OPTIONAL_PARAMETERS if name in given}
    for name, allowed in _NAMED_PARAMETERS.items():
        if name in given and given[name] not in allowed:
            raise ValueError(f"{where}: {name} = {given[name]!r} is not allowed; it must be one of "
                             f"{', '.join(map(repr, allowed))}")
    law, law_parameters = (_law(given, where) if version == 2 else _old_law(given, version, where))
    return GenDPDEParameters(fluid=fluid, estimator=given.get("estimator"), law=law, law_parameters=law_parameters,
                             **values)


def _number(given, name, where):
    """given[name] as a float: finite, and > 0 but for the reference pressure (-0.0 read as 0.0); ValueError naming
    it."""
    value = given[name]
    if isinstance(value, bool) or not isinstance(value, numbers.Real) or not math.isfinite(value):
        raise ValueError(f"{where}: {name} = {value!r} is not allowed; it must be a finite number")
    if name != "reference_pressure" and not value > 0:
        raise ValueError(f"{where}: {name} = {value!r} is not allowed; it must be > 0")
    return float(value) + 0.0


def _law(given, where):
    """(law, its parameters) of a format-3 file: equation_of_state (a name of the table of laws) and its parameters
    by name, each a finite number within the range GenDPDEForce allows (its own check, through a force)."""
    absent = [name for name in ("equation_of_state", _LAW_PARAMETERS) if name not in given]
    if absent:
        raise ValueError(f"{where}: missing {absent}")
    law = LAWS[law_value(given["equation_of_state"])]
    table = given[_LAW_PARAMETERS]
    if not isinstance(table, dict) or sorted(table) != sorted(law.parameter_names):
        raise ValueError(f"{where}: {_LAW_PARAMETERS} = {table!r} is not allowed; the law {law.name} takes "
                         f"{list(law.parameter_names) or 'no parameters'}")
    return law.value, _checked_law(law, [_signed(table, name, f"{where} {_LAW_PARAMETERS}")
                                         for name in law.parameter_names], where)


def _old_law(given, version, where):
    """(law, its parameters) of a file of format 1 or 2: the law named (format 2) or the one its parameters, if any,
    belong to, which formats 1 and 2 wrote as thermal_pressure and thermal_reference_temperature."""
    values = [_signed(given, name, where) for name in _OLD_LAW_PARAMETERS if name in given]
    law = LAWS[law_value(given["equation_of_state"]) if version == 1 and "equation_of_state" in given else
               next(entry.value for entry in LAWS if len(entry.parameters) == len(values) and entry.extends_tait)]
    if len(values) != len(law.parameters):
        raise ValueError(f"{where}: equation_of_state = {law.name!r} does not match the parameters given "
                         f"({', '.join(_OLD_LAW_PARAMETERS)}: the parameters of the thermal Tait law, which this "
                         f"format writes for that law only)")
    return law.value, _checked_law(law, values, where)


def _signed(table, name, where):
    value = table[name]
    if isinstance(value, bool) or not isinstance(value, numbers.Real) or not math.isfinite(value):
        raise ValueError(f"{where}: {name} = {value!r} is not allowed; it must be a finite number")
    return float(value) + 0.0   # (-0.0 read as 0.0: the sign of a zero means nothing)


def _checked_law(law, values, where):
    """``values`` if GenDPDEForce takes them for ``law`` (its check names the parameter and its range), else
    ValueError naming the file."""
    try:
        GenDPDEForce(1.0).setEquationOfState(law.value, values)
    except openmm.OpenMMException as error:
        raise ValueError(f"{where}: {' '.join(str(error).split())}") from None
    return tuple(values)


FLUIDS = {"water": WATER, "argon": ARGON, "argon-expanding": ARGON_EXPANDING,
          "supercritical-argon": SUPERCRITICAL_ARGON}


def fluid_named(name):
    """A built-in fluid by name, or the Fluid of a fluid or model file (.toml, .json; fluid_files); ValueError
    saying what is allowed."""
    if name in FLUIDS:
        return FLUIDS[name]
    if os.path.splitext(name)[1].lower() in (".toml", ".json"):
        if not os.path.isfile(name):
            raise ValueError(f"--fluid {name}: no such file")
        return load_fluid(name)
    raise ValueError(f"--fluid {name} is not allowed; give one of {', '.join(sorted(FLUIDS))} or a fluid file "
                     f"(.toml or .json, docs/fluids.md)")
