# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""The mapping from a fluid's physical properties to GenDPDE parameters (openmmgendpde.models.fluid) and `calibrate`."""

import dataclasses
import math

import numpy as np
import pytest
from openmm import unit

from openmmgendpde import GenDPDEForce
from openmmgendpde.models.argon import ARGON_CUTOFFS, ARGON_STATE, ARGON_UNITS
from openmmgendpde.models.fluid import (
    ARGON,
    ARGON_EXPANDING,
    WATER,
    Fluid,
    coarse_grain,
    heat_capacity_per_molecule,
    set_temperature_field,
)
from openmmgendpde.models.lattice import fcc_box

N_A = 6.02214076e23
K_B = 1.380649e-23


@pytest.mark.parametrize("published", ARGON_CUTOFFS, ids=lambda c: f"R*={c.cutoff}")
def test_argon_mapping_recovers_table_ii(published):
    """The paper's Table II (internal/LiquidArgon.h) from argon's physical state: T0, P0, n0, kappa_T0, C_V exactly
    (they define the reduced units), and for each published cutoff the printed gamma*, kappa* and f_cut to their
    last digit. eta and lambda are one value each for the three cutoffs (the paper's Table I of transport properties
    was not available: fluid.ARGON says how they were chosen), so this checks that the mapping's R^-5 law is the
    paper's: gamma* R*^5 varies by 0.05% across the printed values, and an R^-4 or R^-6 law misses them by 25%."""
    parameters = coarse_grain(ARGON, 5, cutoff=ARGON_UNITS.to_openmm(published.cutoff, "length"))
    reduced = parameters.reduced()
    assert reduced["n0*"] == pytest.approx(ARGON_STATE.density, rel=1e-9)
    assert reduced["T0*"] == pytest.approx(ARGON_STATE.temperature, rel=1e-9)
    assert reduced["pi0*"] == pytest.approx(ARGON_STATE.reference_pressure, rel=1e-9)
    assert reduced["B_T*"] == pytest.approx(ARGON_STATE.bulk_modulus, rel=1e-9)
    assert reduced["C_V*"] == pytest.approx(ARGON_STATE.heat_capacity, rel=1e-9)
    assert round(parameters.neighbors) == published.neighbors
    assert round(reduced["gamma*"], 2) == published.friction
    assert round(reduced["kappa*"], 4) == published.heat_conduction
    assert round(reduced["f_cut"], 2) == published.cutoff_scaling


def test_thermal_expansion_mapping_by_hand():
    """alpha = 2.64e-3 1/K for argon (docs/theory.md section 11): (dP/dT)_V = alpha/kappa_T = n0 k_B + beta (1 + k_B/C),
    so beta = (alpha/kappa_T - n0 k_B)/(1 + k_B/C), and theta0 = T0 (1 + k_B/C); here in SI per particle from the
    state's values (rho = 1418.4 kg/m^3 at 5 atoms of 40.00 g/mol, kappa_T = 1.490/GPa, C = 12.51 k_B), then per mole.
    The force of the model carries the law; a fluid without alpha keeps the Tait law."""
    parameters = coarse_grain(ARGON_EXPANDING, 5, cutoff=ARGON_UNITS.to_openmm(1.6839, "length"))
    f = ARGON_EXPANDING.in_openmm()
    kappa_si = f["compressibility"] * 1e-27 / 1000 * N_A                  # nm^3 mol/kJ -> 1/Pa
    n0_si = parameters.density * 1e27                                        # 1/m^3
    c_over_kb = ARGON_STATE.heat_capacity
    beta_si = (2.64e-3 / kappa_si - n0_si * K_B) / (1 + 1 / c_over_kb)      # Pa/K per particle
    assert kappa_si == pytest.approx(1.490e-9, rel=2e-3)
    assert parameters.thermal_pressure == pytest.approx(beta_si * 1e-27 * N_A / 1000, rel=1e-9)
    assert parameters.thermal_reference_temperature == pytest.approx(parameters.temperature * (1 + 1 / c_over_kb),
                                                                     rel=1e-12)
    law, (beta, theta0) = parameters.liquid(500).force.getEquationOfState()
    assert law == GenDPDEForce.TaitThermalExpansion
    assert beta._value == parameters.thermal_pressure and theta0._value == parameters.thermal_reference_temperature
    plain = coarse_grain(ARGON, 5, cutoff=ARGON_UNITS.to_openmm(1.6839, "length"))
    assert plain.thermal_pressure is None and plain.liquid(500).force.getEquationOfState()[0] == GenDPDEForce.Tait
    # An expansion below the ideal gas's (beta < 0) is refused, naming the property.
    with pytest.raises(ValueError, match="thermal_expansion = 1e-06"):
        coarse_grain(dataclasses.replace(ARGON, thermal_expansion=1e-6 / unit.kelvin), 5,
                     cutoff=ARGON_UNITS.to_openmm(1.6839, "length"))


