# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""`benchmark-cpu`: its arguments and output; the measurement is openmmgendpde.benchmarks.cpu's (whose docstring is
the command's --help)."""

from ..benchmarks import cpu as benchmark
from ..benchmarks.measurement import default_rounds
from .benchmarking import print_results
from .options import THREADS, add_cutoff, add_json, add_progress, add_rounds, fcc_particles
from .progress import Progress
from .protocol import check_argon

DESCRIPTION = benchmark.__doc__


def run(arguments):
    check_argon("benchmark-cpu", arguments.particles, [arguments.cutoff])
    progress = Progress(sum(arguments.rounds or default_rounds(n) for n in arguments.particles), "benchmark-cpu",
                        always=arguments.progress)
    results = [benchmark.benchmark(n, arguments.cutoff, arguments.thread_counts, not arguments.no_reference,
                                   arguments.rounds, progress) for n in arguments.particles]
    progress.finish()
    print_results(f"CPU platform against itself and Reference, liquid argon R* = {arguments.cutoff}, VB, particles "
                  f"renumbered at random; medians of alternating rounds of {benchmark.CALLS} calls (speed-ups: "
                  f"medians of per-round ratios, against {arguments.thread_counts[0]} thread(s)):",
                  benchmark.format_table(results), results, arguments.json)


def add_arguments(parser):
    parser.add_argument("--particles", type=fcc_particles, nargs="+", default=[4000, 32000],
                        help="particle counts, 4 m^3 each (default 4000 32000)")
    parser.add_argument("--thread-counts", type=THREADS, nargs="+", default=[1, 2],
                        help="CPU thread counts, the first the baseline of the speed-ups (default 1 2)")
    parser.add_argument("--no-reference", action="store_true", help="leave out the Reference platform")
    add_cutoff(parser)
    add_rounds(parser, "15, or 7 above 8000 particles")
    add_json(parser)
    add_progress(parser)
    parser.set_defaults(run=run)
