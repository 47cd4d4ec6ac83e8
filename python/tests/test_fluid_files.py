# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""Fluids and calibrated models as files (openmmgendpde.models.fluid_files) and calibrate's --fluid FILE and
--output."""

import dataclasses
import json
import math
import os
import subprocess
import sys

import openmm
import pytest
from helpers import fake_calibration

from openmmgendpde.__main__ import main
from openmmgendpde.api import ESTIMATOR_NAMES, LAW_NAMES
from openmmgendpde.models.fluid import ARGON, ARGON_EXPANDING, WATER, coarse_grain
from openmmgendpde.models.fluid_files import (
    fluid_from_table,
    fluid_table,
    load_fluid,
    load_parameters,
    quantity,
    save_parameters,
)

REPOSITORY = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
WATER_FILE = os.path.join(REPOSITORY, "examples", "fluids", "water.toml")
WATER_TABLE = {"name": "water", "temperature": "298.15 K", "pressure": "0.1 MPa", "mass_density": "997.05 kg/m^3",
               "compressibility": "0.4525 1/GPa", "heat_capacity": "74.44 J/(mol K)",
               "shear_viscosity": "0.89 mPa s", "thermal_conductivity": "0.6065 W/(m K)", "molar_mass": "18.015 g/mol",
               "tait_exponent": 7, "self_diffusion": "2.299e-9 m^2/s", "speed_of_sound": "1496.7 m/s",
               "surface_tension": "71.97 mN/m"}
#: 1 N/m (J/m^2 per molecule) in OpenMM's kJ/mol/nm^2, written out: x Avogadro's number, J -> kJ, m^-2 -> nm^-2.
N_PER_M = 6.02214076e23 * 1e-3 * 1e-18


def _same_properties(a, b, rel=1e-12):
    values_a, values_b = a.in_openmm(), b.in_openmm()
    assert values_a.keys() == values_b.keys()
    for name in values_a:
        assert values_a[name] == pytest.approx(values_b[name], rel=rel), name


def test_the_example_water_file_is_fluid_water():
    """examples/fluids/water.toml (written in other units than fluid.WATER: 1/GPa, mPa s, MPa) gives WATER's
    properties in OpenMM units to rounding."""
    _same_properties(load_fluid(WATER_FILE), WATER)


@pytest.mark.parametrize("text, expected_si", [
    ("298.15 K", 298.15), ("0.1 MPa", 1e5), ("1 bar", 1e5), ("0.4525 1/GPa", 0.4525e-9), ("0.89 mPa s", 0.89e-3),
    ("74.44 J/(mol K)", 74.44), ("18.015 g/mol", 0.018015), ("1 g/cm^3", 1000.0), ("2 kcal/mol", 8368.0),
])
def test_quantities_in_pint_syntax_become_si_quantities(text, expected_si):
    """Each string gives its value in SI base units (the factors written out here: bar = 1e5 Pa, g/cm^3 = 1000
    kg/m^3, kcal = 4184 J)."""
    assert quantity(text).value_in_unit_system(openmm.unit.si_unit_system) == pytest.approx(expected_si, rel=1e-12)


@pytest.mark.parametrize("fluid", [WATER, ARGON, ARGON_EXPANDING], ids=["water", "argon", "argon-expanding"])
@pytest.mark.parametrize("extension", [".toml", ".json"])
def test_a_saved_model_loads_to_the_same_parameters_and_system(fluid, extension, tmp_path):
    """save_parameters then load_parameters: every parameter equal to the last bit (with a changed f_cut and pi0, as
    calibrate leaves them), the fluid's properties to rounding (its file is in SI units), and liquid() builds the
    same System (serialized XML equal); load_fluid reads the fluid of a model file."""
    parameters = dataclasses.replace(coarse_grain(fluid, 5, neighbors=20), cutoff_scaling=1.3371,
                                     reference_pressure=-3.0e-1 / 7)
    path = str(tmp_path / f"model{extension}")
    save_parameters(parameters, path, comment="a test\nof two lines")
    loaded = load_parameters(path)
    for field in dataclasses.fields(parameters):
        if field.name != "fluid":
            assert getattr(loaded, field.name) == getattr(parameters, field.name), field.name
    _same_properties(loaded.fluid, fluid)
    _same_properties(load_fluid(path), fluid)
    assert loaded.targets()["surface_tension"] == (None if fluid.surface_tension is None else
                                                   pytest.approx(0.07197 * N_PER_M, rel=1e-12))
    serialize = openmm.XmlSerializer.serialize
    assert serialize(loaded.liquid(500).system) == serialize(parameters.liquid(500).system)


def test_a_fluid_table_round_trip():
    _same_properties(fluid_from_table(fluid_table(ARGON)), ARGON)
    _same_properties(fluid_from_table(WATER_TABLE), WATER)


@pytest.mark.parametrize("change, message", [
    ({"temperature": None}, "missing ['temperature']"),
    ({"colour": "blue"}, "unknown entries ['colour']"),
    ({"temperature": "298 kelvinz"}, "temperature = '298 kelvinz' cannot be read as 'value unit'"),
    ({"temperature": "25 degC"}, "temperature = '25 degC' cannot be read"),
    ({"temperature": 298.15}, "temperature = 298.15 is not allowed; it must be a string 'value unit'"),
    ({"mass_density": "997 K"}, "mass_density = '997 K' is not allowed; its unit must be compatible with kg/m^3"),
    ({"shear_viscosity": "-0.89 mPa s"}, "shear_viscosity ="),
    ({"pressure": "1 A"}, "its unit may use only mass, length, time, amount of substance and temperature"),
    ({"tait_exponent": "7"}, "tait_exponent = '7' is not allowed; it must be a number > 1"),
    ({"tait_exponent": 1.0}, "tait_exponent = 1.0 is not allowed; it must be finite and > 1"),
    ({"surface_tension": "-71.97 mN/m"}, "surface_tension = -0.07197 kg/(s**2) is not allowed; it must be finite "
                                         "and > 0"),
    ({"surface_tension": "71.97 mN"}, "surface_tension = '71.97 mN' is not allowed; its unit must be compatible with "
                                      "N/m"),
])
def test_bad_fluid_files_are_refused_naming_the_entry(change, message, tmp_path):
    table = dict(WATER_TABLE)
    for key, value in change.items():
        if value is None:
            del table[key]
        else:
            table[key] = value
    path = tmp_path / "fluid.json"
    path.write_text(json.dumps(table))
    with pytest.raises(ValueError) as error:
        load_fluid(str(path))
    assert message in str(error.value) and str(path) in str(error.value)


def test_bad_model_files_are_refused(tmp_path):
    path = str(tmp_path / "model.toml")
    save_parameters(coarse_grain(WATER, 4, neighbors=20), path)
    text = open(path).read()
    for old, new, message in [("openmmgendpde-model-3", "other-2", "format = 'other-2' is not a model file"),
                              ("cutoff = ", "cut = ", "missing ['cutoff']; unknown ['cut']"),
                              ("mass = 72.06", "mass = -72.06", "mass = -72.06 is not allowed; it must be > 0"),
                              ("mass = 72.06", 'mass = "72.06"', "mass = '72.06' is not allowed; it must be a finite")]:
        broken = str(tmp_path / "broken.toml")
        with open(broken, "w") as stream:
            stream.write(text.replace(old, new))
        with pytest.raises(ValueError) as error:
            load_parameters(broken)
        assert message in str(error.value)
    with pytest.raises(ValueError, match="must be .toml or .json"):
        save_parameters(coarse_grain(WATER, 4, neighbors=20), str(tmp_path / "model.txt"))


def test_a_model_file_records_the_estimator_and_the_law_and_refuses_another_estimator(tmp_path):
    """Format 3 writes the estimator that f_cut was tuned for and the equation of state with its parameters by the
    names of the table of laws (format 2 wrote the estimator and the law); loaded, liquid() builds with
    that estimator by default, allows V-A (which has no f_cut), and refuses V-C with V-B's f_cut, naming both (the
    bug of format 1: V-C ran silently on V-B's f_cut)."""
    path = str(tmp_path / "model.toml")
    tuned = coarse_grain(ARGON_EXPANDING, 5, neighbors=20).with_cutoff_scaling(1.3371, "VB")
    save_parameters(tuned, path)
    text = open(path).read()
    assert 'format = "openmmgendpde-model-3"' in text
    assert 'estimator = "VB"' in text and 'equation_of_state = "TaitThermalExpansion"' in text
    beta, theta0 = tuned.law_parameters
    assert f"equation_of_state_parameters = {{beta = {beta!r}, theta0 = {theta0!r}}}" in text
    loaded = load_parameters(path)
    assert loaded.estimator == "VB" and loaded.equation_of_state == "TaitThermalExpansion"
    assert loaded == dataclasses.replace(tuned, fluid=loaded.fluid)
    assert loaded.liquid(500).force.getDensityEstimator() == openmm_gendpde_estimator("VB")
    assert loaded.liquid(500, "VA").force.getDensityEstimator() == openmm_gendpde_estimator("VA")
    with pytest.raises(ValueError, match=r"estimator = 'VC' is not allowed for this model: its f_cut = 1\.3371 was "
                                         r"tuned for VB"):
        loaded.liquid(500, "VC")
    assert loaded.with_cutoff_scaling(1.41, "VC").liquid(500, "VC").force.getCutoffScaling() == 1.41
    # A fresh mapping records no estimator: its f_cut is a first estimate for any.
    assert coarse_grain(WATER, 4, neighbors=20).estimator is None
    assert coarse_grain(WATER, 4, neighbors=20).liquid(500, "VC").force.getDensityEstimator() == \
        openmm_gendpde_estimator("VC")