def test_water_mapping_by_hand():
    """Water, 4 molecules per particle, 20 neighbours, against the formulas evaluated here in SI units."""
    p = coarse_grain(WATER, 4, neighbors=20)
    mass = 4 * 18.015e-3 / N_A                          # kg
    n0 = 997.05 / mass                                  # m^-3
    assert p.mass == pytest.approx(4 * 18.015, rel=1e-12)
    assert p.density == pytest.approx(n0 * 1e-27, rel=1e-12)
    per_mole_nm3 = N_A * 1e-27 / 1e3                    # Pa -> kJ/mol/nm^3
    assert p.bulk_modulus == pytest.approx(1 / (7 * 0.4525e-9) * per_mole_nm3, rel=1e-12)
    assert p.reference_pressure == pytest.approx((0.1e6 - n0 * K_B * 298.15) * per_mole_nm3, rel=1e-9)
    cutoff = (3 * 20 / (4 * math.pi * n0)) ** (1 / 3)  # m
    assert p.cutoff == pytest.approx(cutoff * 1e9, rel=1e-12)
    friction = 1575 * 0.89e-3 / (2 * math.pi * n0**2 * cutoff**5)                     # kg/s
    assert p.friction == pytest.approx(friction / 1.66053906660e-27 * 1e-12, rel=1e-8)   # amu/ps
    kappa = 315 * 0.6065 * 298.15**2 / (2 * math.pi * n0**2 * cutoff**5)               # J K/s
    assert p.heat_conduction == pytest.approx(kappa * N_A / 1e3 * 1e-12, rel=1e-9)      # kJ K/(mol ps)
    assert p.heat_capacity == pytest.approx(4 * 74.44e-3, rel=1e-12)


def test_units_of_the_properties_are_interchangeable():
    """The same water in other units, and c_v per molecule in J/K, per mole, or in k_B, gives the same model."""
    cv = 74.44 / (K_B * N_A)
    variants = [
        WATER,
        Fluid("water", 25.0 * unit.kelvin + 273.15 * unit.kelvin, 1.0 * unit.bar,
              0.99705 * unit.gram / unit.centimeter**3,
              0.4525 / (1e9 * unit.pascal), cv, 0.89 * unit.pascal * unit.second / 1000,
              0.6065e-3 * unit.kilojoule / (unit.second * unit.meter * unit.kelvin), 18.015 * unit.dalton, 7.0),
        Fluid("water", 298.15 * unit.kelvin, 0.1 * unit.megapascal, 997.05 * unit.kilogram / unit.meter**3,
              0.4525e-9 / unit.pascal, cv * K_B * unit.joule / unit.kelvin, 0.89e-3 * unit.pascal * unit.second,
              0.6065 * unit.watt / (unit.meter * unit.kelvin), 18.015 * unit.gram / unit.mole, 7.0),
    ]
    reference = coarse_grain(variants[0], 4, neighbors=20)
    for fluid in variants[1:]:
        p = coarse_grain(fluid, 4, neighbors=20)
        for field in ("mass", "density", "reference_pressure", "bulk_modulus", "cutoff", "friction",
                      "heat_conduction", "heat_capacity", "temperature"):
            assert getattr(p, field) == pytest.approx(getattr(reference, field), rel=1e-9), field
    assert heat_capacity_per_molecule(1.0) == pytest.approx(K_B * N_A / 1000, rel=1e-12)


@pytest.mark.parametrize("call, message", [
    (lambda: coarse_grain(WATER, 0, neighbors=20), "molecules_per_particle = 0"),
    (lambda: coarse_grain(WATER, 4), "exactly one of neighbors"),
    (lambda: coarse_grain(WATER, 4, neighbors=20, cutoff=1.0), "exactly one of neighbors"),
    (lambda: coarse_grain(WATER, 4, neighbors=-1), "neighbors = -1"),
    (lambda: coarse_grain(Fluid("x", 300 * unit.kelvin, 1.0, WATER.mass_density, WATER.compressibility, 3.0,
                                WATER.shear_viscosity, WATER.thermal_conductivity, WATER.molar_mass), 4, neighbors=20),
     "pressure = 1.0 needs a unit"),
])
def test_bad_input_names_the_argument(call, message):
    with pytest.raises(ValueError, match=message):
        call()


