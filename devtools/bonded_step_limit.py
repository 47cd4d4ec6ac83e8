# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""The largest stable step of GenDPDE with stiff bonds, against the bound on their highest frequency
(calibration.stability.BONDED_STEP_LIMIT; docs/soft-matter.md, "The time step with bonds").

A polymer melt in a fluid's liquid (models.polymers.polymer_solution: --chains chains of --length beads on the 500
sites of 5 x 5 x 5 FCC cells, the rest solvent) with bonds so stiff that their Gershgorin bound omega_max
(stability.bonded_frequency) is --omega times the fluid's inverse time unit: the fluid's own limits (dt* 0.135-0.45
for argon, docs/fluids.md) are then far above the bonds'. For each mode and each omega, largest_stable_step's ladder
(starting at dt* = 0.25/omega*) and its pass criterion; printed: the limit dt* and omega_max dt, the number that
BONDED_STEP_LIMIT takes (the smallest over modes and stiffnesses).

    python devtools/bonded_step_limit.py --fluid argon --omega 20 40 80
"""

import argparse

from openmm import unit

from openmmgendpde.calibration.stability import MODES, bonded_frequency, largest_stable_step
from openmmgendpde.models import fluid as fluids
from openmmgendpde.models.polymers import polymer_solution

FLUIDS = {"argon": (fluids.ARGON, 5), "water": (fluids.WATER, 4)}

parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("--fluid", choices=sorted(FLUIDS), default="argon")
parser.add_argument("--omega", type=float, nargs="+", default=[20.0, 40.0, 80.0],
                    help="omega_max of the bonds in the fluid's reduced units (default 20 40 80)")
parser.add_argument("--length", type=int, default=10, help="beads per chain (default 10)")
parser.add_argument("--chains", type=int, default=40, help="chains among the 500 particles (default 40)")
parser.add_argument("--modes", nargs="+", choices=list(MODES), default=list(MODES))
parser.add_argument("--platform", default="CPU")
args = parser.parse_args()

known, molecules = FLUIDS[args.fluid]
parameters = fluids.coarse_grain(known, molecules, neighbors=20)
time_unit = parameters.units.unit("time").value_in_unit(unit.picosecond)
print(f"{args.fluid}: {args.chains} chains of {args.length} beads among 500 particles; time unit {time_unit:.4f} ps")
print(f"{'mode':>13} {'omega*':>7} {'k (kJ/mol/nm^2)':>16} {'dt* limit':>10} {'omega dt':>9}")
for omega in args.omega:
    # omega_max = 2 sqrt(k/m) for a bead with two bonds (Gershgorin, equal masses)
    stiffness = parameters.mass * (omega / time_unit / 2) ** 2

    def build(estimator, seed, stiffness=stiffness):
        return polymer_solution(parameters, args.length, args.chains, (5, 5, 5), estimator, time_step=0.005,
                                seed=seed, bond_stiffness=stiffness)
    bound = bonded_frequency(build("VB", 1).system) * time_unit
    for mode in args.modes:
        limit = largest_stable_step(parameters, "VB", mode, platform=args.platform, build=build,
                                    first_step=0.25 / bound)
        print(f"{mode:>13} {bound:7.2f} {stiffness:16.1f} {limit:10.4f} {bound * limit:9.3f}", flush=True)