def openmm_gendpde_estimator(name):
    from openmmgendpde import GenDPDEForce
    return getattr(GenDPDEForce, name)


def test_a_format_1_model_file_is_still_read_without_an_estimator(tmp_path):
    """A model file of version 0.2 (format 1: no estimator, no equation_of_state) loads with the same numbers and
    estimator None (unknown: any estimator builds, as before)."""
    path = str(tmp_path / "model.toml")
    parameters = coarse_grain(WATER, 4, neighbors=20)
    save_parameters(parameters, path)
    lines = [line for line in open(path).read().splitlines()
             if not line.startswith(("estimator", "equation_of_state"))]
    old = str(tmp_path / "old.toml")
    with open(old, "w") as stream:
        stream.write("\n".join(lines).replace("openmmgendpde-model-3", "openmmgendpde-model-1") + "\n")
    loaded = load_parameters(old)
    assert loaded.estimator is None and loaded == dataclasses.replace(parameters, fluid=loaded.fluid)
    with open(old, "a") as stream:   # format 1 knows no estimator key
        stream.write('estimator = "VB"\n')
    with pytest.raises(ValueError, match=r"unknown \['estimator'\]"):
        load_parameters(old)


#: The names the tables allow, as the refusals list them (a name not in them: no estimator or law is called "Xx").
_ESTIMATORS_ALLOWED = ", ".join(repr(name) for name in ESTIMATOR_NAMES.values())
_LAWS_ALLOWED = ", ".join(repr(name) for name in LAW_NAMES.values())


