# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""The model's thermal expansion measured back (`thermal-expansion`): the thermal pressure coefficient (dP/dT)_V of a
fluid whose particles have the TaitThermalExpansion law (docs/theory.md section 11), and alpha = kappa_T (dP/dT)_V,
beside the fluid's.

The fluid (default: liquid argon at 125.7 K and 85.31 MPa with alpha = 2.64e-3 1/K, `fluid.ARGON_EXPANDING`;
--fluid supercritical: argon at 418.8 K and 85.31 MPa with alpha = 1.97e-3 1/K, `fluid.SUPERCRITICAL_ARGON`) is mapped
by `fluid.coarse_grain` and simulated at its density n0 (fixed volume) at two temperatures T0 - dT and T0 + dT: an
Isothermal melt at the temperature, then the full GenDPDE dynamics (Isoenergetic, the internal energies drawn from
their equilibrium law at that temperature), sampling the virial pressure P and the kinetic temperature T. The slope
(P+ - P-)/(T+ - T-) is (dP/dT)_V; its standard error comes from the two runs' pressures (statistics.correlated_mean:
the error of a correlated series, with its statistical inefficiency). alpha uses the
fluid's own kappa_T (the Tait part of the law reproduces it; `calibrate` measures it). The mapped beta is then
corrected once from the measured slope (`corrected`; the particles' pressures reach the virial pressure through
the estimator, not one for one) and measured again (--iterations).

    .venv/bin/python -m openmmgendpde thermal-expansion --particles 4000 --steps 4000 --threads 2
