# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""`benchmark-integrator`: its arguments and output; the measurement is openmmgendpde.benchmarks.integrator's (whose
docstring is the command's --help)."""

from ..benchmarks import integrator as benchmark
from ..benchmarks.measurement import default_rounds
from .benchmarking import add_benchmark_arguments, print_results
from .options import add_cutoff, platform_description
from .progress import Progress
from .protocol import check_argon

DESCRIPTION = benchmark.__doc__


def run(arguments):
    check_argon("benchmark-integrator", arguments.particles, [arguments.cutoff])
    total = sum(arguments.rounds or default_rounds(n) for n in arguments.particles)
    progress = Progress(total, "benchmark-integrator", always=arguments.progress)
    results = []
    for n in arguments.particles:
        progress.label = f"benchmark-integrator N={n}"
        results.append(benchmark.benchmark(n, arguments.cutoff, arguments.platform, arguments.rounds, progress))
    progress.finish()
    print_results(f"GenDPDEIntegrator on the {platform_description(arguments)}, liquid argon R* = "
                  f"{arguments.cutoff}, VB; medians of alternating rounds from the same state:",
                  benchmark.format_table(results), results, arguments.json)
    print()
    print(f"GenDPDEIntegrator (Isothermal) against OpenMM's DPDIntegrator (friction gamma/m), same System and "
          f"state; kinetic temperatures from {benchmark.TEMPERATURE_SAMPLES} samples {benchmark.STEPS_PER_SAMPLE} "
          f"steps apart (mean +- standard error of {benchmark.TEMPERATURE_BLOCKS} block means):")
    print(benchmark.format_dpd_table(results))


def add_arguments(parser):
    add_benchmark_arguments(parser)
    add_cutoff(parser)
    parser.set_defaults(run=run)
