# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""Makes the SWIG classes behave like OpenMM's own Python classes.

- Arguments accept ``openmm.unit`` quantities or plain numbers in OpenMM units (nm, ps, amu, kJ/mol, K).
  Pressures (Tait parameters) also accept pressure units such as bar or MPa, converted per mole (and pressures per
  kelvin, MPa/K, likewise).
- Getters of parameters and observables return quantities, as OpenMM's getters do; a per-particle result is one
  Quantity holding a numpy array, as ``State.getPositions(asNumpy=True)`` returns.
- ``cast``/``isinstance`` for objects returned by ``System.getForce`` and friends (never taking ownership), and
  ``copy``, ``deepcopy`` and ``pickle`` through ``XmlSerializer`` (the copies own their C++ objects).
"""

import functools
import re

import numpy
from openmm import XmlSerializer, unit

#: Pressure in OpenMM units.
PRESSURE = unit.kilojoule_per_mole / unit.nanometer**3
#: Pressure per temperature in OpenMM units (a thermal pressure coefficient beta = (dpi/dT) at fixed density).
PRESSURE_PER_KELVIN = PRESSURE / unit.kelvin
#: Number density in OpenMM units.
NUMBER_DENSITY = unit.nanometer**-3
#: Marks a dimensionless argument or result (plain float).
DIMENSIONLESS = None


def to_openmm_value(value, target, where):
    """``value`` as a plain number in the OpenMM unit ``target`` (``DIMENSIONLESS`` for a pure number). A Quantity
    holding a list or array, or a list, tuple or object array of Quantities and numbers (one per particle, say),
    becomes a list of plain numbers, each converted; plain numbers (numpy scalars included) pass through."""
    if not unit.is_quantity(value):
        if isinstance(value, (list, tuple)) or (isinstance(value, numpy.ndarray) and value.dtype == object):
            if any(unit.is_quantity(item) for item in value):
                return [to_openmm_value(item, target, f"{where}[{index}]") for index, item in enumerate(value)]
        return value
    if target is DIMENSIONLESS:
        if value.unit.is_dimensionless():
            return value.value_in_unit(unit.dimensionless)
        raise TypeError(f"{where}: expected a dimensionless number, got {value}")
    if value.unit.is_compatible(target):
        return value.value_in_unit(target)
    if target is PRESSURE and value.unit.is_compatible(unit.bar):
        return (value * unit.AVOGADRO_CONSTANT_NA).value_in_unit(target)
    if target is PRESSURE_PER_KELVIN and value.unit.is_compatible(unit.bar / unit.kelvin):
        return (value * unit.AVOGADRO_CONSTANT_NA).value_in_unit(target)
    raise TypeError(f"{where}: {value} cannot be converted to {target}")


def _attach(value, spec):
    """``value`` in the unit ``spec``: a number, or a numpy array (one value per particle), becomes one Quantity
    holding it (never a list of Quantities); a list result with a list of units becomes a list with one unit each;
    a DIMENSIONLESS value stays plain."""
    if spec is DIMENSIONLESS:
        return value
    if isinstance(spec, (list, tuple)):
        return [_attach(v, s) for v, s in zip(value, spec)]
    return unit.Quantity(value, spec)   # a numpy array is held as it is (no copy, no per-item Quantities)


def accept_units(cls, name, arguments):
    """Let ``cls.name`` take quantities. ``arguments`` lists (argument name, OpenMM unit) in positional order;
    further positional arguments (a Context, a list) pass through unchanged."""
    original = getattr(cls, name)
    names = [argument for argument, _ in arguments]
    units = dict(arguments)
    where = f"{cls.__name__}.{name}" if name != "__init__" else cls.__name__

    @functools.wraps(original)
    def method(self, *args, **kwargs):
        converted = [to_openmm_value(value, arguments[i][1], f"{where}({arguments[i][0]})") if i < len(arguments)
                     else value for i, value in enumerate(args)]
        for key, value in kwargs.items():
            if key in units:
                kwargs[key] = to_openmm_value(value, units[key], f"{where}({key})")
            elif key not in names:
                raise TypeError(f"{where}() got an unexpected keyword argument '{key}'")
        # SWIG's proxies take positional arguments only.
        for key in names[len(converted):]:
            if key in kwargs:
                converted.append(kwargs.pop(key))
        return original(self, *converted, **kwargs)

    setattr(cls, name, method)


def return_units(cls, name, spec):
    """Let ``cls.name`` return a quantity in ``spec`` (a unit, or a list of units for a list result); a numpy array
    result becomes ``unit.Quantity(array, spec)``."""
    original = getattr(cls, name)

    @functools.wraps(original)
    def method(self, *args, **kwargs):
        return _attach(original(self, *args, **kwargs), spec)

    setattr(cls, name, method)


def add_cast_copy_and_pickle(cls):
    """Install ``cast``, ``isinstance``, ``__copy__``, ``__deepcopy__`` and pickle support on a SWIG plugin class
    that has the static helpers ``_downcast`` and ``_isinstance``."""

    def cast(obj):
        """This object as a ``{0}``, e.g. a Force from ``System.getForce``. The result never takes over ownership
        of the C++ object (whoever owned it keeps owning it, e.g. the System) and keeps ``obj`` alive."""
        if isinstance(obj, cls):
            return obj
        result = cls._downcast(obj)
        result._cast_source = obj
        return result

    def isinstance_(obj):
        """Whether ``obj`` (e.g. a Force from ``System.getForce``) is a ``{0}``."""
        return cls._isinstance(obj)

    def adopt(temporary):
        """A ``{0}`` that owns the C++ object of ``temporary``, a fresh owning base-class object (from
        XmlSerializer.clone/deserialize) that nothing else refers to."""
        result = cls._downcast(temporary)
        temporary.thisown = False
        result.thisown = True
        return result

    cast.__doc__ = cast.__doc__.format(cls.__name__)
    isinstance_.__doc__ = isinstance_.__doc__.format(cls.__name__)

    def copy(self):
        return adopt(XmlSerializer.clone(self))

    def getstate(self):
        return XmlSerializer.serialize(self)

    def setstate(self, state):
        self.this = adopt(XmlSerializer.deserialize(state)).this

    cls.cast = staticmethod(cast)
    cls.isinstance = staticmethod(isinstance_)
    cls.__copy__ = copy
    cls.__deepcopy__ = lambda self, memo: copy(self)
    cls.__getstate__ = getstate
    cls.__setstate__ = setstate


#: The symbols of the units text of the C++ table of the equations of state (GenDPDEEquationsOfState.h).
UNIT_SYMBOLS = {"kJ": unit.kilojoule, "mol": unit.mole, "nm": unit.nanometer, "K": unit.kelvin,
                 "ps": unit.picosecond, "amu": unit.amu}


def parse_units(text):
    """The OpenMM unit that the table's units text names ("kJ/mol/nm^3/K", "kJ/mol nm^3", "kJ/(mol K)", "nm^-3"; ""
    is DIMENSIONLESS): symbols with integer powers, read left to right, '/' dividing by the next factor and a space
    multiplying by it, parentheses grouping. PRESSURE and PRESSURE_PER_KELVIN come back as themselves (they also
    take per-molecule values in MPa, to_openmm_value)."""
    tokens = re.findall(r"[A-Za-z]+|\^-?[0-9]+|[/()]", text)
    if "".join(tokens) != text.replace(" ", ""):
        raise ValueError(f"units {text!r}: not understood")
    if not tokens:
        return DIMENSIONLESS
    position = 0

    def take():
        nonlocal position
        if position >= len(tokens):
            raise ValueError(f"units {text!r}: incomplete")
        position += 1
        return tokens[position - 1]

    def factor():
        token = take()
        if token == "(":
            value = product()
            if take() != ")":
                raise ValueError(f"units {text!r}: unbalanced parentheses")
        elif token in UNIT_SYMBOLS:
            value = UNIT_SYMBOLS[token]
        else:
            raise ValueError(f"units {text!r}: unknown symbol {token!r}")
        if position < len(tokens) and tokens[position].startswith("^"):
            value = value ** int(take()[1:])
        return value

    def product():
        value = factor()
        while position < len(tokens) and tokens[position] != ")":
            if tokens[position] == "/":
                take()
                value = value / factor()
            else:
                value = value * factor()
        return value

    result = product()
    if position != len(tokens):
        raise ValueError(f"units {text!r}: unbalanced parentheses")
    for known in (PRESSURE, PRESSURE_PER_KELVIN, NUMBER_DENSITY):
        if result == known:
            return known
    return result