"""

import dataclasses
import math

from openmm import unit

from ..analysis.statistics import correlated_mean
from ..analysis.thermodynamics import ThermodynamicProbe
from ..api import GenDPDEIntegrator
from ..models.argon import ARGON_UNITS
from ..models.fluid import ARGON_EXPANDING, coarse_grain
from ..units import BOLTZMANN

#: The default half-difference of the two runs' temperatures, a fraction of T0.
DELTA = 0.08
#: Steps between the samples of a run (run_at's sample_every on the command line), and the fewest samples a run
#: takes there (for the standard errors of correlated_mean).
SAMPLE_EVERY, MIN_SAMPLES = 20, 20
#: MPa per kJ/mol/nm^3 (a pressure per mole of particles, as OpenMM's units are, to one per particle).
MPA_PER_OPENMM_PRESSURE = (1.0 * unit.kilojoule_per_mole / unit.nanometer**3 / unit.AVOGADRO_CONSTANT_NA
                           ).value_in_unit(unit.megapascal)


@dataclasses.dataclass
class ThermalExpansion:
    temperatures: tuple        # the two runs' mean kinetic temperatures (K)
    temperature_errors: tuple  # their standard errors (K)
    pressures: tuple           # their mean virial pressures (MPa)
    pressure_errors: tuple     # their standard errors (MPa)
    slope: float               # (dP/dT)_V measured (MPa/K)
    slope_error: float         # its standard error (MPa/K)
    target_slope: float        # alpha/kappa_T of the fluid (MPa/K)
    alpha: float               # kappa_T (dP/dT)_V (1/K)
    alpha_error: float
    target_alpha: float        # (1/K)
    thermal_pressure: float    # beta of the law measured (kJ/mol/nm^3/K)


@dataclasses.dataclass
class EquilibriumRun:
    """Means of one equilibrium run (OpenMM units)."""
    temperature: object  # statistics.CorrelatedMean of the kinetic temperature (K)
    pressure: object     # statistics.CorrelatedMean of the virial pressure (kJ/mol/nm^3)
    energy: float        # kJ/mol: the mean of K + U + sum eps per particle
    density: float       # nm^-3: N/V


def run_at(parameters, num_particles, temperature, melt_steps, steps, sample_every, platform, seed, density=None,
           estimator="VB", time_step=0.01):
    """EquilibriumRun of the model ``parameters`` at ``temperature`` (K) and n0 (or ``density``, nm^-3): an Isothermal
    melt, then the full dynamics (Isoenergetic, the internal energies drawn from their equilibrium law at that
    temperature)."""
    model = parameters.liquid(num_particles, estimator, mode=GenDPDEIntegrator.Isothermal, time_step=time_step,
                              seed=seed, density=density)
    integrator = model.integrator
    context = model.melted(platform, GenDPDEIntegrator.Isoenergetic, melt_steps, melt_steps // 2, temperature, seed)
    probe = ThermodynamicProbe(model.system)
    pressures, temperatures, energies = [], [], []
    for _ in range(steps // sample_every):
        integrator.step(sample_every)
        state = context.getState(getEnergy=True, getVelocities=True)
        sample = probe.sample(state, context, integrator)
        pressures.append(sample.pressure.value_in_unit(unit.kilojoule_per_mole / unit.nanometer**3))
        temperatures.append(sample.kinetic_temperature.value_in_unit(unit.kelvin))
        energies.append(sample.conserved_energy.value_in_unit(unit.kilojoule_per_mole))
    return EquilibriumRun(temperature=correlated_mean(temperatures), pressure=correlated_mean(pressures),
                          energy=sum(energies) / len(energies) / model.num_particles,
                          density=model.num_particles / model.volume)


def mapped(fluid=ARGON_EXPANDING, molecules_per_particle=None, neighbors=None, cutoff=None):
    """The GenDPDEParameters of ``fluid`` at this coarse-graining level (`fluid.coarse_grain`; default: the paper's
    R* = 1.6839 for argon; MOLECULES_PER_PARTICLE); ValueError if the fluid has no thermal expansion."""
    molecules_per_particle = molecules_per_particle or MOLECULES_PER_PARTICLE
    if cutoff is None and neighbors is None:
        cutoff = ARGON_UNITS.to_openmm(1.6839, "length") if fluid is ARGON_EXPANDING else None
        neighbors = None if cutoff is not None else 20
    parameters = coarse_grain(fluid, molecules_per_particle, neighbors=neighbors, cutoff=cutoff)
    if parameters.thermal_pressure is None:
        raise ValueError(f"{fluid.name}: no thermal_expansion, so no TaitThermalExpansion law to measure")
    return parameters


def corrected(parameters, result):
    """The parameters with beta, the law's thermal pressure dpi/dtheta at n0 (ModelParameters.with_thermal_pressure:
    any law that depends on temperature), scaled so that the thermal part of (dP/dT)_V, beyond the kinetic n0 k_B,
    reaches the fluid's: the response of P to beta is linear (a uniform shift of every pi_i), so one secant step from
    the origin lands, to the measurement's error."""
    kinetic = parameters.density * BOLTZMANN.value_in_unit(unit.kilojoule_per_mole / unit.kelvin) \
        * MPA_PER_OPENMM_PRESSURE
    scale = (result.target_slope - kinetic) / (result.slope - kinetic)
    return parameters.with_thermal_pressure(parameters.thermal_pressure * scale)


def iterated(parameters, history):
    """The parameters with the next beta after the measurements ``history`` (ThermalExpansion, oldest first, the last
    of the parameters given): a secant step on the last two (beta, (dP/dT)_V) where their slopes differ by more than
    2 standard errors of the difference, else corrected() from the last. Where the structure absorbs part of a shift
    of the pi_i (a stiff liquid whose particles are under tension: docs/theory.md section 12) the slope is not
    proportional to beta, and one proportional step missed by 2x (docs/thermal.md); the secant follows the
    measured response. A secant step is held within a factor 3 of the last beta and positive."""
    last = history[-1]
    if len(history) >= 2:
        previous = history[-2]
        difference = last.slope - previous.slope
        if (last.thermal_pressure != previous.thermal_pressure
                and abs(difference) > 2 * math.hypot(last.slope_error, previous.slope_error)):
            beta = last.thermal_pressure + (last.target_slope - last.slope) * (
                last.thermal_pressure - previous.thermal_pressure) / difference
            beta = min(3 * last.thermal_pressure, max(last.thermal_pressure / 3, beta))
            return parameters.with_thermal_pressure(beta)
    return corrected(parameters, last)


