"""Every subcommand of `python3 -m openmmgendpde` end to end at its quick size."""

import csv
import json
import math
import re

import openmm
import pytest
from openmm import unit

from openmmgendpde.__main__ import main
from openmmgendpde.models.argon import ARGON_STATE, ARGON_UNITS

# The quick sizes run in seconds, too short for the error bars to reach their plateau: every study would warn
# (BlockAverageWarning). The warning itself is tested in test_statistics.py.
pytestmark = pytest.mark.filterwarnings("ignore::openmmgendpde.analysis.statistics.BlockAverageWarning")


@pytest.fixture(scope="module")
def table3_output(tmp_path_factory):
    directory = tmp_path_factory.mktemp("table3")
    cells = main(["table3", "--quick", "--output", str(directory)])
    return directory, cells


@pytest.mark.validation
def test_table3_quick(table3_output, capsys):
    directory, _ = table3_output
    rows = list(csv.DictReader(open(directory / "table3.csv")))
    assert len(rows) == 3 * 2 * 4
    assert {row["estimator"] for row in rows} == {"VA", "VB"}
    for row in rows:
        assert float(row["standard error"]) > 0 and abs(float(row["difference"])) < 0.05
    for cutoff in ("1.3365", "1.6839", "2.1564"):
        assert (directory / f"frames-R{cutoff}-VA.npz").exists()
    # Published values as the paper prints them, significant zeros included.
    published = {(row["R_cut*"], row["estimator"], row["quantity"]): row["published"] for row in rows}
    assert published["2.1564", "VA", "n-bar*"] == "0.870" and published["2.1564", "VB", "n-bar*"] == "1.000"
    assert published["2.1564", "VA", "T* (kinetic)"] == "0.0111" and published["1.3365", "VA", "P*"] == "0.008"


@pytest.mark.validation
def test_rdf_from_table3_frames(table3_output, capsys):
    directory, _ = table3_output
    main(["rdf", "--quick", "--frames-from", str(directory), "--output", str(directory)])
    out = capsys.readouterr().out
    assert "first peak" in out
    assert (directory / "fig1-rdf.png").stat().st_size > 10000 and (directory / "fig1-rdf.pdf").exists()
    rows = list(csv.reader(open(directory / "fig1-rdf.csv")))
    assert len(rows[0]) == 7 and len(rows) > 100
    # Far from the origin g(r) -> 1 for every case.
    tail = [[float(x) for x in row[1:]] for row in rows[-20:]]
    assert all(abs(sum(column) / len(column) - 1) < 0.1 for column in zip(*tail))


def test_timing_quick(capsys):
    main(["timing", "--quick", "--cutoffs", "1.3365", "--rounds", "3"])
    out = capsys.readouterr().out
    assert "| 1.3365 |" in out and "1.07" in out   # the published ratio (Table IV), written out


def test_progress_goes_to_stderr_only_and_only_when_asked(capsys):
    main(["timing", "--quick", "--cutoffs", "1.3365", "--rounds", "2", "--progress"])
    captured = capsys.readouterr()
    assert "timing R*=1.3365" in captured.err and "100.0%" in captured.err and "remaining" in captured.err
    assert "remaining" not in captured.out and "| 1.3365 |" in captured.out
    main(["timing", "--quick", "--cutoffs", "1.3365", "--rounds", "2"])
    assert "remaining" not in capsys.readouterr().err   # stderr is not a terminal here: silent without --progress


@pytest.mark.validation
def test_tune_fcut_quick(capsys):
    main(["tune-fcut", "--quick", "--cutoff", "1.3365", "--max-iterations", "2"])
    out = capsys.readouterr().out
    assert "f_cut =" in out and "published f_cut = 1.41" in out   # the paper's value, written out


@pytest.mark.validation
def test_speed_vs_error_quick(tmp_path, capsys):
    main(["speed-vs-error", "--quick", "--steps", "0.02", "0.01", "--production", "10", "--output", str(tmp_path)])
    rows = list(csv.DictReader(open(tmp_path / "speed-vs-error.csv")))
    assert len(rows) == 4 and (tmp_path / "speed-vs-error.png").exists()
    assert all(float(row["wall s per time unit"]) > 0 for row in rows)