@pytest.mark.parametrize("old, new, message", [
    ('estimator = "VB"', 'estimator = "Xx"',
     f"estimator = 'Xx' is not allowed; it must be one of {_ESTIMATORS_ALLOWED}"),
    ('equation_of_state = "Tait"', 'equation_of_state = "TaitThermalExpansion"',
     "equation_of_state_parameters = {} is not allowed; the law TaitThermalExpansion takes ['beta', 'theta0']"),
    ('equation_of_state = "Tait"', 'equation_of_state = "Xx"',
     f"equation_of_state = 'Xx' is not allowed; it must be one of {_LAWS_ALLOWED}"),
    ('equation_of_state = "Tait"\nequation_of_state_parameters = {}',
     'equation_of_state = "VanDerWaals"\nequation_of_state_parameters = {a = 1.0, b = -0.2, k = 0.05}',
     "excluded volume b = -0.2"),
    ('equation_of_state_parameters = {}\n', "", "missing ['equation_of_state_parameters']"),
])
def test_a_model_file_with_a_bad_estimator_or_law_is_refused(old, new, message, tmp_path):
    path = str(tmp_path / "model.toml")
    save_parameters(coarse_grain(WATER, 4, neighbors=20).for_estimator("VB"), path)
    broken = str(tmp_path / "broken.toml")
    with open(broken, "w") as stream:
        stream.write(open(path).read().replace(old, new))
    with pytest.raises(ValueError) as error:
        load_parameters(broken)
    assert message in str(error.value)


