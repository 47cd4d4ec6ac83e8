# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""The CPU platform at several thread counts, side by side with the Reference platform (`benchmark-cpu`).

For each particle count, liquid argon at R* = 1.6839 (VB) is melted from its lattice by Isothermal steps on the CPU
platform, and its particles are renumbered at random: a liquid that has run for a long time has mixed its particles,
so that neighbours in space are not neighbours in index order, and that is the state a long run spends its time in
(on the lattice order every platform runs faster than it will later). From that state, these candidates are timed
in alternating rounds (openmmgendpde.benchmarks.measurement): a force evaluation (Context.getState with energies) and an
Isoenergetic step on the CPU platform with each thread count, and on the Reference platform. Reported: median ms
per call, microseconds per particle-step, the speed-up over the first thread count (median of per-round ratios),
the CPU platform over Reference, and the heap a CPU Context holds per particle after its first step (glibc's count of
allocated bytes before and after).
"""

import ctypes
import dataclasses
import gc

import numpy as np
from openmm import unit

from ..api import GenDPDEIntegrator
from ..models.argon import DEFAULT_CUTOFF, liquid_argon
from .measurement import alternating_rounds, default_rounds, median, median_ratio

#: Isothermal steps that melt the lattice before the particles are renumbered.
MELTING_STEPS = 300
#: Steps or evaluations per timed call.
CALLS = 5


@dataclasses.dataclass
class CpuBenchmark:
    num_particles: int
    cutoff: float
    thread_counts: list
    milliseconds: dict            # candidate -> median ms per force evaluation or step
    microseconds_per_particle_step: dict   # "CPU n threads" / "Reference" -> us per particle per step
    force_speedup: dict           # thread count -> median (first count / this count), force evaluation
    step_speedup: dict            # thread count -> same for the Isoenergetic step
    cpu_over_reference: dict      # thread count -> median (Reference / CPU), step
    memory_bytes_per_particle: float   # heap a CPU Context (created, one step) holds per particle; None if unknown
    rounds: int


def mixed_liquid(num_particles, cutoff):
    """Positions and velocities (nm, nm/ps) of liquid argon melted by MELTING_STEPS Isothermal steps on the CPU
    platform, the particles renumbered at random."""
    argon = liquid_argon(num_particles, cutoff, "VB", seed=1, mode=GenDPDEIntegrator.Isothermal)
    simulation = argon.simulation("CPU")
    argon.integrator.step(MELTING_STEPS)
    state = simulation.context.getState(getPositions=True, getVelocities=True)
    order = np.random.default_rng(2).permutation(num_particles)
    positions = state.getPositions(asNumpy=True).value_in_unit(unit.nanometer)[order]
    velocities = state.getVelocities(asNumpy=True).value_in_unit(unit.nanometer / unit.picosecond)[order]
    return positions, velocities


def context_at(num_particles, cutoff, positions, velocities, platform_name, threads=None):
    """A liquid-argon Context (Isoenergetic GenDPDEIntegrator) on this platform at these positions and velocities;
    returns (context, integrator)."""
    model = liquid_argon(num_particles, cutoff, "VB", seed=1, mode=GenDPDEIntegrator.Isoenergetic)
    properties = {"Threads": str(threads)} if threads is not None else {}
    context = model.context(platform_name, properties=properties, positions=positions, velocities=False)
    context.setVelocities(velocities)
    return context, model.integrator


def benchmark(num_particles, cutoff=DEFAULT_CUTOFF, thread_counts=(1, 2), reference=True, rounds=None,
              progress=None):
    positions, velocities = mixed_liquid(num_particles, cutoff)
    contexts = {}
    memory = []
    for threads in thread_counts:
        gc.collect()
        before = allocated_bytes()
        contexts[f"CPU {threads}"] = context_at(num_particles, cutoff, positions, velocities, "CPU", threads)
        contexts[f"CPU {threads}"][1].step(1)
        if before is not None:
            memory.append((allocated_bytes() - before) / num_particles)
    if reference:
        contexts["Reference"] = context_at(num_particles, cutoff, positions, velocities, "Reference")
    candidates = {}
    for name, (context, integrator) in contexts.items():
        candidates[f"{name} force"] = (lambda c: lambda: [c.getState(getEnergy=True) for _ in range(CALLS)])(context)
        candidates[f"{name} step"] = (lambda i: lambda: i.step(CALLS))(integrator)
    for call in candidates.values():
        call()
    if rounds is None:
        rounds = default_rounds(num_particles)
    seconds = alternating_rounds(candidates, rounds, progress)
    first = thread_counts[0]
    milliseconds = {name: 1e3 * median(values) / CALLS for name, values in seconds.items()}
    return CpuBenchmark(
        num_particles=num_particles, cutoff=cutoff, thread_counts=list(thread_counts), milliseconds=milliseconds,
        microseconds_per_particle_step={name: 1e3 * milliseconds[f"{name} step"] / num_particles
                                        for name in contexts},
        force_speedup={n: median_ratio(seconds, f"CPU {first} force", f"CPU {n} force") for n in thread_counts},
        step_speedup={n: median_ratio(seconds, f"CPU {first} step", f"CPU {n} step") for n in thread_counts},
        cpu_over_reference={n: median_ratio(seconds, "Reference step", f"CPU {n} step") for n in thread_counts}
        if reference else {},
        memory_bytes_per_particle=max(memory) if memory else None, rounds=rounds)


class _MallocInfo(ctypes.Structure):
    """glibc's struct mallinfo2."""
    _fields_ = [(name, ctypes.c_size_t) for name in ("arena", "ordblks", "smblks", "hblks", "hblkhd", "usmblks",
                                                      "fsmblks", "uordblks", "fordblks", "keepcost")]


def allocated_bytes():
    """Bytes allocated by malloc and not freed, in all arenas (glibc's mallinfo2), or None where that is not
    available. Unlike the resident set, it does not depend on which freed pages the allocator reuses."""
    try:
        libc = ctypes.CDLL("libc.so.6")
        libc.mallinfo2.restype = _MallocInfo
    except (OSError, AttributeError):
        return None
    info = libc.mallinfo2()
    return info.uordblks + info.hblkhd


def format_table(results):
    lines = ["| N | platform | force evaluation (ms) | Isoenergetic step (ms) | us per particle-step "
             "| force speed-up | step speed-up | step vs Reference |",
             "|---|---|---|---|---|---|---|---|"]
    for r in results:
        for n in r.thread_counts:
            against_reference = f"{r.cpu_over_reference[n]:.2f}" if r.cpu_over_reference else "-"
            lines.append(f"| {r.num_particles} | CPU, {n} thread{'s' if n > 1 else ''} "
                         f"| {r.milliseconds[f'CPU {n} force']:.2f} | {r.milliseconds[f'CPU {n} step']:.2f} "
                         f"| {r.microseconds_per_particle_step[f'CPU {n}']:.3f} | {r.force_speedup[n]:.2f} "
                         f"| {r.step_speedup[n]:.2f} | {against_reference} |")
        if r.cpu_over_reference:
            lines.append(f"| {r.num_particles} | Reference | {r.milliseconds['Reference force']:.2f} "
                         f"| {r.milliseconds['Reference step']:.2f} "
                         f"| {r.microseconds_per_particle_step['Reference']:.3f} | | | 1 |")
    lines.append("")
    lines.append("Heap a CPU Context holds per particle (after its first step): " + ", ".join(
        f"N = {r.num_particles}: " + (f"{r.memory_bytes_per_particle:.0f} bytes" if r.memory_bytes_per_particle
                                      else "unknown") for r in results))
    return "\n".join(lines)
