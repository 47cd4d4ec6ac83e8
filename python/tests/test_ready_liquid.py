# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""A liquid ready to run (models.melting.bring_to_temperature, Equilibration.temperature_window, READY_LIQUID,
Model.simulation(equilibration=...)) and a Monte Carlo barostat at the temperature of the liquid's ensemble
(BarostatTemperatureReporter, Model.add_barostat); docs/fluids.md, "A liquid ready
to run"."""

import dataclasses
import math
import os

import numpy as np
import openmm
import pytest
from openmm import unit

from openmmgendpde import BarostatTemperatureReporter, GenDPDEIntegrator
from openmmgendpde.analysis.statistics import correlated_mean
from openmmgendpde.models.argon import liquid_argon
from openmmgendpde.models.fluid import coarse_grain
from openmmgendpde.models.fluid_files import load_fluid
from openmmgendpde.models.melting import bring_to_temperature, melt_to_temperature
from openmmgendpde.models.model import READY_LIQUID, Equilibration

WATER_FILE = os.path.join(os.path.dirname(__file__), "..", "..", "examples", "fluids", "water.toml")
KB = unit.MOLAR_GAS_CONSTANT_R.value_in_unit(unit.kilojoule_per_mole / unit.kelvin)
CPU = {"Threads": "1"}


