"""Command-line options shared by the subcommands of ``python -m openmmgendpde``, each defined once here.

Where an option's default differs between subcommands on purpose (the frames that table3 keeps against those rdf
runs, the rounds of timing against those of the benchmarks), the default is a parameter. Options that only share
a name (``--particles``: one size for the studies, a list for the benchmarks; ``--steps``: steps per round in
timing, step sizes in speed-vs-error) are defined by their subcommands.
"""

import argparse
import os

from .presets import ARGON_CUTOFFS

#: R_cut* of the subcommands that study one cutoff (tune-fcut, speed-vs-error, benchmark-integrator): the middle
#: one of the three published.
DEFAULT_CUTOFF = ARGON_CUTOFFS[1].cutoff


def add_platform(parser, default="Reference"):
    import openmm
    from . import KERNEL_NAMES
    platforms = [openmm.Platform.getPlatform(i) for i in range(openmm.Platform.getNumPlatforms())]
    parser.add_argument("--platform", default=default,
                        choices=[p.getName() for p in platforms if p.supportsKernels(KERNEL_NAMES)],
                        help=f"OpenMM platform, one that runs this plugin here (default {default})")
    parser.add_argument("--threads", type=int,
                        help="threads of the CPU platform (its Threads property; default: OpenMM's, one per core)")
    parser.add_argument("--precision", choices=("single", "mixed", "double"),
                        help="precision of a GPU platform, OpenCL or CUDA (its Precision property; default OpenMM's, "
                             "single)")


def apply_threads(arguments):
    """Make --threads the CPU platform's default Threads (and --precision a GPU platform's default Precision) for every
    Context this process creates (OpenMM's own mechanism, Platform.setPropertyDefaultValue). Raises ValueError for a
    bad count or a platform without threads (or precisions)."""
    precision = getattr(arguments, "precision", None)
    if precision is not None:
        if arguments.platform not in ("OpenCL", "CUDA"):
            raise ValueError(f"--precision = {precision} applies to the OpenCL and CUDA platforms only, not to "
                             f"--platform {arguments.platform}")
        import openmm
        openmm.Platform.getPlatformByName(arguments.platform).setPropertyDefaultValue("Precision", precision)
    threads = getattr(arguments, "threads", None)
    if threads is None:
        return
    if arguments.platform != "CPU":
        raise ValueError(f"--threads = {threads} applies to the CPU platform only, not to --platform "
                         f"{arguments.platform}")
    if threads < 1:
        raise ValueError(f"--threads = {threads} is not allowed; it must be >= 1")
    import openmm
    openmm.Platform.getPlatformByName("CPU").setPropertyDefaultValue("Threads", str(threads))


def context_threads(context):
    """The threads a Context computes on: the CPU platform's Threads property, else 1."""
    platform = context.getPlatform()
    return int(platform.getPropertyValue(context, "Threads")) if platform.getName() == "CPU" else 1


def platform_description(arguments):
    """'Reference platform', 'CPU platform, 2 threads' (the count a CPU Context gets now), 'CUDA platform, mixed
    precision'."""
    if arguments.platform in ("OpenCL", "CUDA"):
        import openmm
        precision = openmm.Platform.getPlatformByName(arguments.platform).getPropertyDefaultValue("Precision")
        return f"{arguments.platform} platform, {precision} precision"
    if arguments.platform != "CPU":
        return f"{arguments.platform} platform"
    import openmm
    return f"CPU platform, {openmm.Platform.getPlatformByName('CPU').getPropertyDefaultValue('Threads')} threads"


def add_progress(parser):
    parser.add_argument("--progress", action="store_true", help="show progress even when not on a terminal")


def add_cutoffs(parser):
    parser.add_argument("--cutoffs", type=float, nargs="+", help="R_cut* values (default: the three published)")


def chosen_cutoffs(arguments):
    """The cutoffs of --cutoffs, or the three published ones."""
    return arguments.cutoffs or [entry.cutoff for entry in ARGON_CUTOFFS]


def add_cutoff(parser, fluid=False):
    """--cutoff: R_cut* of the argon model; with ``fluid`` (a subcommand that takes --fluid) it is also the cutoff R
    in nm of a --fluid model, as calibrate's, and its default (None) is resolved by chosen_cutoff."""
    if fluid:
        parser.add_argument("--cutoff", type=float, help=f"R_cut* of the argon model (default {DEFAULT_CUTOFF}); "
                                                         f"with --fluid, the cutoff R in nm (instead of --neighbors)")
    else:
        parser.add_argument("--cutoff", type=float, default=DEFAULT_CUTOFF, help=f"R_cut* (default {DEFAULT_CUTOFF})")


