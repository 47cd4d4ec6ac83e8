# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""Whether LAMMPS's DPD-E step depends on the numbering of its atoms (docs/performance.md, "Against LAMMPS").

LAMMPS sorts its atoms spatially when a run starts and every 1000 steps (`atom_modify sort`). This tool runs the DPD-E
input of benchmarks/compare_lammps_dpde.py on the same liquid, in alternating rounds, four ways: numbered at random with
LAMMPS's default sort, at random with the sort switched off (`atom_modify sort 0 0.0`), at random sorted every step,
and numbered cell by cell with the default sort. It prints LAMMPS's ms per step, median (min-max) of the rounds. Usage:

    .venv/bin/python benchmarks/lammps_layout.py --lmp /tmp/lammps-dpd-react/build/lmp \
        --particles 32000 --steps 100 --rounds 3
"""

import argparse
import os
import statistics
import tempfile

# (this directory: run as a script)
from compare_lammps import laid_out, write_data
from compare_lammps_dpde import CUTOFF, add_run_arguments, run_lammps, write_input
from openmm import unit

from openmmgendpde import GenDPDEIntegrator
from openmmgendpde.benchmarks.cpu import mixed_liquid
from openmmgendpde.models.argon import liquid_argon

#: label -> (numbered cell by cell, the atom_modify line added after read_data or None)
CASES = {
    "random numbering, LAMMPS's default sort": (False, None),
    "random numbering, sort off": (False, "atom_modify sort 0 0.0"),
    "random numbering, sorted every step": (False, "atom_modify sort 1 0.0"),
    "cell numbering, LAMMPS's default sort": (True, None),
}


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    add_run_arguments(parser, rounds=3)
    arguments = parser.parse_args()
    if arguments.steps < 1 or arguments.rounds < 1:
        parser.error("--steps and --rounds must be >= 1")
    model = liquid_argon(arguments.particles, CUTOFF, "VB", seed=1, mode=GenDPDEIntegrator.Isoenergetic)
    positions, velocities = mixed_liquid(arguments.particles, CUTOFF)
    edge = model.system.getDefaultPeriodicBoxVectors()[0][0].value_in_unit(unit.nanometer)
    cutoff = model.force.getCutoffDistance().value_in_unit(unit.nanometer)
    mass = model.system.getParticleMass(0).value_in_unit(unit.dalton)
    temperature = model.integrator.getTemperature().value_in_unit(unit.kelvin)
    with tempfile.TemporaryDirectory() as root:
        runs = {}
        for label, (cell_order, sort_line) in CASES.items():
            directory = os.path.join(root, str(len(runs)))
            os.mkdir(directory)
            p, v = laid_out(positions, velocities, edge, cutoff, cell_order)
            write_data(os.path.join(directory, "liquid.data"), p, v, edge, mass, temperature)
            path = os.path.join(directory, "dpde.in")
            write_input(path, model.integrator, cutoff, 0.1 * cutoff, arguments.steps)
            if sort_line is not None:
                with open(path) as stream:
                    text = stream.read()
                with open(path, "w") as stream:
                    stream.write(text.replace("read_data liquid.data\n", f"read_data liquid.data\n{sort_line}\n"))
            runs[label] = (directory, [])
        for _ in range(arguments.rounds):
            for directory, times in runs.values():
                times.append(run_lammps(arguments.lmp, directory, 1, arguments.steps))
    print(f"LAMMPS DPD-E, 1 thread, N = {arguments.particles}, {arguments.rounds} alternating rounds of "
          f"{arguments.steps} steps; ms per step, median (min-max):")
    for label, (_, times) in runs.items():
        print(f"  {label}: {statistics.median(times):.2f} ({min(times):.2f}-{max(times):.2f})")


if __name__ == "__main__":
    main()
