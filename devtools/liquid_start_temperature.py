# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""Where an Isoenergetic liquid settles after each way of starting it (docs/fluids.md, "A liquid ready to run"):
from the lattice (Model.context, Isoenergetic at once), after the melt (models.melting.melt_then_switch, the
package's protocols), after the melt with the thermal energies put at their mean at T0 (``mean E``:
models.melting.to_mean_thermal_energy) and as READY_LIQUID leaves it (the melt, the thermal energies at their mean,
then models.melting.bring_to_temperature). For each seed: the harmonic mean of theta_i and the kinetic temperature
over a window of Isoenergetic steps (correlated_mean), and for the lattice and the melt the energy at the start of
the Isoenergetic run taken apart, each term over the kinetic and internal heat capacity C_B = (3N - 3) k_B/2 +
N (C_V + k_B) (in K): the internal energies (sum eps_i - N (C_V + k_B) T0), the motion (K - (3N - 3) k_B T0/2) and
the structure (minus the rise of the potential energy from the start to the window's mean); their sum is what the
energy at the start predicts.

    python devtools/liquid_start_temperature.py --fluid argon --seeds 1 2 3 4 5
    python devtools/liquid_start_temperature.py --fluid examples/fluids/water.toml --seeds 1 2 3 4 5

--fluid: argon (the published model, models.argon.liquid_argon), argon-vdw (liquid argon with its thermal
expansion in the van der Waals law, 5 atoms per particle, 20 neighbours, f_cut as mapped), argon-vdw-calibrated
(the same as calibrate --quick leaves it, python/tests/test_laws.py's run: ~2 min more), or a fluid file (4
molecules per particle, 20 neighbours); --model FILE: a model file (calibrate --output). 500 particles, dt* = 0.01
(a model file's own step), the CPU platform with one thread.
"""

import argparse
import dataclasses
import time

import numpy as np
from openmm import unit

from openmmgendpde.analysis.statistics import correlated_mean
from openmmgendpde.analysis.thermodynamics import ThermodynamicProbe, harmonic_temperature
from openmmgendpde.models.argon import liquid_argon
from openmmgendpde.models.fluid import ARGON_EXPANDING, coarse_grain
from openmmgendpde.models.fluid_files import load_fluid, load_parameters
from openmmgendpde.models.melting import melt_then_switch, to_mean_thermal_energy
from openmmgendpde.models.model import READY_LIQUID

KJ = unit.kilojoule_per_mole
KB = unit.MOLAR_GAS_CONSTANT_R.value_in_unit(KJ / unit.kelvin)
CPU = {"Threads": "1"}


def calibrated_van_der_waals():
    """The van der Waals argon's parameters as calibrate --quick writes them (python/tests/test_laws.py's run)."""
    from openmmgendpde.calibration import calibrate
    from openmmgendpde.calibration.calibration import QUICK
    from openmmgendpde.calibration.results import QUICK_CRITERIA

    mapped = coarse_grain(ARGON_EXPANDING, 5, neighbors=20, law="VanDerWaals")
    return calibrate.calibrate(mapped, "VB", QUICK, "CPU", criteria=QUICK_CRITERIA, report=lambda line: None).parameters


def model_of(fluid, seed, model_file=None):
    if model_file is not None:
        return load_parameters(model_file).liquid(500, seed=seed)
    if fluid == "argon-vdw-calibrated":
        if not hasattr(model_of, "calibrated"):
            model_of.calibrated = calibrated_van_der_waals()
        return model_of.calibrated.liquid(500, seed=seed)
    if fluid == "argon":
        return liquid_argon(500, seed=seed)
    if fluid == "argon-vdw":
        return coarse_grain(ARGON_EXPANDING, 5, neighbors=20, law="VanDerWaals").liquid(500, seed=seed)
    return coarse_grain(load_fluid(fluid), 4, neighbors=20).liquid(500, seed=seed)


def window(context, integrator, steps, interval=20):
    """(T_harm, T_kin, mean U) over ``steps`` steps, the temperatures CorrelatedMeans (K), U in kJ/mol."""
    probe = ThermodynamicProbe(context.getSystem())
    harmonic, kinetic, potential = [], [], []
    for _ in range(steps // interval):
        integrator.step(interval)
        state = context.getState(getEnergy=True, getVelocities=True)
        kinetic.append(probe.kinetic_temperature(state))
        harmonic.append(harmonic_temperature(integrator.getParticleTemperatures()))
        potential.append(state.getPotentialEnergy().value_in_unit(KJ))
    return correlated_mean(harmonic), correlated_mean(kinetic), float(np.mean(potential))


def energy_terms(context, integrator, t0):
    """At the start of an Isoenergetic run: (C_B in kJ/mol/K, the internal energies' and the motion's excess over
    their means at T0 in K, the potential energy in kJ/mol)."""
    n = context.getSystem().getNumParticles()
    heat_capacity = integrator.getHeatCapacity().value_in_unit(KJ / unit.kelvin)
    total = (3 * n - 3) * KB / 2 + n * (heat_capacity + KB)
    state = context.getState(getEnergy=True)
    draw = (integrator.getInternalEnergies().value_in_unit(KJ).sum() - n * (heat_capacity + KB) * t0) / total
    motion = (state.getKineticEnergy().value_in_unit(KJ) - (3 * n - 3) * KB * t0 / 2) / total
    return total, draw, motion, state.getPotentialEnergy().value_in_unit(KJ)


def taken_apart(start, potential):
    """The terms of energy_terms in K, with the structure's: minus the rise of the potential energy from the start
    to ``potential`` (the window's mean), over C_B."""
    total, draw, motion, start_potential = start
    structure = -(potential - start_potential) / total
    return (f"internal energies {draw:+.2f}, motion {motion:+.2f}, structure {structure:+.2f}: sum "
            f"{draw + motion + structure:+.2f} K")


def show(name, seed, t0, harmonic, kinetic, extra=""):
    print(f"{name:8s} {seed:4d}  T_harm - T0 = {harmonic.mean - t0:+7.2f} +- {harmonic.standard_error:.2f} K   "
          f"T_kin - T0 = {kinetic.mean - t0:+7.2f} +- {kinetic.standard_error:.2f} K  {extra}", flush=True)


def melted(arguments, seed, t0):
    """(context, integrator) of the fluid melted by the old Isothermal melt and switched to the Isoenergetic mode."""
    model = model_of(arguments.fluid, seed, arguments.model)
    integrator = model.integrator
    integrator.setMode(integrator.Isothermal)
    context = model.context("CPU", properties=CPU, seed=seed)
    melt_then_switch(integrator, arguments.melt, t0, seed)
    return context, integrator


def melt(arguments, seed, t0):
    context, integrator = melted(arguments, seed, t0)
    start_energies = energy_terms(context, integrator, t0)
    integrator.step(arguments.settle)
    harmonic, kinetic, potential = window(context, integrator, arguments.window)
    show("melt", seed, t0, harmonic, kinetic, taken_apart(start_energies, potential))


def mean_energy(arguments, seed, t0):
    context, integrator = melted(arguments, seed, t0)
    factors = to_mean_thermal_energy(context, integrator, t0)
    integrator.step(arguments.settle)
    show("mean E", seed, t0, *window(context, integrator, arguments.window)[:2],
         f"eps x {factors[0]:.4f}, v x {factors[1]:.4f}")


def ready(arguments, seed, t0):
    model = model_of(arguments.fluid, seed, arguments.model)
    context = model.equilibrate("CPU", dataclasses.replace(READY_LIQUID, thermostat_steps=arguments.melt,
                                                           seed=seed, tolerance=arguments.tolerance), CPU)
    report = model.equilibration_report
    harmonic, kinetic, _ = window(context, model.integrator, arguments.window)
    show("ready", seed, t0, harmonic, kinetic, f"{len(report.corrections)} corrections "
         f"({', '.join(f'{c:.4f}' for c in report.corrections)}), {report.steps} steps")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--fluid", default="argon")
    parser.add_argument("--model", help="a model file (calibrate --output) instead of --fluid")
    parser.add_argument("--seeds", type=int, nargs="+", default=[1, 2, 3])
    parser.add_argument("--melt", type=int, default=READY_LIQUID.thermostat_steps, help="thermostat steps")
    parser.add_argument("--settle", type=int, default=1000, help="Isoenergetic steps before the window")
    parser.add_argument("--window", type=int, default=4000, help="Isoenergetic steps measured")
    parser.add_argument("--tolerance", type=float, default=READY_LIQUID.tolerance,
                        help="READY_LIQUID's tolerance (standard errors)")
    parser.add_argument("--rows", nargs="+", default=["lattice", "melt", "mean-E", "ready"],
                        choices=["lattice", "melt", "mean-E", "ready"], help="the ways of starting to run")
    arguments = parser.parse_args()
    start = time.time()
    for seed in arguments.seeds:
        model = model_of(arguments.fluid, seed, arguments.model)
        t0 = model.bath_temperature
        if "lattice" in arguments.rows:
            context = model.context("CPU", properties=CPU, seed=seed)
            start_energies = energy_terms(context, model.integrator, t0)
            model.integrator.step(arguments.settle)
            harmonic, kinetic, potential = window(context, model.integrator, arguments.window)
            show("lattice", seed, t0, harmonic, kinetic, taken_apart(start_energies, potential))
        if "melt" in arguments.rows:
            melt(arguments, seed, t0)
        if "mean-E" in arguments.rows:
            mean_energy(arguments, seed, t0)
        if "ready" in arguments.rows:
            ready(arguments, seed, t0)
    print(f"T0 = {t0:.2f} K; {time.time() - start:.0f} s")


if __name__ == "__main__":
    main()