@pytest.mark.validation
def test_slab_quick(tmp_path, capsys):
    """`slab --quick` for one estimator without the oracle (3 s): every sample and the second-half summary printed,
    and the CSV holds the run's rows with finite densities and surface tensions (the pressure tensor of the force's
    own virial tensors)."""
    main(["slab", "--quick", "--estimators", "VC", "--no-oracle", "--output", str(tmp_path)])
    out = capsys.readouterr().out
    assert "VC: slab of 600 particles, 10 time units" in out and "VC: over the second half (2 samples)" in out
    rows = [line.split(",") for line in (tmp_path / "slab.csv").read_text().splitlines()[1:]]
    assert [row[0] for row in rows] == ["VC"] * 3
    assert all(math.isfinite(float(row[2])) and math.isfinite(float(row[5])) for row in rows)


@pytest.mark.validation
def test_compression_quick(tmp_path, capsys):
    """`compression --quick` of water as mapped (with its background pressure, 500 particles, c = -+3%): a row per
    box, the response and both bulk moduli, the JSON record. The response is expected ~0.9 (2048 particles, -+5%:
    0.85; docs/theory.md section 12) and ~0.25 without p_b (docs/fluids.md, 500 particles); required > 0.5, which
    the model under tension does not reach. Not near freezing: Q6 < 0.1 (a crystal: 0.575)."""
    path = tmp_path / "compression.json"
    main(["compression", "--fluid", "water", "--quick", "--compressions=-0.03,0.03", "--json", str(path)])
    out = capsys.readouterr().out
    assert "| -0.030 |" in out and "| +0.030 |" in out and "n k_B T/S(k -> 0)" in out
    record = json.loads(path.read_text())
    assert record["model"]["background_pressure"] > 0 and len(record["points"]) == 2
    assert record["response"]["value"] > 0.5, record["response"]
    assert record["bulk_modulus"]["value"] > 0 and math.isfinite(record["structure_modulus"]["value"])
    assert all(point["global_q6"] < 0.1 and point["diffusion"]["value"] > 0 for point in record["points"])


@pytest.mark.validation
def test_benchmarks_quick(capsys):
    main(["benchmark-force", "--particles", "500", "--cutoffs", "1.3365", "--rounds", "2"])
    main(["benchmark-integrator", "--particles", "500", "--rounds", "2"])
    out = capsys.readouterr().out
    assert "CustomGB" in out and "Isoenergetic / force" in out
    dpd_rows = [line for line in out.splitlines() if line.startswith("| 500 | with GenDPDEForce")
                or line.startswith("| 500 | no force")]
    assert len(dpd_rows) == 2   # GenDPDE Isothermal against DPDIntegrator, with and without the force
    for row in dpd_rows:
        cells = [cell.strip() for cell in row.strip("|").split("|")]
        assert float(cells[2]) > 0 and float(cells[3]) > 0 and float(cells[4]) > 0
        # Kinetic temperatures of both thermostats within 10% of the bath (T0 = 125.7 K) after 200 steps of 500
        # particles (their fluctuation is ~2% per sample; the point here is that both are reported and sane).
        bath = ARGON_UNITS.to_openmm(ARGON_STATE.temperature, "temperature").value_in_unit(unit.kelvin)
        for cell in cells[6:8]:
            assert abs(float(cell.split("+-")[0]) / bath - 1) < 0.1


@pytest.fixture
def cpu_threads_default():
    """The CPU platform's default Threads, restored after a test whose --threads changes it (process-wide)."""
    platform = openmm.Platform.getPlatformByName("CPU")
    original = platform.getPropertyDefaultValue("Threads")
    yield
    platform.setPropertyDefaultValue("Threads", original)


def test_benchmark_cpu_quick(tmp_path, capsys):
    path = tmp_path / "cpu.json"
    main(["benchmark-cpu", "--particles", "500", "--rounds", "2", "--json", str(path)])
    out = capsys.readouterr().out
    for label in ("| 500 | CPU, 1 thread |", "| 500 | CPU, 2 threads |", "| 500 | Reference |"):
        assert label in out
    (result,) = json.loads(path.read_text())
    assert result["thread_counts"] == [1, 2]
    assert result["force_speedup"]["1"] == 1.0 and result["step_speedup"]["1"] == 1.0   # the baseline itself
    assert all(value > 0 for value in result["milliseconds"].values())
    # A Context holds at least its positions, velocities and forces (72 bytes per particle) and its neighbour rows.
    assert result["memory_bytes_per_particle"] > 72


def test_threads_sets_the_cpu_platform_and_is_reported(tmp_path, cpu_threads_default):
    path = tmp_path / "force.json"
    main(["benchmark-force", "--particles", "500", "--cutoffs", "1.3365", "--rounds", "1", "--platform", "CPU",
          "--threads", "1", "--json", str(path)])
    (result,) = json.loads(path.read_text())
    assert result["platform"] == "CPU" and result["threads"] == 1