def measure(parameters, num_particles=4000, delta=None, melt_steps=1000, steps=4000, sample_every=20,
            platform="CPU", seed=1, estimator="VB", time_step=0.01):
    """ThermalExpansion of the model ``parameters`` (GenDPDEParameters with a thermal law), from runs at
    T0 -+ ``delta`` K (default: 8% of T0, 10 K for the liquid argon: the slope's error from the mean temperatures
    falls as 1/delta)."""
    minus, plus, per_kelvin, error = thermal_pressure_coefficient(
        parameters, num_particles, delta, melt_steps, steps, sample_every, platform, seed, estimator, time_step)
    t_minus, t_plus = minus.temperature.mean, plus.temperature.mean
    p_minus, p_plus = minus.pressure, plus.pressure
    to_mpa = MPA_PER_OPENMM_PRESSURE
    slope, slope_error = per_kelvin * to_mpa, error * to_mpa
    f = parameters.fluid.in_openmm()
    kappa = f["compressibility"] / MPA_PER_OPENMM_PRESSURE   # 1/MPa
    target_alpha = f["thermal_expansion"]
    return ThermalExpansion(
        temperatures=(t_minus, t_plus),
        temperature_errors=(minus.temperature.standard_error, plus.temperature.standard_error),
        pressures=(p_minus.mean * to_mpa, p_plus.mean * to_mpa),
        pressure_errors=(p_minus.standard_error * to_mpa, p_plus.standard_error * to_mpa),
        slope=slope, slope_error=slope_error, target_slope=target_alpha / kappa,
        alpha=kappa * slope, alpha_error=kappa * slope_error, target_alpha=target_alpha,
        thermal_pressure=parameters.thermal_pressure)


def thermal_pressure_coefficient(parameters, num_particles=4000, delta=None, melt_steps=1000, steps=4000,
                                 sample_every=20, platform="CPU", seed=1, estimator="VB", time_step=0.01):
    """(the run at T0 - ``delta``, the run at T0 + ``delta`` (EquilibriumRun each, at n0), (dP/dT)_n between them
    (kJ/mol/nm^3/K), its standard error) of the model ``parameters``, any law (default delta: 8% of T0, 10 K for
    the liquid argon: the slope's error from the mean temperatures falls as 1/delta). The temperatures are the runs'
    mean kinetic temperatures."""
    delta = DELTA * parameters.temperature if delta is None else delta
    minus, plus = [run_at(parameters, num_particles, parameters.temperature + sign * delta, melt_steps, steps,
                          sample_every, platform, seed + k, estimator=estimator, time_step=time_step)
                   for k, sign in enumerate((-1, 1))]
    t_minus, t_plus = minus.temperature.mean, plus.temperature.mean
    slope = (plus.pressure.mean - minus.pressure.mean) / (t_plus - t_minus)
    # The errors of all four means, P's and T's (an error of a mean temperature moves the slope as P's does),
    # summed as if independent (a run's P and T fluctuate together through the kinetic energy: an upper bound).
    error = math.hypot(plus.pressure.standard_error, minus.pressure.standard_error,
                       slope * plus.temperature.standard_error, slope * minus.temperature.standard_error) / (
        t_plus - t_minus)
    return minus, plus, slope, error


#: The molecules per particle of thermal-expansion where --molecules-per-particle is not given.
MOLECULES_PER_PARTICLE = 5


def measured_and_corrected(parameters, iterations=1, report=None, **runs):
    """[ThermalExpansion] of the mapped model ``parameters`` and of each of ``iterations`` corrections of its beta
    (corrected, from the last measurement), each measured (measure with ``runs``); ``report(result)`` is called after
    each."""
    results = []
    for _ in range(iterations + 1):
        result = measure(parameters, **runs)
        if report is not None:
            report(result)
        results.append(result)
        parameters = corrected(parameters, result)
    return results
