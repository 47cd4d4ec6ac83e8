# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""Polymer chains in a GenDPDE solvent: the radius of gyration against the chain length, and the Flory exponent.

    .venv/bin/python examples/polymer_solution.py [--fluid argon] [--lengths 5 10 20 40] [--steps 40000]

Linear chains of the fluid's own particles (an athermal, good solvent) held by harmonic bonds (rest length the
lattice spacing (sqrt(2)/n0)^(1/3), stiffness 100 k_B T0/b0^2; openmmgendpde.models.polymers), a few in each box
(4% of its particles; openmmgendpde.studies.polymers), run with the DPD thermostat at T0 and a tenth of the fluid's
friction (--friction-scale: the chains' conformations, a static property, do not depend on it, but the solvent's
viscosity and with it the chains' relaxation time fall several times). For each length N the script
prints the root-mean-square radius of gyration with its standard error (in nm and in the fluid's length n0^(-1/3)),
the mean bond length over b0, and the chain beads' and the solvent's mean density over n0 (the beads count their
bonded neighbours in their density, docs/soft-matter.md); then nu of R_g ~ N^nu fitted to all lengths, beside the
self-avoiding walk's 0.5876 (a good solvent) and the ideal chain's 0.5. docs/soft-matter.md, "A polymer solution",
holds a measured table.
"""

import argparse

from openmmgendpde.cli.fluids import add_fluid_arguments, parameters_from_arguments
from openmmgendpde.cli.options import COUNT, POSITIVE, SEED, add_platform, one_line_errors, parse_arguments
from openmmgendpde.studies.polymers import flory_study

#: The exponent of the self-avoiding walk in three dimensions (Clisby, Phys. Rev. Lett. 104, 055702 (2010):
#: 0.587597(7)).
SELF_AVOIDING_WALK_NU = 0.587597

one_line_errors("polymer_solution.py")
parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
add_fluid_arguments(parser, default="argon")
add_platform(parser, default="CPU")
parser.add_argument("--lengths", type=COUNT, nargs="+", default=[5, 10, 20, 40],
                    help="chain lengths N, beads (default 5 10 20 40; at least two different ones, each >= 2)")
parser.add_argument("--steps", type=COUNT, default=40000, help="sampled steps per length (default 40000)")
parser.add_argument("--melt-steps", type=COUNT, default=5000, help="steps before sampling (default 5000)")
parser.add_argument("--sample-every", type=COUNT, default=50, help="steps between samples (default 50)")
parser.add_argument("--friction-scale", type=POSITIVE, default=0.1,
                    help="the fluid's friction gamma times this (default 0.1)")
parser.add_argument("--time-step", type=POSITIVE, default=0.05, help="dt in the fluid's reduced time (default 0.05)")
parser.add_argument("--bead-fraction", type=POSITIVE, default=0.04,
                    help="fraction of each box's particles in chains (default 0.04: dilute)")
parser.add_argument("--seed", type=SEED, default=1, help="random seed (default 1)")
args = parse_arguments(parser)
if len(set(args.lengths)) < 2 or min(args.lengths) < 2:
    parser.error(f"--lengths {' '.join(map(str, args.lengths))} is not allowed: give at least two different lengths, "
                 f"each >= 2")
if args.steps // args.sample_every < 10:   # (a correlated mean of fewer means little)
    parser.error(f"--steps {args.steps} with --sample-every {args.sample_every} give fewer than 10 samples")
parameters = parameters_from_arguments(args, "polymer_solution.py")
parameters = parameters.with_transport(args.friction_scale * parameters.friction, parameters.heat_conduction)
length_unit = parameters.density ** (-1 / 3)

print(f"{parameters.fluid.name}: {args.molecules_per_particle:g} molecules per particle, n0^(-1/3) = "
      f"{length_unit:.4f} nm, dt* = {args.time_step}, {args.steps} steps per length, "
      f"friction x {args.friction_scale:g}")
print(f"{'N':>4} {'chains':>6} {'R_g (nm)':>16} {'R_g n0^(1/3)':>16} {'g':>6} {'<b>/b0':>7} {'n_bead/n0':>9} "
      f"{'n_solv/n0':>9}")


def show(row):
    print(f"{row.chain_length:4d} {row.num_chains:6d} {row.radius_of_gyration:8.4f} +- {row.error:.4f} "
          f"{row.radius_of_gyration / length_unit:8.4f} +- {row.error / length_unit:.4f} "
          f"{row.statistical_inefficiency:6.1f} {row.bond_stretch:7.4f} {row.bead_density:9.4f} "
          f"{row.solvent_density:9.4f}", flush=True)


rows, fit = flory_study(parameters, args.lengths, bead_fraction=args.bead_fraction, progress=show,
                        time_step=args.time_step, melt_steps=args.melt_steps, steps=args.steps,
                        sample_every=args.sample_every, platform=args.platform, seed=args.seed)
print(f"nu = {fit.nu:.3f} +- {fit.nu_error:.3f} (chi^2/dof {fit.reduced_chi_squared:.2f}); self-avoiding walk "
      f"{SELF_AVOIDING_WALK_NU:.4f}, ideal chain 0.5")