@pytest.mark.parametrize("arguments, message", [
    (["--platform", "Reference", "--threads", "2"], "--threads = 2 applies to the CPU platform only"),
    (["--platform", "CPU", "--threads", "0"], "argument --threads: 0 is not allowed; it must be an integer from 1 to "
                                              "1024"),
    (["--platform", "CPU", "--precision", "mixed"],
     "--precision = mixed applies to the OpenCL and CUDA platforms only"),
])
def test_bad_threads_are_refused(arguments, message, capsys, cpu_threads_default):
    with pytest.raises(SystemExit):
        main(["benchmark-force", "--particles", "500"] + arguments)
    assert message in capsys.readouterr().err


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


def test_help_lists_every_subcommand(capsys):
    with pytest.raises(SystemExit):
        main(["--help"])
    out = capsys.readouterr().out
    for name in ("table3", "rdf", "timing", "tune-fcut", "speed-vs-error", "benchmark-force", "benchmark-integrator",
                 "benchmark-cpu", "compression"):
        assert name in out


@pytest.mark.parametrize("name", ["slab", "tune-fcut"])
def test_help_names_the_estimators_a_subcommand_runs(name, capsys):
    """The top-level help's line for a subcommand that names estimators names every choice of its --estimator(s)
    option (as that subcommand's own help lists them)."""
    with pytest.raises(SystemExit):
        main([name, "--help"])
    choices = re.search(r"--estimators? \{([A-Z,]+)\}", capsys.readouterr().out).group(1).split(",")
    with pytest.raises(SystemExit):
        main(["--help"])
    summary = re.search(rf"\n    {name} +(.*?)\n    \S", capsys.readouterr().out, re.S).group(1)
    assert len(choices) >= 2 and all(re.search(rf"\b{choice}\b", summary) for choice in choices), (choices, summary)


def test_platform_help_states_the_default_in_use():
    """Each subcommand's --platform help names the default its parser really uses (slab's is CPU, not Reference)."""
    import argparse

    from openmmgendpde.__main__ import SUBCOMMANDS
    checked = 0
    for name, module, _ in SUBCOMMANDS:
        parser = argparse.ArgumentParser()
        module.add_arguments(parser)
        for action in parser._actions:
            if "--platform" in action.option_strings:
                default = parser.get_default("platform")
                assert f"(default {default})" in action.help, (name, default, action.help)
                checked += 1
    # all but benchmark-cpu, which runs CPU and Reference side by side, and lammps-input, which runs nothing
    assert checked == len(SUBCOMMANDS) - 2


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


def _fake_argon_runs(monkeypatch, interrupt_at=None):
    """table3's runs replaced by made-up samples (seconds, not minutes): frames of 500 particles that differ from
    call to call; the run number ``interrupt_at`` (from 1) raises KeyboardInterrupt, as Ctrl-C would."""
    import numpy as np

    import openmmgendpde.studies.table3 as table3
    from openmmgendpde.models.argon_runs import ArgonRun, Samples
    calls = []

    def run_argon(cutoff, estimator, protocol, platform, frames=0, progress=None, **options):
        calls.append((cutoff, estimator))
        if len(calls) == interrupt_at:
            raise KeyboardInterrupt
        rng = np.random.default_rng(len(calls) + 100 * (interrupt_at or 0))
        samples = Samples(box_edge=3.0, frames=[rng.uniform(0, 3, (500, 3)) for _ in range(frames)])
        for name in ("kinetic_temperature", "harmonic_temperature", "density", "pressure"):
            setattr(samples, name, list(1 + 0.01 * rng.standard_normal(40)))
        return ArgonRun(samples, None, None)
    monkeypatch.setattr(table3, "run_argon", run_argon)
    return calls


def _files(directory):
    return {path.name: path.read_bytes() for path in directory.iterdir()}


def test_an_interrupted_table3_leaves_the_previous_frames_complete(tmp_path, monkeypatch, capsys):
    """Ctrl-C during table3 --output D: one line, status 130, and D as the last complete run left it (its frames and
    their manifest), nothing of the interrupted run; rdf's reader takes it."""
    from openmmgendpde.studies.table3 import FRAMES_MANIFEST, read_frames
    _fake_argon_runs(monkeypatch)
    main(["table3", "--quick", "--output", str(tmp_path)])
    before = _files(tmp_path)
    assert FRAMES_MANIFEST in before and len([name for name in before if name.endswith(".npz")]) == 6
    _fake_argon_runs(monkeypatch, interrupt_at=5)
    with pytest.raises(SystemExit) as exit_:
        main(["table3", "--quick", "--output", str(tmp_path)])
    assert exit_.value.code == 130 and capsys.readouterr().err.strip() == "error: table3: interrupted"
    assert _files(tmp_path) == before
    cases = [(cutoff, estimator) for cutoff in (1.3365, 1.6839, 2.1564) for estimator in ("VA", "VB")]
    assert sorted(read_frames(tmp_path, cases)) == sorted(cases)


