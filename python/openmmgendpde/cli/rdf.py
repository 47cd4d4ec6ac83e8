# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""`rdf`: its arguments and output; the study is openmmgendpde.studies.rdf (whose docstring is the command's --help)."""

import pathlib

from ..models.argon import PUBLISHED_ESTIMATORS
from ..studies import rdf as study
from ..studies.table3 import read_frames
from .options import add_cutoffs, add_frames, add_output, chosen_cutoffs
from .progress import Progress
from .protocol import add_protocol_arguments, protocol_from_arguments

DESCRIPTION = study.__doc__


def run(arguments):
    cutoffs = chosen_cutoffs(arguments)
    saved = None
    if arguments.frames_from:   # read and checked before anything runs: a complete set from table3, every case
        try:
            saved = read_frames(arguments.frames_from, [(c, e) for c in cutoffs for e in PUBLISHED_ESTIMATORS])
        except ValueError as error:
            raise SystemExit(f"error: rdf: --frames-from {error}") from None
    protocol = protocol_from_arguments(arguments, cutoffs=() if saved else cutoffs, estimators=PUBLISHED_ESTIMATORS)
    output = pathlib.Path(arguments.output)
    output.mkdir(parents=True, exist_ok=True)
    progress = Progress(len(PUBLISHED_ESTIMATORS) * len(cutoffs) * protocol.total_steps, "rdf",
                        always=arguments.progress)
    curves = study.curves(cutoffs, protocol, arguments.platform, arguments.frames, saved, progress)
    progress.finish()
    stem = output / "fig1-rdf"
    study.plot(curves, cutoffs, stem)
    study.write_csv(curves, cutoffs, output / "fig1-rdf.csv")
    for line in study.signature(curves):
        print(line)
    print(f"Written: {stem}.png, {stem}.pdf, {output / 'fig1-rdf.csv'}")
    return curves


def add_arguments(parser):
    add_protocol_arguments(parser)
    add_cutoffs(parser)
    parser.add_argument("--frames-from", help="read the frames saved by `table3 --output DIR` instead of running")
    add_frames(parser, "per run when running", default=50)
    add_output(parser, "the plots")
    parser.set_defaults(run=run)
