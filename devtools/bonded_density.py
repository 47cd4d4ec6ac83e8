# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""What a bond does to the many-body density of its beads (docs/soft-matter.md, "Bonded beads and the many-body
density"): chains whose bonds are shorter than the liquid's spacing, their beads' mean density and their mean bond
length against the solvent's density and an isolated spring's mean length.

For each rest length b0 (in the fluid's length n0^(-1/3)) and each stiffness (in k_B T0/b0^2): --chains chains of
--length beads among 500 particles (5 x 5 x 5 FCC cells), the DPD thermostat at T0 (dt* = 0.05), 1000 steps from the
lattice, then --steps steps sampled every 20 (studies.polymers.chain_size). Printed: the beads' and the solvent's mean
density over n0 and the mean bond length over b0 beside an isolated spring's, <r>/b0 = 1 + 2 k_B T0/(k b0^2) + ...
(P(r) ~ r^2 exp(-k (r - b0)^2/(2 k_B T0)), by quadrature).

    python devtools/bonded_density.py --bond-lengths 1.1225 0.8 0.5 --stiffness 100
"""

import argparse

import numpy as np

from openmmgendpde.models import fluid as fluids
from openmmgendpde.studies.polymers import chain_size

FLUIDS = {"argon": (fluids.ARGON, 5), "water": (fluids.WATER, 4)}

parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("--fluid", choices=sorted(FLUIDS), default="argon")
parser.add_argument("--bond-lengths", type=float, nargs="+", default=[1.1225, 0.8, 0.5],
                    help="rest lengths b0 in n0^(-1/3) (default 1.1225, the lattice's spacing, 0.8 0.5)")
parser.add_argument("--stiffness", type=float, nargs="+", default=[100.0], help="k in k_B T0/b0^2 (default 100)")
parser.add_argument("--length", type=int, default=10)
parser.add_argument("--chains", type=int, default=20)
parser.add_argument("--steps", type=int, default=6000)
parser.add_argument("--threads", default="1")
args = parser.parse_args()

known, molecules = FLUIDS[args.fluid]
parameters = fluids.coarse_grain(known, molecules, neighbors=20)
unit_length = parameters.density ** (-1 / 3)
kt = 0.00831446261815324 * parameters.temperature   # k_B T0, kJ/mol
print(f"{args.fluid}: {args.chains} chains of {args.length} beads among 500 particles, {args.steps} steps")
print(f"{'b0 n0^(1/3)':>11} {'k b0^2/kT':>9} {'n_bead/n0':>9} {'n_solv/n0':>9} {'<r>/b0':>7} {'spring':>7}")
for b0 in args.bond_lengths:
    for stiffness in args.stiffness:
        length = b0 * unit_length
        k = stiffness * kt / length**2
        row = chain_size(parameters, args.length, args.chains, (5, 5, 5), melt_steps=1000, steps=args.steps,
                         properties={"Threads": args.threads}, bond_length=length, bond_stiffness=k)
        r = np.linspace(max(0.0, 1 - 12 / np.sqrt(stiffness)), 1 + 12 / np.sqrt(stiffness), 100001)
        weight = r**2 * np.exp(-0.5 * stiffness * (r - 1) ** 2)
        print(f"{b0:11.4f} {stiffness:9.0f} {row.bead_density:9.4f} {row.solvent_density:9.4f} "
              f"{row.bond_stretch:7.4f} {(r * weight).sum() / weight.sum():7.4f}", flush=True)
