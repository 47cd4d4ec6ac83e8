# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""What the benchmark subcommands share on the command line: their options and how they print and write their
results."""

import dataclasses
import json

from ..internal.files import atomic_write
from .options import add_json, add_platform, add_progress, add_rounds, fcc_particles


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
