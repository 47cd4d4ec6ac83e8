# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""Two liquids exchanging heat across an interface: particle types with their own heat capacity, equation of state,
mass, and a per-pair heat conduction (docs/types.md).

    .venv/bin/python examples/two_materials.py [--platform CPU] [--steps 8000]

A periodic box of two cubes of 500 particles each: liquid argon (type 0, the published model at R* = 1.6839) and a
heavier, stiffer liquid B (type 1: 4 times the mass, 3 times the heat capacity, 1.5 times the bulk modulus, twice
argon's heat conduction among its own particles). Across the interface the conduction is a quarter of argon's (a
thermal contact resistance). Both are melted together at T0 with the DPD thermostat; then argon starts at 1.2 T0
and B at 0.8 T0 (internal energies and velocities), and full isoenergetic GenDPDE runs. Every 400 steps the script
prints, in reduced units, the harmonic-mean particle temperature of each material, the kinetic temperature and the
relative drift of the conserved energy; at the end, the relaxation time of the temperature difference from a
log-linear fit. The heat argon loses is what B gains: the total energy stays constant.
"""

import argparse

import numpy as np
import openmm
from openmm import unit

from openmmgendpde import GenDPDEIntegrator
from openmmgendpde.cli.options import add_platform, integer, one_line_errors, parse_arguments
from openmmgendpde.models.argon import ARGON_UNITS, liquid_argon

one_line_errors("two_materials.py")
parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
add_platform(parser, default="CPU")
parser.add_argument("--steps", type=integer(400, why=" (a report every 400 steps)"), default=8000,
                    help="isoenergetic steps after melting (dt* = 0.01), reported every 400 (default 8000)")
args = parse_arguments(parser)

# One cube of liquid argon (500 particles, n0* = 1); the box is doubled along x and the second cube becomes B.
argon = liquid_argon(num_particles=500, cutoff=1.6839, time_step=0.01, seed=3)
system, force, integrator = argon.system, argon.force, argon.integrator
edge = argon.box_volume ** (1 / 3)
system.setDefaultPeriodicBoxVectors(openmm.Vec3(2 * edge, 0, 0), openmm.Vec3(0, edge, 0), openmm.Vec3(0, 0, edge))
positions = np.vstack([argon.positions, argon.positions + [edge, 0, 0]])
mass_argon = system.getParticleMass(0)
types = np.repeat([0, 1], 500)
for i in range(500, 1000):
    system.addParticle(4 * mass_argon)
for i in np.flatnonzero(types == 1):
    force.setParticleType(int(i), 1)          # the integrator takes the types from the force (docs/types.md)

n0, pi0, bulk_modulus, exponent = force.getTaitParameters()
force.addTypeParameters(1, n0, pi0, 1.5 * bulk_modulus, exponent)   # same n0 and pi0: the same pressure at n0
heat_capacity, conduction = integrator.getHeatCapacity(), integrator.getHeatConduction()
integrator.addTypeHeatCapacity(1, 3 * heat_capacity)
integrator.addTypePair(1, 1, integrator.getFriction(), 2 * conduction)
integrator.addTypePair(0, 1, integrator.getFriction(), 0.25 * conduction)

context = openmm.Context(system, integrator, openmm.Platform.getPlatformByName(args.platform))
context.setPositions(positions)
t0 = argon.temperature.value_in_unit(unit.kelvin)

# Melt both cubes together with the DPD thermostat at T0 (2000 steps, dt* = 0.01: 20 time units).
context.setVelocitiesToTemperature(t0 * unit.kelvin, 3)
integrator.setMode(GenDPDEIntegrator.Isothermal)
integrator.step(2000)

# Argon at 1.2 T0, B at 0.8 T0: internal energies drawn from each type's equilibrium (Gamma) law and scaled so that
# each material's harmonic-mean temperature is exactly its target, and Maxwell-Boltzmann velocities.
start = np.where(types == 0, 1.2 * t0, 0.8 * t0)
integrator.setMode(GenDPDEIntegrator.Isoenergetic)
integrator.setInternalEnergiesToTemperature(t0 * unit.kelvin, 3)
theta = integrator.getParticleTemperatures().value_in_unit(unit.kelvin)
for t in (0, 1):
    theta[types == t] *= start[types == t][0] * np.mean(1 / theta[types == t])
integrator.setParticleTemperatures(theta)
kb = unit.MOLAR_GAS_CONSTANT_R.value_in_unit(unit.kilojoule_per_mole / unit.kelvin)
masses = np.array([system.getParticleMass(i).value_in_unit(unit.amu) for i in range(1000)])
rng = np.random.default_rng(3)
velocities = rng.normal(size=(1000, 3)) * np.sqrt(kb * start / masses)[:, None]
velocities -= (masses[:, None] * velocities).sum(axis=0) / masses.sum()   # no net momentum
context.setVelocities(velocities)


def harmonic_means():
    theta = integrator.getParticleTemperatures().value_in_unit(unit.kelvin)
    return [1 / np.mean(1 / theta[types == t]) / t0 for t in (0, 1)]


energy_start = integrator.getConservedEnergy().value_in_unit(unit.kilojoule_per_mole)
time_unit = ARGON_UNITS.unit("time").value_in_unit(unit.picosecond)
dt = integrator.getStepSize().value_in_unit(unit.picosecond) / time_unit
print("t*      theta_argon*/T0  theta_B*/T0  T_kin/T0  energy drift")
times, differences = [], []
for block in range(args.steps // 400 + 1):
    if block > 0:
        integrator.step(400)
    argon_theta, b_theta = harmonic_means()
    kinetic = context.getState(getEnergy=True).getKineticEnergy().value_in_unit(unit.kilojoule_per_mole)
    kinetic_temperature = 2 * kinetic / ((3 * 1000 - 3) * kb) / t0
    energy = integrator.getConservedEnergy().value_in_unit(unit.kilojoule_per_mole)
    times.append(block * 400 * dt)
    differences.append(argon_theta - b_theta)
    print(f"{times[-1]:6.1f}  {argon_theta:15.4f}  {b_theta:11.4f}  {kinetic_temperature:8.4f}  "
          f"{(energy - energy_start) / abs(energy_start):+.2e}")

# The difference decays roughly exponentially once the first transient (velocities and neighbours adjusting) is
# over: fit log(difference) over the points above 10% of the start.
times, differences = np.array(times), np.array(differences)
usable = (times > 0) & (differences > 0.1 * differences[0])
if usable.sum() >= 3:
    slope = np.polyfit(times[usable], np.log(differences[usable]), 1)[0]
    print(f"relaxation time of theta_argon - theta_B: {-1 / slope:.1f} time units")
