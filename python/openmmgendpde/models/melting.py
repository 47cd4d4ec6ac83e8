# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""The one "melt, then switch mode" of the package: a liquid melted from its lattice with the DPD thermostat
(Isothermal mode), then run in another mode with each particle's internal energy drawn from its equilibrium law;
and, for the Isoenergetic mode, the liquid then brought to the temperature asked for (bring_to_temperature).

Drawing the internal energies matters: theta_i = T for every particle would leave them k_B T per particle short of
equilibrium (their Gamma law of shape C_V/k_B + 1 has mean C_V T + k_B T), ~7% too cold for argon's C_V = 12.5 k_B.
Every protocol of the package that melts a liquid ends its melt here: the argon studies (argon_runs), a fluid model's
melted Context (fluid.FluidModel.melted), calibrate's runs, the slabs of the slab study and the step-size test.

Why an Isoenergetic liquid does not settle at T0 after the switch, and what bring_to_temperature does about it
(docs/fluids.md, "A liquid ready to run"): its total energy E = K + U + sum eps_i is fixed at the switch, and the
temperature it settles at is the one whose mean energy is E. E at the switch differs from the mean at T0 by (1) the
structure still relaxing after the melt, (2) the draw: sum eps_i of N particles drawn from their Gamma law is off its
mean by a relative 1/sqrt(N (C_V/k_B + 1)), and K and U by their own fluctuations at that instant (the draw alone: a
standard deviation of 1.4 K for 500 particles of argon, 2.1 K for water), and (3) for a law that depends on
temperature, the Isothermal melt sampling the configurations of another law than the Isoenergetic run
(docs/theory.md section 11). Started straight from the lattice, the internal energies are C_V T0 (k_B T0 per
particle short) and the lattice's potential energy is below the liquid's: ~10 K cold. to_mean_thermal_energy removes
(2) but for U; bring_to_temperature measures what remains and corrects it."""

import dataclasses
import math
import numbers

import numpy as np
from openmm import unit

from ..analysis.statistics import CorrelatedMean, correlated_mean
from ..analysis.thermodynamics import ThermodynamicProbe, harmonic_temperature
from ..api import GenDPDEIntegrator
from ..units import BOLTZMANN


def switch_after_melting(integrator, temperature, seed, mode=GenDPDEIntegrator.Isoenergetic):
    """The end of a melt: ``integrator`` in ``mode``, each internal energy drawn at ``temperature`` (K, or a
    Quantity) with ``seed`` (GenDPDEIntegrator.setInternalEnergiesToTemperature)."""
    integrator.setMode(mode)
    integrator.setInternalEnergiesToTemperature(temperature, seed)


def melt_then_switch(integrator, thermostat_steps, temperature, seed, mode=GenDPDEIntegrator.Isoenergetic,
                     step=None):
    """``thermostat_steps`` steps with the DPD thermostat at the integrator's temperature (Isothermal mode), then
    switch_after_melting. ``step(n)`` advances n steps: the integrator's own by default (pass e.g. Simulation.step,
    or a stepper that reports progress)."""
    integrator.setMode(GenDPDEIntegrator.Isothermal)
    (step or integrator.step)(thermostat_steps)
    switch_after_melting(integrator, temperature, seed, mode)


@dataclasses.dataclass(frozen=True)
class LiquidTemperatures:
    """What bring_to_temperature found in its last window of Isoenergetic steps: the ``temperature`` asked for (K),
    the harmonic mean of the particle temperatures theta_i (``harmonic``) and the kinetic temperature
    (``kinetic``), each the CorrelatedMean (K) of its samples over the window, the factors by which the thermal
    energies were scaled (``corrections``, one per correction, in order), the steps run (``steps``, every window
    included) and whether both temperatures were within ``tolerance`` standard errors of ``temperature``
    (``converged``)."""
    temperature: float
    harmonic: CorrelatedMean
    kinetic: CorrelatedMean
    corrections: tuple
    steps: int
    tolerance: float
    converged: bool

    def __str__(self):
        return (f"T_harm = {self.harmonic.mean:.2f} +- {self.harmonic.standard_error:.2f} K, T_kin = "
                f"{self.kinetic.mean:.2f} +- {self.kinetic.standard_error:.2f} K (T0 = {self.temperature:.2f} K; "
                f"{len(self.corrections)} correction{'' if len(self.corrections) == 1 else 's'}, {self.steps} steps, "
                f"{'within' if self.converged else 'NOT within'} {self.tolerance:g} standard errors)")


def check_window(window_steps, sample_interval, tolerance, max_corrections):
    """ValueError naming the first of bring_to_temperature's window arguments that is not allowed."""
    for name, value, least in (("window_steps", window_steps, 1), ("sample_interval", sample_interval, 1),
                               ("max_corrections", max_corrections, 0)):
        if isinstance(value, bool) or not isinstance(value, numbers.Integral) or value < least:
            raise ValueError(f"{name} = {value!r} is not allowed; it must be an integer >= {least}")
    if window_steps < 10 * sample_interval:
        raise ValueError(f"window_steps = {window_steps} is not allowed with sample_interval = {sample_interval}; a "
                         f"window must hold at least 10 samples (window_steps >= {10 * sample_interval})")
    if isinstance(tolerance, bool) or not isinstance(tolerance, numbers.Real) or not tolerance > 0 \
            or not math.isfinite(tolerance):
        raise ValueError(f"tolerance = {tolerance!r} is not allowed; it must be a finite number > 0 (standard errors)")


