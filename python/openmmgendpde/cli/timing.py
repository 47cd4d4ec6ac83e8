# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""`timing`: its arguments and output; the measurement is openmmgendpde.benchmarks.timing (whose docstring is the
command's --help)."""

from openmm import unit

from ..benchmarks import timing as benchmark
from ..models.argon import ARGON_UNITS, PUBLISHED_ESTIMATORS
from .options import COUNT, add_cutoffs, add_rounds, chosen_cutoffs, platform_description
from .progress import Progress
from .protocol import add_protocol_arguments, protocol_from_arguments

DESCRIPTION = benchmark.__doc__


def run(arguments):
    cutoffs = chosen_cutoffs(arguments)
    protocol = protocol_from_arguments(arguments, cutoffs=cutoffs, estimators=PUBLISHED_ESTIMATORS)
    rounds = arguments.rounds or (7 if arguments.quick else 15)
    steps = arguments.steps or (20 if arguments.quick else 50)
    preparation = 2.0 if arguments.quick else 10.0
    progress = Progress(len(cutoffs) * rounds, "timing", always=arguments.progress)
    rows = benchmark.timing_rows(cutoffs, protocol, arguments.platform, rounds, steps, preparation, progress)
    progress.finish()
    time_unit = ARGON_UNITS.unit("time").value_in_unit(unit.picosecond)
    print(f"Wall time per isoenergetic GenDPDE step, {protocol.num_particles} particles, dt* = {protocol.time_step} "
          f"({protocol.time_step * time_unit:.4f} ps), {platform_description(arguments)}; medians of {rounds} "
          f"alternating rounds of {steps} steps")
    print("| R_cut* | VA (ms/step) | VB (ms/step) | VB/VA | VB/VA published (Table IV) |")
    print("|---|---|---|---|---|")
    for row in rows:
        print(f"| {row.cutoff} | {row.milliseconds_per_step['VA']:.2f} | {row.milliseconds_per_step['VB']:.2f} "
              f"| {row.vb_over_va:.3f} | {row.published} |")
    return rows


def add_arguments(parser):
    add_protocol_arguments(parser)
    add_cutoffs(parser)
    add_rounds(parser, "15, quick 7")
    parser.add_argument("--steps", type=COUNT, help="steps per round (default 50, quick 20)")
    parser.set_defaults(run=run)