def test_a_format_2_model_file_is_still_read_with_its_thermal_law(tmp_path):
    """Format 2 (version 0.2's last) wrote the thermal Tait law's parameters as thermal_pressure and
    thermal_reference_temperature: such a file loads with the same law and numbers; one whose equation_of_state does
    not match the parameters given is refused."""
    parameters = coarse_grain(ARGON_EXPANDING, 5, neighbors=20).for_estimator("VB")
    path = str(tmp_path / "model.toml")
    save_parameters(parameters, path)
    beta, theta0 = parameters.law_parameters
    text = open(path).read().replace("openmmgendpde-model-3", "openmmgendpde-model-2").replace(
        f"equation_of_state_parameters = {{beta = {beta!r}, theta0 = {theta0!r}}}",
        f"thermal_pressure = {beta!r}\nthermal_reference_temperature = {theta0!r}")
    old = tmp_path / "old.toml"
    old.write_text(text)
    assert "openmmgendpde-model-2" in text and "thermal_pressure" in text
    loaded = load_parameters(str(old))
    assert loaded == dataclasses.replace(parameters, fluid=loaded.fluid)
    assert (loaded.equation_of_state, loaded.law_parameters) == ("TaitThermalExpansion", (beta, theta0))
    old.write_text(text.replace('equation_of_state = "TaitThermalExpansion"', 'equation_of_state = "Tait"'))
    with pytest.raises(ValueError, match="equation_of_state = 'Tait' does not match the parameters given"):
        load_parameters(str(old))


def test_calibrate_takes_a_fluid_file_and_writes_the_calibrated_model(monkeypatch, tmp_path, capsys):
    """calibrate --fluid FILE --output MODEL with the simulations replaced by made-up measurements: the pressure
    reads P0 + 0.02/kappa_T (beyond the 0.01 allowed) with pi0 as mapped and P0 after any move, so pi0 must end
    -0.02/kappa_T from the mapping (one round, a response of 1); f_cut is 'tuned' to 1.3; the transport
    coefficients read their targets. The model file holds exactly those parameters (computed here from coarse_grain,
    independently of calibrate)."""
    from openmmgendpde.models.fluid import KB
    offset = 0.02
    mapped = coarse_grain(load_fluid(WATER_FILE), 4, neighbors=20)
    fake_calibration(monkeypatch, mapped, offset)
    output = str(tmp_path / "water-model.toml")
    main(["calibrate", "--quick", "--fluid", WATER_FILE, "--output", output])
    assert f"The calibrated model is in {output}" in capsys.readouterr().out
    model = load_parameters(output)
    bulk_modulus = mapped.targets()["bulk_modulus"]
    expected = dataclasses.replace(mapped, cutoff_scaling=1.3, estimator="VB",   # (calibrate's --estimator default)
                                   reference_pressure=mapped.reference_pressure - offset * bulk_modulus)
    assert model.reference_pressure == pytest.approx(expected.reference_pressure, rel=1e-12)
    # C_V matched to the fluid's c_v: the made-up c_U (0.5 k_B), the motion (3/2 k_B) and the Gamma law's k_B off.
    assert model.heat_capacity == pytest.approx(mapped.heat_capacity - 3 * KB, rel=1e-12)
    for field in dataclasses.fields(expected):
        if field.name not in ("fluid", "reference_pressure", "heat_capacity"):
            assert getattr(model, field.name) == getattr(expected, field.name), field.name
    assert "every judged result within its tolerance" in open(output).read()


@pytest.mark.parametrize("arguments, message", [
    (["--fluid", "nowhere.toml"], "--fluid nowhere.toml: no such file"),
    (["--fluid", "mercury"], "--fluid mercury is not allowed; give one of argon, argon-expanding, "
                             "supercritical-argon, water or a fluid file"),
    (["--output", "model.txt"], "--output model.txt is not allowed; it must end in .toml or .json"),
])
def test_calibrate_refuses_a_bad_fluid_or_output_in_one_line(arguments, message):
    result = subprocess.run([sys.executable, "-m", "openmmgendpde", "calibrate", "--quick"] + arguments,
                            capture_output=True, text=True, timeout=120)
    assert result.returncode == 1 and result.stdout == "" and "Traceback" not in result.stderr
    assert message in result.stderr.splitlines()[-1]


