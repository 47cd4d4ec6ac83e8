# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""`table3`: its arguments and output; the study is openmmgendpde.studies.table3 (whose docstring is the command's
--help)."""

import pathlib

from ..api import ESTIMATOR_NAMES
from ..models.argon import PUBLISHED_ESTIMATORS
from ..studies import table3 as study
from .options import add_cutoffs, add_frames, add_output, chosen_cutoffs, platform_description
from .progress import Progress
from .protocol import add_protocol_arguments, protocol_from_arguments

DESCRIPTION = study.__doc__


def run(arguments):
    cutoffs = chosen_cutoffs(arguments)
    protocol = protocol_from_arguments(arguments, cutoffs=cutoffs, estimators=arguments.estimators)
    output = pathlib.Path(arguments.output)
    output.mkdir(parents=True, exist_ok=True)
    frames = arguments.frames if arguments.frames is not None else (10 if arguments.quick else 50)
    print(f"Table III: {protocol.num_particles} particles, dt* = {protocol.time_step}, thermostat "
          f"{protocol.thermostat_time} + isoenergetic equilibration {protocol.equilibration_time} + production "
          f"{protocol.production_time} time units, samples every {protocol.sample_interval}; "
          f"{platform_description(arguments)}", flush=True)
    progress = Progress(len(cutoffs) * len(arguments.estimators) * protocol.total_steps, "table3",
                        always=arguments.progress)
    table = study.reproduce(cutoffs, arguments.estimators, protocol, arguments.platform, frames, progress)
    progress.finish()
    print(study.format_table(table.cells))
    print(study.sampling_summary(table.unsettled, len(table.cells), arguments.verbose))
    print("(!) differs from the published value by more than its error bar (0.0001 for T*, 0.001 otherwise) "
          "plus twice the standard error of the reproduction")
    for line in study.pairing_signature(table.cells):
        print(line)
    if arguments.quick:
        print("(--quick: 500 particles and runs of 50 time units, too short to settle T* at T0; the full-size "
              "reproduction, with every n-bar* and P* within the published error bars, is in docs/argon.md)")
    study.write_csv(table.cells, output / "table3.csv")
    study.save_frames(output, table.frames)   # (all at the end, as one set: rdf --frames-from reads a complete set)
    print(f"Written: {output / 'table3.csv'} and the production frames for `rdf --frames-from {output}`")
    return table.cells


def add_arguments(parser):
    add_protocol_arguments(parser)
    add_cutoffs(parser)
    add_frames(parser, "to keep for the RDF", default_text="50, quick 10")
    add_output(parser, "table3.csv and the frames")
    parser.add_argument("--estimators", nargs="+", choices=list(ESTIMATOR_NAMES.values()),
                        default=list(PUBLISHED_ESTIMATORS),
                        help="estimators to run (default VA VB; VC is compared with the published VB values)")
    parser.add_argument("--verbose", action="store_true",
                        help="each error bar that has not reached its block-average plateau, with its estimates")
    parser.set_defaults(run=run)
