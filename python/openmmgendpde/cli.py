"""Command-line options shared by the subcommands of ``python -m openmmgendpde``, each defined once here.

Where an option's default differs between subcommands on purpose (the frames that table3 keeps against those rdf
runs, the rounds of timing against those of the benchmarks), the default is a parameter. Options that only share
a name (``--particles``: one size for the studies, a list for the benchmarks; ``--steps``: steps per round in
timing, step sizes in speed-vs-error) are defined by their subcommands.
"""

from .presets import ARGON_CUTOFFS

#: R_cut* of the subcommands that study one cutoff (tune-fcut, speed-vs-error, benchmark-integrator): the middle
#: one of the three published.
DEFAULT_CUTOFF = ARGON_CUTOFFS[1].cutoff


def add_platform(parser):
    parser.add_argument("--platform", default="Reference", help="OpenMM platform (default Reference)")


def add_progress(parser):
    parser.add_argument("--progress", action="store_true", help="show progress even when not on a terminal")


def add_cutoffs(parser):
    parser.add_argument("--cutoffs", type=float, nargs="+", help="R_cut* values (default: the three published)")


def chosen_cutoffs(arguments):
    """The cutoffs of --cutoffs, or the three published ones."""
    return arguments.cutoffs or [entry.cutoff for entry in ARGON_CUTOFFS]


def add_cutoff(parser):
    parser.add_argument("--cutoff", type=float, default=DEFAULT_CUTOFF, help=f"R_cut* (default {DEFAULT_CUTOFF})")


def add_output(parser, contents):
    """--output DIR (default results); ``contents`` says what goes there."""
    parser.add_argument("--output", default="results", help=f"directory for {contents} (default results)")


def add_frames(parser, purpose, default=None, default_text=None):
    """--frames: production frames of each run to keep ``purpose``; ``default_text`` describes a default that the
    subcommand resolves itself (``default`` None)."""
    parser.add_argument("--frames", type=int, default=default,
                        help=f"production frames {purpose} (default {default_text or default})")


def add_rounds(parser, default_text):
    """--rounds: alternating timing rounds; each subcommand resolves the default that ``default_text`` states."""
    parser.add_argument("--rounds", type=int, help=f"alternating timing rounds (default {default_text})")
