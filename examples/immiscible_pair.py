# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""Two liquids that do not mix: particle types plus a repulsion between unlike particles (docs/types.md).

    .venv/bin/python examples/immiscible_pair.py [--steps 20000] [--repulsion 0 20]

GenDPDE's density counts every neighbour whatever its type, and the force has no term that prefers like
neighbours, so two types mix (as ideal mixtures do). An immiscible pair needs an energy cost for unlike contacts:
here an OpenMM CustomNonbondedForce, a (1 - r/R)^2 between particles of different types only (the soft repulsion of
DPD), next to the GenDPDEForce. Two cubes of 500 argon particles side by side (types 0 and 1, the same model) are
run with the DPD thermostat at T0 for each repulsion a (in k_B T0); the script prints the fraction of each
particle's neighbours within R that are of the other type: 0.067 at the start (two flat interfaces), rising towards
0.5 as the liquids mix.
"""

import argparse

import numpy as np
import openmm
from openmm import unit

from openmmgendpde import GenDPDEIntegrator
from openmmgendpde.cli.options import NON_NEGATIVE, NON_NEGATIVE_COUNT, add_platform, one_line_errors, parse_arguments
from openmmgendpde.models.argon import liquid_argon

one_line_errors("immiscible_pair.py")
parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
add_platform(parser, default="CPU")
parser.add_argument("--steps", type=NON_NEGATIVE_COUNT, default=20000, help="thermostatted steps (dt* = 0.01)")
parser.add_argument("--repulsion", type=NON_NEGATIVE, nargs="+", default=[0.0, 20.0],
                    help="a in units of k_B T0, >= 0 (default 0 20)")
args = parse_arguments(parser)


def unlike_fraction(positions, box, types, cutoff):
    d = positions[:, None, :] - positions[None, :, :]
    d -= box * np.round(d / box)
    r = np.sqrt((d ** 2).sum(axis=-1))
    near = (r < cutoff) & (r > 0)
    return (near & (types[:, None] != types[None, :])).sum() / near.sum()


for repulsion in args.repulsion:
    argon = liquid_argon(num_particles=500, cutoff=1.6839, time_step=0.01, seed=3,
                         mode=GenDPDEIntegrator.Isothermal)
    system, force, integrator = argon.system, argon.force, argon.integrator
    edge = argon.box_volume ** (1 / 3)
    box = np.array([2 * edge, edge, edge])
    system.setDefaultPeriodicBoxVectors(openmm.Vec3(box[0], 0, 0), openmm.Vec3(0, edge, 0), openmm.Vec3(0, 0, edge))
    positions = np.vstack([argon.positions, argon.positions + [edge, 0, 0]])
    types = np.repeat([0, 1], 500)
    for i in range(500, 1000):
        system.addParticle(system.getParticleMass(0))
        force.setParticleType(i, 1)   # (the integrator takes the types from the force)
    cutoff = force.getCutoffDistance().value_in_unit(unit.nanometer)
    kt = (unit.MOLAR_GAS_CONSTANT_R * argon.temperature).value_in_unit(unit.kilojoule_per_mole)
    if repulsion > 0:
        unlike = openmm.CustomNonbondedForce(f"a*(1 - r/{cutoff})^2*(1 - delta(t1 - t2)); a = {repulsion * kt}")
        unlike.addPerParticleParameter("t")
        for t in types:
            unlike.addParticle([float(t)])
        unlike.setNonbondedMethod(openmm.CustomNonbondedForce.CutoffPeriodic)
        unlike.setCutoffDistance(cutoff)
        system.addForce(unlike)
    context = openmm.Context(system, integrator, openmm.Platform.getPlatformByName(args.platform))
    context.setPositions(positions)
    context.setVelocitiesToTemperature(argon.temperature, 3)
    start = unlike_fraction(positions, box, types, cutoff)
    integrator.step(args.steps)
    end = context.getState(getPositions=True).getPositions(asNumpy=True).value_in_unit(unit.nanometer)
    print(f"a = {repulsion:5.1f} k_B T0: unlike neighbours {start:.3f} at the start, "
          f"{unlike_fraction(end, box, types, cutoff):.3f} after {args.steps} steps")
