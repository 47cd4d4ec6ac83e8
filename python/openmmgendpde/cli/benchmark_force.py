# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""`benchmark-force`: its arguments and output; the measurement is openmmgendpde.benchmarks.force's (whose docstring
is the command's --help)."""

from ..benchmarks import force as benchmark
from ..benchmarks.measurement import default_rounds
from ..models.argon import PUBLISHED_ESTIMATORS
from .benchmarking import add_benchmark_arguments, print_results
from .options import add_cutoffs, chosen_cutoffs, platform_description
from .progress import Progress
from .protocol import check_argon

DESCRIPTION = benchmark.__doc__


def run(arguments):
    cutoffs = chosen_cutoffs(arguments)
    check_argon("benchmark-force", arguments.particles, cutoffs, PUBLISHED_ESTIMATORS)
    cases = [(n, c) for n in arguments.particles for c in cutoffs]
    rounds = arguments.rounds
    total = sum(2 * (rounds or default_rounds(n)) for n, _ in cases)
    progress = Progress(total, "benchmark-force", always=arguments.progress)
    results = []
    for n, cutoff in cases:
        progress.label = f"benchmark-force N={n} R*={cutoff}"
        results.append(benchmark.benchmark(n, cutoff, arguments.platform, rounds, progress))
    progress.finish()
    print_results(f"Force evaluation on the {platform_description(arguments)}, medians of alternating rounds "
                  f"(same configuration for all four columns of each row):", benchmark.format_table(results),
                  results, arguments.json)


def add_arguments(parser):
    add_benchmark_arguments(parser)
    add_cutoffs(parser)
    parser.set_defaults(run=run)
