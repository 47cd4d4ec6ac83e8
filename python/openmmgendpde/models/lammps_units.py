# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""OpenMM's units (nm, kJ/mol, ps, amu, K) in LAMMPS's (UNITS lists every factor; the LAMMPS input writer,
models/lammps_files.py, converts with them):

- ``metal`` (Å, eV, ps, g/mol, K), with 1 kJ/mol = 1000/(e N_A) eV = 1/96.48533212331002 eV (CODATA 2018, exact:
  e = 1.602176634e-19 C, N_A = 6.02214076e23/mol);
- ``real`` (Å, kcal/mol, fs, g/mol, K), with 1 kcal/mol = 4.184 kJ/mol (thermochemical, exact);
- ``lj``, used as a container for OpenMM's own numbers: LAMMPS's lj units have k_B = 1 and every other constant 1,
  so lengths (nm), energies (kJ/mol), masses (amu) and times (ps) are written as they are and only the temperature
  scale changes: temperatures as k_B T (kJ/mol), heat capacities as C/k_B, heat conductions as k_B kappa, thermal
  pressure coefficients as beta/k_B (k_B = 0.00831446261815324 kJ/mol/K, exact SI values). The two engines then
  compute with the same numbers (up to one rounding each), which is how the tests compare them to rounding.

Pressures are energy/volume in every units (eV/Å^3 in metal, kcal/mol/Å^3 in real, kJ/mol/nm^3 in lj): the Tait
parameters pi0 and B_T, the background pressure p_b and beta's pressure are what the pair style takes, not LAMMPS's
pressure units (bar, atm): pair_style gendpde computes U = sum_i ... from them without LAMMPS's nktv2p, so that a
value means the same in any units.

    kind              OpenMM            metal (factor)                  real (factor)
    length            nm                Å (10)                          Å (10)
    velocity          nm/ps             Å/ps (10)                       Å/fs (0.01)
    time              ps                ps (1)                          fs (1000)
    mass              amu               g/mol (1)                       g/mol (1)
    temperature       K                 K (1)                           K (1)
    energy            kJ/mol            eV (E = 0.010364269656262174)   kcal/mol (1/4.184)
    pressure          kJ/mol/nm^3       eV/Å^3 (E/1000)                 kcal/mol/Å^3 (1/4184)
    number density    nm^-3             Å^-3 (1/1000)                   Å^-3 (1/1000)
    volume            nm^3              Å^3 (1000)                      Å^3 (1000)
    friction          amu/ps            g/mol/ps (1)                    g/mol/fs (1/1000)
    heat capacity     kJ/mol/K          eV/K (E)                        kcal/mol/K (1/4.184)
    heat conduction   kJ/mol K/ps       eV K/ps (E)                     kcal/mol K/fs (1/4184)
    thermal pressure  kJ/mol/nm^3/K     eV/Å^3/K (E/1000)               kcal/mol/Å^3/K (1/4184)
    energy x volume   kJ/mol nm^3       eV Å^3 (1000 E)                 kcal/mol Å^3 (1000/4.184)