def test_the_example_nitrogen_file_holds_the_tabulated_state():
    """examples/fluids/nitrogen.toml against the table it cites, recomputed here: mass density 30.017 mol/L x
    28.0134 g/mol, kappa_T = T v alpha^2/(C_p - C_v) with alpha = ln(30.017/28.881)/7.25 K (to the 3 digits
    written), C_v 28.5 J/(mol K) per molecule."""
    values = load_fluid(os.path.join(REPOSITORY, "examples", "fluids", "nitrogen.toml")).in_openmm()
    n_a = 6.02214076e23
    assert values["mass_density"] == pytest.approx(30.017e3 * 28.0134e-3 / 1.66053906660e-27 * 1e-27,
                                                   rel=1e-5)   # kg/m^3 -> amu/nm^3
    alpha = math.log(30.017 / 28.881) / 7.25
    kappa_t = 70 * (1e-3 / 30.017) * alpha**2 / (57.2 - 28.5)   # 1/Pa
    assert values["compressibility"] == pytest.approx(kappa_t * 1e3 / n_a * 1e27, rel=2e-3)   # nm^3 mol/kJ
    assert values["heat_capacity"] == pytest.approx(28.5e-3, rel=1e-12)
    assert values["temperature"] == 70.0


def test_surface_tension_is_optional_and_read_in_any_unit(tmp_path):
    """A fluid file without surface_tension gives a Fluid without it (targets: None); one in dyn/cm (= mN/m) gives
    the value in kJ/mol/nm^2, and a fluid table writes it back in N/m."""
    table = dict(WATER_TABLE)
    del table["surface_tension"]
    fluid = fluid_from_table(table)
    assert fluid.surface_tension is None and "surface_tension" not in fluid.in_openmm()
    assert coarse_grain(fluid, 4, neighbors=20).targets()["surface_tension"] is None
    assert "surface_tension" not in fluid_table(fluid)
    fluid = fluid_from_table(dict(WATER_TABLE, surface_tension="71.97 dyn/cm"))
    assert fluid.in_openmm()["surface_tension"] == pytest.approx(0.07197 * N_PER_M, rel=1e-12)
    value, written_unit = fluid_table(fluid)["surface_tension"].split()
    assert float(value) == pytest.approx(0.07197, rel=1e-12) and written_unit == "N/m"


def test_the_example_surface_tensions_are_their_sources_correlations():
    """water.toml and fluid.WATER: the IAPWS correlation (Vargaftik et al. 1983),
    sigma = 235.8 mN/m tau^1.256 (1 - 0.625 tau), tau = 1 - T/647.096 K, at 298.15 K to the 4 digits written;
    nitrogen.toml: Mulero et al. (2012), sigma = 28.98 mN/m (1 - T/126.192 K)^1.246, at 70 K."""
    tau = 1 - 298.15 / 647.096
    water = 235.8 * tau**1.256 * (1 - 0.625 * tau) * 1e-3 * N_PER_M
    assert load_fluid(WATER_FILE).in_openmm()["surface_tension"] == pytest.approx(water, rel=1e-4)
    assert WATER.in_openmm()["surface_tension"] == pytest.approx(water, rel=1e-4)
    nitrogen = 28.98 * (1 - 70 / 126.192) ** 1.246 * 1e-3 * N_PER_M
    assert load_fluid(os.path.join(REPOSITORY, "examples", "fluids", "nitrogen.toml")).in_openmm()[
        "surface_tension"] == pytest.approx(nitrogen, rel=1e-3)
    assert ARGON.surface_tension is None


@pytest.mark.parametrize("key, text", [
    ("temperature", "298.15 kelvin + 5 K"),
    ("temperature", "2 * 150 K"),
    ("pressure", "0.1 MPa * 2"),
    ("mass_density", "(997.05 kg/m^3)"),
    ("temperature", "nan K"),
])
def test_a_fluid_file_value_is_one_number_with_a_unit_not_an_expression(key, text, tmp_path):
    """pint evaluates expressions ('298.15 kelvin + 5 K' is 303.15 K); a fluid file takes one number followed by a
    unit, and refuses anything else naming the key, the value and what is allowed."""
    path = tmp_path / "fluid.json"
    path.write_text(json.dumps(dict(WATER_TABLE, **{key: text})))
    with pytest.raises(ValueError) as error:
        load_fluid(str(path))
    assert f"{key} = {text!r}" in str(error.value) and "it must be one number followed by its unit" in str(error.value)


