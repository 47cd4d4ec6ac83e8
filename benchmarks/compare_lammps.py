# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""GenDPDE's V-B force against LAMMPS's EAM, which has the same form, side by side (docs/performance.md).

V-A and V-B are embedded-atom potentials: U = sum_i F(rho_i) with rho_i = sum_j w(r_ij), the density function w of
docs/theory.md section 2, the embedding function F(rho) = f(1/V(rho)) (the Tait free energy at the particle's
density) and no pair term. This tool tabulates w and F for liquid argon at R* = 1.6839 (V-B) in LAMMPS's setfl
format (eam/alloy, metal units), then, on the same mixed liquid (openmmgendpde.benchmarks.cpu.mixed_liquid):

1. checks that the two codes agree: LAMMPS's energy and forces (run 0) against the CPU platform's, printed as the
   largest relative differences (the tabulation and LAMMPS's cubic splines limit the agreement, not the codes);
2. times MD steps (velocity Verlet, no thermostat) in alternating rounds: LAMMPS on --ranks MPI ranks (its own
   "Loop time", start-up excluded) against OpenMM's CPU platform with the same number of threads (VerletIntegrator,
   the same step), and prints the medians and the median of the per-round ratios.

LAMMPS sorts its atoms spatially when a run starts; --cell-order numbers the plugin's particles cell by cell too
(default: at random, as a long run has mixed them).

Needs Debian's lammps and openmpi-bin (apt install lammps openmpi-bin). Usage:

    .venv/bin/python benchmarks/compare_lammps.py [--particles 32000] [--ranks 2] [--steps 200] [--rounds 5]
