# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""Every argument of `python3 -m openmmgendpde` checked before anything runs, and every failure in one line: a usage
error (status 2) for a bad value, one line (status 1) for arguments that do not fit together or a run that fails."""


import openmm
import pytest

from openmmgendpde.__main__ import main

# The quick sizes run in seconds, too short for the error bars to reach their plateau: every study would warn
# (BlockAverageWarning). The warning itself is tested in test_statistics.py.
pytestmark = pytest.mark.filterwarnings("ignore::openmmgendpde.analysis.statistics.BlockAverageWarning")

@pytest.mark.parametrize("command, option, place, message", [
    (["calibrate", "--quick"], "--json", "missing/calibration.json", "the directory {tmp}/missing does not exist"),
    (["calibrate", "--quick"], "--plot", "missing/figure", "the directory {tmp}/missing does not exist"),
    (["calibrate", "--quick"], "--output", "missing/model.toml", "the directory {tmp}/missing does not exist"),
    (["calibrate", "--quick"], "--json", ".", "{tmp} is a directory, not a file"),
    (["benchmark-cpu", "--particles", "500"], "--json", "a-file/cpu.json", "{tmp}/a-file is a file, not a directory"),
    (["benchmark-force", "--particles", "500"], "--json", "missing/force.json", "does not exist"),
    (["table3", "--quick"], "--output", "a-file", "{tmp}/a-file is a file, not a directory"),
    (["slab", "--quick"], "--output", "a-file/slab", "{tmp}/a-file is a file, not a directory"),
])
def test_an_output_that_cannot_be_written_is_refused_before_anything_runs(command, option, place, message, tmp_path,
                                                                        capsys, monkeypatch):
    """A file or directory that a subcommand writes at its end (calibrate's after ~25 minutes) is checked when the
    arguments are read: usage error (status 2) naming the option, the path and why, and nothing runs (the run
    function is replaced by one that fails the test)."""
    monkeypatch.chdir(tmp_path)
    (tmp_path / "a-file").write_text("not a directory")
    import openmmgendpde.__main__ as entry
    for _, module, _ in entry.SUBCOMMANDS:
        monkeypatch.setattr(module, "run", lambda arguments: pytest.fail("the subcommand ran"))
    with pytest.raises(SystemExit) as exit_:
        main(command + [option, str(tmp_path / place)])
    assert exit_.value.code == 2
    error = capsys.readouterr().err.splitlines()[-1]
    assert f"argument {option}" in error and message.format(tmp=tmp_path) in error


def test_an_output_directory_that_can_be_made_is_accepted(tmp_path, monkeypatch):
    """--output DIR may name a directory to make (table3 makes it), under one that exists and is writable."""
    import openmmgendpde.cli.table3 as table3
    seen = []
    monkeypatch.setattr(table3, "run", lambda arguments: seen.append(arguments.output))
    main(["table3", "--quick", "--output", str(tmp_path / "new" / "results")])
    assert seen == [str(tmp_path / "new" / "results")]


def test_too_short_production_is_refused():
    with pytest.raises(SystemExit, match="at least 20"):
        main(["table3", "--quick", "--production", "4"])


@pytest.mark.parametrize("value", ["0.0", "-0.01", "nan"])
def test_calibrate_refuses_a_time_step_that_is_not_positive(value, capsys):
    """calibrate --time-step: a usage error (status 2) naming the option, the value and what is allowed, before any
    run."""
    with pytest.raises(SystemExit) as exit_:
        main(["calibrate", "--quick", "--time-step", value])
    assert exit_.value.code == 2
    assert capsys.readouterr().err.splitlines()[-1].endswith(
        f"error: argument --time-step: {value} is not allowed; it must be a finite number > 0")


@pytest.fixture
def nothing_runs(monkeypatch):
    """Every subcommand's run replaced by one that fails the test: the arguments must be refused first."""
    import openmmgendpde.__main__ as entry
    for _, module, _ in entry.SUBCOMMANDS:
        monkeypatch.setattr(module, "run", lambda arguments: pytest.fail("the subcommand ran"))


@pytest.mark.parametrize("arguments, message", [
    (["thermal-expansion", "--particles", "100"], "argument --particles: 100 is not allowed; it must be 4 m^3"),
    (["thermal-expansion", "--particles", "0"], "argument --particles: 0 is not allowed; it must be 4 m^3"),
    (["thermal-expansion", "--steps", "0"], "argument --steps: 0 is not allowed; it must be an integer >= 400"),
    (["thermal-expansion", "--delta", "nan"], "argument --delta: nan is not allowed; it must be a finite number > 0"),
    (["thermal-expansion", "--delta", "0"], "argument --delta: 0 is not allowed; it must be a finite number > 0"),
    (["thermal-expansion", "--delta", "-5"], "argument --delta: -5 is not allowed"),
    (["thermal-expansion", "--melt", "-1"], "argument --melt: -1 is not allowed; it must be an integer >= 0"),
    (["thermal-expansion", "--seed", "99999999999"], "argument --seed: 99999999999 is not allowed; it must be an "
                                                     "integer from 0 to 1000000000"),
    (["thermal-expansion", "--iterations", "-1"], "argument --iterations: -1 is not allowed"),
    (["table3", "--particles", "100"], "argument --particles: 100 is not allowed; it must be 4 m^3"),
    (["table3", "--time-step", "-0.01"], "argument --time-step: -0.01 is not allowed; it must be a finite number > 0"),
    (["table3", "--cutoffs", "1.5"], "argument --cutoffs: 1.5 is not allowed; R_cut* must be one of the published"),
    (["table3", "--frames", "0"], "argument --frames: 0 is not allowed; it must be an integer >= 1"),
    (["rdf", "--production", "inf"], "argument --production: inf is not allowed"),
    (["timing", "--steps", "0"], "argument --steps: 0 is not allowed"),
    (["timing", "--rounds", "0"], "argument --rounds: 0 is not allowed"),
    (["tune-fcut", "--tolerance", "0"], "argument --tolerance: 0 is not allowed"),
    (["tune-fcut", "--max-iterations", "0"], "argument --max-iterations: 0 is not allowed"),
    (["speed-vs-error", "--steps", "0.01", "-1"], "argument --steps: -1 is not allowed"),
    (["calibrate", "--particles", "100"], "argument --particles: 100 is not allowed"),
    (["calibrate", "--seed", "-1"], "argument --seed: -1 is not allowed"),
    (["calibrate", "--molecules-per-particle", "nan"], "argument --molecules-per-particle: nan is not allowed"),
    (["slab", "--duration", "inf"], "argument --duration: inf is not allowed"),
    (["slab", "--thermostat-time", "-1"], "argument --thermostat-time: -1 is not allowed"),
    (["benchmark-force", "--particles", "100"], "argument --particles: 100 is not allowed"),
    (["benchmark-integrator", "--cutoff", "3"], "argument --cutoff: 3 is not allowed; R_cut* must be one of"),
    (["benchmark-cpu", "--thread-counts", "0"], "argument --thread-counts: 0 is not allowed"),
])
def test_a_bad_number_is_a_usage_error_before_anything_runs(arguments, message, nothing_runs, capsys):
    """Every number of every subcommand is checked when the arguments are read (finite, in range, an integer for a
    count, 4 m^3 particles, a published R_cut*, a seed OpenMM takes): usage error, status 2, one line naming the
    option, the value and what is allowed."""
    with pytest.raises(SystemExit) as exit_:
        main(arguments)
    assert exit_.value.code == 2
    assert message in capsys.readouterr().err.splitlines()[-1]


@pytest.mark.parametrize("arguments, message", [
    (["benchmark-force", "--particles", "500", "--json", "/proc/x.json"], "/proc/x.json cannot be written"),
    (["table3", "--output", "/proc/results"], "/proc/results cannot be written"),
])
def test_an_output_where_no_file_can_be_made_is_refused(arguments, message, nothing_runs, capsys):
    """Writable permission bits are not enough (root passes them; /proc takes no new file): a file is made there and
    removed when the arguments are read."""
    with pytest.raises(SystemExit) as exit_:
        main(arguments)
    assert exit_.value.code == 2 and message in capsys.readouterr().err.splitlines()[-1]


@pytest.mark.parametrize("arguments, message", [
    (["thermal-expansion", "--delta", "200"], "error: thermal-expansion: --delta 200 is not allowed; it must be < T0 = "
                                              "125.7 K"),
    (["thermal-expansion", "--particles", "32"], "error: thermal-expansion: the box"),
    (["thermal-expansion", "--fluid", "water"], "error: thermal-expansion: liquid water, 298.15 K, 0.1 MPa: no "
                                                "thermal_expansion, so no TaitThermalExpansion law to measure"),
    (["thermal-expansion", "--fluid", "oil"], "error: thermal-expansion: --fluid oil is not allowed; give one of "
                                              "argon, argon-expanding, supercritical-argon, water or a fluid file"),
    (["table3", "--particles", "32"], "error: table3: 32 particles make a box of edge"),
    (["tune-fcut", "--quick", "--cutoff", "1.5"], "error: tune-fcut: --cutoff 1.5 is not allowed"),
    (["tune-fcut", "--quick", "--start", "0.5"], "error: tune-fcut: GenDPDEForce: cutoff scaling f_cut = 0.5 is not "
                                                 "allowed"),
    (["benchmark-force", "--particles", "32"], "error: benchmark-force: 32 particles make a box"),
    (["slab", "--duration", "10", "--every", "20"], "error: slab: --every 20 is not allowed; it must be at most "
                                                    "--duration 10"),
    (["slab", "--every", "0.001"], "error: slab: --every 0.001 is not allowed; it must be at least one step"),
    (["rdf", "--quick", "--frames-from", "/nonexistent"], "error: rdf: --frames-from /nonexistent is not a directory"),
])
def test_arguments_that_do_not_fit_together_end_in_one_line_before_anything_runs(arguments, message, monkeypatch):
    """Arguments checked against each other (the particles against the cutoff, dT against T0, f_cut against the
    force's range) before any simulation: a one-line error (status 1) naming the subcommand (Context creation fails
    the test)."""
    monkeypatch.setattr(openmm, "Context", lambda *a, **k: pytest.fail("a simulation started"))
    with pytest.raises(SystemExit) as exit_:
        main(arguments)
    assert str(exit_.value).startswith(message) and "\n" not in str(exit_.value)


@pytest.mark.parametrize("failure, status, message", [
    (openmm.OpenMMException("GenDPDEIntegrator: the internal energy of particle 3 would become -0.1 kJ/mol"), 1,
     "error: timing: GenDPDEIntegrator: the internal energy of particle 3 would become -0.1 kJ/mol"),
    (OSError(28, "No space left on device", "/dev/full"), 1, "error: timing: /dev/full: No space left on device"),
    (KeyboardInterrupt(), 130, "error: timing: interrupted"),
])
def test_a_failure_during_the_run_ends_in_one_line(failure, status, message, monkeypatch, capsys):
    """A simulation that goes bad, an output that cannot be written, Ctrl-C: one line on stderr and a nonzero status,
    not a traceback."""
    import openmmgendpde.cli.timing as timing

    def fail(arguments):
        raise failure
    monkeypatch.setattr(timing, "run", fail)
    with pytest.raises(SystemExit) as exit_:
        main(["timing", "--quick"])
    code = exit_.value.code
    if isinstance(code, str):   # SystemExit(message): Python writes it to stderr and exits with status 1
        assert status == 1 and code == message
    else:
        assert code == status and capsys.readouterr().err.strip() == message


def test_a_script_failure_ends_in_one_line():
    """cli.one_line_errors (the examples): an OpenMMException nothing catches is one line on stderr, status 1."""
    import subprocess
    import sys
    result = subprocess.run([sys.executable, "-c", "import openmm\n"
                             "from openmmgendpde.cli.options import one_line_errors\n"
                             "one_line_errors('x.py')\nraise openmm.OpenMMException('the step was not applied')"],
                            capture_output=True, text=True, timeout=60)
    assert result.returncode == 1 and result.stderr == "error: x.py: the step was not applied\n"


@pytest.mark.parametrize("extra, option", [(["--fluid", "argon"], "--fluid argon"),
                                           (["--fluid", "water"], "--fluid water"),
                                           (["--neighbors", "30"], "--neighbors 30.0"),
                                           (["--molecules-per-particle", "2"], "--molecules-per-particle 2.0")])
def test_compression_refuses_the_options_of_a_fluid_with_a_model(extra, option, tmp_path, monkeypatch):
    """`compression --model M --fluid F` (or the fluid's coarse-graining): a one-line error, status 1, before anything
    runs (issue 54: --fluid was ignored and the model's fluid compressed, status 0), even where --fluid names the
    default fluid. --model alone compresses exactly the model file's parameters (the study's arguments checked here:
    the study itself is replaced)."""
    from openmmgendpde.models.fluid import ARGON, coarse_grain
    from openmmgendpde.models.fluid_files import load_parameters, save_parameters
    from openmmgendpde.studies import compression
    path = str(tmp_path / "model.toml")
    save_parameters(coarse_grain(ARGON, 5, neighbors=20), path)
    monkeypatch.setattr(openmm, "Context", lambda *a, **k: pytest.fail("a simulation started"))
    with pytest.raises(SystemExit) as exit_:
        main(["compression", "--quick", "--model", path] + extra)
    assert str(exit_.value) == (f"error: compression: {option} is not allowed with --model {path}: a model file holds "
                                f"its fluid and every parameter; give one of --model and --fluid")
    compressed = []
    monkeypatch.setattr(compression, "compress", lambda parameters, *arguments, **keywords: compressed.append(
        parameters) or pytest.fail("compressed"))
    with pytest.raises(pytest.fail.Exception):
        main(["compression", "--quick", "--model", path])
    assert compressed == [load_parameters(path)]
