# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""What the subcommands write: table3's frames as one complete set that rdf reads, calibrate's outputs each on its
own, the fluid every command takes, and the one line on the error bars."""


import openmm
import pytest

from openmmgendpde.__main__ import main

# The quick sizes run in seconds, too short for the error bars to reach their plateau: every study would warn
# (BlockAverageWarning). The warning itself is tested in test_statistics.py.
pytestmark = pytest.mark.filterwarnings("ignore::openmmgendpde.analysis.statistics.BlockAverageWarning")

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
