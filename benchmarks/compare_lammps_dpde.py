# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""GenDPDEIntegrator's Isoenergetic step against LAMMPS's DPD-E (DPD-REACT package), side by side
(docs/performance.md, "Against LAMMPS (DPD-E and EAM)").

LAMMPS's energy-conserving DPD is the closest published code to this plugin's integrator: `pair_style
dpd/fdt/energy` (here with no conservative force, a0 = 0), `fix shardlow` (the same Shardlow splitting of the pair
terms, pair by pair at fixed positions), `fix eos/cv` (theta_i = u_i / C_V) and `fix nve`. This tool runs both on the
same liquid (liquid argon at R* = 1.6839, melted and renumbered at random: openmmgendpde.benchmarks.cpu.mixed_liquid),
with the same particles, box, cutoff, time step, neighbour skin (0.1 R, rebuilt when a particle has moved half of
it), weight 1 - r/R, heat conduction kappa and heat capacity C_V; LAMMPS's sigma is that of the plugin's friction
gamma at the bath temperature (sigma^2 = 2 gamma k_B T: DPD-E fixes sigma, GenDPDE fixes gamma, the same dynamics at
T). GenDPDE's step does more: it also evaluates the many-body V-B force (two passes over the pairs) that LAMMPS's run
leaves out.

Alternating rounds: LAMMPS (its own "Loop time", start-up excluded) on 1 thread and on --threads OpenMP threads
(`-sf omp -pk omp N`; DPD-REACT's styles have no threaded variants, so this measures what a second thread gives
LAMMPS), then the plugin's Isoenergetic step on Reference, on the CPU platform with 1 thread and with --threads
threads. Prints the medians (and the spread) of the per-round ms/step and the median per-round ratios.

LAMMPS sorts its atoms spatially when a run starts (and every 1000 steps), whatever their numbering; the plugin keeps
the numbering it is given. --cell-order gives the plugin the same start, particles numbered cell by cell, to measure
what the layout is worth.

LAMMPS with DPD-REACT is not in Debian's binary package: build it from Debian's source package with
devtools/build_lammps_dpd_react.sh (about 4 minutes on 2 cores), which prints the path of `lmp`. Usage:

    .venv/bin/python benchmarks/compare_lammps_dpde.py --lmp /tmp/lammps-dpd-react/build/lmp \
        --particles 32000 --steps 100 --rounds 5
"""

import argparse
import os
import re
import statistics
import subprocess
import tempfile
import time

import numpy as np

# (this directory: run as a script)
from compare_lammps import KJ_PER_MOL_PER_EV, add_layout_argument, laid_out, liquid, write_data
from openmm import unit

from openmmgendpde import GenDPDEIntegrator
from openmmgendpde.benchmarks.cpu import context_at
from openmmgendpde.models.argon import liquid_argon

CUTOFF = 1.6839
#: Boltzmann's constant in LAMMPS's metal units (eV/K)
BOLTZMANN_EV = 8.617343e-5


def write_input(path, integrator, cutoff, skin, steps):
    """The DPD-E run: LAMMPS metal units (eV, ps, A)."""
    gamma = integrator.getFriction().value_in_unit(unit.kilojoule_per_mole * unit.picosecond / unit.nanometer ** 2)
    gamma /= KJ_PER_MOL_PER_EV * 100.0                                   # eV ps / A^2
    temperature = integrator.getTemperature().value_in_unit(unit.kelvin)
    sigma = np.sqrt(2.0 * gamma * BOLTZMANN_EV * temperature)
    kappa = integrator.getHeatConduction().value_in_unit(unit.kilojoule_per_mole * unit.kelvin / unit.picosecond)
    kappa /= KJ_PER_MOL_PER_EV                                           # eV K / ps
    heat_capacity = integrator.getHeatCapacity().value_in_unit(unit.kilojoule_per_mole / unit.kelvin)
    heat_capacity /= KJ_PER_MOL_PER_EV                                   # eV / K
    time_step = integrator.getStepSize().value_in_unit(unit.picosecond)
    with open(path, "w") as stream:
        stream.write(f"""units metal
