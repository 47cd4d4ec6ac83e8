# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""The cost of an equation of state that depends on temperature, against the Tait law, per Isoenergetic step.

Two copies of liquid argon at R* = 1.6839 (VB, the published gamma*, kappa*, C_V*), one with the Tait law and one
with TaitThermalExpansion at liquid argon's alpha = 2.64e-3 1/K (beta = alpha gamma_T B_T, theta0 = T0), from the same
melted state, stepped in alternating rounds (openmmgendpde.benchmarks.measurement) on each platform asked for. Prints
the median ms per step of each and the median of the per-round ratios (thermal/Tait). The issue's goal is <= 1.15.

    .venv/bin/python benchmarks/thermal_cost.py --particles 4000 32000 --platforms Reference CPU:1 CPU:2
"""

import argparse

import numpy as np
from openmm import unit

from openmmgendpde import GenDPDEForce, GenDPDEIntegrator
from openmmgendpde.benchmarks.measurement import alternating_rounds, median, median_ratio
from openmmgendpde.models.argon import liquid_argon

ALPHA = 2.64e-3   # 1/K, liquid argon at 125.7 K, 85.31 MPa (the liquid state)


def contexts(num_particles, platform_name, threads):
    """The Tait and the thermal copy, each with its Context, in the same melted state."""
    made = {}
    for label in ("Tait", "TaitThermalExpansion"):
        model = liquid_argon(num_particles)
        if label != "Tait":
            _, _, bulk_modulus, gamma = model.force.getTaitParameters()
            beta = ALPHA * gamma * bulk_modulus.value_in_unit(unit.kilojoule_per_mole / unit.nanometer**3)
            model.force.setEquationOfState(GenDPDEForce.TaitThermalExpansion, [beta, model.temperature])
        properties = {"Threads": str(threads)} if platform_name == "CPU" else {}
        context = model.context(platform_name, properties=properties, seed=1)
        made[label] = (model, context)
    # Melt the lattice once (Tait copy, DPD thermostat) and give both copies that state.
    model, context = made["Tait"]
    model.integrator.setMode(GenDPDEIntegrator.Isothermal)
    model.integrator.step(300)
    model.integrator.setMode(GenDPDEIntegrator.Isoenergetic)
    state = context.getState(getPositions=True, getVelocities=True)
    for other, other_context in made.values():
        other_context.setPositions(state.getPositions())
        other_context.setVelocities(state.getVelocities())
        other.integrator.setParticleTemperatures([model.temperature] * model.num_particles)
    return made


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--particles", type=int, nargs="+", default=[4000, 32000])
    parser.add_argument("--platforms", nargs="+", default=["Reference", "CPU:1", "CPU:2"],
                        help="platform names; CPU:k is the CPU platform with k threads")
    parser.add_argument("--steps", type=int, default=10, help="steps per call")
    parser.add_argument("--rounds", type=int, default=9)
    arguments = parser.parse_args()
    print("N, platform: Tait ms/step, thermal ms/step (medians, min-max), thermal/Tait (median of the rounds' ratios)")
    for num_particles in arguments.particles:
        for entry in arguments.platforms:
            name, _, threads = entry.partition(":")
            made = contexts(num_particles, name, int(threads or 1))
            steps = arguments.steps
            candidates = {label: (lambda integrator=model.integrator: integrator.step(steps))
                          for label, (model, _) in made.items()}
            for call in candidates.values():
                call()   # warm up (first evaluation, pair lists)
            seconds = alternating_rounds(candidates, arguments.rounds)
            ms = {label: np.array(values) * 1000 / steps for label, values in seconds.items()}
            print(f"{num_particles}, {entry}: Tait {median(ms['Tait']):.2f} ({ms['Tait'].min():.2f}-"
                  f"{ms['Tait'].max():.2f}), thermal {median(ms['TaitThermalExpansion']):.2f} "
                  f"({ms['TaitThermalExpansion'].min():.2f}-{ms['TaitThermalExpansion'].max():.2f}), ratio "
                  f"{median_ratio(seconds, 'TaitThermalExpansion', 'Tait'):.3f}", flush=True)


if __name__ == "__main__":
    main()
