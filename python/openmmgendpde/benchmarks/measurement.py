"""Measuring speed on a noisy machine: every comparison is made side by side in one run.

Candidates are called in alternating rounds (the order rotates every round), each call is timed on its own, and
results are reported as medians: the median time per call, and the median over rounds of the per-round ratio
between two candidates (robust to another process slowing down part of the run).
"""

import dataclasses
import json
import statistics
import time

from ..cli.options import add_json, add_platform, add_progress, add_rounds, fcc_particles
from ..internal.files import atomic_write


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


def add_benchmark_arguments(parser):
    """The options shared by the benchmark subcommands."""
    parser.add_argument("--particles", type=fcc_particles, nargs="+", default=[4000, 32000],
                        help="particle counts, 4 m^3 each (default 4000 32000)")
    add_platform(parser)
    add_rounds(parser, "15, or 7 above 8000 particles")
    add_json(parser)
    add_progress(parser)


def print_results(header, table, results, json_path):
    """Print a benchmark's header line and table; write the results (dataclasses) as JSON if asked."""
    print(header)
    print(table)
    if json_path:
        with atomic_write(json_path) as stream:
            json.dump([dataclasses.asdict(r) for r in results], stream, indent=1)
