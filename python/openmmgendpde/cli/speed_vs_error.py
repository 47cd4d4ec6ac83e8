# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""`speed-vs-error`: its arguments and output; the study is openmmgendpde.studies.speed_vs_error (whose docstring is
the command's --help)."""

import dataclasses
import pathlib

from ..models.argon import PUBLISHED_ESTIMATORS
from ..studies import speed_vs_error as study
from .options import add_cutoff, add_output, platform_description
from .progress import Progress
from .protocol import TIME_STEP, add_protocol_arguments, protocol_from_arguments

DESCRIPTION = study.__doc__


def run(arguments):
    protocol = protocol_from_arguments(arguments, defaults=study.DEFAULTS, cutoffs=[arguments.cutoff],
                                       estimators=PUBLISHED_ESTIMATORS)
    if arguments.quick and arguments.production is None:
        protocol = dataclasses.replace(protocol, production_time=10.0)
    steps = arguments.steps or ([0.02, 0.01, 0.005] if arguments.quick else [0.04, 0.02, 0.01, 0.005, 0.0025])
    output = pathlib.Path(arguments.output)
    output.mkdir(parents=True, exist_ok=True)
    progress = Progress(study.total_steps(protocol, steps), "speed-vs-error", always=arguments.progress)
    points = study.study(arguments.cutoff, steps, protocol, arguments.platform, progress)
    progress.finish()
    print(f"R_cut* = {arguments.cutoff}, {protocol.num_particles} particles, {protocol.production_time} time units per "
          f"step size from one state equilibrated at dt* = {min(steps)}; {platform_description(arguments)}")
    print(study.table(points))
    study.write_csv(points, output / "speed-vs-error.csv")
    study.plot(points, output / "speed-vs-error")
    print(f"Written: {output / 'speed-vs-error.csv'}, {output / 'speed-vs-error'}.png/.pdf")
    return points


def add_arguments(parser):
    add_protocol_arguments(parser, defaults=study.DEFAULTS)
    add_cutoff(parser)
    parser.add_argument("--steps", type=TIME_STEP, nargs="+",
                        help="step sizes dt* (default 0.04 0.02 0.01 0.005 0.0025; quick 0.02 0.01 0.005)")
    add_output(parser, "the table and plot")
    parser.set_defaults(run=run)