def isoenergetic_window(context, integrator, steps=4000, interval=20):
    """(T_harm, T_kin) of the next ``steps`` steps, each a CorrelatedMean (K) of samples every ``interval`` steps,
    computed here from OpenMM's kinetic energy (3N - 3 degrees of freedom; the test Systems' total momentum is
    ~1e-3 of a particle's, so the centre-of-mass frame changes nothing at this precision) and the particle
    temperatures, independently of the package's ThermodynamicProbe."""
    dof = 3 * context.getSystem().getNumParticles() - 3
    harmonic, kinetic = [], []
    for _ in range(steps // interval):
        integrator.step(interval)
        kinetic.append(2 * context.getState(getEnergy=True).getKineticEnergy().value_in_unit(
            unit.kilojoule_per_mole) / (dof * KB))
        theta = integrator.getParticleTemperatures().value_in_unit(unit.kelvin)
        harmonic.append(1 / np.mean(1 / theta))
    return correlated_mean(harmonic), correlated_mean(kinetic)


def assert_at(temperature, window, last):
    """Each mean of ``window`` (the test's) within its tolerance of ``temperature``: the liquid was accepted
    (``last``, the LiquidTemperatures of its last window) when that window's mean T_last was within
    last.tolerance (2) of its standard errors s_last of T0, so its true temperature is within
    |T_last - T0| + (T_last's own error) of T0; the test's window adds its error s_test. Tolerance:
    |T_last - T0| + 3 sqrt(s_last^2 + s_test^2), a 0.3% chance of failing a liquid that is where its last window
    put it."""
    for measured, before in zip(window, (last.harmonic, last.kinetic)):
        assert abs(before.mean - temperature) <= last.tolerance * before.standard_error
        allowed = abs(before.mean - temperature) + 3 * math.hypot(measured.standard_error, before.standard_error)
        assert abs(measured.mean - temperature) <= allowed, (measured, before, temperature)


@pytest.mark.validation
def test_a_ready_argon_simulation_is_at_its_temperature_where_the_lattice_is_not():
    """Liquid argon (500 particles, V-B, R* = 1.6839, dt* = 0.01), Model.simulation(equilibration=READY_LIQUID) on
    the CPU platform: over the following 4000 Isoenergetic steps the harmonic mean of theta_i and the kinetic
    temperature equal T0 = 125.70 K.

    Tolerance (assert_at): the offset |T_last - T0| that READY_LIQUID's last window accepted (at most 2 of its
    standard errors) plus 3 combined standard errors sqrt(s_last^2 + s_test^2) (correlated_mean: ~0.1 K for T_harm,
    ~0.4-0.6 K for T_kin; ~0.5 K and ~2 K in all): the liquid's temperature is known to its last window's error, and
    the test window's mean has its own; 3 of them is a 0.3% chance of failing a liquid that is where that window put
    it. Exact in equilibrium: T_kin = T_harm (1 - 1/A), 1 - 1/A = 0.99987 here (docs/integrator.md), far below the
    errors. Without the correction the melt alone (melt_then_switch) settles where the energy at the switch puts it,
    -1.4 to +4.0 K from T0 over 5 seeds (docs/fluids.md, devtools/liquid_start_temperature.py).

    The old way misses: Model.simulation() without it, run Isoenergetic from the lattice, starts the internal
    energies at C_V T0, k_B T0 per particle short of the mean of their Gamma law, with the lattice's potential
    energy below the liquid's; that deficit, over the heat capacity (3/2 + C_V/k_B + 1) k_B = 15 k_B per particle,
    leaves it ~9% cold (10.5-11.8 K below T0 over 5 seeds, docs/fluids.md), which must be more than 10 standard
    errors and more than 5 K from T0."""
    model = liquid_argon(500, seed=11)
    temperature = model.bath_temperature
    simulation = model.simulation("CPU", 11, CPU, equilibration=dataclasses.replace(READY_LIQUID, seed=11))
    assert model.integrator.getMode() == GenDPDEIntegrator.Isoenergetic
    last = model.equilibration_report
    assert last.converged and last.temperature == pytest.approx(temperature)
    assert_at(temperature, isoenergetic_window(simulation.context, model.integrator), last)

    lattice = liquid_argon(500, seed=11)
    context = lattice.context("CPU", properties=CPU, seed=11)
    lattice.integrator.step(1000)
    harmonic, kinetic = isoenergetic_window(context, lattice.integrator, 2000)
    assert temperature - harmonic.mean > 10 * harmonic.standard_error and temperature - harmonic.mean > 5
    assert temperature - kinetic.mean > 5 * kinetic.standard_error


@pytest.mark.validation
def test_a_ready_water_context_is_at_its_temperature():
    """Water from examples/fluids/water.toml (models.fluid: 4 molecules per particle, 20 neighbours; 500 particles,
    V-B, dt* = 0.01), Model.equilibrate with READY_LIQUID (the Context layer): over the following 4000 Isoenergetic
    steps T_harm and T_kin equal T0 = 298.15 K, within the tolerance of assert_at (as for argon: the offset the last
    window accepted plus 3 combined standard errors of the test window's mean and the last window's,
    correlated_mean; ~0.15 K and ~1.3 K each). Without the correction the same melt leaves
    water where the energy at the switch puts it: its structure still relaxes (the potential energy rises by ~0.3
    kJ/mol per particle after 1000 thermostat steps, ~1 K) and the drawn internal energies are off their mean by
    1/sqrt(N (C_V/k_B + 1)) = 0.8%, ~2 K (docs/fluids.md)."""
    model = coarse_grain(load_fluid(WATER_FILE), 4, neighbors=20).liquid(500, seed=12)
    temperature = model.bath_temperature
    context = model.equilibrate("CPU", dataclasses.replace(READY_LIQUID, seed=12), CPU)
    last = model.equilibration_report
    assert last.converged and last.temperature == pytest.approx(298.15)
    assert_at(temperature, isoenergetic_window(context, model.integrator), last)


def test_bring_to_temperature_scales_the_thermal_energies_by_the_measured_ratio():
    """One correction of a liquid started from the lattice (argon, 500 particles, ~10 K cold): the factor is T0 over
    the mean of the first window's harmonic-mean temperatures (computed here from the particle temperatures), > 1
    since the liquid was cold, and between the window's last sample and the next step the internal energies are
    multiplied by it and the kinetic energy too (velocities by its square root), nothing else."""
    model = liquid_argon(500, seed=13)
    context = model.context("CPU", properties=CPU, seed=13)
    integrator = model.integrator
    before, after, harmonic = [], [], []

    def look():
        state = context.getState(getVelocities=True)
        energies = integrator.getInternalEnergies().value_in_unit(unit.kilojoule_per_mole)
        return energies, state.getVelocities(asNumpy=True).value_in_unit(unit.nanometer / unit.picosecond)

    def step(n):
        before.append(look())
        integrator.step(n)
        after.append(look())
        harmonic.append(1 / np.mean(1 / integrator.getParticleTemperatures().value_in_unit(unit.kelvin)))

    report = bring_to_temperature(context, integrator, model.bath_temperature * unit.kelvin, window_steps=200,
                                  sample_interval=20, max_corrections=1, step=step)
    assert len(report.corrections) == 1 and report.steps == 400 and not report.converged
    factor = report.corrections[0]
    assert factor == pytest.approx(model.bath_temperature / np.mean(harmonic[:10]), rel=1e-12)
    assert 1.03 < factor < 1.15
    np.testing.assert_allclose(before[10][0], after[9][0] * factor, rtol=1e-14)
    np.testing.assert_allclose(before[10][1], after[9][1] * math.sqrt(factor), rtol=1e-14)
    assert str(report).startswith("T_harm = ") and "NOT within 2 standard errors" in str(report)


def test_bad_arguments_are_refused_before_anything_runs():
    model = liquid_argon(500, seed=14)
    with pytest.raises(ValueError, match="temperature_window = 100 is not allowed with mode = 1"):
        Equilibration(100, temperature_window=100, mode=GenDPDEIntegrator.Isothermal)
    with pytest.raises(ValueError, match="window_steps = 100 is not allowed with sample_interval = 20"):
        Equilibration(100, temperature_window=100)
    with pytest.raises(ValueError, match="thermostat_steps = -1 is not allowed"):
        Equilibration(-1)
    with pytest.raises(ValueError, match="tolerance = 0 is not allowed"):
        Equilibration(10, temperature_window=1000, tolerance=0)
    with pytest.raises(ValueError, match="equilibration = 'yes' is not allowed"):
        model.simulation("Reference", equilibration="yes")
    context = model.context("Reference")
    model.integrator.setMode(GenDPDEIntegrator.Isothermal)
    with pytest.raises(ValueError, match="integrator mode = 1 is not allowed"):
        bring_to_temperature(context, model.integrator, 125.7)
    with pytest.raises(ValueError, match="temperature = -1 is not allowed"):
        melt_to_temperature(context, model.integrator, 10, -1, 1)
    assert context.getState().getStepCount() == 0 and model.integrator.getMode() == GenDPDEIntegrator.Isothermal
    with pytest.raises(ValueError, match="pressure = 'high' is not allowed"):
        model.add_barostat("high")
    with pytest.raises(ValueError, match="frequency = 0 is not allowed"):
        model.add_barostat(1 * unit.bar, 0)
    assert model.system.getNumForces() == 1
    with pytest.raises(openmm.OpenMMException, match="reportInterval = 0 is not allowed"):
        BarostatTemperatureReporter(0)
    with pytest.raises(openmm.OpenMMException, match="BarostatTemperatureReporter.setTemperature: the System has no "
                                                     "Monte Carlo barostat"):
        BarostatTemperatureReporter.setTemperature(context)


def test_the_barostat_follows_the_liquid_s_temperature_in_the_isoenergetic_mode_and_the_bath_s_in_the_isothermal():
    """Argon (500 particles) run Isoenergetic from the lattice settles ~10 K below T0 (the test above); the
    reporter sets MonteCarloBarostat.Temperature() to the harmonic mean of theta_i, computed here from the particle
    temperatures (to rounding), not T0; in the Isothermal mode to the bath's T0."""
    model = liquid_argon(500, seed=15)
    barostat = model.add_barostat(1000 * unit.bar, 25)
    assert barostat.getDefaultTemperature().value_in_unit(unit.kelvin) == pytest.approx(model.bath_temperature)
    simulation = model.simulation("CPU", 15, CPU)
    reporter = BarostatTemperatureReporter(25)
    simulation.reporters.append(reporter)
    simulation.step(1000)
    theta = model.integrator.getParticleTemperatures().value_in_unit(unit.kelvin)
    parameter = simulation.context.getParameter(barostat.Temperature())
    assert parameter == pytest.approx(1 / np.mean(1 / theta), rel=1e-12) == reporter.temperature
    assert model.bath_temperature - parameter > 5
    model.integrator.setMode(GenDPDEIntegrator.Isothermal)
    simulation.step(25)
    assert simulation.context.getParameter(barostat.Temperature()) == pytest.approx(model.bath_temperature,
                                                                                     rel=1e-12)
