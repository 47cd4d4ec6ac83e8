# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""`lammps-input`: a model file as input for the LAMMPS plugin. The files are read back and compared with the OpenMM
model that the project builds (positions, box, masses, velocities) and with the model file's parameters converted by
hand, with the CODATA constants written here (not taken from the code under test)."""

import math
import os
import pathlib
import subprocess
from decimal import Decimal

import numpy as np
import pytest
from openmm import unit

from openmmgendpde import GenDPDEForce
from openmmgendpde.__main__ import main
from openmmgendpde.analysis.pressure import virial_tensor
from openmmgendpde.gendpde import sweepCandidateRange
from openmmgendpde.models.fluid import ARGON_EXPANDING, coarse_grain
from openmmgendpde.models.fluid_files import load_parameters, save_parameters
from openmmgendpde.models.lammps_files import lammps_input, round_up, sweep_cells, thermo_table

FIGURES = pathlib.Path(__file__).resolve().parents[2] / "docs" / "figures"
ARGON_FILE = str(FIGURES / "calibrated-argon-model.toml")
WATER_FILE = str(FIGURES / "calibrated-water-model.toml")

#: 1 kJ/mol in eV, from the exact CODATA 2018 e and N_A: 1000 J / (N_A e).
EV_PER_KJ_PER_MOL = 1000 / (1.602176634e-19 * 6.02214076e23)
ANGSTROM_PER_NM = 10.0
#: kJ/mol/nm^3 in eV/Å^3: the energy factor over 1000 Å^3 per nm^3.
PRESSURE = EV_PER_KJ_PER_MOL / 1000
#: 1 kcal/mol in kJ/mol (thermochemical), and OpenMM's k_B in kJ/mol/K (exact SI k_B and N_A).
KCAL = 4.184
KB = 1.380649e-23 * 6.02214076e23 / 1000


def read_data(path):
    """A LAMMPS data file (atom_style atomic): {'atoms': N, 'types': K, 'box': [(lo, hi)] * 3, 'Masses': {type: m},
    'Atoms': [(id, type, x, y, z)], 'Velocities': [(id, vx, vy, vz)]}."""
    lines = pathlib.Path(path).read_text().splitlines()[1:]   # (the first line is a title)
    data, section = {"box": []}, None
    for line in lines:
        words = line.split("#")[0].split()
        if not words:
            continue
        if words[0] in ("Masses", "Atoms", "Velocities"):
            section = words[0]
            data[section] = []
        elif section is not None:
            data[section].append(tuple(int(w) if k < (2 if section == "Atoms" else 1) else float(w)
                                       for k, w in enumerate(words)))
        elif words[1:] == ["atoms"]:
            data["atoms"] = int(words[0])
        elif words[1:] == ["atom", "types"]:
            data["types"] = int(words[0])
        elif len(words) == 4 and words[2].endswith("lo"):
            data["box"].append((float(words[0]), float(words[1])))
    data["Masses"] = {int(row[0]): row[1] for row in data["Masses"]}
    return data


def read_script(path):
    """A LAMMPS input script as commands (lists of words): comments removed, '&' continuations joined, ${name} of
    the index variables substituted (the first definition wins, as in LAMMPS; undefined ones are left)."""
    commands, pending, variables = [], "", {}
    for line in pathlib.Path(path).read_text().splitlines():
        line = pending + line.split("#")[0].rstrip()
        if line.endswith("&"):
            pending = line[:-1] + " "
            continue
        pending = ""
        for name, value in variables.items():
            line = line.replace("${" + name + "}", value)
        words = line.split()
        if words[:1] == ["variable"] and words[2] == "index":
            variables.setdefault(words[1], words[3])
        if words:
            commands.append(words)
    return commands


def command(commands, name, *first):
    """The one command ``name`` whose first words are ``first``: its remaining words."""
    found = [c[1 + len(first):] for c in commands if c[0] == name and tuple(c[1:1 + len(first)]) == first]
    assert len(found) == 1, (name, first, found)
    return found[0]


def keywords(words):
    """The keyword arguments of a fix line: {keyword: [its numbers as texts]} (several for heat_capacity etc.)."""
    counts = {"heat_capacity": 2, "friction": 3, "conduction": 3, "temperature": 1, "initial": 1}
    result, k = {}, 0
    while k < len(words):
        result.setdefault(words[k], []).append(words[k + 1:k + 1 + counts[words[k]]])
        k += 1 + counts[words[k]]
    return result


def written(tmp_path, model_file, *options):
    main(["lammps-input", model_file, "--output", str(tmp_path), *options])
    return read_data(tmp_path / "gendpde.data"), read_script(tmp_path / "in.gendpde")


def test_the_data_file_is_the_openmm_model(tmp_path):
    """Atoms, box, masses, positions and velocities are those of the model that liquid() builds and Model.context
    starts (the seed's Maxwell-Boltzmann velocities), in Å and Å/ps, ids in OpenMM's order from 1."""
    data, _ = written(tmp_path, ARGON_FILE, "--particles", "500", "--seed", "7")
    parameters = load_parameters(ARGON_FILE)
    model = parameters.liquid(500)
    state = model.context("Reference", seed=7).getState(getVelocities=True)
    velocities = state.getVelocities(asNumpy=True).value_in_unit(unit.nanometer / unit.picosecond)
    edge = model.system.getDefaultPeriodicBoxVectors()[0][0].value_in_unit(unit.nanometer)
    assert data["atoms"] == 500 and data["types"] == 1
    assert data["box"] == [(0.0, ANGSTROM_PER_NM * edge)] * 3
    assert data["Masses"] == {1: parameters.mass}
    atoms = data["Atoms"]
    assert [row[0] for row in atoms] == list(range(1, 501)) and {row[1] for row in atoms} == {1}
    positions = np.array([row[2:] for row in atoms])
    assert np.all((positions >= 0) & (positions < ANGSTROM_PER_NM * edge))
    assert np.max(np.abs(positions - ANGSTROM_PER_NM * model.positions)) < 1e-12
    assert [row[0] for row in data["Velocities"]] == list(range(1, 501))
    written_velocities = np.array([row[1:] for row in data["Velocities"]])
    assert np.max(np.abs(written_velocities - ANGSTROM_PER_NM * velocities)) < 1e-12
    # Not zero, and at T0: sum m v^2 = 3 N k_B T within the draw's scatter (Å^2/ps^2 -> nm^2/ps^2: 1/100).
    kinetic = parameters.mass * np.sum(written_velocities**2) / 100
    assert kinetic / (3 * 500 * 0.00831446261815324 * parameters.temperature) == pytest.approx(1, abs=0.15)


def _expanding_model(tmp_path):
    path = str(tmp_path / "expanding.toml")
    save_parameters(coarse_grain(ARGON_EXPANDING, 5, neighbors=20), path)
    return path


@pytest.mark.parametrize("model_file", [ARGON_FILE, WATER_FILE, "expanding"])
def test_the_numbers_are_the_model_parameters_in_metal_units(model_file, tmp_path):
    """pair_style, pair_coeff, the fix and the step: each parameter of the model file times its factor (Å = nm/10,
    eV = kJ/mol x 1000/(e N_A)), the law and the background pressure where the model has them."""
    given = model_file
    if model_file == "expanding":
        model_file = _expanding_model(tmp_path)
    _, commands = written(tmp_path / "out", model_file, "--particles", "500")
    p = load_parameters(model_file)
    # (the cases cover the thermal law and the background pressure)
    assert (p.thermal_pressure is not None) == (given == "expanding")
    assert (p.background_pressure is not None) == (given == WATER_FILE)
    style = command(commands, "pair_style")
    assert style[0] == "gendpde" and style[2] == "vb"
    assert float(style[1]) == pytest.approx(10 * p.cutoff, rel=1e-15) and float(style[3]) == p.cutoff_scaling
    if p.background_pressure:
        assert style[4] == "background"
        assert float(style[5]) == pytest.approx(p.background_pressure * PRESSURE, rel=1e-12)
    else:
        assert len(style) == 4
    coefficients = command(commands, "pair_coeff", "1", "1")
    expected = [p.density / 1000, p.reference_pressure * PRESSURE, p.bulk_modulus * PRESSURE, p.tait_exponent]
    if p.thermal_pressure is None:
        assert coefficients[0] == "Tait"
    else:
        assert coefficients[0] == "TaitThermalExpansion"
        expected += [p.thermal_pressure * PRESSURE, p.thermal_reference_temperature]
    assert [float(x) for x in coefficients[1:]] == pytest.approx(expected, rel=1e-12)
    assert command(commands, "variable", "mode") == ["index", "isoenergetic"]
    fix = command(commands, "fix", "integrate", "all", "gendpde")
    assert fix[:2] == ["isoenergetic", "1"]
    options = keywords(fix[2:])
    assert float(options["heat_capacity"][0][1]) == pytest.approx(p.heat_capacity * EV_PER_KJ_PER_MOL, rel=1e-12)
    assert options["heat_capacity"][0][0] == "1"
    assert options["friction"] == [["1", "1", repr(p.friction)]]
    assert options["conduction"][0][:2] == ["1", "1"]
    assert float(options["conduction"][0][2]) == pytest.approx(p.heat_conduction * EV_PER_KJ_PER_MOL, rel=1e-12)
    assert float(options["temperature"][0][0]) == p.temperature == float(options["initial"][0][0])
    # The model's step, dt* = 0.01 of its reduced time: L sqrt(m/energy), L = n0^(-1/3) nm and energy
    # L^3 gamma_T B_T kJ/mol (kJ/mol = amu nm^2/ps^2).
    length = p.density ** (-1 / 3)
    time_unit = length * math.sqrt(p.mass / (length**3 * p.tait_exponent * p.bulk_modulus))
    assert float(command(commands, "timestep")[0]) == pytest.approx(0.01 * time_unit, rel=1e-12)


def test_the_sweep_cells_are_at_least_the_candidates_reach_wide():
    """The fix's sweep cells are at least the candidates' reach, sweepCandidateRange(R) = 1.1 R, wide (the core's
    candidateRange, R + 0.1 R): a box 4.3 R wide holds 4 cells of R but not of 1.1 R, and the writer refuses it, as
    the fix would; 4.5 R holds 4; 8.5 R holds 8 cells of R but only 7 of 1.1 R, so 4; 8.9 R holds 8."""
    assert sweepCandidateRange(1.0) == 1.1 and sweepCandidateRange(2.5) == 2.5 + 0.1 * 2.5
    with pytest.raises(ValueError, match="needs at least 4 cells of 1.1 R"):
        sweep_cells(4.3, 1.0)
    assert sweep_cells(4.5, 1.0) == 4 and sweep_cells(8.5, 1.0) == 4 and sweep_cells(8.9, 1.0) == 8


def test_the_ghost_cutoff_by_hand(tmp_path):
    """Argon at 2048 particles: a box of 78.247 Å and R = 10.3755 Å hold m = 6 sweep cells at least 1.1 R =
    11.413 Å wide, so 4 of width L/4 = 19.56 Å; the skin is 0.1 R = 1.03755 Å rounded up to 1.038, and the ghosts
    1.5 x 19.56 + 1.038 = 30.381 Å, rounded up to 30.39 Å; with --skin 2.5: 31.843 -> 31.85."""
    data, commands = written(tmp_path, ARGON_FILE)
    edge = data["box"][0][1]
    cutoff = float(command(commands, "pair_style")[1])
    assert data["atoms"] == 2048 and 78.24 < edge < 78.25 and 10.375 < cutoff < 10.376
    assert math.floor(edge / (1.1 * cutoff)) == 6
    assert 30.38 < 1.5 * edge / 4 + 1.038 <= 30.39
    assert command(commands, "neighbor") == ["1.038", "bin"]
    assert command(commands, "comm_modify") == ["cutoff", "30.39"]
    _, commands = written(tmp_path / "skin", ARGON_FILE, "--skin", "2.5")
    assert 31.84 < 1.5 * edge / 4 + 2.5 <= 31.85
    assert command(commands, "neighbor") == ["2.5", "bin"]
    assert command(commands, "comm_modify") == ["cutoff", "31.85"]


def test_the_numbers_in_real_units(tmp_path):
    """--units real: Å, kcal/mol (1 kcal/mol = 4.184 kJ/mol), fs, g/mol, K by hand. Water's model (with its
    background pressure): R and the box in Å, pressures (pi0, B_T, p_b) as energy/volume in kcal/mol/Å^3 (not atm),
    n0 in Å^-3, C_V in kcal/mol/K, friction in g/mol/fs, conduction in kcal/mol K/fs, the step and the velocities in
    fs and Å/fs."""
    data, commands = written(tmp_path, WATER_FILE, "--particles", "500", "--units", "real")
    metal, _ = written(tmp_path / "metal", WATER_FILE, "--particles", "500")
    p = load_parameters(WATER_FILE)
    assert commands[[c[0] for c in commands].index("units")] == ["units", "real"]
    assert data["box"] == metal["box"]
    assert np.array([row[1:] for row in data["Velocities"]]) == pytest.approx(
        np.array([row[1:] for row in metal["Velocities"]]) / 1000, rel=1e-15)
    style = command(commands, "pair_style")
    assert float(style[1]) == pytest.approx(10 * p.cutoff, rel=1e-15)
    assert style[4] == "background" and float(style[5]) == pytest.approx(p.background_pressure / KCAL / 1000, rel=1e-15)
    coefficients = command(commands, "pair_coeff", "1", "1")
    assert coefficients[0] == "Tait"
    assert [float(x) for x in coefficients[1:]] == pytest.approx(
        [p.density / 1000, p.reference_pressure / KCAL / 1000, p.bulk_modulus / KCAL / 1000, p.tait_exponent],
        rel=1e-15)
    options = keywords(command(commands, "fix", "integrate", "all", "gendpde")[2:])
    assert float(options["heat_capacity"][0][1]) == pytest.approx(p.heat_capacity / KCAL, rel=1e-15)
    assert float(options["friction"][0][2]) == pytest.approx(p.friction / 1000, rel=1e-15)
    assert float(options["conduction"][0][2]) == pytest.approx(p.heat_conduction / KCAL / 1000, rel=1e-15)
    assert float(command(commands, "timestep")[0]) == pytest.approx(
        1000 * float(command(written(tmp_path / "again", WATER_FILE, "--particles", "500")[1], "timestep")[0]),
        rel=1e-15)


def test_the_numbers_in_lj_units_are_openmm_s(tmp_path):
    """--units lj holds OpenMM's numbers (nm, kJ/mol, ps, amu) with k_B = 1: R and the box in nm, the Tait
    parameters as OpenMM has them, temperatures as k_B T (kJ/mol), C_V as C/k_B, kappa as k_B kappa."""
    data, commands = written(tmp_path, ARGON_FILE, "--particles", "500", "--units", "lj")
    p = load_parameters(ARGON_FILE)
    model = p.liquid(500)
    edge = model.system.getDefaultPeriodicBoxVectors()[0][0].value_in_unit(unit.nanometer)
    assert data["box"] == [(0.0, edge)] * 3
    assert float(command(commands, "pair_style")[1]) == p.cutoff
    assert [float(x) for x in command(commands, "pair_coeff", "1", "1")[1:]] == [
        p.density, p.reference_pressure, p.bulk_modulus, p.tait_exponent]
    options = keywords(command(commands, "fix", "integrate", "all", "gendpde")[2:])
    assert float(options["heat_capacity"][0][1]) == p.heat_capacity / KB
    assert float(options["conduction"][0][2]) == KB * p.heat_conduction
    assert float(options["temperature"][0][0]) == KB * p.temperature == float(options["initial"][0][0])


def test_the_script_has_the_plugin_syntax_in_order(tmp_path):
    """The commands of the plugin's syntax in order, the variables on top (run, step, mode, seed: -var overrides
    them), --plugin as the default of the variable plugin, the conserved energy in the thermo output."""
    plugin = tmp_path / "lib" / "gendpdeplugin.so"
    _, commands = written(tmp_path, ARGON_FILE, "--particles", "500", "--mode", "isothermal", "--seed", "42",
                          "--steps", "50", "--thermo", "5", "--step-size", "0.002", "--plugin", str(plugin))
    names = [c[0] for c in commands if c[0] != "variable"]
    assert names == ["units", "atom_style", "atom_modify", "boundary", "plugin", "read_data", "pair_style",
                     "pair_coeff", "neighbor", "neigh_modify", "comm_modify", "fix", "timestep", "thermo_style",
                     "thermo_modify", "thermo", "run"]
    assert commands[[c[0] for c in commands].index("units")] == ["units", "metal"]
    assert command(commands, "atom_style") == ["atomic"] and command(commands, "boundary") == ["p", "p", "p"]
    assert command(commands, "plugin") == ["load", str(plugin)]
    assert command(commands, "read_data") == ["gendpde.data"]
    assert command(commands, "neigh_modify") == ["every", "1", "delay", "0", "check", "yes"]
    assert command(commands, "fix", "integrate", "all", "gendpde")[:2] == ["isothermal", "42"]
    assert command(commands, "timestep") == ["0.002"] and command(commands, "run") == ["50"]
    assert command(commands, "thermo") == ["5"]
    assert command(commands, "variable", "conserved") == ["equal", "etotal+f_integrate"]
    assert "v_conserved" in command(commands, "thermo_style") and "f_integrate" in command(commands, "thermo_style")
    _, commands = written(tmp_path / "default", ARGON_FILE, "--particles", "500")
    assert command(commands, "plugin") == ["load", "${plugin}"]   # given with lmp -var plugin PATH


def test_several_types_each_with_its_law_masses_and_pair_coefficients():
    """A System of two particle types (OpenMM types 0 and 3: LAMMPS types 1 and 2), the second with its own Tait
    parameters, van der Waals law, mass, heat capacity and a pair entry (0, 3), and a background pressure: one
    pair_coeff per type, each pair of types its friction and conduction; no Velocities section without them."""
    model = load_parameters(ARGON_FILE).liquid(500, seed=5)
    force, integrator, system = model.force, model.integrator, model.system
    for i in range(1, 500, 2):
        force.setParticleType(i, 3)
        system.setParticleMass(i, 100.0)
    force.addTypeParameters(3, 5.0, 10.0, 50.0, 7.0)
    force.addTypeEquationOfState(3, GenDPDEForce.VanDerWaals, [0.5, 0.05, 0.04])
    force.setBackgroundPressure(5.0)
    integrator.addTypeHeatCapacity(3, 0.2)
    integrator.addTypePair(3, 0, 1000.0, 300.0)
    texts = lammps_input(system, integrator, model.positions)
    lines = texts.data.splitlines()
    assert "2 atom types" in lines and "Velocities" not in lines
    masses = lines.index("Masses")
    assert lines[masses + 2:masses + 4] == ["1 200.00131678036", "2 100.0"]
    atoms = lines.index("Atoms # atomic")
    assert [line.split()[1] for line in lines[atoms + 2:atoms + 6]] == ["1", "2", "1", "2"]
    script = texts.script.replace("&\n", "")
    p = load_parameters(ARGON_FILE)
    background = 5.0 * PRESSURE
    first = [p.density / 1000, p.reference_pressure * PRESSURE, p.bulk_modulus * PRESSURE, 6.0]
    second = [0.5 * EV_PER_KJ_PER_MOL * 1000, 0.05 * 1000, 0.04 * EV_PER_KJ_PER_MOL]
    coefficients = [line.split() for line in script.splitlines() if line.startswith("pair_coeff")]
    assert [c[:4] for c in coefficients] == [["pair_coeff", "1", "1", "Tait"], ["pair_coeff", "2", "2", "VanDerWaals"]]
    for words, expected in zip(coefficients, (first, second)):
        assert [float(x) for x in words[4:]] == pytest.approx(expected, rel=1e-12)
    style = next(line.split() for line in script.splitlines() if line.startswith("pair_style"))
    assert style[5] == "background" and float(style[6]) == pytest.approx(background, rel=1e-12)
    fix = keywords(next(line.split() for line in script.splitlines() if line.startswith("fix"))[6:])
    assert [(k, float(c)) for k, c in fix["heat_capacity"]] == [
        ("1", pytest.approx(p.heat_capacity * EV_PER_KJ_PER_MOL, rel=1e-12)),
        ("2", pytest.approx(0.2 * EV_PER_KJ_PER_MOL, rel=1e-12))]
    assert fix["friction"] == [["1", "1", repr(p.friction)], ["1", "2", "1000.0"], ["2", "2", repr(p.friction)]]
    assert [(a, b, float(k)) for a, b, k in fix["conduction"]] == [
        ("1", "1", pytest.approx(p.heat_conduction * EV_PER_KJ_PER_MOL, rel=1e-12)),
        ("1", "2", pytest.approx(300.0 * EV_PER_KJ_PER_MOL, rel=1e-12)),
        ("2", "2", pytest.approx(p.heat_conduction * EV_PER_KJ_PER_MOL, rel=1e-12))]


@pytest.mark.parametrize("value, expected", [(30.3808, 30.39), (29.35, 29.35), (1.0375458478399015, 1.038),
                                             (0.00012341, 0.0001235), (99995.1, 100000.0), (7.0, 7.0),
                                             (29.350000000000005, 29.36), (0.1 + 0.2, 0.3001)])
def test_round_up_to_four_significant_digits(value, expected):
    assert round_up(value) == expected and round_up(value) >= value


def test_round_up_is_never_below_the_value():
    rng = np.random.default_rng(1)
    for value in rng.uniform(0, 50, 2000) * 10.0 ** rng.integers(-5, 5, 2000):
        rounded = round_up(value)
        assert value <= rounded <= value * (1 + 1e-3) and len(Decimal(repr(rounded)).normalize().as_tuple().digits) <= 4


def _bad_model(tmp_path):
    path = tmp_path / "bad.toml"
    path.write_text(pathlib.Path(ARGON_FILE).read_text().replace("mass = 200.00131678036", "mass = -1.0"))
    return str(path)


def _fluid_only(tmp_path):
    path = tmp_path / "fluid.toml"
    path.write_text('name = "x"\ntemperature = "300 K"\n')
    return str(path)


@pytest.mark.parametrize("arguments, message", [
    (["{tmp}/missing.toml"], "error: lammps-input: {tmp}/missing.toml: no such file"),
    (["{bad}"], "error: lammps-input: {bad} [parameters]: mass = -1.0 is not allowed; it must be > 0"),
    (["{fluid}"], "error: lammps-input: {fluid}: format = None is not a model file this version reads"),
    ([WATER_FILE, "--particles", "256"], "error: lammps-input: the box is 31.3"),
    ([ARGON_FILE, "--particles", "32"], "error: lammps-input: the box"),
    ([ARGON_FILE, "--particles", "500", "--step-size", "2000"], "error: lammps-input: GenDPDEIntegrator"),
    ([ARGON_FILE, "--particles", "256", "--units", "lj"], "error: lammps-input: the box is 3.91237 nm wide"),
])
def test_bad_input_is_one_line(arguments, message, tmp_path):
    """A missing or bad model file, a box the fix cannot sweep, a step the integrator refuses: one line, status 1,
    nothing written."""
    names = {"tmp": str(tmp_path), "bad": _bad_model(tmp_path), "fluid": _fluid_only(tmp_path)}
    with pytest.raises(SystemExit) as exit_:
        main(["lammps-input", *[a.format(**names) for a in arguments], "--output", str(tmp_path / "out")])
    assert str(exit_.value).startswith(message.format(**names)) and "\n" not in str(exit_.value)
    assert not (tmp_path / "out" / "in.gendpde").exists()


@pytest.mark.parametrize("option, value", [("--particles", "501"), ("--seed", "0"), ("--seed", "2147483648"),
                                           ("--step-size", "nan"), ("--skin", "-1"), ("--steps", "x"),
                                           ("--mode", "adiabatic"), ("--plugin", "a b.so"), ("--thermo", "0"),
                                           ("--units", "si")])
def test_a_bad_option_is_a_usage_error(option, value, tmp_path, capsys):
    with pytest.raises(SystemExit) as exit_:
        main(["lammps-input", ARGON_FILE, option, value, "--output", str(tmp_path)])
    assert exit_.value.code == 2 and option in capsys.readouterr().err.splitlines()[-1]
    assert not (tmp_path / "in.gendpde").exists()


ROOT = pathlib.Path(__file__).resolve().parents[2]
LMP = pathlib.Path(os.environ.get("GENDPDE_LMP", ROOT / "build/lammps/lammps/lmp"))
PLUGIN = pathlib.Path(os.environ.get("GENDPDE_LAMMPS_PLUGIN", ROOT / "build/lammps/plugin/gendpdeplugin.so"))


def write_input(tmp_path, model_file, *options):
    """lammps-input of ``model_file`` with ``options`` into tmp_path (the LAMMPS package must be built)."""
    if not (LMP.exists() and PLUGIN.exists()):
        pytest.fail(f"the LAMMPS package is not built ({LMP}, {PLUGIN}): run lammps/build.sh")
    main(["lammps-input", model_file, *options, "--output", str(tmp_path)])


def run_lammps(tmp_path):
    """lmp with the plugin on tmp_path/in.gendpde: the thermo rows by step."""
    result = subprocess.run([str(LMP), "-var", "plugin", str(PLUGIN), "-in", "in.gendpde", "-log", "none"],
                            cwd=tmp_path, capture_output=True, text=True, timeout=300)
    assert result.returncode == 0, result.stdout[-3000:] + result.stderr[-2000:]
    return thermo_table(result.stdout)


@pytest.mark.lammps
def test_lammps_runs_the_written_input_as_openmm_runs_the_model(tmp_path):
    """lmp with the plugin on the files of the argon model (500 particles, 20 steps): at step 0 the potential energy
    and the internal energies are OpenMM's (Reference, the same lattice, velocities and T0) converted to eV; the kinetic
    energy differs by LAMMPS's mvv2e (6.3e-8 below the exact 10/(e N_A)); after 20 steps the three agree to 1e-6 (the
    engines' k_B differ by 1.13e-6), and the conserved energy holds."""
    write_input(tmp_path, ARGON_FILE, "--particles", "500", "--steps", "20", "--thermo", "20")
    rows = run_lammps(tmp_path)
    model = load_parameters(ARGON_FILE).liquid(500, seed=1)
    context = model.context("Reference", seed=1)
    for step, tolerance in ((0, 1e-12), (20, 1e-6)):
        model.integrator.step(step - context.getStepCount())
        state = context.getState(getEnergy=True)
        openmm_values = {"PotEng": state.getPotentialEnergy(), "KinEng": state.getKineticEnergy(),
                         "f_integrate": model.integrator.getInternalEnergies().sum()}
        for name, value in openmm_values.items():
            expected = float(value.value_in_unit(unit.kilojoule_per_mole)) * EV_PER_KJ_PER_MOL
            allowed = max(tolerance, 1e-7 if name == "KinEng" else 0)
            assert rows[step][name] == pytest.approx(expected, rel=allowed), (step, name)
    assert rows[20]["v_conserved"] == pytest.approx(rows[0]["v_conserved"], rel=1e-7)


