# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""A steady shear flow of liquid argon driven by momentum swaps (reverse non-equilibrium shear flow, docs/flows.md),
run the OpenMM way: an openmm.app.Simulation with two reporters, ReverseShearFlow (which swaps) and ProfileReporter
(which writes v_x(z) per bin to a CSV file), and the viscosity from what they recorded.

    python examples/shear_flow.py                      # 2048 particles, a swap every 25 steps (~1 minute)
    python examples/shear_flow.py --cells 4 4 8 --develop 3500 --steps 4000

The flow starts at rest and develops as its slowest mode, in tau = rho (L/2)^2/(eta pi^2), ~1200 steps for this
box length (L = 7.8 nm): --develop 4000 leaves ~3% of it (studies.shear lays the expected profile at the start
instead, and `python -m openmmgendpde flow-curve` runs that protocol). Expect 0.20 +- 0.02 mPa s: seeds 1, 2 and 3
gave 139.8 +- 5.9, 118.8 +- 4.9 and 126.8 +- 2.9 amu/(nm ps) (docs/flows.md: a single run's error is itself
uncertain).
"""

import argparse
import io

import numpy as np
from openmm import unit

from openmmgendpde import GenDPDEIntegrator
from openmmgendpde.analysis import shear
from openmmgendpde.analysis.profiles import ProfileReporter
from openmmgendpde.calibration.report import mpa_s
from openmmgendpde.cli.options import one_line_errors
from openmmgendpde.models.fluid import ARGON, coarse_grain
from openmmgendpde.models.melting import melt_then_switch
from openmmgendpde.models.shear import ReverseShearFlow


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cells", type=int, nargs=3, default=(8, 8, 8), help="FCC cells (default 8 8 8)")
    parser.add_argument("--interval", type=int, default=25, help="steps between swaps (default 25)")
    parser.add_argument("--slabs", type=int, default=20, help="slabs = bins along z (default 20)")
    parser.add_argument("--develop", type=int, default=4000, help="steps for the flow to develop (default 4000)")
    parser.add_argument("--steps", type=int, default=12000, help="steps measured (default 12000)")
    parser.add_argument("--every", type=int, default=100, help="steps between profiles (default 100)")
    parser.add_argument("--seed", type=int, default=1)
    arguments = parser.parse_args()

    parameters = coarse_grain(ARGON, 5, neighbors=20)
    model = parameters.liquid(cells=tuple(arguments.cells), mode=GenDPDEIntegrator.Isothermal, seed=arguments.seed)
    simulation = model.simulation("CPU")
    melt_then_switch(model.integrator, 1000, parameters.temperature, arguments.seed, step=simulation.step)

    flow = ReverseShearFlow(arguments.interval, arguments.slabs)
    simulation.reporters.append(flow)
    simulation.step(arguments.develop)
    flow.reset()                                # count the swaps of the measured steps only
    start = simulation.context.getState().getTime().value_in_unit(unit.picosecond)
    profiles = io.StringIO()
    simulation.reporters.append(ProfileReporter(profiles, arguments.every, bins=arguments.slabs))
    simulation.step(arguments.steps)
    duration = simulation.context.getState().getTime().value_in_unit(unit.picosecond) - start

    table = np.genfromtxt(io.StringIO(profiles.getvalue()), delimiter=",", names=True, comments="#")
    frames = table["vx"].reshape(-1, arguments.slabs)
    centre = table["centre"][:arguments.slabs]
    length = model.box_edges[2]
    result = shear.shear_viscosity(flow.momenta, flow.area, duration, centre, frames, length, arguments.slabs,
                                   parameters.cutoff / 2)
    print(f"{model.num_particles} particles, a swap every {arguments.interval} steps, {len(flow.momenta)} swaps in "
          f"{duration:.1f} ps, {len(frames)} profiles")
    print("z (nm)   v_x (nm/ps)")
    for z, v, fitted in zip(centre, result.profile, result.fitted):
        print(f"{z:6.2f}  {v:+.4f}{'' if fitted else '   (not fitted)'}")
    print(f"J = {result.momentum_flux:.4g} +- {result.momentum_flux_error:.2g} kJ/mol/nm^3, gamma_dot = "
          f"{result.shear_rate:.4g} +- {result.shear_rate_error:.2g} 1/ps")
    print(f"eta = {result.viscosity:.4g} +- {result.error:.2g} amu/(nm ps) = {mpa_s(result.viscosity):.4g} +- "
          f"{mpa_s(result.error):.2g} mPa s")


if __name__ == "__main__":
    one_line_errors("shear_flow.py")
    main()