@pytest.mark.parametrize("key, text", [
    ("thermal_expansion", "2.64e-3 1/(K mol)"),   # made 'per molecule' by Avogadro's number: 4.4e-27 1/K
    ("thermal_expansion", "4.4e-27 mol/K"),        # made 'per mole': 2.64e-3 1/K
    ("temperature", "4.9e-22 K mol"),
    ("speed_of_sound", "1496.7 m/(s mol)"),
    ("self_diffusion", "2.3e-9 m^2 mol/s"),
])
def test_a_property_that_is_not_molar_takes_no_per_mole_conversion(key, text, tmp_path):
    """The per-mole rule (a quantity per molecule made per mole by Avogadro's number) is for the properties whose
    OpenMM unit is per mole (energies, pressures, masses); a thermal expansion coefficient, a temperature or a speed
    with mol in its unit is refused, naming the key, the value and the unit it must have."""
    path = tmp_path / "fluid.json"
    path.write_text(json.dumps(dict(WATER_TABLE, **{key: text})))
    with pytest.raises(ValueError) as error:
        load_fluid(str(path))
    assert f"{key} = {text!r} is not allowed; its unit must be compatible with" in str(error.value)
    assert "not per mole" in str(error.value)


def test_the_per_mole_rule_still_converts_the_molar_properties(tmp_path):
    """Per molecule in SI (J/K, Pa, kg) or per mole: the same Fluid either way."""
    avogadro = 6.02214076e23
    per_molecule = dict(WATER_TABLE, heat_capacity=f"{74.44 / avogadro!r} J/K",
                        molar_mass=f"{18.015e-3 / avogadro!r} kg", pressure=f"{0.1e6!r} Pa")
    path = tmp_path / "fluid.json"
    path.write_text(json.dumps(per_molecule))
    _same_properties(load_fluid(str(path)), load_fluid(WATER_FILE), rel=1e-12)


@pytest.mark.parametrize("change, message", [
    ({"temperature": "1e300 K"}, "the mapping"),
    ({"tait_exponent": 1e6}, "gamma_T = 1000000 is not allowed"),
])
@pytest.mark.parametrize("command", ["calibrate", "tune-fcut"])
def test_a_fluid_out_of_range_ends_in_one_line_before_anything_runs(command, change, message, tmp_path, capsys,
                                                                    monkeypatch):
    """A fluid file whose values the mapping cannot turn into a model (an overflow) or that the force refuses (gamma_T
    beyond GenDPDEForce's range): a one-line error, status 1, before any simulation (Context creation fails the
    test)."""
    monkeypatch.setattr(openmm, "Context", lambda *a, **k: pytest.fail("a simulation started"))
    path = tmp_path / "fluid.json"
    path.write_text(json.dumps(dict(WATER_TABLE, **change)))
    with pytest.raises(SystemExit) as exit_:
        main([command, "--quick", "--fluid", str(path)])
    assert str(exit_.value).startswith(f"error: {command}: ") and message in str(exit_.value)
    assert "\n" not in str(exit_.value)


@pytest.mark.parametrize("name, text", [("fluid.toml", b'name = "water \xff"\n'),
                                        ("fluid.json", b'{"name": "water \xff"}')])
def test_a_fluid_file_that_is_not_utf8_is_refused_naming_the_file(name, text, tmp_path):
    """A fluid file that is not UTF-8 text (TOML and JSON are): ValueError naming the file and the byte, and calibrate
    --fluid FILE ends in that one line (issue 54: the error was Python's UnicodeDecodeError without the file)."""
    path = tmp_path / name
    path.write_bytes(text)
    with pytest.raises(ValueError) as error:
        load_fluid(str(path))
    assert str(path) in str(error.value) and "must be UTF-8 text (byte b'\\xff'" in str(error.value)
    result = subprocess.run([sys.executable, "-m", "openmmgendpde", "calibrate", "--quick", "--fluid", str(path)],
                            capture_output=True, text=True, timeout=120)
    assert result.returncode == 1 and "Traceback" not in result.stderr
    assert f"error: calibrate: {path}: not a valid" in result.stderr.splitlines()[-1]


