#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""Digests of every deterministic result of the plugin, to show that a change which must not change behaviour
(a refactoring, a new build) leaves every result bit-identical.

    .venv/bin/python devtools/result_digest.py > before.txt      # on the old code
    .venv/bin/python devtools/result_digest.py > after.txt       # on the new code
    diff before.txt after.txt                                 # no output: bit-identical

One line per result: a name and the SHA-256 (16 hex digits) of its float64 bytes. Covered, on the Reference and
CPU platforms: energies, forces and every observable of GenDPDEForce (V-A and V-B, periodic, non-periodic and
triclinic, a dilute gas), 60-step trajectories of GenDPDEIntegrator in every mode (positions, velocities, internal
energies, conserved energy), a continuation from a checkpoint, the force-free DPD thermostat, the pointwise physics
functions on a grid, and the numbers that `table3 --quick` and `tune-fcut --quick` write. Takes about a minute.
V-C's force scenes are digested too (its arithmetic may be rearranged, so a change there is reported, not an error).

    .venv/bin/python devtools/result_digest.py --platforms OpenCL     # also (or only) another platform's force scenes
"""

import argparse
import contextlib
import hashlib
import io
import pathlib
import re
import sys
import tempfile

import numpy as np
import openmm
from openmm import unit

import openmmgendpde
from openmmgendpde import GenDPDEForce, GenDPDEIntegrator, physics
from openmmgendpde.__main__ import main
from openmmgendpde.models.argon import liquid_argon


def plain(value):
    """A float64 array of ``value``: Quantities in their own unit (OpenMM units throughout), lists of Vec3."""
    if unit.is_quantity(value):
        value = value.value_in_unit(value.unit)
    return np.asarray(value, dtype=np.float64)


def digest(name, *values):
    sha = hashlib.sha256()
    for value in values:
        sha.update(plain(value).tobytes())
    print(f"{name} {sha.hexdigest()[:16]}")


def jittered(argon, seed, jitter=0.02):
    """The preset's lattice positions with Gaussian jitter (nm), so that no two distances are equal."""
    return argon.positions + np.random.default_rng(seed).normal(0.0, jitter, argon.positions.shape)


def force_scenes():
    """(name, system, force, positions) for a set of force evaluations."""
    scenes = []
    for estimator in ("VA", "VB", "VC"):
        argon = liquid_argon(500, 1.6839, estimator)
        scenes.append((f"liquid-{estimator}", argon.system, argon.force, jittered(argon, 1)))
    argon = liquid_argon(500, 1.3365, "VB")
    argon.force.setNonbondedMethod(GenDPDEForce.CutoffNonPeriodic)
    scenes.append(("open-VB", argon.system, argon.force, jittered(argon, 2)))
    argon = liquid_argon(864, 1.6839, "VB")
    a, b, c = (v.value_in_unit(unit.nanometer) for v in argon.system.getDefaultPeriodicBoxVectors())
    argon.system.setDefaultPeriodicBoxVectors(a, openmm.Vec3(0.3 * a[0], b[1], 0),
                                              openmm.Vec3(-0.2 * a[0], 0.25 * a[0], c[2]))
    scenes.append(("triclinic-VB", argon.system, argon.force, jittered(argon, 3)))
    argon = liquid_argon(500, 1.6839, "VB")   # a dilute open cluster: isolated particles, k from 0 up
    argon.force.setNonbondedMethod(GenDPDEForce.CutoffNonPeriodic)
    argon.force.setCutoffScaling(1.41)
    scenes.append(("gas-VB", argon.system, argon.force, jittered(argon, 4) * 2.2))
    argon = liquid_argon(500, 1.6839, "VC")   # an open cluster: V-C's surface factor at work
    argon.force.setNonbondedMethod(GenDPDEForce.CutoffNonPeriodic)
    scenes.append(("open-VC", argon.system, argon.force, jittered(argon, 8)))
    return scenes


def force_results(platform):
    for name, system, force, positions in force_scenes():
        context = openmm.Context(system, openmm.VerletIntegrator(0.001), platform)
        context.setPositions(positions)
        state = context.getState(getEnergy=True, getForces=True)
        digest(f"{platform.getName()} force {name} energy", state.getPotentialEnergy())
        digest(f"{platform.getName()} force {name} forces", state.getForces(asNumpy=True))
        digest(f"{platform.getName()} force {name} observables", force.getPrimitiveDensities(context),
               force.getParticleDensities(context), force.getParticleVolumes(context),
               force.getParticlePressures(context), force.getVirial(context))