@pytest.mark.parametrize("damage, message", [
    ("no manifest", "holds no complete set of table3 frames"),
    ("a file replaced", "is not the file table3 wrote"),
    ("a file missing", "frames-R2.1564-VB.npz is missing"),
    ("fewer cutoffs", "has no frames of R_cut* = 1.6839 VA"),
])
def test_rdf_refuses_an_incomplete_or_foreign_frame_directory_in_one_line(damage, message, tmp_path, monkeypatch):
    """rdf --frames-from D reads a complete set only (table3's manifest, every case, each file as table3 wrote it):
    else one line (status 1) before anything runs."""
    import numpy as np

    from openmmgendpde.studies.table3 import FRAMES_MANIFEST
    _fake_argon_runs(monkeypatch)
    main(["table3", "--quick", "--output", str(tmp_path)] + (["--cutoffs", "1.3365"] if damage == "fewer cutoffs"
                                                               else []))
    if damage == "no manifest":   # the 4 of 6 frame files an interrupted table3 used to leave
        (tmp_path / FRAMES_MANIFEST).unlink()
        for path in sorted(tmp_path.glob("*.npz"))[4:]:
            path.unlink()
    elif damage == "a file replaced":
        np.savez_compressed(tmp_path / "frames-R1.6839-VA.npz", positions=np.zeros((2, 500, 3)), box_edge=3.0)
    elif damage == "a file missing":
        (tmp_path / "frames-R2.1564-VB.npz").unlink()
    monkeypatch.setattr(openmm, "Context", lambda *a, **k: pytest.fail("a simulation started"))
    with pytest.raises(SystemExit) as exit_:
        main(["rdf", "--quick", "--frames-from", str(tmp_path), "--output", str(tmp_path / "rdf")])
    assert str(exit_.value).startswith(f"error: rdf: --frames-from {tmp_path}") and message in str(exit_.value)
    assert "\n" not in str(exit_.value) and not (tmp_path / "rdf" / "fig1-rdf.csv").exists()


def _fake_water_calibration(monkeypatch):
    from helpers import fake_calibration

    from openmmgendpde.models.fluid import WATER, coarse_grain
    fake_calibration(monkeypatch, coarse_grain(WATER, 4, neighbors=20))


def test_calibrate_writes_every_output_it_can_and_reports_the_one_it_cannot(tmp_path, monkeypatch, capsys):
    """calibrate --json /dev/full (a write that fails after the run): the model (--output) is still written, and the
    failure is one line (status 1) naming the option and the reason."""
    from openmmgendpde.models.fluid_files import load_parameters
    _fake_water_calibration(monkeypatch)
    model = tmp_path / "model.toml"
    with pytest.raises(SystemExit) as exit_:
        main(["calibrate", "--quick", "--fluid", "water", "--output", str(model), "--json", "/dev/full"])
    assert exit_.value.code == ("error: calibrate: --json /dev/full could not be written (/dev/full: No space left on "
                                "device); the other outputs were written")
    assert load_parameters(str(model)).fluid.name.startswith("liquid water")
    assert [path.name for path in tmp_path.iterdir()] == ["model.toml"]   # no temporary file left


def test_a_simulation_failure_in_calibrate_names_its_stage(monkeypatch):
    """An OpenMMException in a stage of calibrate (a negative internal energy in the bulk-modulus runs, as argon at
    4 atoms per particle gave): one line (status 1) naming the stage, the error and the options that set the step and
    the heat capacity."""
    from openmmgendpde.calibration.calibration import Calibration
    _fake_water_calibration(monkeypatch)

    def bulk_modulus(self):
        raise openmm.OpenMMException("GenDPDEIntegrator: the internal energy of particle 39 would become -0.36 kJ/mol "
                                     "(<= 0) at step 3076; the step was not applied.")
    monkeypatch.setattr(Calibration, "bulk_modulus", bulk_modulus)
    with pytest.raises(SystemExit) as exit_:
        main(["calibrate", "--quick", "--fluid", "water"])
    assert exit_.value.code == ("error: calibrate: the stage 'Bulk modulus: B_T iterated on n dP/dn' failed: "
                                "GenDPDEIntegrator: the internal energy of particle 39 would become -0.36 kJ/mol "
                                "(<= 0) at step 3076; the step was not applied. (dt* = 0.01: --time-step; heat "
                                "capacity: --molecules-per-particle)")