def chosen_cutoff(arguments):
    """R_cut* of --cutoff for the argon model, or DEFAULT_CUTOFF."""
    return DEFAULT_CUTOFF if arguments.cutoff is None else arguments.cutoff


def _writable_directory_for(path, what):
    """Raise ArgumentTypeError unless a file or directory at ``path`` could be made: the nearest existing directory
    above it is writable, and nothing in the way is a file."""
    directory = os.path.dirname(os.path.abspath(path))
    while not os.path.exists(directory):
        directory = os.path.dirname(directory)
    if not os.path.isdir(directory):
        raise argparse.ArgumentTypeError(f"{path} cannot be written ({what}): {directory} is a file, not a directory")
    if not os.access(directory, os.W_OK):
        raise argparse.ArgumentTypeError(f"{path} cannot be written ({what}): the directory {directory} is not "
                                         f"writable")


def writable_file(path):
    """An argparse type for a file a subcommand writes at its end (--json, calibrate's --output): refused when the
    arguments are read, before anything runs, if it could not be written then (its directory missing or not writable,
    or a directory in its place)."""
    if os.path.isdir(path):
        raise argparse.ArgumentTypeError(f"{path} is a directory, not a file")
    if os.path.exists(path) and not os.access(path, os.W_OK):
        raise argparse.ArgumentTypeError(f"{path} cannot be written (not writable)")
    _writable_directory_for(path, "a file")
    if not os.path.isdir(os.path.dirname(os.path.abspath(path))):
        raise argparse.ArgumentTypeError(f"{path} cannot be written: the directory "
                                         f"{os.path.dirname(os.path.abspath(path))} does not exist")
    return path


def writable_directory(path):
    """An argparse type for a directory a subcommand writes into (made if absent): refused when the arguments are
    read if it could not be made or written."""
    if os.path.exists(path):
        if not os.path.isdir(path):
            raise argparse.ArgumentTypeError(f"{path} is a file, not a directory")
        if not os.access(path, os.W_OK):
            raise argparse.ArgumentTypeError(f"{path} cannot be written (the directory is not writable)")
        return path
    _writable_directory_for(path, "a directory to make")
    return path


def add_json(parser, contents="the results"):
    """--json FILE: also write ``contents`` there (checked when the arguments are read: writable_file)."""
    parser.add_argument("--json", type=writable_file, help=f"also write {contents} to this JSON file")


def add_output(parser, contents):
    """--output DIR (default results); ``contents`` says what goes there."""
    parser.add_argument("--output", default="results", type=writable_directory,
                        help=f"directory for {contents} (default results)")


def add_frames(parser, purpose, default=None, default_text=None):
    """--frames: production frames of each run to keep ``purpose``; ``default_text`` describes a default that the
    subcommand resolves itself (``default`` None)."""
    parser.add_argument("--frames", type=int, default=default,
                        help=f"production frames {purpose} (default {default_text or default})")


def add_rounds(parser, default_text):
    """--rounds: alternating timing rounds; each subcommand resolves the default that ``default_text`` states."""
    parser.add_argument("--rounds", type=int, help=f"alternating timing rounds (default {default_text})")


#: The arguments of the Python API that the command line sets, as its errors name them, and the options that set them.
_OPTIONS = {"num_particles = ": "--particles ", "molecules_per_particle = ": "--molecules-per-particle ",
            "neighbors = ": "--neighbors ", "cutoff = ": "--cutoff "}


def command_line_error(command, error, box_advice=None):
    """A SystemExit (status 1) with the one-line error of the API's ValueError ``error``, worded for the command line:
    the options instead of the Python arguments, and ``box_advice`` instead of the API's for a box too small for the
    cutoff (the command line has no cells)."""
    message = " ".join(str(error).split())
    for name, option in _OPTIONS.items():
        message = message.replace(name, option)
    message = message.replace("; give cells for other boxes", "")
    if box_advice:
        message = message.replace("use more cells", box_advice)
    return SystemExit(f"error: {command}: {message}")
