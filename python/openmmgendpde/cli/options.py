# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""Command-line options shared by the subcommands of ``python -m openmmgendpde``, each defined once here.

Where an option's default differs between subcommands on purpose (the frames that table3 keeps against those rdf
runs, the rounds of timing against those of the benchmarks), the default is a parameter. Options that only share
a name (``--particles``: one size for the studies, a list for the benchmarks; ``--steps``: steps per round in
timing, step sizes in speed-vs-error) are defined by their subcommands.
"""

import argparse
import math
import os
import sys

from ..models.argon import ARGON_CUTOFFS, DEFAULT_CUTOFF


def integer(minimum, maximum=None, why=""):
    """An argparse type: an integer >= ``minimum`` (and <= ``maximum``). A value that is not is refused when the
    arguments are read (usage error, status 2), naming the value and what is allowed, and ``why`` (a clause
    starting with ', ' or ' (') where the range needs a reason."""
    allowed = f"an integer >= {minimum}" if maximum is None else f"an integer from {minimum} to {maximum}"

    def check(text):
        try:
            value = int(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"{text!r} is not allowed; it must be {allowed}{why}") from None
        if value < minimum or (maximum is not None and value > maximum):
            raise argparse.ArgumentTypeError(f"{value} is not allowed; it must be {allowed}{why}")
        return value
    return check


def number(above=None, at_least=None, below=None, at_most=None, why=""):
    """An argparse type: a finite number within the bounds given (> ``above``, >= ``at_least``, < ``below``,
    <= ``at_most``). A value that is not (nan and inf included) is refused when the arguments are read, naming the
    value and what is allowed, and ``why`` where the range needs a reason."""
    bounds = [f"{sign} {bound:g}" for sign, bound in ((">", above), (">=", at_least), ("<", below), ("<=", at_most))
              if bound is not None]
    allowed = "a finite number" + (" " + " and ".join(bounds) if bounds else "")

    def check(text):
        try:
            value = float(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"{text!r} is not allowed; it must be {allowed}{why}") from None
        if not (math.isfinite(value) and (above is None or value > above) and (at_least is None or value >= at_least)
                and (below is None or value < below) and (at_most is None or value <= at_most)):
            raise argparse.ArgumentTypeError(f"{text} is not allowed; it must be {allowed}{why}")
        return value
    return check


#: Counts of steps, rounds, runs, frames ...: an integer >= 1 (or >= 0 where nothing is a choice).
COUNT = integer(1)
NON_NEGATIVE_COUNT = integer(0)
#: Lengths of time, step sizes, rates: a finite number > 0 (or >= 0 where none is a choice).
POSITIVE = number(above=0)
NON_NEGATIVE = number(at_least=0)
#: The largest --seed: OpenMM's random seeds are 32-bit integers, and the runs derive further seeds from it by adding
#: their run numbers, so it stays well below 2^31 - 1.
MAX_SEED = 10**9
SEED = integer(0, MAX_SEED, " (OpenMM's seeds are 32-bit integers, and the runs add their run numbers to it; 0: "
                            "OpenMM picks one)")
#: The most CPU threads --threads takes: more than any machine this runs on has cores.
MAX_THREADS = 1024
THREADS = integer(1, MAX_THREADS)
#: The largest m of a cube of 4 m^3 particles: 4 million particles (16 times the largest documented run, 256000),
#: so that a mistyped count is refused instead of exhausting the memory.
MAX_CELLS = 100


def fcc_particles(text):
    """An argparse type: a particle count that fills a cubic box with an FCC lattice, 4 m^3 for an integer m from 1
    to MAX_CELLS (500, 864, 2048, 4000, ...)."""
    try:
        value = integer(4, 4 * MAX_CELLS**3)(text)
        if 4 * round((value / 4) ** (1 / 3)) ** 3 == value:
            return value
    except argparse.ArgumentTypeError:
        pass
    raise argparse.ArgumentTypeError(f"{text} is not allowed; it must be 4 m^3 for an integer m from 1 to {MAX_CELLS} "
                                     f"(500, 864, 2048, 4000, ...: an FCC lattice in a cubic box)")


def published_cutoff(text):
    """An argparse type: R_cut* of the argon model, one of the three published cutoffs (its f_cut and its published
    results are known for those only); the published value itself is returned."""
    value = number(above=0)(text)
    for entry in ARGON_CUTOFFS:
        if abs(entry.cutoff - value) < 1e-6:
            return entry.cutoff
    raise argparse.ArgumentTypeError(f"{text} is not allowed; R_cut* must be one of the published cutoffs "
                                     f"{', '.join(str(entry.cutoff) for entry in ARGON_CUTOFFS)}")


def add_platform(parser, default="Reference", allowed=None):
    """--platform (one that runs this plugin here; of those, only the names in ``allowed`` if given), --threads and
    --precision; apply_threads (or parse_arguments) applies the last two."""
    import openmm

    from ..api import KERNEL_NAMES
    platforms = [openmm.Platform.getPlatform(i) for i in range(openmm.Platform.getNumPlatforms())]
    parser.add_argument("--platform", default=default,
                        choices=[p.getName() for p in platforms if p.supportsKernels(KERNEL_NAMES)
                                 and (allowed is None or p.getName() in allowed)],
                        help=f"OpenMM platform, one that runs this plugin here (default {default})")
    parser.add_argument("--threads", type=THREADS,
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


def parse_arguments(parser, argv=None):
    """parser.parse_args(argv), then apply_threads: a bad --threads or --precision is a usage error (status 2)."""
    arguments = parser.parse_args(argv)
    try:
        apply_threads(arguments)
    except ValueError as error:
        parser.error(str(error))
    return arguments


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
    parser.add_argument("--cutoffs", type=published_cutoff, nargs="+",
                        help="R_cut* values, of the three published (default: all three)")


def chosen_cutoffs(arguments):
    """The cutoffs of --cutoffs, or the three published ones."""
    return arguments.cutoffs or [entry.cutoff for entry in ARGON_CUTOFFS]


def add_cutoff(parser, fluid=False):
    """--cutoff: R_cut* of the argon model; with ``fluid`` (a subcommand that takes --fluid) it is also the cutoff R
    in nm of a --fluid model, as calibrate's, and its default (None) is resolved by chosen_cutoff."""
    if fluid:
        parser.add_argument("--cutoff", type=POSITIVE, help=f"R_cut* of the argon model, one of the three published "
                                                            f"(default {DEFAULT_CUTOFF}); with --fluid, the cutoff R "
                                                            f"in nm (instead of --neighbors)")
    else:
        parser.add_argument("--cutoff", type=published_cutoff, default=DEFAULT_CUTOFF,
                            help=f"R_cut*, one of the three published (default {DEFAULT_CUTOFF})")


