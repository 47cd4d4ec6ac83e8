# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""The conserved-energy error of isoenergetic GenDPDE at free surfaces, V-B against V-C (docs/interfaces.md, "V-C's
energy error"): a liquid-argon slab and droplet in vacuum (openmmgendpde.studies.slab's set-ups: 1000 particles at n* =
0.82, R* = 1.6839, f_cut 1.35 for V-B and 1.3525 for V-C, velocities and internal energies drawn at T0) run for a fixed
number of steps at each step size; printed: the change of K + U + sum eps per N k_B T0 at a few checkpoints.

    python devtools/vc_energy_drift.py --systems slab droplet --estimators VB VC --step-sizes 0.01 0.005 --steps 4000

With --crossings (V-C runs only), the particles whose one-sidedness a^2 = c^2 |g|^2/(n0^2 + eps^2) crosses V-C's
threshold t = 0.4 are counted step by step, from the positions (numpy and scipy's k-d tree; the same formulas as
the physics core, core/include/gendpde/GenDPDEPhysicsCore.h), over the first --crossing-steps steps, with the
fraction of the particles above t at the end of them and the median change of a^2 in one step for the particles
within 0.1 of t (how many steps a crossing of the threshold's bend takes).
--mode Conservative runs velocity Verlet alone (no pair dynamics) instead of the isoenergetic mode.
"""

import argparse
import time

import numpy as np
from openmm import unit

from openmmgendpde import GenDPDEIntegrator
from openmmgendpde.models.argon import ARGON_UNITS
from openmmgendpde.studies.slab import argon_model, droplet_positions, slab_positions

NM = unit.nanometer
THRESHOLD = 0.4   # V-C's t (gendpdeSurfaceFactor)


def one_sidedness(positions, box, cutoff):
    """a^2 of every particle (V-C, docs/theory.md section 3): positions and box edges in nm, cutoff R in nm."""
    from scipy.spatial import cKDTree
    x = positions - np.floor(positions / box) * box
    pairs = cKDTree(x, boxsize=box).query_pairs(cutoff, output_type="ndarray")
    d = x[pairs[:, 0]] - x[pairs[:, 1]]
    d -= box * np.round(d / box)
    r = np.sqrt((d * d).sum(axis=1))
    y = 1 - r / cutoff
    weight = 15 / (2 * np.pi * cutoff**3) * y * y
    moment = ((r / cutoff) * y * y / r)[:, None] * d                 # phi(r) e_ij, e_ij from j to i
    n0 = np.zeros(len(x))
    g = np.zeros((len(x), 3))
    np.add.at(n0, pairs[:, 0], weight)
    np.add.at(n0, pairs[:, 1], weight)
    np.add.at(g, pairs[:, 0], moment)
    np.add.at(g, pairs[:, 1], -moment)
    c, eps = 30 / (np.pi * cutoff**3), 3 / (4 * np.pi * cutoff**3)
    return c * c * (g * g).sum(axis=1) / (n0 * n0 + eps * eps)


def make_model(system, estimator, step_size, seed, platform, mode):
    positions, box = (slab_positions()[:2] if system == "slab" else droplet_positions()[:2])
    model, context = argon_model(positions, box, estimator, platform=platform, seed=seed)
    model.integrator.setStepSize(ARGON_UNITS.to_openmm(step_size, "time"))
    if mode == "Conservative":
        model.integrator.setMode(GenDPDEIntegrator.Conservative)
    return model, context


def run(system, estimator, step_size, steps, checkpoints, seed, platform, mode, crossing_steps, equilibration):
    """(errors per N k_B T0 at each checkpoint, crossings per step or None, seconds)."""
    model, context = make_model(system, estimator, step_size, seed, platform, mode)
    if equilibration:
        model.integrator.step(int(round(equilibration / step_size)))
    n = model.num_particles
    kt = (unit.MOLAR_GAS_CONSTANT_R * model.temperature).value_in_unit(unit.kilojoule_per_mole)
    def energy():
        return model.integrator.getConservedEnergy().value_in_unit(unit.kilojoule_per_mole)

    start, begun = energy(), time.perf_counter()
    crossings = None
    done = 0
    if crossing_steps:
        cutoff = model.force.getCutoffDistance().value_in_unit(NM)
        a2 = one_sidedness(model.wrapped_positions(context), model.box_edges, cutoff)
        count, changes = 0, []
        for _ in range(crossing_steps):
            model.integrator.step(1)
            now = one_sidedness(model.wrapped_positions(context), model.box_edges, cutoff)
            count += int(((now > THRESHOLD) != (a2 > THRESHOLD)).sum())
            changes.append(np.abs(now - a2)[np.abs(a2 - THRESHOLD) < 0.1])
            a2 = now
        crossings = (count / crossing_steps, (a2 > THRESHOLD).mean(), np.median(np.concatenate(changes)))
        done = crossing_steps
    errors = []
    for checkpoint in checkpoints:
        model.integrator.step(checkpoint - done)
        done = checkpoint
        errors.append((energy() - start) / (n * kt))
    return errors, crossings, time.perf_counter() - begun


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--systems", nargs="+", choices=("slab", "droplet"), default=["slab", "droplet"])
    parser.add_argument("--estimators", nargs="+", choices=("VB", "VC"), default=["VB", "VC"])
    parser.add_argument("--step-sizes", nargs="+", type=float, default=[0.01, 0.005], help="dt* (default 0.01 0.005)")
    parser.add_argument("--steps", type=int, default=4000, help="steps per run (default 4000)")
    parser.add_argument("--duration", type=float,
                        help="instead of --steps: reduced time per run, the same for every step size")
    parser.add_argument("--equilibrate", type=float, default=0.0,
                        help="reduced time run at the same step before the energy is first read (default 0: from the "
                             "lattice)")
    parser.add_argument("--checkpoints", type=int, default=4, help="equally spaced reports per run (default 4)")
    parser.add_argument("--seeds", nargs="+", type=int, default=[5], help="velocity/energy/noise seeds (default 5)")
    parser.add_argument("--mode", choices=("Isoenergetic", "Conservative"), default="Isoenergetic")
    parser.add_argument("--platform", default="CPU")
    parser.add_argument("--crossings", action="store_true", help="count threshold crossings (V-C runs)")
    parser.add_argument("--crossing-steps", type=int, default=500, help="steps over which to count them (500)")
    arguments = parser.parse_args()
    print("system   estimator   dt*   seed   steps: error / (N k_B T0) at each checkpoint   [crossings per step, "
          "fraction above t at the end, median |change of a^2| per step within 0.1 of t]   seconds")
    for system in arguments.systems:
        for estimator in arguments.estimators:
            for step_size in arguments.step_sizes:
                steps = (int(round(arguments.duration / step_size)) if arguments.duration else arguments.steps)
                checkpoints = [steps * (k + 1) // arguments.checkpoints for k in range(arguments.checkpoints)]
                for seed in arguments.seeds:
                    counting = arguments.crossing_steps if arguments.crossings and estimator == "VC" else 0
                    errors, crossings, seconds = run(system, estimator, step_size, steps, checkpoints, seed,
                                                     arguments.platform, arguments.mode, counting,
                                                     arguments.equilibrate)
                    extra = f"   [{crossings[0]:.2f}, {crossings[1]:.3f}, {crossings[2]:.4f}]" if crossings else ""
                    print(f"{system:8s} {estimator:3s} {step_size:7.4f} {seed:3d}   "
                          + "  ".join(f"{c}: {e:+.2e}" for c, e in zip(checkpoints, errors))
                          + f"{extra}   {seconds:.0f} s", flush=True)


if __name__ == "__main__":
    main()
