# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
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