def chosen_cutoff(arguments):
    """R_cut* of --cutoff for the argon model (one of the published: else a one-line error naming the subcommand; the
    option also takes a cutoff in nm for --fluid, so its type cannot check it), or DEFAULT_CUTOFF."""
    if arguments.cutoff is None:
        return DEFAULT_CUTOFF
    try:
        return published_cutoff(str(arguments.cutoff))
    except argparse.ArgumentTypeError as error:
        raise SystemExit(f"error: {command_of(arguments)}: --cutoff {error}") from None


def command_of(arguments):
    """The subcommand of parsed ``arguments`` (__main__ keeps it as arguments.command), for its one-line errors."""
    return getattr(arguments, "command", None) or "openmmgendpde"


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
    _try_creating_in(directory, path, what)


def _try_creating_in(directory, path, what):
    """Raise ArgumentTypeError unless a file can be created in ``directory`` now (and it is removed at once): the
    permission bits do not tell for every file system (/proc, a read-only mount; root passes os.access)."""
    import tempfile
    try:
        with tempfile.TemporaryFile(dir=directory):
            pass
    except OSError as error:
        raise argparse.ArgumentTypeError(f"{path} cannot be written ({what}): no file can be made in {directory} "
                                         f"({error.strerror or error})") from None


def writable_file(path):
    """An argparse type for a file a subcommand writes at its end (--json, calibrate's --output): refused when the
    arguments are read, before anything runs, if it could not be written then (its directory missing or not writable,
    or a directory in its place). A regular file is written atomically (files.atomic_write: a temporary file in its
    directory, renamed over it), so its directory must be writable; an existing file that is not a regular one (a
    device such as /dev/stdout, a pipe) is written in place and need only be writable itself."""
    given = path
    if os.path.isdir(path):
        raise argparse.ArgumentTypeError(f"{path} is a directory, not a file")
    if os.path.exists(path) and not os.access(path, os.W_OK):
        raise argparse.ArgumentTypeError(f"{path} cannot be written (not writable)")
    if os.path.exists(path) and not os.path.isfile(path):
        return path
    if os.path.islink(path):
        path = os.path.realpath(path)   # the file it names is the one replaced
    _writable_directory_for(path, "a file")
    if not os.path.isdir(os.path.dirname(os.path.abspath(path))):
        raise argparse.ArgumentTypeError(f"{path} cannot be written: the directory "
                                         f"{os.path.dirname(os.path.abspath(path))} does not exist")
    return given


