#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""Periodic Poiseuille flow of a GenDPDE liquid (docs/flows.md, "Body forces and channel flows"): a body force +F x-hat
in the lower half of the box along z and -F x-hat in the upper half drives two opposite parabolic flows; a
ProfileReporter writes the velocity profile, and transport.viscosity_from_profiles reads the shear viscosity from it
in one call. openmmgendpde.StateDataReporter prints OpenMM's columns with the conserved energy and the harmonic-mean
temperature, GenDPDEReporter the virial pressure (which leaves the body force out).

    python examples/poiseuille_flow.py                       # 3 x 3 x 8 cells of argon (288 particles), ~40 s
    python examples/poiseuille_flow.py --cells 3 3 6 --measure 8 --out /tmp/flow
"""

import argparse
import math
import pathlib
import sys
import tempfile

import numpy as np
from openmm import unit

from openmmgendpde import GenDPDEIntegrator, GenDPDEReporter, StateDataReporter
from openmmgendpde.analysis.flows import momentum_diffusion_time, poiseuille_shape
from openmmgendpde.analysis.profiles import ProfileReporter
from openmmgendpde.analysis.statistics import correlated_mean
from openmmgendpde.analysis.transport import viscosity_from_profiles
from openmmgendpde.models.flows import BODY_FORCE_GROUP, poiseuille_body_force
from openmmgendpde.models.fluid import ARGON, KB, coarse_grain


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cells", type=int, nargs=3, default=[3, 3, 8], help="lattice cells along x, y, z")
    parser.add_argument("--peak", type=float, default=0.15, help="peak flow velocity over the thermal velocity")
    parser.add_argument("--develop", type=float, default=2.0, help="momentum diffusion times before the profiles count")
    parser.add_argument("--measure", type=float, default=12.0, help="momentum diffusion times measured")
    parser.add_argument("--bins", type=int, default=12, help="profile bins along z (even)")
    parser.add_argument("--platform", default="CPU")
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--out", default=None, help="directory of profile.csv and state.csv (default: a temporary one)")
    args = parser.parse_args(argv)
    if args.bins < 2 or args.bins % 2 or min(args.cells) < 3 or args.peak <= 0 or args.measure <= 0:
        parser.error(f"--bins {args.bins}, --cells {args.cells}, --peak {args.peak}, --measure {args.measure}: the "
                     f"bins must be even, every cell count >= 3 (the box at least 2 cutoffs), --peak and --measure > 0")
    out = pathlib.Path(args.out or tempfile.mkdtemp(prefix="poiseuille-"))
    out.mkdir(parents=True, exist_ok=True)

    # The liquid: argon coarse-grained 5 to 1, at its mapped state; the targets are its mapped transport coefficients.
    parameters = coarse_grain(ARGON, 5, neighbors=20)
    model = parameters.liquid(cells=tuple(args.cells), mode=GenDPDEIntegrator.Isothermal, seed=args.seed)
    n, length = model.num_particles / model.volume, model.box_edges[2]
    eta_target = parameters.targets()["shear_viscosity"]
    thermal = math.sqrt(KB * parameters.temperature / parameters.mass)
    # F so that the peak velocity n F L^2/(32 eta) is --peak thermal velocities (with the target eta).
    force = 32 * eta_target * args.peak * thermal / (n * length**2)
    model.system.addForce(poiseuille_body_force(force, length, model.num_particles))   # group BODY_FORCE_GROUP
    simulation = model.simulation(args.platform)
    tau = momentum_diffusion_time(n * parameters.mass, eta_target, length)
    step = model.integrator.getStepSize().value_in_unit(unit.picosecond)
    interval = max(1, round(tau / 10 / step))
    print(f"{model.num_particles} particles, box {model.box_edges.round(3).tolist()} nm, F = {force:.4g} kJ/mol/nm, "
          f"tau = {tau:.3g} ps = {tau / step:.0f} steps; profiles every {interval} steps")

    # Melt with the thermostat, then run isoenergetic from the expected profile laid on the thermal velocities.
    simulation.step(300)
    model.integrator.setMode(GenDPDEIntegrator.Isoenergetic)
    model.integrator.setInternalEnergiesToTemperature(parameters.temperature, args.seed)
    state = simulation.context.getState(getPositions=True, getVelocities=True)
    z = state.getPositions(asNumpy=True).value_in_unit(unit.nanometer)[:, 2]
    velocities = state.getVelocities(asNumpy=True).value_in_unit(unit.nanometer / unit.picosecond)
    velocities[:, 0] += n * force / (2 * eta_target) * poiseuille_shape(z, length)
    simulation.context.setVelocities(velocities)

    start = simulation.context.getState().getTime().value_in_unit(unit.picosecond) + args.develop * tau
    simulation.reporters.append(ProfileReporter(str(out / "profile.csv"), interval, axis=2, bins=args.bins,
                                                force=model.force))
    report_every = interval * 10
    simulation.reporters.append(StateDataReporter(sys.stdout, report_every, step=True, time=True, totalEnergy=True,
                                                  conservedEnergy=True, harmonicTemperature=True))
    simulation.reporters.append(GenDPDEReporter(str(out / "state.csv"), report_every))
    simulation.step(round((args.develop + args.measure) * tau / step))

    result = viscosity_from_profiles(out / "profile.csv", force, start=start)
    waited = args.develop * tau / momentum_diffusion_time(n * parameters.mass, result.value, length)
    print(f"eta = {result.value:.4g} +- {result.error:.2g} amu/(nm ps) from {result.details['frames']} profiles "
          f"(target {eta_target:.4g}: measured/target = {result.value / eta_target:.3f}); peak "
          f"{result.details['peak_velocity'] / thermal:.3f} v_th; waited {waited:.2f} tau of this eta")
    # The momentum balance of the steady flow: P_xz = n F (z - L/4) in the lower half, -n F (z - 3L/4) in the upper.
    profiles = np.genfromtxt(out / "profile.csv", delimiter=",", names=True, comments="#").reshape(-1, args.bins)
    profiles = profiles[profiles["time"][:, 0] >= start]
    centre = profiles["centre"][0]
    required = n * force * np.where(centre < length / 2, centre - length / 4, 3 * length / 4 - centre)
    carried = correlated_mean(profiles["Pxz"] @ required / (required @ required))
    print(f"shear stress: the momentum balance needs P_xz = n F (z - L/4) (+-{n * force * length / 4:.3g} kJ/mol/nm^3 "
          f"at the ends of the lower half); the ProfileReporter's Pxz (kinetic and conservative parts) carries "
          f"{carried.mean:.2f} +- {carried.standard_error:.2f} of it; the rest is the stress of the dissipative and "
          f"random pair forces (the integrator's sweep), which no reporter measures")
    log = np.genfromtxt(out / "state.csv", delimiter=",", comments="#")
    print(f"virial pressure {np.mean(log[:, 6]):.1f} bar (mean of {len(log)} reports; the body force left out); "
          f"harmonic-mean theta {log[0, 4]:.2f} -> {log[-1, 4]:.2f} K (viscous heating); the body force's "
          f"group {BODY_FORCE_GROUP} is left out of the fluid's energy")
    print(f"files: {out / 'profile.csv'}, {out / 'state.csv'}")
    return result


if __name__ == "__main__":
    main()
