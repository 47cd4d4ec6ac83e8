# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""The slab of any fluid (openmmgendpde.studies.slab.fluid_slab) and the --fluid option of `slab` and `tune-fcut`
(docs/interfaces.md, "A slab of any fluid")."""

import argparse
import dataclasses
import os
import re
import subprocess
import sys

import numpy as np
import pytest
from openmm import unit

from openmmgendpde import GenDPDEForce, GenDPDEIntegrator
from openmmgendpde.__main__ import main
from openmmgendpde.cli import slab as slab_command
from openmmgendpde.models.fluid import ARGON, WATER, coarse_grain
from openmmgendpde.models.fluid_files import load_parameters, save_parameters
from openmmgendpde.studies import slab as slab_module
from openmmgendpde.studies.slab import SLAB_THERMOSTAT_TIME, fluid_slab, sample_run
from openmmgendpde.studies.surfaces import surface_tension_table

NM = unit.nanometer
WATER_FILE = os.path.join(os.path.dirname(__file__), "..", "..", "examples", "fluids", "water.toml")
ONE_THREAD = {"Threads": "1"}
#: dt* of a V-C water slab (4 molecules per particle, 20 neighbours): stability.suggest_time_step(parameters, 'VC'),
#: measured (0.5 x the Conservative limit 0.095 x V-C's stable_step_factor 0.1), written here to spare the 10 s of
#: measuring it.
WATER_VC_STEP = 0.0048


@pytest.fixture(scope="module")
def water():
    return coarse_grain(WATER, 4, neighbors=20)


def test_slab_at_the_cut_lies_in_its_region_with_the_stated_vacuum_and_the_fluids_model(water):
    """With no thermostatted stage the builder returns the slab as cut: every particle within [vacuum/2, vacuum/2 +
    thickness) along z (the melted liquid's box, its thickness n_z cells at n0), the box lengthened by exactly the
    vacuum, and a System whose particles, force and integrator are those of the fluid's model
    (parameters.liquid with the same cells): masses, cutoff, estimator, f_cut, Tait parameters, friction, heat
    conduction, C_V, T0; the integrator Isoenergetic with the internal energies drawn at T0."""
    cells = (3, 3, 4)
    vacuum = 2.5
    slab = fluid_slab(water, cells, "VC", vacuum=vacuum * NM, time_step=WATER_VC_STEP, melt_time=2.0,
                      thermostat_time=0.0, properties=ONE_THREAD, seed=3)
    reference = water.liquid(cells=cells, estimator="VC")
    edges = [reference.system.getDefaultPeriodicBoxVectors()[k][k].value_in_unit(NM) for k in range(3)]
    assert slab.thickness == pytest.approx(edges[2])
    assert slab.vacuum == pytest.approx(vacuum)
    box = slab.context.getState().getPeriodicBoxVectors()
    assert [box[k][k].value_in_unit(NM) for k in range(3)] == pytest.approx([edges[0], edges[1], edges[2] + vacuum])
    assert slab.system.getDefaultPeriodicBoxVectors()[2][2].value_in_unit(NM) == pytest.approx(edges[2] + vacuum)
    z = slab.context.getState(getPositions=True).getPositions(asNumpy=True).value_in_unit(NM)[:, 2]
    z = z - np.floor(z / (edges[2] + vacuum)) * (edges[2] + vacuum)
    assert z.min() >= vacuum / 2 - 1e-9 and z.max() < vacuum / 2 + edges[2]
    # Nothing in the vacuum: the faces' gap across the boundary is at least the vacuum.
    assert z.min() + (edges[2] + vacuum - z.max()) >= vacuum - 1e-9
    system = slab.system
    assert system.getNumParticles() == reference.num_particles == 4 * np.prod(cells)
    assert slab.topology.getNumAtoms() == reference.topology.getNumAtoms()
    assert [system.getParticleMass(i) for i in range(system.getNumParticles())] == [
        reference.system.getParticleMass(i) for i in range(reference.num_particles)]
    assert system.getParticleMass(0).value_in_unit(unit.amu) == pytest.approx(water.mass)
    assert system.getNumForces() == reference.system.getNumForces() == 1
    force, expected = GenDPDEForce.cast(system.getForce(0)), reference.force
    assert force.getDensityEstimator() == expected.getDensityEstimator() == GenDPDEForce.VC
    assert force.getCutoffDistance() == expected.getCutoffDistance()
    assert force.getCutoffScaling() == expected.getCutoffScaling()
    assert [str(x) for x in force.getTaitParameters()] == [str(x) for x in expected.getTaitParameters()]
    integrator, other = slab.model.integrator, reference.integrator
    for getter in ("getFriction", "getHeatConduction", "getHeatCapacity", "getTemperature"):
        assert getattr(integrator, getter)() == getattr(other, getter)(), getter
    assert integrator.getMode() == GenDPDEIntegrator.Isoenergetic
    assert min(integrator.getInternalEnergies().value_in_unit(unit.kilojoule_per_mole)) > 0
    # The default vacuum is twice the slab's thickness; one thinner than twice the cutoff is refused.
    assert fluid_slab(water, cells, "VC", time_step=WATER_VC_STEP, melt_time=0.1, thermostat_time=0.0,
                      properties=ONE_THREAD).vacuum == pytest.approx(2 * edges[2])
    with pytest.raises(ValueError, match="twice the cutoff"):
        fluid_slab(water, cells, "VC", vacuum=1.9 * water.cutoff, time_step=WATER_VC_STEP, properties=ONE_THREAD)


def _temperatures(water, thermostat_time):
    """(mean kinetic, mean harmonic internal temperature) in K of a 600-particle V-C water slab over 10 time units
    of isoenergetic GenDPDE after fluid_slab (20 time units of melt, ``thermostat_time`` thermostatted), sampled
    every time unit."""
    slab = fluid_slab(water, (5, 5, 6), "VC", time_step=WATER_VC_STEP, thermostat_time=thermostat_time,
                      properties=ONE_THREAD, seed=5)
    samples = sample_run(slab.model, slab.context, slab.thickness, 10.0, 1.0, water.units)[1:]
    return (np.mean([s.kinetic_temperature for s in samples]), np.mean([s.harmonic_temperature for s in samples]))


@pytest.mark.validation
def test_thermostatted_vc_water_slab_stays_at_t0_where_the_unthermostatted_one_heats(water):
    """The heating that the thermostatted stage removes (docs/interfaces.md, "A slab of any fluid"): a V-C water slab
    cut from a melted liquid and started isoenergetic at once heats as its new surfaces relax (measured here, 600
    particles, seed 5: T_kin 334.7 K and T_harm 323.6 K over 10 time units, T0 = 298.15 K); thermostatted for
    SLAB_THERMOSTAT_TIME first, it stays at T0 (299.0 K and 299.0 K). Tolerance 6 K (2%) on both means: a kinetic
    temperature of 600 particles scatters by sqrt(2/(3N)) = 3.3% (10 K) per sample, and the 10 samples are
    correlated over ~1 time unit, so their mean is good to ~4 K; the harmonic mean of theta_i (C_V = 36 k_B per
    particle) to ~2 K. The unthermostatted slab must exceed T0 by 15 K in both (it exceeds it by 25-37 K)."""
    assert SLAB_THERMOSTAT_TIME > 0
    kinetic, harmonic = _temperatures(water, SLAB_THERMOSTAT_TIME)
    assert abs(kinetic - water.temperature) < 6 and abs(harmonic - water.temperature) < 6, (kinetic, harmonic)
    kinetic, harmonic = _temperatures(water, 0.0)
    assert kinetic - water.temperature > 15 and harmonic - water.temperature > 15, (kinetic, harmonic)


@pytest.mark.validation
def test_slab_command_runs_a_fluid_file(tmp_path, capsys):
    """`slab --fluid FILE` (examples/fluids/water.toml, --quick: 600 particles, 10 time units): the fluid named, the
    temperatures printed and written beside the argon columns."""
    main(["slab", "--fluid", WATER_FILE, "--quick", "--estimators", "VC", "--no-oracle", "--time-step",
          str(WATER_VC_STEP), "--melt-time", "5", "--output", str(tmp_path), "--threads", "1"])
    out = capsys.readouterr().out
    assert "VC: slab of 600 particles of liquid water, 298.15 K, 0.1 MPa (T0 = 298.15 K), dt* = 0.0048" in out
    assert f"thermostatted {SLAB_THERMOSTAT_TIME:g} time units after the cut" in out and "T_harm" in out
    lines = (tmp_path / "slab.csv").read_text().splitlines()
    assert lines[0].endswith("kinetic_temperature_K,harmonic_temperature_K") and len(lines) == 1 + 3
    assert all(abs(float(line.split(",")[-1]) - 298.15) < 15 for line in lines[1:])


@pytest.mark.parametrize("command", [["slab"], ["tune-fcut", "--quick"]])
@pytest.mark.parametrize("fluid, message", [
    ("mercury", "--fluid mercury is not allowed; give one of argon, argon-expanding, supercritical-argon, water or a "
                "fluid file"),
    ("missing.toml", "--fluid missing.toml: no such file"),
    ("BAD", "bad.toml: missing ['molar_mass']"),
])
def test_a_bad_fluid_is_refused_in_one_line_before_anything_runs(command, fluid, message, tmp_path, capsys):
    if fluid == "BAD":
        text = open(WATER_FILE).read().replace('molar_mass = "18.015 g/mol"', "")
        fluid = str(tmp_path / "bad.toml")
        open(fluid, "w").write(text)
    output = tmp_path / "out"
    with pytest.raises(SystemExit) as error:
        main(command + ["--fluid", fluid, "--output", str(output)] if command == ["slab"] else
             command + ["--fluid", fluid])
    text = str(error.value)
    assert text.startswith(f"error: {command[0]}: ") and message in text and "\n" not in text
    assert not output.exists() and capsys.readouterr().out == ""


def test_a_cutoff_too_long_for_the_slab_s_box_names_the_options_that_shorten_it(tmp_path):
    """The slab's box is fixed (--quick or not): a --fluid whose cutoff does not fit is refused naming --neighbors
    and --cutoff, not the Python API's cells, before anything runs."""
    output = tmp_path / "out"
    with pytest.raises(SystemExit) as error:
        main(["slab", "--quick", "--fluid", "water", "--neighbors", "1e4", "--output", str(output)])
    text = str(error.value)
    assert text.startswith("error: slab: --fluid water: the box ") and "is less than twice the cutoff" in text
    assert text.endswith("use fewer --neighbors (a smaller --cutoff)") and "cells" not in text
    assert not output.exists()


def test_a_bad_fluid_exits_with_status_1():
    result = subprocess.run([sys.executable, "-m", "openmmgendpde", "slab", "--fluid", "mercury"],
                            capture_output=True, text=True, timeout=60)
    assert result.returncode == 1 and result.stdout == ""
    assert result.stderr.strip().splitlines() == [
        "error: slab: --fluid mercury is not allowed; give one of argon, argon-expanding, supercritical-argon, water "
        "or a fluid file (.toml or .json, "
        "docs/fluids.md)"]


@pytest.mark.parametrize("option", [["--thermostat-time", "5"], ["--neighbors", "30"], ["--cutoff", "1.2"]])
def test_fluid_options_without_fluid_are_refused(option):
    message = f"^error: slab: {option[0]} applies to the slab of a --fluid or --model only$"
    with pytest.raises(SystemExit, match=message):
        main(["slab"] + option)


def _slab_arguments(argv):
    parser = argparse.ArgumentParser()
    slab_command.add_arguments(parser)
    return parser.parse_args(argv)


def test_fluid_coarse_graining_defaults_are_calibrates():
    """--fluid without the coarse-graining options is coarse-grained as calibrate does (4 molecules per particle,
    20 neighbours); each option given is used."""
    cells = (5, 5, 6)
    parameters = slab_command.fluid_parameters(_slab_arguments(["--fluid", "water"]), cells)
    assert parameters == coarse_grain(WATER, 4, neighbors=20)
    parameters = slab_command.fluid_parameters(_slab_arguments(["--fluid", "water", "--neighbors", "30",
                                                               "--molecules-per-particle", "3"]), cells)
    assert parameters == coarse_grain(WATER, 3, neighbors=30)
    parameters = slab_command.fluid_parameters(_slab_arguments(["--fluid", "water", "--cutoff", "1.1"]), cells)
    assert parameters == coarse_grain(WATER, 4, cutoff=1.1)


@pytest.fixture
def model_file(water, tmp_path):
    """A model file of water whose parameters no coarse-graining gives (f_cut and the friction changed, as a
    calibration changes them)."""
    path = str(tmp_path / "water-model.toml")
    save_parameters(dataclasses.replace(water, cutoff_scaling=1.2345, friction=1.1 * water.friction), path)
    return path


@pytest.mark.validation
def test_slab_command_runs_a_model_file(model_file, monkeypatch, tmp_path, capsys):
    """`slab --model FILE` (--quick: 600 particles, 10 time units): the slab is built from exactly the file's
    parameters (load_parameters; its System has the file's f_cut and friction), named in the output, and the
    surface tension over the second half is printed in mN/m beside water's 71.97 mN/m."""
    built = []

    def spy(parameters, *arguments, **options):
        built.append((parameters, fluid_slab(parameters, *arguments, **options)))
        return built[-1][1]

    monkeypatch.setattr(slab_module, "fluid_slab", spy)
    main(["slab", "--model", model_file, "--quick", "--estimators", "VC", "--no-oracle", "--time-step",
          str(WATER_VC_STEP), "--melt-time", "5", "--output", str(tmp_path), "--threads", "1"])
    out = capsys.readouterr().out
    expected = load_parameters(model_file)
    assert len(built) == 1 and built[0][0] == expected
    slab = built[0][1]
    assert GenDPDEForce.cast(slab.system.getForce(0)).getCutoffScaling() == expected.cutoff_scaling == 1.2345
    assert slab.model.integrator.getFriction().value_in_unit(unit.amu / unit.picosecond) == pytest.approx(
        expected.friction, rel=1e-12)
    assert (f"VC: slab of 600 particles of liquid water, 298.15 K, 0.1 MPa (the model in {model_file}; "
            f"T0 = 298.15 K), dt* = 0.0048") in out
    assert re.search(r"^\| VC \| 71\.97 \| [0-9.e+-]+ ", out, re.MULTILINE), out


def test_slab_model_is_the_files_parameters(model_file):
    assert slab_command.fluid_parameters(_slab_arguments(["--model", model_file]), (5, 5, 6)) == load_parameters(
        model_file)


@pytest.mark.parametrize("options, message", [
    (["--fluid", "water"], "--fluid and --model exclude each other"),
    (["--molecules-per-particle", "4"], "--molecules-per-particle applies to --fluid only"),
    (["--neighbors", "20"], "--neighbors applies to --fluid only"),
    (["--cutoff", "1.0"], "--cutoff applies to --fluid only"),
])
def test_model_and_fluid_options_are_refused_in_one_line(options, message, model_file, tmp_path, capsys):
    output = tmp_path / "out"
    with pytest.raises(SystemExit) as error:
        main(["slab", "--model", model_file, "--output", str(output)] + options)
    text = str(error.value)
    assert text.startswith("error: slab: ") and message in text and "\n" not in text
    assert not output.exists() and capsys.readouterr().out == ""


@pytest.mark.parametrize("kind, message", [
    ("missing", "--model {path}: no such file"),
    ("fluid file", "--model {path}: format = None is not a model file"),
    ("broken", "--model {path} [parameters]: missing ['cutoff']"),
    ("text", "--model {path} is not allowed; a model file ends in .toml or .json"),
    ("small", "--model {path}: the box"),
])
def test_a_missing_or_bad_model_file_is_refused_naming_it(kind, message, model_file, tmp_path, capsys):
    path = {"missing": str(tmp_path / "nowhere.toml"), "fluid file": WATER_FILE,
            "broken": str(tmp_path / "broken.toml"), "text": str(tmp_path / "model.txt"),
            "small": str(tmp_path / "small.toml")}[kind]
    text = open(model_file).read()
    if kind in ("broken", "text"):
        open(path, "w").write(text.replace("cutoff = ", "cut = ") if kind == "broken" else text)
    if kind == "small":   # a cutoff longer than half the slab's 5 cells across
        open(path, "w").write(re.sub(r"^cutoff = .*$", "cutoff = 2.0", text, flags=re.MULTILINE))
    output = tmp_path / "out"
    with pytest.raises(SystemExit) as error:
        main(["slab", "--model", path, "--output", str(output)])
    text = str(error.value)
    assert text.startswith("error: slab: ") and message.format(path=path) in text and "\n" not in text
    assert not output.exists() and capsys.readouterr().out == ""


def test_a_bad_model_exits_with_status_1(tmp_path):
    result = subprocess.run([sys.executable, "-m", "openmmgendpde", "slab", "--model", str(tmp_path / "none.toml")],
                            capture_output=True, text=True, timeout=60)
    assert result.returncode == 1 and result.stdout == ""
    assert result.stderr.strip().splitlines() == [f"error: slab: --model {tmp_path / 'none.toml'}: no such file"]


def _millinewton_per_metre(parameters):
    """The model's reduced unit of surface tension, energy/length^2 (energy L^3/kappa_T = L^3 gamma_T B_T per
    mole, L = n0^(-1/3)), in mN/m, written out in SI: kJ/mol -> J per particle, nm -> m."""
    length = parameters.density ** (-1 / 3)
    energy = length**3 * parameters.tait_exponent * parameters.bulk_modulus * 1e3 / 6.02214076e23
    return energy / (length * 1e-9) ** 2 * 1e3


def test_the_surface_tension_table_converts_to_millinewton_per_metre(water):
    """Made-up reduced tensions: the mean in mN/m (the reduced unit written out in SI here), an error, the target
    (water's 71.97 mN/m) and their ratio; a fluid without a surface tension has '-' for the target and the
    ratio; one sample has no error."""
    values = [0.05, 0.07, 0.06, 0.065, 0.055, 0.06]
    scale = _millinewton_per_metre(water)
    text = surface_tension_table({"VC": values, "VB": [0.05]}, water)
    lines = text.splitlines()
    assert "liquid-vapour surface tension of liquid water, 298.15 K, 0.1 MPa" in lines[0]
    assert lines[1] == "| estimator | target (mN/m) | slab (mN/m) | slab/target | independent samples |"
    cells = [cell.strip() for cell in lines[3].strip("|").split("|")]
    assert cells[0] == "VC" and cells[1] == "71.97"
    mean, error = (float(x) for x in cells[2].split(" +- "))
    assert mean == pytest.approx(np.mean(values) * scale, rel=1e-3) and 0 < error < 0.2 * mean
    assert float(cells[3]) == pytest.approx(np.mean(values) * scale / 71.97, abs=1e-3)
    assert cells[4].endswith("of 6")
    assert lines[4].startswith(f"| VB | 71.97 | {0.05 * scale:.4g} (one sample: no error) |")
    argon = coarse_grain(ARGON, 5, neighbors=20)
    lines = surface_tension_table({"VC": values}, argon).splitlines()
    assert "(not given" in lines[0]
    cells = [cell.strip() for cell in lines[3].strip("|").split("|")]
    assert cells[1] == "-" and cells[3] == "-"
    assert float(cells[2].split(" +- ")[0]) == pytest.approx(np.mean(values) * _millinewton_per_metre(argon),
                                                             rel=1e-3)


def test_tune_fcut_tunes_a_fluid_file(capsys):
    """`tune-fcut --fluid FILE --estimator VC` runs calibrate's tuning for the fluid (one iteration of its QUICK
    plan, 256 particles) and prints the f_cut it found."""
    main(["tune-fcut", "--fluid", WATER_FILE, "--estimator", "VC", "--quick", "--particles", "256",
          "--max-iterations", "1", "--platform", "CPU", "--threads", "1"])
    out = capsys.readouterr().out
    assert "liquid water, 298.15 K, 0.1 MPa: 4 molecules per particle, 20.0 neighbours" in out
    assert "f_cut iteration 1: n-bar = " in out and "f_cut of VC = " in out
