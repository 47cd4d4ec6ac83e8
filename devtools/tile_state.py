# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""Make a larger liquid from a saved one: its particles wrapped into its cubic box, the box tiled k x k x k (the
velocities repeated), and all particles renumbered at random: the liquids of the scaling tables in docs/performance.md
("Against LAMMPS", "At scale"), e.g. from the 4,000-particle liquid of benchmarks/time_steps.py:

    .venv/bin/python benchmarks/time_steps.py --state s4000.npz --particles 4000 --count 1
    .venv/bin/python devtools/tile_state.py s4000.npz 4 t4.npz      # 256,000 particles

The edge is liquid_argon's for the saved particle count (R* = 1.6839), the box the benchmarks give that liquid.
"""

import argparse

import numpy as np
from openmm import unit

from openmmgendpde import GenDPDEIntegrator
from openmmgendpde.models.argon import liquid_argon


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("state", help="the saved liquid (.npz of positions and velocities, nm and nm/ps)")
    parser.add_argument("copies", type=int, help="k: the box tiled k x k x k")
    parser.add_argument("output", help="the .npz to write")
    parser.add_argument("--seed", type=int, default=7, help="of the random numbering (default 7)")
    arguments = parser.parse_args()
    if arguments.copies < 1:
        parser.error("copies must be >= 1")
    saved = np.load(arguments.state)
    positions, velocities = saved["positions"], saved["velocities"]
    model = liquid_argon(len(positions), 1.6839, "VB", seed=1, mode=GenDPDEIntegrator.Isoenergetic)
    edge = model.system.getDefaultPeriodicBoxVectors()[0][0].value_in_unit(unit.nanometer)
    k = arguments.copies
    shifts = edge * np.array([(a, b, c) for a in range(k) for b in range(k) for c in range(k)], dtype=float)
    tiled = (np.mod(positions, edge)[None, :, :] + shifts[:, None, :]).reshape(-1, 3)
    order = np.random.default_rng(arguments.seed).permutation(len(tiled))
    np.savez(arguments.output, positions=tiled[order], velocities=np.tile(velocities, (k ** 3, 1))[order])
    print(f"{len(tiled)} particles, edge {k * edge:.6f} nm")


if __name__ == "__main__":
    main()
