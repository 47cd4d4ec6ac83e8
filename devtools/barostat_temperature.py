# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""The density that a MonteCarloBarostat gives an Isoenergetic liquid that is not at the barostat's temperature
(docs/fluids.md, "A barostat at the liquid's temperature"): liquid argon (500 particles, models.argon.liquid_argon)
run Isoenergetic from the lattice, so that it settles ~10 K below T0, at the model's pressure P0 with a barostat
(Model.add_barostat, a move every 5 steps) at T0, then with the barostat following the liquid's temperature
(reporter.BarostatTemperatureReporter). Printed: the harmonic mean of theta_i and the mass density over the run
after the first 4000 steps (correlated_mean), and the difference the ideal-gas term of the acceptance predicts,
dn/n = n k_B (T_barostat - T)/K_T with K_T = gamma_T B_T (n/n0)^gamma_T, the Tait modulus.

    python devtools/barostat_temperature.py --steps 60000
"""

import argparse

from openmm import unit

from openmmgendpde import BarostatTemperatureReporter
from openmmgendpde.analysis.statistics import correlated_mean
from openmmgendpde.analysis.thermodynamics import harmonic_temperature
from openmmgendpde.models.argon import ARGON_STATE, ARGON_UNITS, liquid_argon

KB = unit.MOLAR_GAS_CONSTANT_R.value_in_unit(unit.kilojoule_per_mole / unit.kelvin)


def run(follow, steps, seed):
    """(T_harm, mass density in g/mL, number density in nm^-3), each a CorrelatedMean."""
    model = liquid_argon(500, seed=seed)
    pressure = (ARGON_UNITS.to_openmm(ARGON_STATE.pressure, "pressure") / unit.AVOGADRO_CONSTANT_NA).in_units_of(
        unit.bar)
    model.add_barostat(pressure, 5, seed)
    simulation = model.simulation("CPU", seed, {"Threads": "1"})
    if follow:
        simulation.reporters.append(BarostatTemperatureReporter(5))
    mass = sum(model.system.getParticleMass(i).value_in_unit(unit.gram / unit.mole)
               for i in range(model.num_particles)) / 6.02214076e23
    simulation.step(4000)
    temperatures, volumes = [], []
    for _ in range(steps // 100):
        simulation.step(100)
        volume = simulation.context.getState().getPeriodicBoxVolume().value_in_unit(unit.nanometer**3)
        volumes.append(volume)
        temperatures.append(harmonic_temperature(model.integrator.getParticleTemperatures()))
    number = correlated_mean([model.num_particles / v for v in volumes])
    grams = correlated_mean([mass / (v * 1e-21) for v in volumes])
    return correlated_mean(temperatures), grams, number, model


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--steps", type=int, default=60000)
    parser.add_argument("--seed", type=int, default=21)
    arguments = parser.parse_args()
    results = {}
    for follow in (False, True):
        temperature, grams, number, model = run(follow, arguments.steps, arguments.seed)
        results[follow] = (temperature, grams, number)
        print(f"barostat {'following the liquid' if follow else 'at T0 = %.2f K' % model.bath_temperature}: "
              f"T_harm = {temperature.mean:.2f} +- {temperature.standard_error:.2f} K, density "
              f"{grams.mean:.5f} +- {grams.standard_error:.5f} g/mL", flush=True)
    (t_fixed, g_fixed, n_fixed), g_follow = results[False], results[True][1]
    p = model.parameters
    modulus = p.tait_exponent * p.bulk_modulus * (n_fixed.mean / p.density) ** p.tait_exponent
    predicted = n_fixed.mean * KB * (model.bath_temperature - t_fixed.mean) / modulus
    measured = g_follow.mean / g_fixed.mean - 1
    error = (g_follow.standard_error ** 2 + g_fixed.standard_error ** 2) ** 0.5 / g_fixed.mean
    print(f"density following / at T0 - 1 = {measured:.5f} +- {error:.5f}; predicted n k_B (T0 - T)/K_T = "
          f"{predicted:.5f}")


if __name__ == "__main__":
    main()