atom_style dpd
boundary p p p
comm_modify mode single vel yes
read_data liquid.data
pair_style dpd/fdt/energy {cutoff * 10.0:.17g} 245455
pair_coeff 1 1 0.0 {sigma:.17g} {kappa:.17g} {cutoff * 10.0:.17g}
neighbor {skin * 10.0:.17g} bin
neigh_modify every 1 delay 0 check yes
timestep {time_step:.17g}
fix shardlow all shardlow
fix integrate all nve
fix eos all eos/cv {heat_capacity:.17g}
thermo_style custom step temp pe ke
run {steps}
""")


def run_lammps(lmp, directory, threads, steps):
    command = [lmp, "-in", "dpde.in", "-log", "log.lammps", "-screen", "none"]
    if threads > 1:
        command += ["-sf", "omp", "-pk", "omp", str(threads)]
    environment = dict(os.environ, OMP_NUM_THREADS=str(threads))
    subprocess.run(command, cwd=directory, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                   env=environment)
    with open(os.path.join(directory, "log.lammps")) as stream:
        log = stream.read()
    return 1e3 * float(re.search(r"Loop time of (\S+) on", log).group(1)) / steps


def time_steps(integrator, steps):
    start = time.perf_counter()
    integrator.step(steps)
    return 1e3 * (time.perf_counter() - start) / steps


def summary(values):
    return f"{statistics.median(values):.2f} ({min(values):.2f}-{max(values):.2f})"


def add_run_arguments(parser, rounds):
    """--lmp, --particles, --steps and --rounds, for this tool and benchmarks/lammps_layout.py."""
    parser.add_argument("--lmp", default=os.environ.get("GENDPDE_LAMMPS", "lmp"),
                        help="a LAMMPS executable with DPD-REACT (default $GENDPDE_LAMMPS or lmp)")
    parser.add_argument("--particles", type=int, default=32000)
    parser.add_argument("--steps", type=int, default=100, help="steps per timed run (default 100)")
    parser.add_argument("--rounds", type=int, default=rounds, help=f"alternating rounds (default {rounds})")


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    add_run_arguments(parser, rounds=5)
    parser.add_argument("--threads", type=int, default=2, help="the second thread count (default 2)")
    parser.add_argument("--no-reference", action="store_true", help="leave out the Reference platform")
    add_layout_argument(parser)
    arguments = parser.parse_args()
    if arguments.threads < 1 or arguments.steps < 1 or arguments.rounds < 1:
        parser.error("--threads, --steps and --rounds must be >= 1")
    try:
        help_text = subprocess.run([arguments.lmp, "-h"], capture_output=True, text=True).stdout
    except OSError as error:
        parser.error(f"--lmp {arguments.lmp}: {error.strerror} (build it: devtools/build_lammps_dpd_react.sh)")
    if "DPD-REACT" not in help_text:
        parser.error(f"{arguments.lmp} has no DPD-REACT package (build it: devtools/build_lammps_dpd_react.sh)")

    arguments.particles, positions, velocities = liquid(arguments, CUTOFF)
    model = liquid_argon(arguments.particles, CUTOFF, "VB", seed=1, mode=GenDPDEIntegrator.Isoenergetic)
    edge = model.system.getDefaultPeriodicBoxVectors()[0][0].value_in_unit(unit.nanometer)
    cutoff = model.force.getCutoffDistance().value_in_unit(unit.nanometer)
    positions, velocities = laid_out(positions, velocities, edge, cutoff, arguments.cell_order)
    mass = model.system.getParticleMass(0).value_in_unit(unit.dalton)
    temperature = model.integrator.getTemperature().value_in_unit(unit.kelvin)
    candidates = {"Reference": ("Reference", None)} if not arguments.no_reference else {}
    candidates["CPU, 1 thread"] = ("CPU", 1)
    if arguments.threads > 1:
        candidates[f"CPU, {arguments.threads} threads"] = ("CPU", arguments.threads)
    integrators = {}
    for label, (platform, threads) in candidates.items():
        context, integrator = context_at(arguments.particles, CUTOFF, positions, velocities, platform, threads)
        integrator.step(10)
        integrators[label] = (context, integrator)
    lammps_threads = [1] + ([arguments.threads] if arguments.threads > 1 else [])

    times = {f"LAMMPS DPD-E, {t} thread{'s' if t > 1 else ''}": [] for t in lammps_threads}
    times.update({f"GenDPDE {label}": [] for label in integrators})
    ratios = {label: [] for label in times}
    with tempfile.TemporaryDirectory() as directory:
        write_data(os.path.join(directory, "liquid.data"), positions, velocities, edge, mass, temperature)
        write_input(os.path.join(directory, "dpde.in"), model.integrator, cutoff, 0.1 * cutoff, arguments.steps)
        for _ in range(arguments.rounds):
            this_round = {}
            for t in lammps_threads:
                this_round[f"LAMMPS DPD-E, {t} thread{'s' if t > 1 else ''}"] = run_lammps(
                    arguments.lmp, directory, t, arguments.steps)
            for label, (context, integrator) in integrators.items():
                this_round[f"GenDPDE {label}"] = time_steps(integrator, arguments.steps)
            lammps_one = this_round["LAMMPS DPD-E, 1 thread"]
            for label, value in this_round.items():
                times[label].append(value)
                ratios[label].append(lammps_one / value)
    layout = "numbered cell by cell" if arguments.cell_order else "numbered at random"
    print(f"N = {arguments.particles}, liquid argon R* = {CUTOFF}, {layout}, {arguments.rounds} alternating rounds of "
          f"{arguments.steps} steps; ms per step, median (min-max); speed-up = LAMMPS DPD-E on 1 thread / candidate "
          f"(median of the per-round ratios):")
    print("| N | candidate | ms per step | speed-up over LAMMPS DPD-E, 1 thread |")
    print("|---|---|---|---|")
    for label in times:
        print(f"| {arguments.particles} | {label} | {summary(times[label])} | {statistics.median(ratios[label]):.2f} |")


if __name__ == "__main__":
    main()