@pytest.mark.lammps
def test_the_conserved_energy_column_is_the_total_in_lj_units(tmp_path):
    """--units lj holds OpenMM's own numbers (kJ/mol, nm, ps, amu, k_B T with OpenMM's k_B): at step 0 the script's
    v_conserved is OpenMM's K + U + sum eps (Reference, the same lattice and velocities) to 1e-9. Before, lj units'
    default thermo normalisation divided etotal by the 500 atoms while f_integrate (in the variable) stayed the total:
    v_conserved was the internal energy plus 1/500 of K + U."""
    write_input(tmp_path, ARGON_FILE, "--particles", "500", "--steps", "0", "--units", "lj")
    row = run_lammps(tmp_path)[0]
    model = load_parameters(ARGON_FILE).liquid(500, seed=1)
    context = model.context("Reference", seed=1)
    assert context.getSystem().getNumParticles() == 500
    conserved = model.integrator.getConservedEnergy().value_in_unit(unit.kilojoule_per_mole)
    assert row["v_conserved"] == pytest.approx(conserved, rel=1e-9)


@pytest.mark.lammps
def test_lammps_energy_and_virial_pressure_with_a_background_pressure(tmp_path):
    """Water's model has a background pressure p_b: U gains p_b V_box and the virial -3 p_b V_box
    (GenDPDEForce.setBackgroundPressure). lmp at step 0: the potential energy is OpenMM's (Reference) converted to
    eV to 1e-12, and the virial pressure (compute pressure NULL virial) is OpenMM's virial W/(3V) to 1e-6 (LAMMPS's
    metal pressure factor nktv2p is 8.4e-8 off the exact one); without the box term the pressure would be off by
    p_b = 3,499 bar."""
    write_input(tmp_path, WATER_FILE, "--particles", "500", "--steps", "0")
    script = (tmp_path / "in.gendpde").read_text()
    lines = [line + " c_virialPressure" if line.startswith("thermo_style custom") else line
             for line in script.splitlines()]
    thermo = next(k for k, line in enumerate(lines) if line.startswith("thermo_style"))
    lines.insert(thermo, "compute virialPressure all pressure NULL virial")
    (tmp_path / "in.gendpde").write_text("\n".join(lines) + "\n")
    row = run_lammps(tmp_path)[0]
    model = load_parameters(WATER_FILE).liquid(500, seed=1)
    assert model.force.getBackgroundPressure().value_in_unit(unit.kilojoule_per_mole / unit.nanometer**3) > 0
    context = model.context("Reference", seed=1)
    energy = context.getState(getEnergy=True).getPotentialEnergy().value_in_unit(unit.kilojoule_per_mole)
    assert row["PotEng"] == pytest.approx(energy * EV_PER_KJ_PER_MOL, rel=1e-12)
    box = context.getState().getPeriodicBoxVectors(asNumpy=True).value_in_unit(unit.nanometer)
    virial = np.trace(virial_tensor(model.force, context)) / (3 * abs(np.linalg.det(box)))   # kJ/mol/nm^3
    bar = (1 * unit.kilojoule_per_mole / unit.nanometer**3 / unit.AVOGADRO_CONSTANT_NA).value_in_unit(unit.bar)
    assert row["c_virialPressure"] == pytest.approx(virial * bar, rel=1e-6)


