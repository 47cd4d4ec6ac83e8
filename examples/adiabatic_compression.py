# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""Adiabatic compression of a liquid whose particles expand with temperature (docs/theory.md section 11).

Liquid argon with its thermal expansion (fluid.ARGON_EXPANDING: 125.7 K, 85.31 MPa, alpha = 2.64e-3 1/K; 5 atoms per
particle, R* = 1.6839), melted at T0, is compressed quasi-statically in the Conservative mode (velocity Verlet, no
exchange of heat between particles): a number of small deformations of the box, each scaling the box and the
positions so that the volume falls by a fixed fraction, with the integrator's setAdiabaticPositionChanges(True) (the
deformation keeps each particle's entropy, as the motion does), each followed by steps of the dynamics.

A particle of the TaitThermalExpansion law has sigma(n) = beta/n and C_V = C, so at fixed entropy
dtheta/dn = theta (dpi/dtheta)_n/(n^2 C) = theta beta/(n^2 C), i.e. theta = theta0 exp(beta (1/n0 - 1/n)/C).
Printed per stage: the volume, the mean particle density <n>, the mean particle temperature <theta>, the prediction of
that law at the mean density, theta(<n>) = <theta0> exp(beta (1/<n0> - 1/<n>)/C), the largest relative miss of a
particle's theta_i from its own isentrope theta_i0 exp(beta (1/n_i0 - 1/n_i)/C), and the relative drift of
K + U + sum eps (the conserved energy; the deformations do work, so it is reported since the last deformation).

    .venv/bin/python examples/adiabatic_compression.py                # 864 particles, 20 stages of 0.5%
"""

import argparse
import math

import numpy as np
from openmm import unit

from openmmgendpde import GenDPDEIntegrator
from openmmgendpde.calibration.expansion import mapped
from openmmgendpde.cli.options import (
    COUNT,
    NON_NEGATIVE_COUNT,
    add_platform,
    fcc_particles,
    number,
    one_line_errors,
    parse_arguments,
)
from openmmgendpde.models.fluid import ARGON_EXPANDING


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--particles", type=fcc_particles, default=864, help="4 m^3 particles (default 864)")
    parser.add_argument("--stages", type=NON_NEGATIVE_COUNT, default=20, help="deformations of the box (default 20)")
    parser.add_argument("--fraction", type=number(above=0, below=1), default=0.005,
                        help="volume removed per stage, > 0 and < 1 (default 0.005)")
    parser.add_argument("--steps", type=COUNT, default=100, help="Conservative steps after each stage (default 100)")
    add_platform(parser, default="CPU", allowed=("Reference", "CPU"))
    arguments = parse_arguments(parser)

    parameters = mapped()                                    # 5 atoms per particle, R* = 1.6839
    try:
        model = parameters.liquid(arguments.particles, mode=GenDPDEIntegrator.Isothermal, seed=3)
    except ValueError as error:
        parser.error(f"--particles {arguments.particles}: {error}".replace("use more cells", "use more --particles"))
    # Every argument checked before anything runs: the box at the end of the last stage still holds the cutoff.
    edge = model.volume ** (1 / 3) * (1 - arguments.fraction) ** (arguments.stages / 3)
    if edge < 2 * parameters.cutoff:
        parser.error(f"--fraction {arguments.fraction:g} and --stages {arguments.stages} are not allowed with "
                     f"--particles {arguments.particles}: the box would end {edge:.3f} nm across, less than twice the "
                     f"cutoff {parameters.cutoff:.3f} nm; use more --particles, or compress less")
    integrator, force = model.integrator, model.force
    context = model.melted(arguments.platform, GenDPDEIntegrator.Conservative, 500, 200, seed=3)   # melt at T0
    integrator.setAdiabaticPositionChanges(True)

    beta, capacity = parameters.thermal_pressure, parameters.heat_capacity
    kelvin, density_unit = unit.kelvin, unit.nanometer**-3

    def observe():
        theta = integrator.getParticleTemperatures().value_in_unit(kelvin)
        n = force.getParticleDensities(context).value_in_unit(density_unit)
        return n, theta

    particle_n0, particle_theta0 = observe()
    n0, theta0 = float(np.mean(particle_n0)), float(np.mean(particle_theta0))
    volume0 = model.volume
    print(f"{ARGON_EXPANDING.name}: {arguments.particles} particles, beta = {beta:.4f} kJ/mol/nm^3/K, "
          f"C = {capacity:.5f} kJ/mol/K")
    print(f"dtheta/dn at fixed s at the start: theta beta/(n^2 C) = {theta0 * beta / (n0 * n0 * capacity):.4f} K nm^3")
    print(" V/V0     <n> (nm^-3)  <theta> (K)  theta(<n>) (K)  difference  per particle  energy drift")
    print(f" {1:.4f}   {n0:.5f}      {theta0:.3f}      {theta0:.3f}          {0:+.2e}   {0:+.2e}    {0:+.1e}")
    scale = (1 - arguments.fraction) ** (1 / 3)
    for stage in range(arguments.stages):
        state = context.getState(getPositions=True)
        a, b, c = state.getPeriodicBoxVectors()
        context.setPeriodicBoxVectors(a * scale, b * scale, c * scale)
        context.setPositions(state.getPositions(asNumpy=True) * scale)
        start = integrator.getConservedEnergy().value_in_unit(unit.kilojoule_per_mole)
        integrator.step(arguments.steps)
        end = integrator.getConservedEnergy().value_in_unit(unit.kilojoule_per_mole)
        particle_n, particle_theta = observe()
        n, theta = float(np.mean(particle_n)), float(np.mean(particle_theta))
        predicted = theta0 * math.exp(beta * (1 / n0 - 1 / n) / capacity)
        # Each particle on its own isentrope: theta_i0 exp(beta (1/n_i0 - 1/n_i)/C), the largest relative miss.
        own = particle_theta0 * np.exp(beta * (1 / particle_n0 - 1 / particle_n) / capacity)
        volume = model.volume * scale ** (3 * (stage + 1))
        print(f" {volume / volume0:.4f}   {n:.5f}      {theta:.3f}      {predicted:.3f}          "
              f"{theta / predicted - 1:+.2e}   {np.max(np.abs(particle_theta / own - 1)):.2e}    "
              f"{(end - start) / abs(start):+.1e}", flush=True)


if __name__ == "__main__":
    one_line_errors("adiabatic_compression.py")
    main()
