# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""A liquid-argon GenDPDE simulation with OpenMM's Simulation, a GenDPDEReporter and a DCD trajectory.

    .venv/bin/python examples/liquid_argon.py [--estimator VA] [--cutoff 1.3365]

500 particles (5 argon atoms each) on an FCC lattice at n0* = 1 are melted with the DPD thermostat at T0, their
internal energies drawn at T0, then run with full (isoenergetic) GenDPDE, the energy corrected until the particle
and kinetic temperatures are within their errors of T0 (READY_LIQUID, docs/fluids.md "A liquid ready to run";
printed first). The reporter prints, in reduced units,
the kinetic and particle temperatures, the mean density n-bar* (0.8 with VA at R* = 1.3365: the pairing instability;
1.0 with VB), the virial pressure and the conserved energy with its drift.
"""

import argparse
import sys

from openmm import app

from openmmgendpde import GenDPDEReporter
from openmmgendpde.cli.options import one_line_errors, published_cutoff
from openmmgendpde.models.argon import ARGON_UNITS, liquid_argon
from openmmgendpde.models.model import READY_LIQUID

one_line_errors("liquid_argon.py")
parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("--estimator", default="VB", choices=["VA", "VB"])
parser.add_argument("--cutoff", type=published_cutoff, default=1.3365, help="R_cut*: 1.3365, 1.6839 or 2.1564")
args = parser.parse_args()

argon = liquid_argon(num_particles=500, cutoff=args.cutoff, estimator=args.estimator, time_step=0.01, seed=1)
# Melt the lattice with the DPD thermostat at T0 (the heat goes to the bath), then full (isoenergetic) GenDPDE
# with the internal energies drawn at T0, and the liquid brought to T0 (without it, it settles where the energy it
# had at the switch puts it: off T0 by a draw of ~1.4 K).
simulation = argon.simulation(platform="Reference", equilibration=READY_LIQUID)
print(f"# ready: {argon.equilibration_report}")

simulation.reporters.append(GenDPDEReporter(sys.stdout, 200, units=ARGON_UNITS))
simulation.reporters.append(app.DCDReporter("liquid_argon.dcd", 200))
simulation.step(4000)