def trajectory_results(platform):
    modes = {"Isoenergetic": GenDPDEIntegrator.Isoenergetic, "Isothermal": GenDPDEIntegrator.Isothermal,
             "Conservative": GenDPDEIntegrator.Conservative}
    for name, mode in modes.items():
        for estimator in ("VA", "VB"):
            argon = liquid_argon(500, 1.6839, estimator, time_step=0.005, seed=7, mode=mode)
            simulation = argon.simulation(platform.getName(), velocity_seed=3)
            context, integrator = simulation.context, argon.integrator
            context.setPositions(jittered(argon, 5))
            integrator.step(40)
            checkpoint = context.createCheckpoint()
            integrator.step(20)
            state = context.getState(getPositions=True, getVelocities=True)
            label = f"{platform.getName()} {name} {estimator}"
            digest(f"{label} trajectory", state.getPositions(asNumpy=True), state.getVelocities(asNumpy=True),
                   integrator.getInternalEnergies(), integrator.getConservedEnergy())
            context.loadCheckpoint(checkpoint)
            integrator.step(20)
            again = context.getState(getPositions=True, getVelocities=True)
            digest(f"{label} continued", again.getPositions(asNumpy=True), again.getVelocities(asNumpy=True),
                   integrator.getInternalEnergies())
    # The force-free DPD thermostat (the integrator's own pair list).
    argon = liquid_argon(500, 1.6839, "VB", time_step=0.01, seed=9, mode=GenDPDEIntegrator.Isothermal)
    system = openmm.System()
    system.setDefaultPeriodicBoxVectors(*argon.system.getDefaultPeriodicBoxVectors())
    for i in range(argon.num_particles):
        system.addParticle(argon.system.getParticleMass(i))
    system.addForce(openmm.CustomExternalForce("0*periodicdistance(x, y, z, 0, 0, 0)"))
    argon.integrator.setCutoffDistance(argon.force.getCutoffDistance())
    context = openmm.Context(system, argon.integrator, platform)
    context.setPositions(jittered(argon, 6))
    context.setVelocitiesToTemperature(125.7, 4)
    argon.integrator.step(60)
    state = context.getState(getPositions=True, getVelocities=True)
    digest(f"{platform.getName()} plain DPD", state.getPositions(asNumpy=True), state.getVelocities(asNumpy=True))


def physics_results():
    ks = np.concatenate([[0.0, 1e-300, 1e-12], np.geomspace(1e-6, 1e12, 400)])
    digest("physics volumeIntegralsVB", [physics.volumeIntegralsVB(k) for k in ks])
    digest("physics particleVolumeVB", [physics.particleVolumeVB(n, 0.77) for n in np.linspace(0, 40, 300)])
    digest("physics particleVolumeVA", [physics.particleVolumeVA(n) for n in np.linspace(0.1, 40, 300)])
    digest("physics densityWeight", [physics.densityWeight(r, 1.04) for r in np.linspace(0, 1.2, 300)])
    digest("physics taitEquationOfState", [physics.taitEquationOfState(n, 4.27, 46.9, 67.4, 6.0)
                                           for n in np.linspace(0.5, 9, 300)])


def command_line_results():
    with tempfile.TemporaryDirectory() as directory:
        with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(io.StringIO()):
            main(["table3", "--quick", "--output", directory])
        rows = pathlib.Path(directory, "table3.csv").read_text().splitlines()[1:]
        digest("table3 --quick csv", [[float(x) for x in row.split(",")[3:7]] for row in rows])
        for frames in sorted(pathlib.Path(directory).glob("frames-*.npz")):
            digest(f"table3 --quick {frames.stem}", np.load(frames)["positions"])
    output = io.StringIO()
    with contextlib.redirect_stdout(output), contextlib.redirect_stderr(io.StringIO()):
        main(["tune-fcut", "--quick"])
    numbers = [float(x) for x in re.findall(r"[-+]?\d+\.\d+", output.getvalue())]
    digest("tune-fcut --quick", numbers)


def run(arguments):
    print(f"# openmmgendpde {openmmgendpde.__version__}, OpenMM {openmm.__version__}", file=sys.stderr)
    if arguments.platforms:   # only the force scenes of these platforms (e.g. OpenCL in double precision)
        for name in arguments.platforms:
            platform = openmm.Platform.getPlatformByName(name)
            if name in ("OpenCL", "CUDA"):
                platform.setPropertyDefaultValue("Precision", arguments.precision)
            force_results(platform)
        return
    physics_results()
    for name in ("Reference", "CPU"):
        platform = openmm.Platform.getPlatformByName(name)
        force_results(platform)
        trajectory_results(platform)
    command_line_results()


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--platforms", nargs="+", help="digest only the force scenes on these platforms")
    parser.add_argument("--precision", default="double", help="of the GPU platforms (default double)")
    run(parser.parse_args())
