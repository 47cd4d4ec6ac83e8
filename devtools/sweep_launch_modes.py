# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""The device sweep's two launch modes side by side, on one platform: the stages of a step in shared launches (the
check and the cells of a build in one, the 8 colours in another: the default) and a launch per stage
(GENDPDE_SWEEP_LAUNCH_PER_STAGE=1, as before they shared launches). Both must give the same trajectory to the last
bit (the same pair updates in the same order); the script says whether they do, then times Isoenergetic steps in
each mode, alternating, and prints the medians and the ratio.

    python devtools/sweep_launch_modes.py --platform CUDA --particles 108000 --steps 50 --rounds 5

Liquid argon (V-B, R* = 1.6839), from a melted state file (benchmarks/time_steps.py makes one if --state does not
exist). Exits 1 if the trajectories differ.
"""

import argparse
import os
import statistics
import subprocess
import sys
import time

import numpy as np
from openmm import unit

MODE_VARIABLE = "GENDPDE_SWEEP_LAUNCH_PER_STAGE"


def context_in_mode(per_stage, state, platform, precision):
    """A Context of the state's liquid whose sweep takes this launch mode (read when the Context is made)."""
    from openmmgendpde import GenDPDEIntegrator
    from openmmgendpde.models.argon import liquid_argon

    os.environ[MODE_VARIABLE] = "1" if per_stage else "0"
    try:
        model = liquid_argon(len(state["positions"]), 1.6839, "VB", seed=1, mode=GenDPDEIntegrator.Isoenergetic)
        context = model.context(platform, properties={"Precision": precision}, seed=1)
    finally:
        del os.environ[MODE_VARIABLE]
    context.setPositions(state["positions"] * unit.nanometer)
    context.setVelocities(state["velocities"] * unit.nanometer / unit.picosecond)
    return model.integrator, context


def trajectory(per_stage, state, platform, precision, steps):
    integrator, context = context_in_mode(per_stage, state, platform, precision)
    integrator.step(steps)
    found = context.getState(getPositions=True, getVelocities=True)
    return (
        found.getPositions(asNumpy=True).value_in_unit(unit.nanometer),
        found.getVelocities(asNumpy=True).value_in_unit(unit.nanometer / unit.picosecond),
        np.array(integrator.getInternalEnergies()),
    )


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--platform", default="CUDA")
    parser.add_argument("--precision", default="mixed")
    parser.add_argument("--particles", type=int, default=108000)
    parser.add_argument("--state", help="positions and velocities (.npz); default /tmp/gendpde-state-N.npz")
    parser.add_argument("--steps", type=int, default=50, help="steps per timing and in the comparison")
    parser.add_argument("--rounds", type=int, default=5, help="timings of each mode, alternating")
    args = parser.parse_args(argv)
    path = args.state or f"/tmp/gendpde-state-{args.particles}.npz"
    if not os.path.exists(path):
        subprocess.run(
            [
                sys.executable,
                os.path.join(os.path.dirname(__file__), "..", "benchmarks", "time_steps.py"),
                "--state",
                path,
                "--particles",
                str(args.particles),
                "--platform",
                args.platform,
                "--melt-platform",
                args.platform,
                "--precision",
                args.precision,
                "--what",
                "step",
                "--count",
                "1",
            ],
            check=True,
            stdout=subprocess.DEVNULL,
        )
    state = np.load(path)
    shared, apart = (
        trajectory(per_stage, state, args.platform, args.precision, args.steps) for per_stage in (False, True)
    )
    same = all(np.array_equal(a, b) for a, b in zip(shared, apart))
    largest = max(float(np.max(np.abs(a - b))) for a, b in zip(shared, apart))
    outcome = (
        "the same trajectory, bit for bit" if same else f"different trajectories (largest difference {largest:.3g})"
    )
    print(
        f"N = {args.particles}, {args.platform} {args.precision}, {args.steps} steps: shared launches and a launch "
        f"per stage give {outcome}"
    )
    runs = {mode: context_in_mode(mode, state, args.platform, args.precision) for mode in (False, True)}
    for integrator, _ in runs.values():
        integrator.step(5)  # (kernels compiled, capacities settled)
    times = {False: [], True: []}
    for _ in range(args.rounds):
        for mode, (integrator, context) in runs.items():
            context.getState(getEnergy=False)  # (the queue drained)
            start = time.perf_counter()
            integrator.step(args.steps)
            context.getState(getPositions=True)
            times[mode].append(1e3 * (time.perf_counter() - start) / args.steps)
    shared_ms, apart_ms = statistics.median(times[False]), statistics.median(times[True])
    print(
        f"N = {args.particles}, {args.platform} {args.precision}: ms per Isoenergetic step, median of "
        f"{args.rounds} (min-max): shared launches {shared_ms:.4g} ({min(times[False]):.4g}-{max(times[False]):.4g}), "
        f"a launch per stage {apart_ms:.4g} ({min(times[True]):.4g}-{max(times[True]):.4g}); per stage / shared = "
        f"{apart_ms / shared_ms:.3f}"
    )
    return 0 if same else 1


if __name__ == "__main__":
    sys.exit(main())