"""

import argparse
import os
import re
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

import numpy as np
import openmm
from openmm import unit

from openmmgendpde import physics
from openmmgendpde.benchmarks.cpu import mixed_liquid
from openmmgendpde.models.argon import liquid_argon

CUTOFF = 1.6839
#: kJ/mol per eV
KJ_PER_MOL_PER_EV = 96.48533212331002
#: Grid points of the tabulated functions (LAMMPS interpolates them with cubic splines).
TABLE_POINTS = 20000


def tait_parameters(force):
    values = force.getTaitParameters()
    return (values[0].value_in_unit(unit.nanometer ** -3),
            values[1].value_in_unit(unit.kilojoule_per_mole / unit.nanometer ** 3),
            values[2].value_in_unit(unit.kilojoule_per_mole / unit.nanometer ** 3), values[3])


def write_setfl(path, model, max_density):
    """The setfl file: F(rho) in eV for rho in A^-3, w(r) in A^-3 for r in A, r phi = 0."""
    force = model.force
    cutoff = force.getCutoffDistance().value_in_unit(unit.nanometer)
    reduced_range = cutoff / force.getCutoffScaling()
    reference, pressure, modulus, exponent = tait_parameters(force)
    mass = model.system.getParticleMass(0).value_in_unit(unit.dalton)
    rho = np.linspace(0.0, max_density, TABLE_POINTS)                 # nm^-3
    embedding = np.array([physics.taitEquationOfState(1.0 / physics.particleVolumeVB(n0, reduced_range)[0],
                                                      reference, pressure, modulus, exponent)[1] for n0 in rho])
    r = np.linspace(0.0, cutoff, TABLE_POINTS)                        # nm
    weight = np.array([physics.densityWeight(x, cutoff)[0] for x in r])
    with open(path, "w") as stream:
        stream.write("GenDPDE V-B liquid argon as an EAM potential (openmm-gendpde benchmarks/compare_lammps.py)\n")
        stream.write("F(rho) = Tait free energy at 1/V_VB(rho); rho = sum_j w(r_ij); no pair term\n\n")
        stream.write("1 Ar\n")
        stream.write(f"{TABLE_POINTS} {rho[1] / 1000.0:.17g} {TABLE_POINTS} {r[1] * 10.0:.17g} "
                     f"{cutoff * 10.0:.17g}\n")
        stream.write(f"18 {mass:.17g} 0.0 fcc\n")
        np.savetxt(stream, embedding / KJ_PER_MOL_PER_EV, fmt="%.17g")
        np.savetxt(stream, weight / 1000.0, fmt="%.17g")
        np.savetxt(stream, np.zeros(TABLE_POINTS), fmt="%.1f")


def add_layout_argument(parser):
    """--cell-order and --state, for both comparison tools."""
    parser.add_argument("--cell-order", action="store_true",
                        help="number the plugin's particles cell by cell, as LAMMPS sorts its own atoms (default: at "
                             "random, the layout a long run has mixed its particles into)")
    parser.add_argument("--state", help="a saved liquid (.npz of positions and velocities, nm and nm/ps, as "
                                        "benchmarks/time_steps.py writes; its particle count replaces --particles) "
                                        "instead of melting one: for 1,000,000 particles, whose melting takes minutes")


def liquid(arguments, cutoff):
    """(number of particles, positions, velocities) of the liquid the tools compare: --state's, or
    openmmgendpde.benchmarks.cpu.mixed_liquid (melted, numbered at random) of --particles."""
    if arguments.state is None:
        return (arguments.particles, *mixed_liquid(arguments.particles, cutoff))
    saved = np.load(arguments.state)
    return len(saved["positions"]), saved["positions"], saved["velocities"]


def laid_out(positions, velocities, edge, cutoff, cell_order):
    """The particles numbered cell by cell (cells of at least the cutoff, z-major) if cell_order, else as given: the
    layout LAMMPS gives its own atoms, which it sorts spatially when a run starts and every 1000 steps (atom_modify
    sort)."""
    if not cell_order:
        return positions, velocities
    cells = max(1, int(edge // cutoff))
    index = np.floor(np.mod(positions, edge) / edge * cells).astype(np.int64) % cells
    order = np.lexsort((index[:, 0], index[:, 1], index[:, 2]))
    return positions[order], velocities[order]


def write_data(path, positions, velocities, edge, mass, temperature=None):
    """A LAMMPS data file (A and A/ps): atomic style, or dpd style (id type theta x y z) given the particles'
    temperature (K; benchmarks/compare_lammps_dpde.py)."""
    style, theta = ("atomic", "") if temperature is None else ("dpd", f" {temperature:.17g}")
    with open(path, "w") as stream:
        stream.write(f"GenDPDE liquid argon\n\n{len(positions)} atoms\n1 atom types\n\n")
        for axis in "xyz":
            stream.write(f"0.0 {edge * 10.0:.17g} {axis}lo {axis}hi\n")
        stream.write(f"\nMasses\n\n1 {mass:.17g}\n\nAtoms # {style}\n\n")
        wrapped = np.mod(positions, edge) * 10.0
        for index, (x, y, z) in enumerate(wrapped):
            stream.write(f"{index + 1} 1{theta} {x:.17g} {y:.17g} {z:.17g}\n")
        stream.write("\nVelocities\n\n")
        for index, (x, y, z) in enumerate(velocities * 10.0):
            stream.write(f"{index + 1} {x:.17g} {y:.17g} {z:.17g}\n")


def write_input(path, pair_style, skin, time_step, steps, dump):
    with open(path, "w") as stream:
        stream.write(f"""units metal