@pytest.mark.lammps
def test_lammps_in_real_units_takes_pressures_as_energy_per_volume(tmp_path):
    """--units real against OpenMM (Reference), water's model with its background pressure p_b at step 0: the
    potential energy is OpenMM's in kcal/mol to 1e-12 (pi0, B_T and p_b are written as energy/volume, kcal/mol/Å^3,
    and the pair style reads them so; read as atm, as the docs once said, U's box term p_b V_box alone would be
    68,568 times too large), the internal energies sum N C_V T0, the virial pressure (compute pressure NULL virial,
    atm) is OpenMM's virial W/(3V) to 1e-6 (LAMMPS's real nktv2p is 1.2e-7 below the exact factor), and after 20
    steps the conserved energy holds."""
    write_input(tmp_path, WATER_FILE, "--particles", "500", "--steps", "20", "--thermo", "20", "--units", "real")
    script = (tmp_path / "in.gendpde").read_text().replace(
        "thermo_style custom step temp pe ke etotal f_integrate v_conserved press",
        "compute virialPressure all pressure NULL virial\n"
        "thermo_style custom step temp pe ke etotal f_integrate v_conserved press c_virialPressure")
    assert "units real" in script and "c_virialPressure" in script
    (tmp_path / "in.gendpde").write_text(script)
    rows = run_lammps(tmp_path)
    parameters = load_parameters(WATER_FILE)
    model = parameters.liquid(500, seed=1)
    assert model.force.getBackgroundPressure().value_in_unit(unit.kilojoule_per_mole / unit.nanometer**3) > 0
    context = model.context("Reference", seed=1)
    energy = context.getState(getEnergy=True).getPotentialEnergy().value_in_unit(unit.kilojoule_per_mole)
    assert rows[0]["PotEng"] == pytest.approx(energy / KCAL, rel=1e-12)
    internal = model.integrator.getInternalEnergies().sum().value_in_unit(unit.kilojoule_per_mole)
    assert rows[0]["f_integrate"] == pytest.approx(internal / KCAL, rel=1e-12)
    assert internal == pytest.approx(500 * parameters.heat_capacity * parameters.temperature, rel=1e-12)
    box = context.getState().getPeriodicBoxVectors(asNumpy=True).value_in_unit(unit.nanometer)
    virial = np.trace(virial_tensor(model.force, context)) / (3 * abs(np.linalg.det(box)))   # kJ/mol/nm^3
    atm = (1 * unit.kilojoule_per_mole / unit.nanometer**3 / unit.AVOGADRO_CONSTANT_NA).value_in_unit(unit.atmosphere)
    assert rows[0]["c_virialPressure"] == pytest.approx(virial * atm, rel=1e-6)
    assert rows[20]["v_conserved"] == pytest.approx(rows[0]["v_conserved"], rel=1e-7)


def test_the_default_particle_count_is_calibrate_s():
    """lammps-input's default --particles is the count models are calibrated with (cli sits below calibration, so it
    cannot import it)."""
    from openmmgendpde.calibration.calibration import Plan
    from openmmgendpde.cli.lammps_input import DEFAULT_PARTICLES
    assert DEFAULT_PARTICLES == Plan.particles
