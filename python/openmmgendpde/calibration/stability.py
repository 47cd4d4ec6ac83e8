# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""The largest stable time step of a fluid model, measured (docs/fluids.md "Time step").

A step size passes when, from a melted liquid (Isothermal steps at dt* = 0.005), `steps` steps at that size in the
given mode run without an error (the integrator refuses a blown-up step or an internal energy <= 0) and keep their
defining quantity: the drift of the conserved energy K + U + sum eps within 1% of the energy that the mode moves
(K + sum eps in the Isoenergetic mode, K in the Conservative mode, where eps is inert), and in the Isothermal mode
the kinetic temperature averaged over the last 10 samples (50 steps apart) within 10% of T0 (the bath's; a sample's
own scatter is sqrt(2/(3N)) = 3.7% for 500 particles). Step sizes are tried on a doubling ladder from dt* = 0.01, then
the last interval is bisected twice. `suggest_time_step` returns half the smallest limit over the three modes, times
an accuracy factor for V-C (its stable_step_factor in the table of estimators).

The limits are measured on a bulk liquid, where V-C is V-B (its surface factor is 1 for 99% of the particles); at free
surfaces V-C's conserved-energy error at a given step is ~100 times V-B's (docs/interfaces.md, "V-C's energy error":
slab and droplet of liquid argon, second order in dt), because its surface factor makes the energy of a surface
particle much stiffer than V-B's. So V-C needs a step sqrt(100) = 10 times smaller for the same drift: measured,
V-C at dt* = 0.0067 drifts as much as V-B at its suggested 0.067 (-6.6e-5 against -6.0e-5 N k_B T0 for the slab,
-2.3e-4 against -2.4e-4 for the droplet, 40 time units from the lattice).
"""

import math

import openmm
from openmm import unit

from ..analysis.thermodynamics import ThermodynamicProbe
from ..api import GenDPDEIntegrator, estimator_of
from ..models.melting import melt_then_switch

MODES = {"Isoenergetic": GenDPDEIntegrator.Isoenergetic, "Isothermal": GenDPDEIntegrator.Isothermal,
         "Conservative": GenDPDEIntegrator.Conservative}


def _passes(parameters, estimator, mode, time_step, steps, particles, platform, seed):
    model = parameters.liquid(particles, estimator, mode=GenDPDEIntegrator.Isothermal, time_step=0.005, seed=seed)
    integrator = model.integrator
    context = model.context(platform, parameters.temperature, seed)
    melt_then_switch(integrator, 500, parameters.temperature, seed, MODES[mode])
    integrator.setStepSize(parameters.units.to_openmm(time_step, "time"))
    probe = ThermodynamicProbe(model.system)
    try:
        start = integrator.getConservedEnergy().value_in_unit(unit.kilojoule_per_mole)
        kinetic = context.getState(getEnergy=True).getKineticEnergy().value_in_unit(unit.kilojoule_per_mole)
        internal = sum(integrator.getInternalEnergies().value_in_unit(unit.kilojoule_per_mole))
        scale = kinetic + (internal if mode == "Isoenergetic" else 0.0)
        integrator.step(steps - 500)
        temperatures = []
        for _ in range(10):
            integrator.step(50)
            state = context.getState(getEnergy=True, getVelocities=True)
            temperatures.append(probe.sample(state, context, integrator).kinetic_temperature.value_in_unit(unit.kelvin))
        end = integrator.getConservedEnergy().value_in_unit(unit.kilojoule_per_mole)
    except openmm.OpenMMException:
        return False
    if mode == "Isothermal":
        return abs(sum(temperatures) / len(temperatures) / parameters.temperature - 1) < 0.10
    return math.isfinite(end) and abs(end - start) < 0.01 * scale


def largest_stable_step(parameters, estimator="VB", mode="Isoenergetic", steps=1000, particles=500,
                        platform="CPU", seed=1):
    """The largest dt* (reduced time of the model) that passes (module docstring), to within 1/4 of a doubling."""
    passed, failed = None, None
    step = 0.01
    while step <= 1.0:
        if _passes(parameters, estimator, mode, step, steps, particles, platform, seed):
            passed, step = step, 2 * step
        else:
            failed = step
            break
    if passed is None:
        return 0.0
    if failed is None:
        return passed
    for _ in range(2):
        middle = math.sqrt(passed * failed)
        if _passes(parameters, estimator, mode, middle, steps, particles, platform, seed):
            passed = middle
        else:
            failed = middle
    return passed


def suggest_time_step(parameters, estimator="VB", **options):
    """Half the smallest measured limit over the three modes, times the estimator's stable_step_factor (the table of
    estimators, api.ESTIMATORS: for the same conserved-energy drift at free surfaces as V-B's; V-C's 0.1, measured
    for liquid argon by devtools/vc_energy_drift.py: its drift is second order in dt and ~100 times V-B's at the same
    step), in the model's reduced time, and in ps."""
    limit = min(largest_stable_step(parameters, estimator, mode, **options) for mode in MODES)
    step = 0.5 * limit * estimator_of(estimator).stable_step_factor
    return step, parameters.units.to_openmm(step, "time")