def test_a_negative_zero_in_a_model_file_reads_as_zero(tmp_path):
    """-0.0 where a sign means nothing (the reference pressure, a law's parameter, a fluid's pressure) reads as +0.0:
    the model read back, and written again, says 0.0, not -0.0 (issue 54)."""
    path = str(tmp_path / "model.toml")
    save_parameters(coarse_grain(WATER, 4, neighbors=20).with_law("TaitThermalExpansion", thermal_pressure=0.0),
                    path)
    text = open(path).read()
    zeroed = "\n".join("reference_pressure = -0.0" if line.startswith("reference_pressure = ") else
                       'pressure = "-0.0 Pa"' if line.startswith("pressure = ") else line
                       for line in text.splitlines())
    assert zeroed.count("-0.0") == 2 and "{beta = 0.0," in zeroed
    zeroed = zeroed.replace("{beta = 0.0,", "{beta = -0.0,")
    with open(path, "w") as stream:
        stream.write(zeroed)
    parameters = load_parameters(path)
    signs = [math.copysign(1, value) for value in (parameters.reference_pressure, parameters.law_parameters[0],
                                                   parameters.fluid.in_openmm()["pressure"])]
    assert signs == [1, 1, 1]
    save_parameters(parameters, path)
    assert "-0.0" not in open(path).read()


def test_gamma_t_is_the_fluid_s_bulk_modulus_derivative_where_given(tmp_path):
    """gamma_T's rule (issue 54): a fluid file's bulk_modulus_derivative, (dK_T/dP)_T, a measured property, is gamma_T
    (the Tait law's dK/dP is gamma_T: K = gamma_T B_T (n/n0)^gamma_T, P = B_T ((n/n0)^gamma_T - 1) + const): water
    with 6 maps to gamma_T = 6 and B_T = 1/(6 kappa_T) = 2209.9/6 MPa (kappa_T = 0.4525/GPa), and the Tait law's dK/dP
    at n0, by a central difference of the law written out here, is 6; a tait_exponent that differs is refused naming
    both, an equal one accepted; a value <= 1 refused. Without either, gamma_T stays 7."""
    from openmmgendpde.calibration.report import mpa
    table = {key: value for key, value in WATER_TABLE.items() if key != "tait_exponent"}
    path = tmp_path / "fluid.json"
    path.write_text(json.dumps(dict(table, bulk_modulus_derivative=6)))
    parameters = coarse_grain(load_fluid(str(path)), 4, neighbors=20)
    assert parameters.tait_exponent == 6.0
    assert mpa(parameters.bulk_modulus) == pytest.approx(1e3 / 0.4525 / 6, rel=1e-9)
    n0, gamma, modulus = parameters.density, parameters.tait_exponent, parameters.bulk_modulus

    def tait(n):   # (pressure, n dP/dn) of the law
        return modulus * ((n / n0) ** gamma - 1), gamma * modulus * (n / n0) ** gamma
    h = 1e-5 * n0
    (p_low, k_low), (p_high, k_high) = tait(n0 - h), tait(n0 + h)
    assert (k_high - k_low) / (p_high - p_low) == pytest.approx(6.0, rel=1e-8)
    again = fluid_from_table(fluid_table(load_fluid(str(path))))   # (written, read back)
    assert again.tait_exponent == again.bulk_modulus_derivative == 6.0
    path.write_text(json.dumps(dict(table, bulk_modulus_derivative=6, tait_exponent=6)))
    assert load_fluid(str(path)).tait_exponent == 6.0
    for extra, message in [({"bulk_modulus_derivative": 6, "tait_exponent": 7},
                            "tait_exponent = 7.0 is not allowed with bulk_modulus_derivative = 6.0: gamma_T is the "
                            "fluid's (dK_T/dP)_T"),
                           ({"bulk_modulus_derivative": 1}, "bulk_modulus_derivative = 1.0 is not allowed; it must be "
                                                            "a finite number > 1"),
                           ({"bulk_modulus_derivative": "6"}, "bulk_modulus_derivative = '6' is not allowed")]:
        path.write_text(json.dumps(dict(table, **extra)))
        with pytest.raises(ValueError) as error:
            load_fluid(str(path))
        assert str(path) in str(error.value) and message in str(error.value)
    path.write_text(json.dumps(table))
    assert load_fluid(str(path)).tait_exponent == 7.0