The constants are not the same in the two engines, and no factor can make them so (except in lj, where LAMMPS's are
all 1). OpenMM's k_B is CODATA 2018's, 0.00831446261815324 kJ/mol/K; LAMMPS's metal k_B, force->boltz =
8.617343e-5 eV/K (older CODATA), which the package uses, is 1.13e-6 relatively larger, and its real k_B,
0.0019872067 kcal/mol/K, 1.23e-6 larger. A model whose parameters were fitted with OpenMM's k_B sees in LAMMPS a k_B
that much larger wherever k_B enters (the thermostat's noise, sigma^2 = 2 gamma k_B T; the fluctuation-dissipation
balance of the internal energies; the temperature LAMMPS reports from the kinetic energy). Likewise LAMMPS's metal
mvv2e = 1.0364269e-4 eV per g/mol Å^2/ps^2 is 6.3e-8 relatively below the exact 10/(e N_A), and its nktv2p (eV/Å^3
to bar, used only for the pressure it reports) 8.4e-8 below; in real units mvv2e is 6.6e-11 above the exact 10^4/4.184.
All are far below any statistical error of a run, but trajectories of the two engines in metal or real units are not
the same to the last bit even from the same state and seed.
"""

import math

from openmm import unit

#: 1 kJ/mol in eV: 1000/(e N_A), CODATA 2018 (exact e and N_A).
ELEMENTARY_CHARGE = 1.602176634e-19   # C
AVOGADRO = 6.02214076e23              # 1/mol
ENERGY = 1e3 / (ELEMENTARY_CHARGE * AVOGADRO)
#: 1 kcal/mol in kJ/mol (thermochemical calorie, exact).
KILOCALORIE = 4.184
#: OpenMM's k_B in kJ/mol/K (k_B N_A, exact SI values): LAMMPS's lj temperature unit here.
BOLTZMANN = 1.380649e-23 * 6.02214076e23 / 1000
#: LAMMPS's k_B in metal units (update.cpp: force->boltz), which the package uses, in eV/K.
LAMMPS_METAL_BOLTZMANN = 8.617343e-5

#: units -> {kind: (LAMMPS unit, multiplier, divisor)}: a value in those units is value x multiplier / divisor of
#: the value in OpenMM's (the divisor keeps lj's conversions the single rounding of value / k_B).
UNITS = {
    "metal": {
        "length": ("Å", 10.0, 1.0), "velocity": ("Å/ps", 10.0, 1.0), "time": ("ps", 1.0, 1.0),
        "mass": ("g/mol", 1.0, 1.0), "temperature": ("K", 1.0, 1.0), "energy": ("eV", ENERGY, 1.0),
        "pressure": ("eV/Å^3", ENERGY * 1e-3, 1.0), "number_density": ("Å^-3", 1e-3, 1.0),
        "volume": ("Å^3", 1e3, 1.0), "friction": ("g/mol/ps", 1.0, 1.0), "heat_capacity": ("eV/K", ENERGY, 1.0),
        "heat_conduction": ("eV K/ps", ENERGY, 1.0), "thermal_pressure": ("eV/Å^3/K", ENERGY * 1e-3, 1.0),
        "energy_volume": ("eV Å^3", ENERGY * 1e3, 1.0),
    },
    "real": {
        "length": ("Å", 10.0, 1.0), "velocity": ("Å/fs", 0.01, 1.0), "time": ("fs", 1e3, 1.0),
        "mass": ("g/mol", 1.0, 1.0), "temperature": ("K", 1.0, 1.0), "energy": ("kcal/mol", 1.0, KILOCALORIE),
        "pressure": ("kcal/mol/Å^3", 1.0, KILOCALORIE * 1e3), "number_density": ("Å^-3", 1e-3, 1.0),
        "volume": ("Å^3", 1e3, 1.0), "friction": ("g/mol/fs", 1e-3, 1.0),
        "heat_capacity": ("kcal/mol/K", 1.0, KILOCALORIE),
        "heat_conduction": ("kcal/mol K/fs", 1.0, KILOCALORIE * 1e3),
        "thermal_pressure": ("kcal/mol/Å^3/K", 1.0, KILOCALORIE * 1e3),
        "energy_volume": ("kcal/mol Å^3", 1e3, KILOCALORIE),
    },
    "lj": {
        "length": ("nm", 1.0, 1.0), "velocity": ("nm/ps", 1.0, 1.0), "time": ("ps", 1.0, 1.0),
        "mass": ("amu", 1.0, 1.0), "temperature": ("kJ/mol: k_B T", BOLTZMANN, 1.0),
        "energy": ("kJ/mol", 1.0, 1.0), "pressure": ("kJ/mol/nm^3", 1.0, 1.0),
        "number_density": ("nm^-3", 1.0, 1.0), "volume": ("nm^3", 1.0, 1.0), "friction": ("amu/ps", 1.0, 1.0),
        "heat_capacity": ("C/k_B", 1.0, BOLTZMANN), "heat_conduction": ("(kJ/mol)^2/ps: k_B kappa", BOLTZMANN, 1.0),
        "thermal_pressure": ("nm^-3: beta/k_B", 1.0, BOLTZMANN), "energy_volume": ("kJ/mol nm^3", 1.0, 1.0),
    },
}
#: What each units' script says of itself (its first comment lines).
UNITS_NOTE = {
    "metal": ["Units: metal (Å, eV, ps, g/mol, K), converted from OpenMM's (nm, kJ/mol, ps, amu, K) with",
              "1 kJ/mol = 1000/(e N_A) eV (CODATA 2018); LAMMPS's metal k_B (8.617343e-5 eV/K) is 1.13e-6 relatively",
              "larger than OpenMM's (openmmgendpde.models.lammps_files). Pressures are energy/volume (eV/Å^3)."],
    "real": ["Units: real (Å, kcal/mol, fs, g/mol, K), converted from OpenMM's (nm, kJ/mol, ps, amu, K) with",
             "1 kcal/mol = 4.184 kJ/mol; LAMMPS's real k_B (0.0019872067 kcal/mol/K) is 1.23e-6 relatively larger",
             "than OpenMM's (openmmgendpde.models.lammps_files). Pressures are energy/volume (kcal/mol/Å^3)."],
    "lj": ["Units: lj holding OpenMM's numbers (nm, kJ/mol, ps, amu) with k_B = 1: temperatures as k_B T (kJ/mol),",
           "heat capacities as C/k_B, heat conductions as k_B kappa (openmmgendpde.models.lammps_files)."],
}
#: The Tait parameters n0, pi0, B_T, gamma_T (a law that extends Tait takes them first).
TAIT_KINDS = ("number_density", "pressure", "pressure", None)   # gamma_T: a plain number
#: The OpenMM unit of each kind of UNITS (in_units converts Quantities from it).
OPENMM_UNITS = {
    "length": unit.nanometer, "velocity": unit.nanometer / unit.picosecond, "time": unit.picosecond,
    "mass": unit.amu, "temperature": unit.kelvin, "energy": unit.kilojoule_per_mole,
    "pressure": unit.kilojoule_per_mole / unit.nanometer**3, "number_density": unit.nanometer**-3,
    "volume": unit.nanometer**3, "friction": unit.amu / unit.picosecond,
    "heat_capacity": unit.kilojoule_per_mole / unit.kelvin,
    "heat_conduction": unit.kilojoule_per_mole * unit.kelvin / unit.picosecond,
    "thermal_pressure": unit.kilojoule_per_mole / unit.nanometer**3 / unit.kelvin,
    "energy_volume": unit.kilojoule_per_mole * unit.nanometer**3,
}


def in_units(value, kind, units="metal"):
    """``value`` (a float in OpenMM units, or a Quantity) of ``kind`` (a key of UNITS[units], or None for a plain
    number) in LAMMPS's ``units`` (a key of UNITS)."""
    if kind is None:
        return float(value)
    if unit.is_quantity(value):
        value = value.value_in_unit(OPENMM_UNITS[kind])
    _, multiplier, divisor = UNITS[units][kind]
    return float(value) * multiplier / divisor


def kind_of(openmm_unit):
    """The kind (a key of UNITS[units], or None for a plain number) of a parameter in ``openmm_unit``."""
    if openmm_unit is None or openmm_unit == unit.dimensionless:
        return None
    for kind, known in OPENMM_UNITS.items():
        if openmm_unit.is_compatible(known) and math.isclose(openmm_unit.conversion_factor_to(known), 1.0):
            return kind
    raise ValueError(f"a law's parameter is in {openmm_unit}, which lammps_files cannot convert to LAMMPS's units")
