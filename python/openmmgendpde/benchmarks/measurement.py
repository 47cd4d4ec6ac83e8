# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""Measuring speed on a noisy machine: every comparison is made side by side in one run.

Candidates are called in alternating rounds (the order rotates every round), each call is timed on its own, and
results are reported as medians: the median time per call, and the median over rounds of the per-round ratio
between two candidates (robust to another process slowing down part of the run).
"""

import statistics
import time


def alternating_rounds(candidates, rounds, progress=None):
    """Call each of ``candidates`` (name -> callable) once per round for ``rounds`` rounds, rotating the order.
    Returns name -> list of seconds per call (one entry per round)."""
    names = list(candidates)
    seconds = {name: [] for name in names}
    for round_index in range(rounds):
        shift = round_index % len(names)
        for name in names[shift:] + names[:shift]:
            start = time.perf_counter()
            candidates[name]()
            seconds[name].append(time.perf_counter() - start)
        if progress is not None:
            progress.advance()
    return seconds


def median(values):
    return statistics.median(values)


def median_ratio(seconds, numerator, denominator):
    """Median over rounds of seconds[numerator] / seconds[denominator]."""
    return statistics.median(a / b for a, b in zip(seconds[numerator], seconds[denominator]))


def default_rounds(num_particles):
    """Alternating rounds for a benchmark of this size: 15, or 7 above 8000 particles."""
    return 15 if num_particles <= 8000 else 7


def context_threads(context):
    """The threads a Context computes on: the CPU platform's Threads property, else 1."""
    platform = context.getPlatform()
    return int(platform.getPropertyValue(context, "Threads")) if platform.getName() == "CPU" else 1