atom_style atomic
boundary p p p
read_data liquid.data
pair_style {pair_style}
pair_coeff * * gendpde_vb.eam.alloy Ar
neighbor {skin * 10.0:.17g} bin
neigh_modify every 1 delay 0 check yes
timestep {time_step:.17g}
fix integrate all nve
thermo_style custom step pe
thermo_modify format float %.17g
""")
        if dump:
            stream.write("dump forces all custom 1 forces.dump id fx fy fz\n"
                         "dump_modify forces format float %.17g sort id\nrun 0\n")
        else:
            stream.write(f"run {steps}\n")


def run_lammps(directory, ranks, input_name):
    command = ["mpirun", "--allow-run-as-root", "--oversubscribe", "-np", str(ranks), "lmp", "-in", input_name,
               "-log", "log.lammps", "-screen", "none"]
    subprocess.run(command, cwd=directory, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    with open(os.path.join(directory, "log.lammps")) as stream:
        return stream.read()


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--particles", type=int, default=32000)
    parser.add_argument("--ranks", type=int, default=2, help="LAMMPS MPI ranks = OpenMM CPU threads (default 2)")
    parser.add_argument("--steps", type=int, default=200, help="MD steps per timed run (default 200)")
    parser.add_argument("--rounds", type=int, default=5, help="alternating rounds (default 5)")
    parser.add_argument("--pair-style", default="eam/alloy/opt", help="LAMMPS pair style (default eam/alloy/opt)")
    add_layout_argument(parser)
    arguments = parser.parse_args()
    if shutil.which("lmp") is None or shutil.which("mpirun") is None:
        sys.exit("needs LAMMPS and MPI: apt install lammps openmpi-bin")

    arguments.particles, positions, velocities = liquid(arguments, CUTOFF)
    model = liquid_argon(arguments.particles, CUTOFF, "VB", seed=1)
    edge = model.system.getDefaultPeriodicBoxVectors()[0][0].value_in_unit(unit.nanometer)
    cutoff = model.force.getCutoffDistance().value_in_unit(unit.nanometer)
    positions, velocities = laid_out(positions, velocities, edge, cutoff, arguments.cell_order)
    time_step = model.integrator.getStepSize().value_in_unit(unit.picosecond)
    mass = model.system.getParticleMass(0).value_in_unit(unit.dalton)
    integrator = openmm.VerletIntegrator(time_step)
    context = model.context("CPU", properties={"Threads": str(arguments.ranks)}, positions=positions,
                            integrator=integrator, velocities=False)
    context.setVelocities(velocities)
    state = context.getState(getEnergy=True, getForces=True)
    energy = state.getPotentialEnergy().value_in_unit(unit.kilojoule_per_mole)
    forces = state.getForces(asNumpy=True).value_in_unit(unit.kilojoule_per_mole / unit.nanometer)
    mean_density = np.mean(model.force.getPrimitiveDensities(context).value_in_unit(unit.nanometer ** -3))

    with tempfile.TemporaryDirectory() as directory:
        write_setfl(os.path.join(directory, "gendpde_vb.eam.alloy"), model, 4.0 * mean_density)
        write_data(os.path.join(directory, "liquid.data"), positions, velocities, edge, mass)
        skin = 0.1 * cutoff   # the skin of the plugin's neighbour list
        write_input(os.path.join(directory, "check.in"), arguments.pair_style, skin, time_step, 0, True)
        write_input(os.path.join(directory, "time.in"), arguments.pair_style, skin, time_step, arguments.steps, False)

        # 1. Agreement.
        log = run_lammps(directory, arguments.ranks, "check.in")
        lammps_energy = float(re.findall(r"^\s*0\s+(\S+)\s*$", log, re.M)[0]) * KJ_PER_MOL_PER_EV
        dump = np.loadtxt(os.path.join(directory, "forces.dump"), skiprows=9)
        lammps_forces = dump[dump[:, 0].argsort(), 1:] * KJ_PER_MOL_PER_EV * 10.0   # eV/A -> kJ/mol/nm
        force_error = np.abs(lammps_forces - forces).max() / np.abs(forces).max()
        print(f"N = {arguments.particles}: potential energy OpenMM {energy:.10g} kJ/mol, LAMMPS {lammps_energy:.10g}"
              f" kJ/mol (relative difference {abs(lammps_energy - energy) / abs(energy):.2e}); largest force "
              f"difference {force_error:.2e} of the largest force")

        # 2. Speed, alternating rounds.
        openmm_ms, lammps_ms, ratios = [], [], []
        integrator.step(10)
        for _ in range(arguments.rounds):
            log = run_lammps(directory, arguments.ranks, "time.in")
            loop = float(re.search(r"Loop time of (\S+) on", log).group(1))
            start = time.perf_counter()
            integrator.step(arguments.steps)
            elapsed = time.perf_counter() - start
            lammps_ms.append(1e3 * loop / arguments.steps)
            openmm_ms.append(1e3 * elapsed / arguments.steps)
            ratios.append(loop / elapsed)
        print(f"MD step (velocity Verlet), {arguments.ranks} cores, medians of {arguments.rounds} alternating rounds "
              f"of {arguments.steps} steps:")
        print("| N | LAMMPS " + arguments.pair_style + f", {arguments.ranks} MPI ranks (ms/step) "
              f"| OpenMM CPU platform, {arguments.ranks} threads (ms/step) | LAMMPS / OpenMM |")
        print("|---|---|---|---|")
        print(f"| {arguments.particles} | {statistics.median(lammps_ms):.2f} | {statistics.median(openmm_ms):.2f} "
              f"| {statistics.median(ratios):.2f} |")


if __name__ == "__main__":
    main()
