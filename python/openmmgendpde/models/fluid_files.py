"""Fluids and calibrated models as files (TOML or JSON), so that any fluid can be set up without writing Python and a
calibrated model can be built again (docs/fluids.md, "Fluid files").

A fluid file holds the properties of a Fluid, each a string "value unit" in the syntax of pint (the units library
of the scientific Python stack: "997.05 kg/m^3", "0.4525e-9 1/Pa", "74.44 J/(mol K)", "0.89 mPa s",
"0.6065 W/(m K)", "18.015 g/mol"; per molecule or per mole, as a Fluid takes them), except heat_capacity, which may
also be a plain number in k_B per molecule, and tait_exponent, a plain number; self_diffusion (m^2/s),
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

import tomllib
from openmm import unit

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

#: The format key of the model files this version writes. Format 2 records the estimator that f_cut was tuned for and
#: the equation of state; format 1 files (without them) are still read, their estimator unknown (None).
MODEL_FORMAT = "openmmgendpde-model-2"
#: Every format this version reads.
MODEL_FORMATS = ("openmmgendpde-model-1", MODEL_FORMAT)
#: The parameters of a model file that are names, not numbers, and the names each allows.
_NAMED_PARAMETERS = {"estimator": ("VA", "VB", "VC"), "equation_of_state": ("Tait", "TaitThermalExpansion")}

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
#: The parameters of GenDPDEParameters that a model file may hold but need not (None: absent): those of a law that
#: depends on temperature.
_OPTIONAL_PARAMETERS = ["thermal_pressure", "thermal_reference_temperature", "background_pressure"]
#: The parameters of GenDPDEParameters that a model file holds, in order (the fluid and the optional ones aside).
_PARAMETERS = [field for field in GenDPDEParameters.__dataclass_fields__
               if field not in ("fluid", *_OPTIONAL_PARAMETERS, *_NAMED_PARAMETERS)]


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
    result = float(magnitude) * unit.dimensionless
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
            with open(path) as stream:
                return json.load(stream)
    except (tomllib.TOMLDecodeError, json.JSONDecodeError) as error:
        raise ValueError(f"{path}: not a valid {extension[1:].upper()} file: {error}") from None
    raise ValueError(f"{path}: a fluid file must be .toml or .json")


def fluid_from_table(table, source="fluid"):
    """A Fluid from a table (dict) of a fluid file; ValueError naming ``source`` and the bad entry."""
    if not isinstance(table, dict):
        raise ValueError(f"{source}: expected a table of properties, got {type(table).__name__}")
    known = set(_SI_UNITS) | set(_OPTIONAL_UNITS) | {"name", "tait_exponent"}
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
        if "tait_exponent" in table:
            exponent = table["tait_exponent"]
            if isinstance(exponent, bool) or not isinstance(exponent, numbers.Real):
                raise ValueError(f"tait_exponent = {exponent!r} is not allowed; it must be a number > 1")
            values["tait_exponent"] = float(exponent)
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
    """The GenDPDEParameters of a model file written by save_parameters; ValueError naming what is wrong."""
    table = _read(path)
    _check_model(table, path)
    fluid = fluid_from_table(table["fluid"], f"{path} [fluid]")
    given = table["parameters"]
    missing = sorted(set(_PARAMETERS) - set(given))
    named = _NAMED_PARAMETERS if table["format"] != MODEL_FORMATS[0] else {}
    unknown = sorted(set(given) - set(_PARAMETERS) - set(_OPTIONAL_PARAMETERS) - set(named))
    if missing or unknown:
        raise ValueError(f"{path} [parameters]: " + "; ".join(
            part for part in (f"missing {missing}" if missing else "", f"unknown {unknown}" if unknown else "")
            if part))
    values = {}
    for name in _PARAMETERS + [name for name in _OPTIONAL_PARAMETERS if name in given]:
        value = given[name]
        if isinstance(value, bool) or not isinstance(value, numbers.Real) or not math.isfinite(value):
            raise ValueError(f"{path} [parameters]: {name} = {value!r} is not allowed; it must be a finite number")
        if name != "reference_pressure" and not value > 0:
            raise ValueError(f"{path} [parameters]: {name} = {value!r} is not allowed; it must be > 0")
        values[name] = float(value)
    for name, allowed in named.items():
        if name in given and given[name] not in allowed:
            raise ValueError(f"{path} [parameters]: {name} = {given[name]!r} is not allowed; it must be one of "
                             f"{', '.join(map(repr, allowed))}")
    parameters = GenDPDEParameters(fluid=fluid, estimator=given.get("estimator"), **values)
    law = given.get("equation_of_state", parameters.equation_of_state)
    if law != parameters.equation_of_state:
        raise ValueError(f"{path} [parameters]: equation_of_state = {law!r} does not match the parameters given "
                         f"(TaitThermalExpansion needs thermal_pressure and thermal_reference_temperature, Tait "
                         f"neither)")
    return parameters


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
