# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""Time force evaluations or Isoenergetic steps of liquid argon (R* = 1.6839, V-B) from a saved state, with whatever
version of openmmgendpde the running Python has installed: the tool that compares two builds side by side
(docs/performance.md), e.g. this one against the last release, each in its own virtual environment, alternating.

    python benchmarks/time_steps.py --state mixed.npz --platform CPU --threads 2 --what step --count 100

The state (positions and velocities, nm and nm/ps) is read from --state; if the file does not exist it is made
first: the lattice melted by 300 Isothermal steps on the CPU platform (--melt-platform: another, e.g. the GPU being
timed, with the same Precision), the particles renumbered at random (the
state a long run lives in; openmmgendpde.benchmarks.cpu does the same). Prints the milliseconds per call.
It uses only liquid_argon and the public API, so that older versions run it too.
"""

import argparse
import gc
import os
import time

import numpy as np
from openmm import unit

from openmmgendpde import GenDPDEIntegrator
from openmmgendpde.models.argon import liquid_argon

CUTOFF = 1.6839


def make_state(path, num_particles, platform="CPU", properties=None):
    model = liquid_argon(num_particles, CUTOFF, "VB", seed=1, mode=GenDPDEIntegrator.Isothermal)
    context = model.context(platform, properties=properties or {}, seed=1)
    model.integrator.step(300)
    state = context.getState(getPositions=True, getVelocities=True)
    order = np.random.default_rng(2).permutation(num_particles)
    np.savez(path, positions=state.getPositions(asNumpy=True).value_in_unit(unit.nanometer)[order],
             velocities=state.getVelocities(asNumpy=True).value_in_unit(unit.nanometer / unit.picosecond)[order])


def give_types(model, count, entries=True):
    force, integrator = model.force, model.integrator
    for i in range(model.num_particles):
        force.setParticleType(i, i % count)
        integrator.setParticleType(i, i % count)
    if not entries:
        return
    for a in range(count):
        force.addTypeParameters(a, *force.getTaitParameters())
        integrator.addTypeHeatCapacity(a, integrator.getHeatCapacity())
        for b in range(a, count):
            integrator.addTypePair(a, b, integrator.getFriction(), integrator.getHeatConduction())


def print_per_step(integrator, count, num_particles):
    """count steps, each timed alone; prints the median, the slow steps (> 1.5 x the median) and their extra cost."""
    times = []
    for _ in range(count):
        start = time.perf_counter()
        integrator.step(1)
        times.append(1e3 * (time.perf_counter() - start))
    median = float(np.median(times))
    slow = [(k, t) for k, t in enumerate(times) if t > 1.5 * median]
    extra = float(np.mean([t - median for _, t in slow])) if slow else 0.0
    print(f"median step {median:.3f} ms ({1e3 * median / num_particles:.3f} us per particle); {len(slow)} slow steps "
          f"{[k for k, _ in slow]}, {extra:.1f} ms more each ({1e3 * extra / num_particles:.2f} us per particle)")


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--state", required=True, help=".npz file of the state (made if absent)")
    parser.add_argument("--particles", type=int, default=32000, help="for a new state (default 32000)")
    parser.add_argument("--platform", default="CPU")
    parser.add_argument("--melt-platform", default="CPU", help="the platform that makes a new state (default CPU)")
    parser.add_argument("--threads", type=int, help="the CPU platform's Threads")
    parser.add_argument("--precision", choices=("single", "mixed", "double"),
                        help="a GPU platform's Precision (OpenCL, CUDA)")
    parser.add_argument("--what", choices=("force", "step"), default="step",
                        help="force: getState with energy and forces; step: Isoenergetic steps (default)")
    parser.add_argument("--count", type=int, default=100, help="calls timed (default 100), after 10 untimed")
    parser.add_argument("--estimator", choices=("VA", "VB", "VC"), default="VB", help="density estimator (default VB)")
    parser.add_argument("--types", type=int, default=0,
                        help="give the particles this many types in turn (needs particle types), each with argon's "
                             "parameters in its own entries, so that the physics is the same and only the type "
                             "tables differ")
    parser.add_argument("--no-type-entries", action="store_true",
                        help="give the --types no entries: every type uses the force's and integrator's parameters")
    parser.add_argument("--per-step", action="store_true",
                        help="time each step alone (--what step) and first print the median step, the steps that "
                             "took more than 1.5 times as long (those that built the neighbour list and the sweep "
                             "order) and what they cost more than the median, in ms and in us per particle")
    parser.add_argument("--memory", action="store_true", help="also print the peak resident memory (MB)")
    parser.add_argument("--heap", action="store_true",
                        help="also print the heap the Context holds per particle after its first 10 steps (bytes; "
                             "glibc's count of allocated bytes, mallinfo2, before the Context and after)")
    arguments = parser.parse_args()
    if not os.path.exists(arguments.state):
        melt_properties = {"Precision": arguments.precision} if arguments.precision and arguments.melt_platform in (
            "OpenCL", "CUDA") else {}
        make_state(arguments.state, arguments.particles, arguments.melt_platform, melt_properties)
    saved = np.load(arguments.state)
    num_particles = len(saved["positions"])
    model = liquid_argon(num_particles, CUTOFF, arguments.estimator, seed=1, mode=GenDPDEIntegrator.Isoenergetic)
    if arguments.types > 0:
        give_types(model, arguments.types, not arguments.no_type_entries)
    properties = {"Threads": str(arguments.threads)} if arguments.threads else {}
    if arguments.precision:
        properties["Precision"] = arguments.precision
    positions, velocities = saved["positions"], saved["velocities"]
    if arguments.heap:   # (imported here: without --heap the tool runs with versions that lack it)
        from openmmgendpde.benchmarks.cpu import allocated_bytes
    gc.collect()
    heap_before = allocated_bytes() if arguments.heap else None
    context = model.context(arguments.platform, properties=properties, positions=positions, velocities=False)
    context.setVelocities(velocities)
    model.integrator.step(10)
    if heap_before is not None:
        gc.collect()
        heap = (allocated_bytes() - heap_before) / num_particles
    start = time.perf_counter()
    if arguments.what == "step" and arguments.per_step:
        print_per_step(model.integrator, arguments.count, num_particles)
    elif arguments.what == "step":
        model.integrator.step(arguments.count)
    else:
        for _ in range(arguments.count):
            context.getState(getEnergy=True, getForces=True)
    milliseconds = (time.perf_counter() - start) / arguments.count * 1e3
    line = f"{milliseconds:.3f}"
    if arguments.memory:
        import resource
        line += f" ms, peak {resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024:.0f} MB"
    if arguments.heap:
        line += f", heap {heap:.0f} bytes per particle" if heap_before is not None else ", heap unknown"
    print(line)


if __name__ == "__main__":
    main()