def _checked_target(temperature, window_steps, sample_interval, tolerance, max_corrections):
    """``temperature`` in K (a float), after check_window; ValueError naming an argument that is not allowed."""
    check_window(window_steps, sample_interval, tolerance, max_corrections)
    target = temperature.value_in_unit(unit.kelvin) if unit.is_quantity(temperature) else temperature
    if isinstance(target, bool) or not isinstance(target, numbers.Real) or not 0 < target < math.inf:
        raise ValueError(f"temperature = {temperature!r} is not allowed; it must be a finite temperature > 0 (K)")
    return float(target)


def bring_to_temperature(context, integrator, temperature, window_steps=1000, sample_interval=20, tolerance=2.0,
                         max_corrections=4, step=None):
    """Bring an Isoenergetic liquid to ``temperature`` (K, or a Quantity) and return the LiquidTemperatures of its
    last window.

    Each window runs ``window_steps`` steps and samples the harmonic mean of theta_i (the thermodynamic temperature
    of the particles) and the kinetic temperature every ``sample_interval`` steps (each mean with its correlated
    standard error, analysis.statistics.correlated_mean). While either mean is farther than ``tolerance`` standard
    errors from ``temperature``, and at most ``max_corrections`` times, the energy the liquid lacks (or has in
    excess) is put into its kinetic and internal energies in proportion to their heat capacities: every eps_i is
    multiplied by T0/T_harm and every velocity by its square root (T_harm: the window's mean), then another window
    runs. The potential energy then follows the temperature by the configurational heat capacity, a few per cent of
    the kinetic and internal ones' (argon 0.4 k_B against 15 k_B per particle), which the next window corrects.

    ``context`` holds ``integrator`` (a GenDPDEIntegrator in its Isoenergetic mode, else ValueError); ``step(n)``
    advances n steps (default: the integrator's own). Bad arguments raise ValueError naming the argument, its value
    and what is allowed, before anything runs."""
    target = _checked_target(temperature, window_steps, sample_interval, tolerance, max_corrections)
    if integrator.getMode() != GenDPDEIntegrator.Isoenergetic:
        raise ValueError(f"integrator mode = {integrator.getMode()} is not allowed; bring_to_temperature corrects the "
                         f"energy of an Isoenergetic liquid (GenDPDEIntegrator.Isoenergetic = "
                         f"{GenDPDEIntegrator.Isoenergetic}); the Isothermal mode's thermostat keeps its bath's")
    step = step or integrator.step
    probe = ThermodynamicProbe(context.getSystem())
    corrections, steps = [], 0
    while True:
        harmonic, kinetic = [], []
        for _ in range(window_steps // sample_interval):
            step(sample_interval)
            steps += sample_interval
            state = context.getState(getEnergy=True, getVelocities=True)
            kinetic.append(probe.kinetic_temperature(state))
            harmonic.append(harmonic_temperature(integrator.getParticleTemperatures()))
        harmonic, kinetic = correlated_mean(harmonic), correlated_mean(kinetic)
        converged = all(abs(m.mean - target) <= tolerance * m.standard_error for m in (harmonic, kinetic))
        if converged or len(corrections) >= max_corrections:
            return LiquidTemperatures(target, harmonic, kinetic, tuple(corrections), steps, float(tolerance),
                                      converged)
        factor = target / harmonic.mean
        _scale_thermal_energies(context, integrator, factor, math.sqrt(factor))
        corrections.append(float(factor))


def to_mean_thermal_energy(context, integrator, temperature):
    """Scale the internal energies and the velocities of ``context`` (``integrator``: its GenDPDEIntegrator) so that
    sum eps_i = sum_i (C_i + k_B) T and the kinetic energy in the centre-of-mass frame is (3N - 3) k_B T/2, their
    means at ``temperature`` T (K) (C_i = eps_i/theta_i, each particle's heat capacity): after a draw at T
    (switch_after_melting) the liquid then starts on the energy of T's mean instead of one off it by the draw's
    fluctuation (a relative 1/sqrt(N (C_V/k_B + 1)) for the internal energies, sqrt(2/(3N - 3)) for the motion; 1.4 and
    0.5 K for 500 particles of argon). Scaling keeps the law the draw gave the shares: independent Gamma variates of
    one scale divided by their sum are independent of it (Dirichlet), and so is the direction of Maxwell-Boltzmann
    velocities (sqrt(m_i) v_i) of their norm. Returns the two factors (internal energies, velocities)."""
    energies = integrator.getInternalEnergies().value_in_unit(unit.kilojoule_per_mole)
    theta = integrator.getParticleTemperatures().value_in_unit(unit.kelvin)
    kb = BOLTZMANN.value_in_unit(unit.kilojoule_per_mole / unit.kelvin)
    energy_factor = float(np.sum((energies / theta + kb) * temperature) / np.sum(energies))
    probe = ThermodynamicProbe(context.getSystem())
    kinetic = probe.internal_kinetic_energy(context.getState(getEnergy=True, getVelocities=True))
    velocity_factor = math.sqrt(probe.degrees_of_freedom * kb * temperature / (2 * kinetic))
    _scale_thermal_energies(context, integrator, energy_factor, velocity_factor)
    return energy_factor, velocity_factor


def _scale_thermal_energies(context, integrator, energy_factor, velocity_factor):
    """Every internal energy of ``integrator`` times ``energy_factor``, every velocity of ``context`` times
    ``velocity_factor`` (nothing else changes)."""
    energies = integrator.getInternalEnergies().value_in_unit(unit.kilojoule_per_mole)
    velocities = context.getState(getVelocities=True).getVelocities(asNumpy=True)
    integrator.setInternalEnergies(np.asarray(energies) * energy_factor)
    context.setVelocities(velocities * velocity_factor)


def melt_to_temperature(context, integrator, thermostat_steps, temperature, seed, settle_steps=0,
                        window_steps=1000, sample_interval=20, tolerance=2.0, max_corrections=4, step=None):
    """A liquid at ``temperature`` in the Isoenergetic mode: melt_then_switch (``thermostat_steps`` with the DPD
    thermostat at the integrator's bath temperature, then the internal energies drawn at ``temperature`` with
    ``seed``), the thermal energies put at their mean at ``temperature`` (to_mean_thermal_energy),
    ``settle_steps`` Isoenergetic steps, then bring_to_temperature with the other arguments. Returns its
    LiquidTemperatures."""
    target = _checked_target(temperature, window_steps, sample_interval, tolerance, max_corrections)
    step = step or integrator.step
    melt_then_switch(integrator, thermostat_steps, temperature, seed, GenDPDEIntegrator.Isoenergetic, step)
    to_mean_thermal_energy(context, integrator, target)
    step(settle_steps)
    return bring_to_temperature(context, integrator, temperature, window_steps, sample_interval, tolerance,
                                max_corrections, step)
