# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""Reduced GenDPDE units (mass, length, energy; k_B = 1) and their conversion to OpenMM units.

>>> from openmmgendpde.units import ARGON_UNITS
>>> ARGON_UNITS.to_openmm(0.011054, "temperature")          # T0* of liquid argon
Quantity(value=125.7..., unit=kelvin)
>>> ARGON_UNITS.from_openmm(125.7 * unit.kelvin, "temperature")
0.01105...
"""

import math

from openmm import unit

from .gendpde import LiquidArgon as _Model

#: Boltzmann's constant in OpenMM units (kJ/mol/K), the value OpenMM itself uses.
BOLTZMANN = (unit.BOLTZMANN_CONSTANT_kB * unit.AVOGADRO_CONSTANT_NA).in_units_of(unit.kilojoule_per_mole / unit.kelvin)

#: The OpenMM unit of every kind of quantity the conversions know.
OPENMM_UNITS = {
    "mass": unit.amu,
    "length": unit.nanometer,
    "energy": unit.kilojoule_per_mole,
    "time": unit.picosecond,
    "temperature": unit.kelvin,
    "velocity": unit.nanometer / unit.picosecond,
    "force": unit.kilojoule_per_mole / unit.nanometer,
    "pressure": unit.kilojoule_per_mole / unit.nanometer**3,
    "number_density": unit.nanometer**-3,
    "volume": unit.nanometer**3,
    "friction": unit.amu / unit.picosecond,
    "heat_conduction": unit.kilojoule_per_mole * unit.kelvin / unit.picosecond,
    "heat_capacity": unit.kilojoule_per_mole / unit.kelvin,
    "surface_tension": unit.kilojoule_per_mole / unit.nanometer**2,
}


def _per_mole(quantity, target):
    """A per-particle SI value (kg, J) or a per-mole value, as a per-mole quantity in ``target``."""
    if quantity.unit.is_compatible(target):
        return quantity.in_units_of(target)
    return (quantity * unit.AVOGADRO_CONSTANT_NA).in_units_of(target)


class ReducedUnits:
    """A reduced unit system defined by the mass m of one particle, a length L and an energy u, with k_B = 1.

    Derived units: time L sqrt(m/u), temperature u/k_B, pressure u/L^3, number density 1/L^3, friction m/time,
    heat conduction u (u/k_B)/time, heat capacity k_B, surface tension u/L^2. ``mass`` and ``energy`` may be given
    per particle (kg, J) or per mole (amu, kJ/mol).
    """

    def __init__(self, mass, length, energy):
        self.mass = _per_mole(mass, unit.amu)
        self.length = length.in_units_of(unit.nanometer)
        self.energy = _per_mole(energy, unit.kilojoule_per_mole)

    def unit(self, kind):
        """The size of one reduced unit of ``kind`` (a key of ``OPENMM_UNITS``) as an OpenMM quantity."""
        m = self.mass.value_in_unit(unit.amu)
        length = self.length.value_in_unit(unit.nanometer)
        energy = self.energy.value_in_unit(unit.kilojoule_per_mole)
        kb = BOLTZMANN.value_in_unit(OPENMM_UNITS["heat_capacity"])
        time = length * math.sqrt(m / energy)   # amu nm^2/ps^2 = kJ/mol, so this is in ps
        values = {
            "mass": m, "length": length, "energy": energy, "time": time, "temperature": energy / kb,
            "velocity": length / time, "force": energy / length, "pressure": energy / length**3,
            "number_density": length**-3, "volume": length**3, "friction": m / time,
            "heat_conduction": energy * (energy / kb) / time, "heat_capacity": kb,
            "surface_tension": energy / length**2,
        }
        if kind not in values:
            raise ValueError(f"unknown kind of quantity '{kind}'; known: {', '.join(sorted(values))}")
        return unit.Quantity(values[kind], OPENMM_UNITS[kind])

    def to_openmm(self, value, kind):
        """A reduced value of ``kind`` as an OpenMM quantity."""
        return value * self.unit(kind)

    def from_openmm(self, quantity, kind):
        """An OpenMM quantity (or a plain number in OpenMM units) of ``kind`` as a reduced value."""
        if unit.is_quantity(quantity):
            quantity = quantity.value_in_unit(OPENMM_UNITS[kind])
        return quantity / self.unit(kind).value_in_unit(OPENMM_UNITS[kind])

    def __repr__(self):
        return f"ReducedUnits(mass={self.mass}, length={self.length}, energy={self.energy})"


#: The reduced units of the published liquid-argon model (openmmgendpde.models.argon): sigma, epsilon and the mass of
#: a particle, whose numbers have one home, the C++ header internal/LiquidArgon.h.
ARGON_UNITS = ReducedUnits(mass=_Model.particleMass * unit.kilogram, length=_Model.length * unit.nanometer,
                           energy=_Model.energy * unit.joule)