@pytest.mark.parametrize("fluid, molecules", [("water", 4), ("argon", 5), ("argon-expanding", 5),
                                              ("supercritical-argon", 7)])
def test_calibrates_default_coarse_graining_leaves_the_particles_heat_capacity(fluid, molecules, monkeypatch, capsys):
    """calibrate's default molecules per particle: 4, or more where the molecules hold little heat, so that C_V
    stays >= 9 k_B once c_v is matched (calibrate.MIN_DEFAULT_INTERNAL_HEAT_CAPACITY; argon at 4 stopped on a
    negative internal energy at dt* = 0.01). The mapped C_V minus the 5/2 k_B of the motion and the Gamma law is at
    least 9 k_B."""
    from openmmgendpde.models.fluid import KB, coarse_grain, default_molecules_per_particle
    from openmmgendpde.models.fluid_files import FLUIDS
    assert default_molecules_per_particle(FLUIDS[fluid]) == molecules
    parameters = coarse_grain(FLUIDS[fluid], molecules, neighbors=20)
    assert parameters.heat_capacity / KB - 2.5 >= 9.0
    assert coarse_grain(FLUIDS[fluid], molecules - 1, neighbors=20).heat_capacity / KB - 2.5 < 9.0 or molecules == 4
    _fake_water_calibration(monkeypatch)
    main(["calibrate", "--quick", "--fluid", fluid])
    assert f": {molecules} molecules per particle, 20.0 neighbours" in capsys.readouterr().out


def test_thermal_expansion_takes_a_fluid_as_every_command_does(capsys):
    """--fluid NAME|FILE as calibrate takes it: a fluid file with a thermal expansion is mapped at 20 neighbours and 5
    molecules per particle (the command's defaults), the built-in argon-expanding at the paper's R* = 1.6839; the
    names it took before (liquid, supercritical) still work, with a warning naming the new one."""
    import argparse
    import os

    from openmmgendpde.calibration.expansion import mapped
    from openmmgendpde.cli.thermal_expansion import fluid_of
    from openmmgendpde.models.fluid import ARGON_EXPANDING, SUPERCRITICAL_ARGON

    def given(fluid, **options):
        return argparse.Namespace(**{"fluid": fluid, "molecules_per_particle": None, "neighbors": None,
                                     "cutoff": None, **options})

    nitrogen = os.path.join(os.path.dirname(__file__), "..", "..", "examples", "fluids", "nitrogen-expanding.toml")
    fluid, parameters = fluid_of(given(nitrogen))
    assert "nitrogen" in fluid.name and parameters.thermal_pressure is not None
    assert parameters.neighbors == pytest.approx(20.0, rel=1e-12) and parameters.molecules_per_particle == 5
    assert fluid_of(given(nitrogen, neighbors=30.0))[1].neighbors == pytest.approx(30.0, rel=1e-12)
    assert fluid_of(given("argon-expanding"))[1] == mapped(ARGON_EXPANDING)
    capsys.readouterr()
    assert fluid_of(given("liquid"))[1] == mapped(ARGON_EXPANDING)
    assert fluid_of(given("supercritical"))[1] == mapped(SUPERCRITICAL_ARGON)
    warnings = capsys.readouterr().err.splitlines()
    assert warnings == ["warning: thermal-expansion: --fluid liquid is now --fluid argon-expanding (the old name is "
                        "removed in version 0.3)",
                        "warning: thermal-expansion: --fluid supercritical is now --fluid supercritical-argon (the "
                        "old name is removed in version 0.3)"]


def test_table3_says_in_one_line_how_many_error_bars_are_too_small():
    """The main job's output is its table and one line about sampling: the block averages that had not reached their
    plateau are counted there (named with --verbose), not printed as warnings before the table."""
    import warnings

    from openmmgendpde.analysis.statistics import BlockAverageWarning
    from openmmgendpde.studies.table3 import sampling_summary
    text = "R_cut* = 1.3365 VA P*: the block-average error has not reached its plateau: blocks of 6 samples"
    unsettled = [warnings.WarningMessage(BlockAverageWarning(text), BlockAverageWarning, "table3.py", 1)] * 2
    assert sampling_summary([], 24) == "Sampling: every one of the 24 error bars reached its block-average plateau."
    line = sampling_summary(unsettled, 24)
    assert "\n" not in line and line.startswith("Sampling: 2 of the 24 error bars had not reached their block-average "
                                                "plateau, so they are too small")
    assert sampling_summary(unsettled, 24, verbose=True).splitlines()[1:] == [f"  {text}", f"  {text}"]
