#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""The critical path of the sweep (docs/theory.md section 6) in liquid argon, for the order every platform follows
and for the order it replaced, counted from one configuration:

    .venv/bin/python devtools/sweep_levels.py --particles 32000 108000 --steps 300

The critical path is what a device that runs every block of a colour at once, level after level, waits for: the sum
over the 8 colours of the most levels of any block of the colour.
- per candidate list (the order now): cells at least 1.1 R wide, each block's candidates (closer than 1.1 R) at their
  greedy levels (a pair's level: the smallest that no earlier pair of either particle has, in (i, j) order);
- per step (the order of 0.1-0.4): cells at least R wide, each block's pairs (closer than R) in (i, j) order with the
  runs of four consecutive first particles interleaved, a pair's level one more than the last level of either of its
  particles before it.
The liquid is the argon model (V-B, R* = 1.6839) melted from its FCC lattice for --steps steps on the CPU platform.
The pairs and levels are counted here in Python, independently of the plugin's code (a measurement, not a check).
"""

import argparse
import collections

import numpy as np
import openmm
from scipy.spatial import cKDTree

from openmmgendpde.gendpde import sweepCellCount
from openmmgendpde.models.argon import liquid_argon


def melted_liquid(num_particles, steps):
    """(positions (nm, wrapped), box edge (nm), R (nm)) of the argon model after ``steps`` steps from its lattice."""
    argon = liquid_argon(num_particles, seed=1)
    context = openmm.Context(argon.system, argon.integrator, openmm.Platform.getPlatformByName("CPU"))
    context.setPositions(argon.positions)
    argon.integrator.step(steps)
    state = context.getState(getPositions=True, enforcePeriodicBox=True)
    edge = state.getPeriodicBoxVectors()[0][0].value_in_unit(openmm.unit.nanometer)
    positions = np.mod(state.getPositions(asNumpy=True).value_in_unit(openmm.unit.nanometer), edge)
    positions[positions >= edge] = 0.0   # (a wrap that rounds up to the edge)
    cutoff = argon.force.getCutoffDistance().value_in_unit(openmm.unit.nanometer)
    return positions, edge, cutoff


def blocks_of_pairs(positions, edge, reach):
    """The pairs closer than ``reach`` in (i, j) order, grouped by (colour, block), as the definition puts them."""
    tree = cKDTree(positions, boxsize=edge)
    pairs = np.array(sorted(tree.query_pairs(reach, output_type="set")), dtype=np.int64)
    n = sweepCellCount(edge, reach, True)
    cell = np.minimum((positions / edge * n).astype(np.int64), n - 1)
    ci, cj = cell[pairs[:, 0]], cell[pairs[:, 1]]
    d = cj - ci
    d = np.where(d > 1, d - n, np.where(d < -1, d + n, d))
    block = np.where(d == -1, cj, ci) // 2
    colour = (block[:, 0] % 2) + 2 * (block[:, 1] % 2) + 4 * (block[:, 2] % 2)
    nb = (n + 1) // 2
    index = (block[:, 2] * nb + block[:, 1]) * nb + block[:, 0]
    groups = collections.defaultdict(list)
    for k in np.lexsort((index, colour)):   # stable: (i, j) order within a block
        groups[(int(colour[k]), int(index[k]))].append((int(pairs[k, 0]), int(pairs[k, 1])))
    return len(pairs), groups


def greedy_levels(block):
    used = collections.defaultdict(set)
    most = 0
    for i, j in block:
        level = 0
        while level in used[i] or level in used[j]:
            level += 1
        used[i].add(level)
        used[j].add(level)
        most = max(most, level + 1)
    return most


def interleaved_levels(block):
    runs = []
    for i, j in block:
        if not runs or runs[-1][0][0] != i:
            runs.append([])
        runs[-1].append((i, j))
    sequence = []
    for g in range(0, len(runs), 4):
        group = runs[g:g + 4]
        for rank in range(max(len(run) for run in group)):
            sequence += [run[rank] for run in group if rank < len(run)]
    last = collections.defaultdict(int)
    most = 0
    for i, j in sequence:
        level = max(last[i], last[j]) + 1
        last[i] = last[j] = level
        most = max(most, level)
    return most


def critical_path(groups, levels):
    per_block = {key: levels(block) for key, block in groups.items()}
    path = sum(max((v for (c, _), v in per_block.items() if c == colour), default=0) for colour in range(8))
    values = np.array(list(per_block.values()))
    return path, values.mean(), values.max(), len(per_block)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--particles", type=int, nargs="+", default=[32000])
    parser.add_argument("--steps", type=int, default=300, help="steps of melting before counting")
    args = parser.parse_args()
    print("| N | order | pairs counted | blocks | levels per block (mean, max) | critical path |")
    print("|---|---|---|---|---|---|")
    for num_particles in args.particles:
        positions, edge, cutoff = melted_liquid(num_particles, args.steps)
        for name, reach, levels in (("per step, interleaved (old)", cutoff, interleaved_levels),
                                    ("per candidate list, greedy (now)", 1.1 * cutoff, greedy_levels)):
            count, groups = blocks_of_pairs(positions, edge, reach)
            path, mean, most, blocks = critical_path(groups, levels)
            print(f"| {num_particles} | {name} | {count} | {blocks} | {mean:.1f}, {most} | {path} |", flush=True)


if __name__ == "__main__":
    main()