def writable_stem(*suffixes):
    """An argparse type for STEM of a figure written to STEM + each of ``suffixes`` (default .png and .pdf, as
    plotting.save writes): each checked as writable_file checks a file."""
    suffixes = suffixes or (".png", ".pdf")

    def check(stem):
        for suffix in suffixes:
            writable_file(stem + suffix)
        return stem
    return check


def writable_directory(path):
    """An argparse type for a directory a subcommand writes into (made if absent): refused when the arguments are
    read if it could not be made or written."""
    if os.path.exists(path):
        if not os.path.isdir(path):
            raise argparse.ArgumentTypeError(f"{path} is a file, not a directory")
        if not os.access(path, os.W_OK):
            raise argparse.ArgumentTypeError(f"{path} cannot be written (the directory is not writable)")
        _try_creating_in(path, path, "a directory")
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
    parser.add_argument("--frames", type=COUNT, default=default,
                        help=f"production frames {purpose} (default {default_text or default})")


def add_rounds(parser, default_text):
    """--rounds: alternating timing rounds; each subcommand resolves the default that ``default_text`` states."""
    parser.add_argument("--rounds", type=COUNT, help=f"alternating timing rounds (default {default_text})")


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


def checked_model(command, build, box_advice=None):
    """build(): a model built once before anything runs, so that every argument is checked against the others (the
    particles against the cutoff) and against the ranges that GenDPDEForce and GenDPDEIntegrator allow; a ValueError
    or OpenMMException it raises becomes the one-line error of command_line_error (status 1)."""
    import openmm
    try:
        return build()
    except (ValueError, openmm.OpenMMException) as error:
        raise command_line_error(command, error, box_advice) from None


def failure_message(error):
    """A failure of a run (RUN_FAILURES) as one line: an OSError as 'PATH: reason', others their message."""
    if isinstance(error, MemoryError):
        return "out of memory" + (f" ({error})" if str(error) else "")
    if isinstance(error, OSError) and error.filename is not None:
        return f"{error.filename}: {error.strerror or error}"
    return " ".join(str(error).split())


def run_failures():
    """The exceptions that end a run with a one-line error instead of a traceback: a simulation that goes bad
    (openmm.OpenMMException: a refused step, a blown-up integration), an output that cannot be written (OSError) and
    memory exhausted (MemoryError). Others are errors of the program and keep their traceback."""
    import openmm
    return openmm.OpenMMException, OSError, MemoryError


def run_command(command, function, *arguments):
    """function(*arguments) for the command ``command``: a failure during the run (run_failures) ends the process with
    'error: <command>: <message>' (status 1), Ctrl-C with 'error: <command>: interrupted' (status 130)."""
    try:
        return function(*arguments)
    except KeyboardInterrupt:
        print(f"error: {command}: interrupted", file=sys.stderr)
        raise SystemExit(130) from None
    except run_failures() as error:
        raise SystemExit(f"error: {command}: {failure_message(error)}") from None


def one_line_errors(command):
    """For a script (the examples): a failure during its run (run_failures) or Ctrl-C that nothing catches is printed
    as 'error: <command>: <message>' on stderr instead of a traceback (the exit status stays nonzero); any other
    exception keeps its traceback. Installed as sys.excepthook."""
    default = sys.excepthook

    def hook(kind, error, traceback):
        if issubclass(kind, KeyboardInterrupt):
            print(f"error: {command}: interrupted", file=sys.stderr)
        elif issubclass(kind, run_failures()):
            print(f"error: {command}: {failure_message(error)}", file=sys.stderr)
        else:
            default(kind, error, traceback)
    sys.excepthook = hook
