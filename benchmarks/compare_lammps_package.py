# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""The LAMMPS package (lammps/: pair_style gendpde + fix gendpde) against LAMMPS's own DPD-E step and EAM, and against
this plugin's CPU platform, side by side (docs/lammps.md, "Speed").

On one liquid (liquid argon at R* = 1.6839 with V-B, melted and numbered at random, or --state), alternating rounds of:
- LAMMPS GenDPDE: the files `python -m openmmgendpde lammps-input` writes for the model (Isoenergetic: the pair
  sweep across subdomains, the many-body force, velocity Verlet), on 1 and 2 MPI ranks;
- LAMMPS DPD-E: pair dpd/fdt/energy with no conservative force, fix shardlow, fix eos/cv, fix nve (the same
  Shardlow sweep, no many-body force: benchmarks/compare_lammps_dpde.py's input), on 1 and 2 ranks;
- LAMMPS EAM: eam/alloy/opt tabulating the same V-B force, velocity Verlet (benchmarks/compare_lammps.py's input),
  on 1 and 2 ranks;
- this plugin's GenDPDEIntegrator (Isoenergetic) on the CPU platform with 1 and 2 threads.
LAMMPS's own "Loop time" (start-up excluded); ms per step, medians (min-max) over the rounds, and the medians of the
per-round ratios. Needs lammps/build.sh (LAMMPS with MPI, DPD-REACT, MANYBODY, OPT and the plugin). Usage:

    .venv/bin/python benchmarks/compare_lammps_package.py --particles 32000 --steps 50 --rounds 5
    .venv/bin/python benchmarks/compare_lammps_package.py --state argon256k.npz --steps 10 --rounds 3

--weak-state STATE (a liquid of twice the particles): in the same rounds, LAMMPS GenDPDE and DPD-E on 2 ranks with
it, for the weak scaling t(N, 1 rank)/t(2N, 2 ranks).
"""

import argparse
import os
import pathlib
import re
import statistics
import subprocess
import tempfile

import numpy as np

# (this directory: run as a script)
from compare_lammps import add_layout_argument, liquid, write_data, write_setfl
from compare_lammps import write_input as write_eam_input
from compare_lammps_dpde import summary, time_steps
from compare_lammps_dpde import write_input as write_dpde_input
from openmm import unit

from openmmgendpde import GenDPDEIntegrator
from openmmgendpde.benchmarks.cpu import context_at
from openmmgendpde.models.argon import liquid_argon
from openmmgendpde.models.lammps_files import lammps_input, write_lammps_input

CUTOFF = 1.6839
ROOT = pathlib.Path(__file__).resolve().parents[1]


def run_lammps(lmp, directory, script, ranks, steps, plugin=None):
    command = ["mpirun", "--allow-run-as-root", "--oversubscribe", "-np", str(ranks), str(lmp), "-in", script,
               "-log", "log.lammps", "-screen", "none"]
    if plugin is not None:
        command += ["-var", "plugin", str(plugin)]
    subprocess.run(command, cwd=directory, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    log = (pathlib.Path(directory) / "log.lammps").read_text()
    return 1e3 * float(re.search(r"Loop time of (\S+) on", log).group(1)) / steps


def parse_arguments():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--lmp", default=ROOT / "build/lammps/lammps/lmp", type=pathlib.Path)
    parser.add_argument("--plugin", default=ROOT / "build/lammps/plugin/gendpdeplugin.so", type=pathlib.Path)
    parser.add_argument("--particles", type=int, default=32000)
    parser.add_argument("--steps", type=int, default=50, help="steps per timed run (default 50)")
    parser.add_argument("--rounds", type=int, default=5, help="alternating rounds (default 5)")
    parser.add_argument("--ranks", default="1,2", help="MPI ranks (and CPU threads) to compare (default 1,2)")
    parser.add_argument("--weak-state", help="a saved liquid of twice the particles, for weak scaling (2 ranks)")
    add_layout_argument(parser)
    arguments = parser.parse_args()
    for path in (arguments.lmp, arguments.plugin):
        if not path.exists():
            parser.error(f"{path} does not exist: run lammps/build.sh")
    return arguments


def write_inputs(directory, arguments, model, positions, velocities):
    """The LAMMPS inputs of the three candidates (GenDPDE, DPD-E, eam/alloy/opt) in sub-directories of ``directory``,
    and with --weak-state those of twice the particles (GenDPDE and DPD-E); {name: directory}, and the weak case's
    particle count (None without it)."""
    edge = model.system.getDefaultPeriodicBoxVectors()[0][0].value_in_unit(unit.nanometer)
    cutoff = model.force.getCutoffDistance().value_in_unit(unit.nanometer)
    mass = model.system.getParticleMass(0).value_in_unit(unit.dalton)
    temperature = model.integrator.getTemperature().value_in_unit(unit.kelvin)
    time_step = model.integrator.getStepSize().value_in_unit(unit.picosecond)
    directories = {name: os.path.join(directory, name) for name in ("gendpde", "dpde", "eam")}
    for path in directories.values():
        os.makedirs(path)
    write_lammps_input(directories["gendpde"], lammps_input(model.system, model.integrator, positions, velocities,
                                                            steps=arguments.steps, thermo=arguments.steps))
    write_data(os.path.join(directories["dpde"], "liquid.data"), positions, velocities, edge, mass, temperature)
    write_dpde_input(os.path.join(directories["dpde"], "dpde.in"), model.integrator, cutoff, 0.1 * cutoff,
                     arguments.steps)
    write_data(os.path.join(directories["eam"], "liquid.data"), positions, velocities, edge, mass)
    write_setfl(os.path.join(directories["eam"], "gendpde_vb.eam.alloy"), model, 4.0 * arguments.particles
                / edge**3)
    write_eam_input(os.path.join(directories["eam"], "eam.in"), "eam/alloy/opt", 0.1 * cutoff, time_step,
                    arguments.steps, False)
    if not arguments.weak_state:
        return directories, None
    # the same liquid, twice the particles: GenDPDE and DPD-E on 2 ranks
    saved = np.load(arguments.weak_state)
    big = liquid_argon(len(saved["positions"]), CUTOFF, "VB", seed=1, mode=GenDPDEIntegrator.Isoenergetic)
    big_edge = big.system.getDefaultPeriodicBoxVectors()[0][0].value_in_unit(unit.nanometer)
    for name in ("weak-gendpde", "weak-dpde"):
        directories[name] = os.path.join(directory, name)
        os.makedirs(directories[name])
    write_lammps_input(directories["weak-gendpde"],
                       lammps_input(big.system, big.integrator, saved["positions"], saved["velocities"],
                                    steps=arguments.steps, thermo=arguments.steps))
    write_data(os.path.join(directories["weak-dpde"], "liquid.data"), saved["positions"], saved["velocities"],
               big_edge, mass, temperature)
    write_dpde_input(os.path.join(directories["weak-dpde"], "dpde.in"), big.integrator, cutoff, 0.1 * cutoff,
                     arguments.steps)
    return directories, len(saved["positions"])


def timed_rounds(arguments, ranks, labels, contexts, directories, weak):
    """ms per step of every candidate (labels) and of the weak case's (``weak``: {name: []} to fill), in alternating
    rounds: {label: [ms, ...]}."""
    times = {label: [] for r in ranks for label in labels[r]}
    if weak:
        times["weak GenDPDE"], times["weak DPD-E"] = weak["LAMMPS GenDPDE"], weak["LAMMPS DPD-E"]
    for _ in range(arguments.rounds):
        if weak:
            weak["LAMMPS GenDPDE"].append(run_lammps(arguments.lmp, directories["weak-gendpde"], "in.gendpde", 2,
                                                     arguments.steps, arguments.plugin))
            weak["LAMMPS DPD-E"].append(run_lammps(arguments.lmp, directories["weak-dpde"], "dpde.in", 2,
                                                   arguments.steps))
        for r in ranks:
            gendpde, dpde, eam, cpu = labels[r]
            times[gendpde].append(run_lammps(arguments.lmp, directories["gendpde"], "in.gendpde", r,
                                             arguments.steps, arguments.plugin))
            times[dpde].append(run_lammps(arguments.lmp, directories["dpde"], "dpde.in", r, arguments.steps))
            times[eam].append(run_lammps(arguments.lmp, directories["eam"], "eam.in", r, arguments.steps))
            times[cpu].append(time_steps(contexts[r][1], arguments.steps))
    return times


def report(arguments, ranks, labels, times, weak, weak_particles):
    load = os.getloadavg()[0]
    layout = "numbered cell by cell" if arguments.cell_order else "numbered at random"
    print(f"N = {arguments.particles}, liquid argon R* = {CUTOFF} V-B, {layout}; {arguments.rounds} alternating rounds "
          f"of {arguments.steps} steps; ms per step, median (min-max); load average at the end {load:.2f}")
    print("| N | candidate | ms per step | LAMMPS GenDPDE / candidate (same ranks) |")
    print("|---|---|---|---|")
    for r in ranks:
        for label in labels[r]:
            ratios = [g / c for g, c in zip(times[labels[r][0]], times[label])]
            print(f"| {arguments.particles} | {label} | {summary(times[label])} | {statistics.median(ratios):.2f} |")
    if 1 in ranks and len(ranks) > 1:
        for label_index, name in enumerate(("LAMMPS GenDPDE", "LAMMPS DPD-E", "LAMMPS eam/alloy/opt",
                                            "OpenMM CPU platform")):
            one = times[labels[1][label_index]]
            for r in ranks[1:]:
                speedups = [a / b for a, b in zip(one, times[labels[r][label_index]])]
                print(f"{name}: {r} ranks/threads {statistics.median(speedups):.2f}x one (strong scaling)")
    for name, values in (weak.items() if 1 in ranks else ()):
        one = times[labels[1][0 if name == "LAMMPS GenDPDE" else 1]]
        efficiency = [a / b for a, b in zip(one, values)]
        print(f"{name}: 2 ranks with {weak_particles} particles {summary(values)} ms per step; weak scaling "
              f"t(N, 1 rank)/t(2N, 2 ranks) = {statistics.median(efficiency):.2f}")


def main():
    arguments = parse_arguments()
    ranks = [int(r) for r in arguments.ranks.split(",")]
    arguments.particles, positions, velocities = liquid(arguments, CUTOFF)
    model = liquid_argon(arguments.particles, CUTOFF, "VB", seed=1, mode=GenDPDEIntegrator.Isoenergetic)
    contexts = {}
    for r in ranks:
        contexts[r] = context_at(arguments.particles, CUTOFF, positions, velocities, "CPU", r)
        contexts[r][1].step(5)
    labels = {r: [f"LAMMPS GenDPDE, {r} rank{'s' if r > 1 else ''}", f"LAMMPS DPD-E, {r} rank{'s' if r > 1 else ''}",
                  f"LAMMPS eam/alloy/opt, {r} rank{'s' if r > 1 else ''}",
                  f"OpenMM CPU platform GenDPDE, {r} thread{'s' if r > 1 else ''}"] for r in ranks}
    with tempfile.TemporaryDirectory() as directory:
        directories, weak_particles = write_inputs(directory, arguments, model, positions, velocities)
        weak = {"LAMMPS GenDPDE": [], "LAMMPS DPD-E": []} if weak_particles else {}
        times = timed_rounds(arguments, ranks, labels, contexts, directories, weak)
    report(arguments, ranks, labels, times, weak, weak_particles)


if __name__ == "__main__":
    main()
