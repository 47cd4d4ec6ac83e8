# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""The command-line options of the liquid-argon studies (table3, rdf, timing, tune-fcut, speed-vs-error): those that
override the run protocol of openmmgendpde.models.argon_runs (which says what a run does), checked before anything
runs. All times are in reduced units (the time unit is 0.8962 ps).
"""

import dataclasses

from ..models.argon import liquid_argon
from ..models.argon_runs import FULL, QUICK
from .options import SEED, add_platform, add_progress, checked_model, command_of, fcc_particles, number

#: dt* of the argon studies: > 0, and at most the interval between samples (FULL and QUICK sample every 0.5).
TIME_STEP = number(above=0, at_most=FULL.sample_interval,
                   why=f" (the samples are {FULL.sample_interval:g} time units apart)")


def add_protocol_arguments(parser, defaults=FULL):
    """Command-line options of the studies: those that override the protocol (--quick selects QUICK), the platform
    and --progress."""
    parser.add_argument("--quick", action="store_true",
                        help="short runs for CI: 500 particles, dt* = 0.01, 10 + 10 + 30 time units")
    parser.add_argument("--particles", type=fcc_particles,
                        help=f"particle count, 4 m^3 (default {defaults.num_particles})")
    parser.add_argument("--time-step", type=TIME_STEP, help=f"dt* (default {defaults.time_step})")
    parser.add_argument("--production", type=number(above=0),
                        help=f"production time* (default {defaults.production_time})")
    parser.add_argument("--seed", type=SEED, help=f"random seed (default {defaults.seed})")
    add_platform(parser)
    add_progress(parser)


def protocol_from_arguments(arguments, defaults=FULL, cutoffs=(), estimators=("VB",)):
    """The Protocol of the options (add_protocol_arguments), checked before anything runs: enough production samples
    for error bars, and a box that holds each of ``cutoffs`` (with each of ``estimators``), built once here (no
    Context); a one-line error (status 1) naming the subcommand otherwise."""
    command = command_of(arguments)
    protocol = QUICK if arguments.quick else defaults
    overrides = {"num_particles": arguments.particles, "time_step": arguments.time_step,
                 "production_time": arguments.production, "seed": arguments.seed}
    protocol = dataclasses.replace(protocol, **{key: value for key, value in overrides.items() if value is not None})
    samples = protocol.steps(protocol.production_time) // protocol.steps(protocol.sample_interval)
    if samples < 20:
        raise SystemExit(f"error: {command}: a production of {protocol.production_time} time units gives {samples} "
                         f"samples (every {protocol.sample_interval}); at least 20 are needed for block-average "
                         f"error bars")
    check_argon(command, [protocol.num_particles], cutoffs, estimators, time_step=protocol.time_step,
                seed=protocol.seed)
    return protocol


def check_argon(command, counts, cutoffs, estimators=("VB",), **options):
    """Each liquid_argon(count, cutoff, estimator, **options) built once (no Context), before anything runs: a count
    too small for a cutoff's box, or an option out of range, ends in a one-line error naming ``command``."""
    for count in counts:
        for cutoff in cutoffs:
            for estimator in estimators:
                checked_model(command, lambda: liquid_argon(count, cutoff, estimator, **options))
