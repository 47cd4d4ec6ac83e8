# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""A fluid's physical properties at one state point (Fluid), each an openmm.unit Quantity, checked and converted to
OpenMM units (per molecule in SI, or per mole); models.fluid maps them onto a model (coarse_grain)."""

import dataclasses
import math
import numbers

from openmm import unit

from ..units import BOLTZMANN

#: The OpenMM units of the parameters (plain floats in GenDPDEParameters).
FRICTION = unit.amu / unit.picosecond
HEAT_CONDUCTION = unit.kilojoule_per_mole * unit.kelvin / unit.picosecond
PRESSURE = unit.kilojoule_per_mole / unit.nanometer**3
VISCOSITY = unit.amu / (unit.nanometer * unit.picosecond)
CONDUCTIVITY = unit.kilojoule_per_mole / (unit.picosecond * unit.nanometer * unit.kelvin)
HEAT_CAPACITY = unit.kilojoule_per_mole / unit.kelvin


MASS_DENSITY = unit.amu / unit.nanometer**3
MOLAR_MASS = unit.gram / unit.mole
COMPRESSIBILITY = PRESSURE**-1


def amount_power(unit_):
    """The power of the amount of substance (mol) in an openmm.unit Unit: -1 for kJ/mol, 1 for a compressibility in
    OpenMM units (nm^3 mol/kJ), 0 for a temperature or an SI unit per molecule (Pa, J/K)."""
    return int(round(sum(power for dimension, power in unit_.iter_base_dimensions() if dimension.name == "amount")))


def _in_openmm(quantity, target, name):
    """A Quantity in ``target`` (an OpenMM unit): directly if compatible; else, where ``target`` is per mole (OpenMM's
    energies, pressures and masses are) and the quantity per molecule (SI: J, Pa, W, kg, 1/Pa ...: no mol in its
    unit), made per mole (times Avogadro's number, or divided by it for the inverse of an energy, such as a
    compressibility). Nothing else: a property with no mol in its unit (a temperature, a thermal expansion coefficient,
    a speed) takes only a compatible unit, and a quantity per mole is not made per molecule. Raises ValueError naming
    the property if neither works."""
    if not unit.is_quantity(quantity):
        raise ValueError(f"{name} = {quantity!r} needs a unit (an openmm.unit Quantity compatible with {target})")
    if quantity.unit.is_compatible(target):
        return quantity.value_in_unit(target)
    moles = amount_power(target)
    if moles and not amount_power(quantity.unit):
        per_mole = quantity * unit.AVOGADRO_CONSTANT_NA ** -moles
        if per_mole.unit.is_compatible(target):
            return per_mole.value_in_unit(target)
    raise ValueError(f"{name} = {quantity} is not compatible with {target}"
                     + (" (per mole, or per molecule in SI)" if moles else ""))


def _positive(name, value, given=None):
    """``value`` if it is a finite number > 0, else ValueError naming ``name`` and the value as ``given``."""
    if not (isinstance(value, numbers.Real) and math.isfinite(value) and value > 0):
        raise ValueError(f"{name} = {value if given is None else given} is not allowed; it must be finite and > 0")
    return value


def heat_capacity_per_molecule(value):
    """c_v per molecule in kJ/mol/K from a Quantity per molecule (J/K), per mole of molecules (J/(mol K),
    kJ/mol/K), or a plain number in units of k_B; ValueError unless it is finite and > 0."""
    if unit.is_quantity(value):
        per_molecule = _in_openmm(value, HEAT_CAPACITY, "heat_capacity")
    else:
        per_molecule = value * BOLTZMANN.value_in_unit(HEAT_CAPACITY) if isinstance(value, numbers.Real) else None
    return _positive("heat_capacity", per_molecule, value)


#: gamma_T of a Fluid that gives neither tait_exponent nor bulk_modulus_derivative: 7, the exponent of the Tait
#: equation commonly used for water (a model choice, not a measured property).
DEFAULT_TAIT_EXPONENT = 7.0
#: The OpenMM units of a Fluid's properties (heat_capacity and tait_exponent aside).
_PROPERTY_UNITS = {"temperature": unit.kelvin, "pressure": PRESSURE, "mass_density": MASS_DENSITY,
                   "compressibility": COMPRESSIBILITY, "shear_viscosity": VISCOSITY,
                   "thermal_conductivity": CONDUCTIVITY, "molar_mass": MOLAR_MASS}
#: The OpenMM units of the optional properties.
_OPTIONAL_PROPERTY_UNITS = {"self_diffusion": unit.nanometer**2 / unit.picosecond,
                            "speed_of_sound": unit.nanometer / unit.picosecond,
                            "surface_tension": unit.kilojoule_per_mole / unit.nanometer**2,
                            "thermal_expansion": unit.kelvin**-1}
#: The OpenMM unit of every property with a unit (heat_capacity also takes a plain number in k_B).
PROPERTY_UNITS = {**_PROPERTY_UNITS, "heat_capacity": HEAT_CAPACITY, **_OPTIONAL_PROPERTY_UNITS}


@dataclasses.dataclass(frozen=True)
class Fluid:
    """A fluid at one state point; every property an openmm.unit Quantity in any compatible unit (SI per molecule,
    or per mole), except heat_capacity, which may also be a number in k_B per molecule. Every property must be
    finite and > 0 but the pressure (finite, of either sign), and tait_exponent > 1: a Fluid that is not raises
    ValueError naming the property, its value and what is allowed. The optional properties (self_diffusion,
    speed_of_sound, surface_tension) are not fitted, only measured back; None where not known.

    gamma_T (tait_exponent) is the fluid's (dK_T/dP)_T where that is given (bulk_modulus_derivative, a plain number:
    the Tait law's K = n dP/dn = gamma_T B_T (n/n0)^gamma_T has dK/dP = gamma_T exactly), else tait_exponent as
    given, else DEFAULT_TAIT_EXPONENT (7); both given must be equal."""
    name: str
    temperature: unit.Quantity            # T0
    pressure: unit.Quantity               # P0
    mass_density: unit.Quantity           # rho
    compressibility: unit.Quantity        # isothermal, kappa_T
    heat_capacity: object                 # isochoric, per molecule (c_v)
    shear_viscosity: unit.Quantity        # eta
    thermal_conductivity: unit.Quantity   # lambda
    molar_mass: unit.Quantity             # M
    tait_exponent: float = None           # gamma_T of the Tait equation (None: bulk_modulus_derivative, else 7)
    self_diffusion: unit.Quantity = None  # the molecules' self-diffusion coefficient: not fitted, measured back
    speed_of_sound: unit.Quantity = None  # not fitted: compared with the model's (from its measured n dP/dn)
    surface_tension: unit.Quantity = None  # liquid-vapour; not fitted: compared with a slab's (`slab`)
    thermal_expansion: unit.Quantity = None  # alpha (1/K): if given, the model's law is TaitThermalExpansion
    bulk_modulus_derivative: float = None  # (dK_T/dP)_T, a measured property: if given, gamma_T is it

    def __post_init__(self):
        derivative = self.bulk_modulus_derivative
        if derivative is not None:
            if isinstance(derivative, bool) or not (isinstance(derivative, numbers.Real) and 1 < derivative < math.inf):
                raise ValueError(f"bulk_modulus_derivative = {derivative!r} is not allowed; it must be a finite "
                                 f"number > 1 (the fluid's (dK_T/dP)_T, which the Tait exponent gamma_T is)")
            if self.tait_exponent is not None and self.tait_exponent != derivative:
                raise ValueError(f"tait_exponent = {self.tait_exponent!r} is not allowed with bulk_modulus_derivative "
                                 f"= {derivative!r}: gamma_T is the fluid's (dK_T/dP)_T (the Tait law's dK/dP); give "
                                 f"one of them, or both equal")
        if self.tait_exponent is None:
            object.__setattr__(self, "tait_exponent", DEFAULT_TAIT_EXPONENT if derivative is None else derivative)
        self.in_openmm()

    def in_openmm(self):
        """The properties as plain floats in OpenMM units (temperature K, pressure kJ/mol/nm^3, mass_density
        amu/nm^3, compressibility nm^3 mol/kJ, shear_viscosity amu/(nm ps), thermal_conductivity kJ/(mol ps nm K),
        molar_mass g/mol, heat_capacity kJ/mol/K per molecule, tait_exponent, and self_diffusion nm^2/ps if
        given, speed_of_sound nm/ps if given, surface_tension kJ/mol/nm^2 if given), checked as the class says."""
        values = {}
        for name, target in _PROPERTY_UNITS.items():
            given = getattr(self, name)
            values[name] = _in_openmm(given, target, name)
            if name != "pressure":
                _positive(name, values[name], given)
            elif not math.isfinite(values[name]):
                raise ValueError(f"pressure = {given} is not allowed; it must be finite")
        values["heat_capacity"] = heat_capacity_per_molecule(self.heat_capacity)
        if not (isinstance(self.tait_exponent, numbers.Real) and 1 < self.tait_exponent < math.inf):
            raise ValueError(f"tait_exponent = {self.tait_exponent} is not allowed; it must be finite and > 1")
        values["tait_exponent"] = self.tait_exponent
        for name, target in _OPTIONAL_PROPERTY_UNITS.items():
            if getattr(self, name) is not None:
                values[name] = _positive(name, _in_openmm(getattr(self, name), target, name), getattr(self, name))
        return values