@pytest.mark.parametrize("change, message", [
    ({"compressibility": 0 / unit.pascal}, "compressibility = 0 /Pa is not allowed; it must be finite and > 0"),
    ({"compressibility": -0.45e-9 / unit.pascal}, "compressibility = -4.5e-10 /Pa is not allowed"),
    ({"temperature": 298.15}, "temperature = 298.15 needs a unit"),
    ({"temperature": -10 * unit.kelvin}, "temperature = -10 K is not allowed; it must be finite and > 0"),
    ({"temperature": 300 * unit.nanometer}, "temperature = 300 nm is not compatible with kelvin"),
    ({"molar_mass": 18.0}, "molar_mass = 18.0 needs a unit"),
    ({"molar_mass": -18 * unit.gram / unit.mole}, "molar_mass = -18 g/mol is not allowed"),
    ({"mass_density": 0 * unit.kilogram / unit.meter**3}, "mass_density = 0 kg/\\(m\\*\\*3\\) is not allowed"),
    ({"shear_viscosity": -0.89e-3 * unit.pascal * unit.second}, "shear_viscosity = -0.00089 s Pa is not allowed"),
    ({"thermal_conductivity": -0.6 * unit.watt / (unit.meter * unit.kelvin)}, "thermal_conductivity = -0.6"),
    ({"heat_capacity": -3.0}, "heat_capacity = -3.0 is not allowed"),
    ({"heat_capacity": "3"}, "heat_capacity = 3 is not allowed"),
    ({"pressure": math.nan * unit.pascal}, "pressure = nan Pa is not allowed; it must be finite"),
    ({"tait_exponent": 1.0}, "tait_exponent = 1.0 is not allowed; it must be finite and > 1"),
    ({"surface_tension": -0.072 * unit.newton / unit.meter}, "surface_tension = -0.072 N/m is not allowed; it must be "
                                                             "finite and > 0"),
    ({"surface_tension": 0.072 * unit.newton}, "surface_tension = 0.072 N is not compatible with"),
], ids=lambda value: str(value)[:40])
def test_bad_fluid_properties_are_refused_naming_the_property(change, message):
    """A Fluid with a property out of range or without its unit: ValueError naming the property, its value and
    what is allowed, when the Fluid is made (so before coarse_grain computes anything from it)."""
    with pytest.raises(ValueError, match=message):
        coarse_grain(dataclasses.replace(WATER, **change), 4, neighbors=20)


def test_fcc_box_fills_any_rectangular_box_at_the_density():
    """n_x x n_y x n_z cubic FCC cells: N = 4 n_x n_y n_z at exactly the density, every nearest-neighbour distance
    a/sqrt(2) (periodic images included), so a slab or an elongated box starts as a perfect crystal."""
    density = 8.0
    positions, box = fcc_box(density, (2, 3, 7))
    widths = np.array([box[0][0], box[1][1], box[2][2]])
    assert len(positions) == 4 * 2 * 3 * 7
    assert len(positions) / np.prod(widths) == pytest.approx(density, rel=1e-12)
    a = (4 / density) ** (1 / 3)
    delta = positions[:, None, :] - positions[None, :, :]
    delta -= widths * np.round(delta / widths)
    distance = np.sqrt((delta**2).sum(axis=-1)) + np.eye(len(positions)) * 1e9
    assert distance.min(axis=1) == pytest.approx(np.full(len(positions), a / math.sqrt(2)), rel=1e-12)


def test_slab_box_model_and_a_temperature_field():
    """A model in an elongated box (2 x 2 x 8 cells) with two halves at two temperatures set by a field."""
    import openmm
    parameters = coarse_grain(WATER, 4, neighbors=10)
    model = parameters.liquid(cells=(3, 3, 8))
    context = openmm.Context(model.system, model.integrator, openmm.Platform.getPlatformByName("Reference"))
    context.setPositions(model.positions)
    length = model.system.getDefaultPeriodicBoxVectors()[2][2].value_in_unit(unit.nanometer)
    set_temperature_field(model.integrator, model.positions, lambda r: 280.0 if r[2] < length / 2 else 320.0)
    theta = model.integrator.getParticleTemperatures().value_in_unit(unit.kelvin)
    expected = np.where(model.positions[:, 2] < length / 2, 280.0, 320.0)
    assert theta == pytest.approx(expected, rel=1e-12)
    with pytest.raises(ValueError, match="less than twice the cutoff"):
        parameters.liquid(cells=(1, 3, 8))




def test_every_model_is_a_model_and_leaves_its_lattice_one_way():
    """The published argon and a fluid's model are both models.model.Model, and equilibrate() brings either off its
    lattice by one Equilibration protocol: after it the integrator is in the protocol's mode, and the internal
    energies were drawn from their equilibrium law at T0, whose mean is (C_V + k_B) T0 (a Gamma law of shape
    C_V/k_B + 1). 500 particles of C_V = 12.5 k_B (argon) or 36 k_B (water at 4 per particle): the mean has a
    relative standard deviation below 1.3%; 5 steps after the draw move it little. Tolerance 5%."""
    from openmmgendpde import GenDPDEIntegrator
    from openmmgendpde.models.argon import liquid_argon
    from openmmgendpde.models.model import Equilibration, Model
    from openmmgendpde.units import BOLTZMANN
    kb = BOLTZMANN.value_in_unit(unit.kilojoule_per_mole / unit.kelvin)
    for model in (liquid_argon(500, 1.6839, "VB"), coarse_grain(WATER, 4, neighbors=20).liquid(500)):
        assert isinstance(model, Model) and model.volume > 0
        context = model.equilibrate("CPU", Equilibration(20, 5, GenDPDEIntegrator.Isoenergetic, seed=3))
        assert context.getIntegrator().getMode() == GenDPDEIntegrator.Isoenergetic
        heat_capacity = model.integrator.getHeatCapacity().value_in_unit(unit.kilojoule_per_mole / unit.kelvin)
        energies = model.integrator.getInternalEnergies().value_in_unit(unit.kilojoule_per_mole)
        expected = (heat_capacity + kb) * model.bath_temperature
        assert abs(np.mean(energies) / expected - 1) < 0.05, (np.mean(energies), expected)
