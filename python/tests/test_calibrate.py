# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""calibrate (openmmgendpde.calibration): the judgement of a calibration, its iterations, its stages on made-up
measurements and in short runs, and the measurements it rests on (heat capacity, thermal expansion, stability)."""

import dataclasses
import json
import math
import subprocess
import sys

import pytest
from helpers import made_up_thermal_pressure

from openmmgendpde.__main__ import main
from openmmgendpde.calibration.results import Property
from openmmgendpde.models.fluid import ARGON_EXPANDING, KB, WATER, coarse_grain

#: Avogadro's and Boltzmann's constants (SI, exact), written out.
N_A = 6.02214076e23
K_B = 1.380649e-23

#: calibrate's results from two runs (`calibrate --quick --fluid water --platform CPU`, with `--neighbors 2` for
#: the second, before issue 24: the pressure after one shift of pi0, one wave measurement per coefficient, written
#: here under the rows of today's table, the steady-flow rows copied from the waves): the first reaches every target
#: --quick is judged on, the second misses the pressure (55.67 MPa, 0.0251/kappa_T from P0) and the viscosity (0.039
#: of its target). The heat-capacity rows (not measured then) are made up within their 2%.
WATER_QUICK = {Property.DENSITY: (8.3325, 8.2745, 0.036),
               Property.HEAT_CAPACITY: (4132.0, 4150.0, 10.0),
               Property.PRESSURE: (0.1, -6.171, 10.13),
               Property.BULK_MODULUS: (2209.9, 1828.2, 187.3),
               Property.KINETIC_TEMPERATURE: (298.15, 297.59, 0.947),
               Property.HARMONIC_TEMPERATURE: (298.15, 296.57, 0.0576),
               Property.VISCOSITY_WAVE: (0.89, 0.7837, 0.0433),
               Property.VISCOSITY_FLOW: (0.89, 0.7837, 0.0433),
               Property.CONDUCTIVITY_WAVE: (0.6065, 0.8275, 0.0928),
               Property.CONDUCTIVITY_HEAT_FLUX: (0.6065, 0.8275, 0.0928)}


WATER_TWO_NEIGHBOURS = {Property.DENSITY: (8.3325, 8.4432, 0.0107),
                        Property.HEAT_CAPACITY: (4132.0, 4140.0, 15.0),
                        Property.PRESSURE: (0.1, 55.67, 2.362),
                        Property.BULK_MODULUS: (2209.9, 156.55, 31.97),
                        Property.KINETIC_TEMPERATURE: (298.15, 290.66, 4.879),
                        Property.HARMONIC_TEMPERATURE: (298.15, 296.86, 0.459),
                        Property.VISCOSITY_WAVE: (0.89, 0.034413, 0.00717),
                        Property.VISCOSITY_FLOW: (0.89, 0.034413, 0.00717),
                        Property.CONDUCTIVITY_WAVE: (0.6065, 0.14393, 0.137),
                        Property.CONDUCTIVITY_HEAT_FLUX: (0.6065, 0.14393, 0.137)}


def _results(rows):  # (rows: Property -> (target, model, error))
    return {name: {"target": t, "model": m, "error": e} for name, (t, m, e) in rows.items()}


def test_misses_judges_a_calibration():
    """calibrate's criteria (docs/fluids.md) on the two runs above. --quick's (QUICK_CRITERIA): nothing missed in
    the first; in the second the pressure (allowed P0 +- 0.01 x 2209.9 MPa = -22.0 to 22.2 MPa, widened by 2 x
    2.362) and both viscosities (allowed 0.445 to 1.78 mPa s, widened by 2 x 0.00717), each line with the model's
    comparison with its target; the conductivity (0.237 of its target) is within 2 of its (large) standard errors of
    the allowed range. The full criteria (5% for transport) miss the first run's conductivities (0.8275 above
    0.6065 x 1.05 + 2 x 0.0928 = 0.8224) but not its viscosities (0.7837 above 0.89 x 0.95 - 2 x 0.0433 = 0.7589)."""
    from openmmgendpde.calibration.results import CRITERIA, QUICK_CRITERIA, misses
    assert misses(_results(WATER_QUICK), QUICK_CRITERIA) == []
    assert [miss.property for miss in misses(_results(WATER_QUICK), CRITERIA)] == [
        Property.CONDUCTIVITY_WAVE, Property.CONDUCTIVITY_HEAT_FLUX]
    missed = misses(_results(WATER_TWO_NEIGHBOURS), QUICK_CRITERIA)
    assert len(missed) == 3
    assert str(missed[0]).startswith("pressure, pi0 tuned (MPa): 55.67 +- 2.4 against the target 0.1 "
                                "((P - P0) kappa_T = 0.0251); allowed -21.999 to 22.199")
    assert str(missed[1]).startswith("shear viscosity, wave (mPa s): 0.034413 +- 0.0072 against the target 0.89 "
                                "(model/target = 0.039); allowed 0.445 to 1.78")
    # Each kind of criterion at its edge, 2 standard errors included.
    edge = dict(WATER_QUICK)
    edge[Property.DENSITY] = (10.0, 10.0 * 1.02 + 2 * 0.01, 0.01)
    edge[Property.CONDUCTIVITY_WAVE] = (1.0, 0.5 - 2 * 0.01, 0.01)
    edge[Property.VISCOSITY_WAVE] = (1.0, 1.05 + 2 * 0.01, 0.01)
    assert misses(_results(edge), QUICK_CRITERIA) == []
    assert "shear viscosity, wave (mPa s)" not in " ".join(map(str, misses(_results(edge), CRITERIA)))
    edge[Property.DENSITY] = (10.0, 10.0 * 1.02 + 2 * 0.01 + 1e-9, 0.01)
    edge[Property.CONDUCTIVITY_WAVE] = (1.0, 0.5 - 2 * 0.01 - 1e-9, 0.01)
    edge[Property.VISCOSITY_WAVE] = (1.0, 1.05 + 2 * 0.01 + 1e-9, 0.01)
    assert [miss.property for miss in misses(_results(edge), QUICK_CRITERIA)] == [
        Property.DENSITY, Property.CONDUCTIVITY_WAVE]
    assert "shear viscosity, wave (mPa s)" in " ".join(map(str, misses(_results(edge), CRITERIA)))
    # An error from 4 replicas widens the range by Student's t(0.975, 3) = 3.1824 standard errors (tables), not 2.
    results = _results(WATER_QUICK)
    results[Property.VISCOSITY_WAVE] = {"target": 1.0, "model": 1.05 + 3.18 * 0.01, "error": 0.01,
                                                "samples": 4}
    assert "shear viscosity, wave (mPa s)" not in " ".join(map(str, misses(results, CRITERIA)))
    results[Property.VISCOSITY_WAVE]["model"] = 1.05 + 3.19 * 0.01
    assert "widened by 3.18 standard errors" in " ".join(map(str, misses(results, CRITERIA)))


def test_misses_judges_the_thermal_expansion_where_it_was_measured():
    """The thermal expansion row is judged (5%, widened by 2 standard errors) when a calibration has it, and a
    calibration of a fluid without thermal expansion (no such row) is judged on the other rows alone."""
    from openmmgendpde.calibration.results import CRITERIA, misses
    results = _results(WATER_TWO_NEIGHBOURS)
    without = misses(results, CRITERIA)
    results[Property.THERMAL_EXPANSION] = {"target": 2.64, "model": 2.64 * 1.05 + 2 * 0.01, "error": 0.01}
    assert misses(results, CRITERIA) == without
    results[Property.THERMAL_EXPANSION]["model"] = 2.64 * 1.05 + 2 * 0.01 + 1e-9
    assert misses(results, CRITERIA)[:-1] == without
    assert misses(results, CRITERIA)[-1].property is Property.THERMAL_EXPANSION


@pytest.mark.validation
def test_calibrate_measures_the_thermal_expansion_and_keeps_the_corrected_beta():
    """calibrate's thermal-expansion stage (thermal_expansion_rows) on liquid argon with alpha = 2.64e-3 1/K, with
    short runs (500 particles, 800 sampled steps at T0 -+ 10 K): the rows' target is 2.64 (1e-3/K); the model's alpha
    as mapped is 0.914-0.940 of it in long runs (docs/thermal.md), so expected 0.927 x 2.64, required within 3 of the
    row's standard errors (0.17-0.24, 7-9% of it, in seeds 3-5; seed 5 read 1.135 x 2.64) and 0.013 x 2.64 (the long
    runs' spread); beta is moved by expansion.corrected from the first measurement and kept in the calibration's
    parameters."""
    from openmmgendpde.calibration import expansion
    from openmmgendpde.calibration.calibrate import thermal_expansion_rows
    from openmmgendpde.calibration.calibration import QUICK, Calibration
    plan = dataclasses.replace(QUICK, melt=400, frames=40, interval=20)
    calibration = Calibration(expansion.mapped(), "VB", plan, "CPU", report=lambda _: None)
    beta = calibration.parameters.thermal_pressure
    (first_name, first_target, first), (second_name, second_target, second) = thermal_expansion_rows(
        calibration, plan, "CPU", seed=3)
    assert second_name is Property.THERMAL_EXPANSION and first_name != second_name
    assert first_target == second_target == pytest.approx(2.64)
    assert 0 < first.error < 0.15 * first_target and 0 < second.error < 0.15 * second_target
    assert abs(first.value - 0.927 * first_target) < 3 * first.error + 0.013 * first_target, first
    # beta is scaled by (target - n0 k_B)/(measured - n0 k_B) of the slopes: up where alpha fell short.
    assert calibration.parameters.thermal_pressure != beta
    assert (calibration.parameters.thermal_pressure > beta) == (first.value < first_target)


def test_a_property_that_missed_and_whose_iteration_failed_counts_once():
    """The failure lines of water's calibration at 20 neighbours before its background pressure (issue 24): the bulk
    modulus's judged row and its iteration's advice are one property, not two; an iteration's failure goes with the
    rows of its property; distinct rows stay distinct."""
    from openmmgendpde.calibration.results import Miss, missed_properties
    bulk_row = Miss(Property.BULK_MODULUS.quantity, "bulk modulus n dP/dn (MPa): 214.33 +- 19 against the target "
                    "2209.9", Property.BULK_MODULUS)
    bulk_iteration = Miss.of_iteration(Property.BULK_MODULUS, "bulk modulus n dP/dn: bulk_modulus 190.1 -> 570.4 moved "
                                       "it 129.1 -> 58.68 (target 1331): a response of the wrong sign")
    assert missed_properties([bulk_row] + bulk_iteration) == ["bulk modulus n dP/dn"]
    wave, flow = (Miss(p.quantity, p.label + ": 1", p) for p in (Property.VISCOSITY_WAVE, Property.VISCOSITY_FLOW))
    friction = Miss.of_iteration(Property.VISCOSITY_WAVE, "shear viscosity: friction 1 -> 3 did not move it")
    assert missed_properties([wave, flow] + friction) == ["shear viscosity, wave", "shear viscosity, Poiseuille flow"]
    conduction = Miss(Property.CONDUCTIVITY_WAVE.quantity, "1", Property.CONDUCTIVITY_WAVE)
    assert missed_properties(friction + [conduction]) == ["shear viscosity", "thermal conductivity, wave"]
    assert missed_properties([]) == [] and Miss.of_iteration(Property.DENSITY, None) == []


def made_up_thermodynamics(pressure_offset=0.0):
    """Calibration.thermodynamics replaced by made-up measurements: every target met, but the pressure, which reads
    P0 + pressure_offset/kappa_T; c_U = 0.5 k_B."""
    from openmmgendpde.calibration.calibration import Measured
    from openmmgendpde.models.fluid import KB

    def thermodynamics(self, density=None, pressure_error=None):
        t = self.parameters.targets()
        self.configurational_heat_capacity = Measured(0.5 * KB, 0.01 * KB, 50)
        return {"density": Measured(t["density"], 1e-3), "kinetic_temperature": Measured(t["temperature"], 0.1),
                "heat_capacity": self.heat_capacity(), "configurational_heat_capacity": Measured(0.5 * KB, 0.01 * KB),
                "harmonic_temperature": Measured(t["temperature"], 0.1), "self_diffusion": Measured(1e-3, 1e-5),
                "pressure": Measured(t["pressure"] + pressure_offset * t["bulk_modulus"], 1e-3)}
    return thermodynamics


@pytest.mark.parametrize("pressure_offset, viscosity_ratio, expected, frictions", [
    (0.0, 1.0, [], [1, 1 / 0.7]),
    (0.025, 0.039, ["pressure, pi0 tuned (MPa)", "shear viscosity, wave (mPa s)",
                    "shear viscosity, Poiseuille flow (mPa s)"], [1, 1 / 0.7, 3 / 0.7]),
])
def test_calibrate_reports_a_failed_calibration_and_exits_non_zero(pressure_offset, viscosity_ratio, expected,
                                                                   frictions, monkeypatch, tmp_path, capsys):
    """calibrate's judgement end to end, with the simulations replaced by made-up measurements: the waves give the
    target times friction/gamma0 x 0.7 (so the iteration must raise the friction to gamma0/0.7), the conductivity
    wave the target, the pressure P0 + pressure_offset/kappa_T whatever pi0 is, the Poiseuille flow viscosity_ratio
    x the target: a calibration that misses prints which results missed on stderr, writes them to the JSON file
    and exits with status 1; one that does not says so and returns its results. A Poiseuille flow at 0.039 of the
    target makes calibrate take one more step on it (the friction x 3, MAX_STEP), which the made-up wave then reads
    at 3 times the target: both viscosities miss."""
    from openmmgendpde.calibration.calibration import Calibration, Measured
    gamma0 = coarse_grain(WATER, 4, neighbors=20).friction

    monkeypatch.setattr(Calibration, "tune_cutoff_scaling",
                        lambda self, iterations=None: self.parameters.cutoff_scaling)
    monkeypatch.setattr(Calibration, "thermodynamics", made_up_thermodynamics(pressure_offset))
    monkeypatch.setattr(Calibration, "bulk_modulus",
                        lambda self: (Measured(self.parameters.targets()["bulk_modulus"], 1.0), Measured(1.0, 0.01)))
    monkeypatch.setattr(Calibration, "thermal_pressure", made_up_thermal_pressure)
    monkeypatch.setattr(Calibration, "shear_viscosity", lambda self: Measured(
        0.7 * self.parameters.friction / gamma0 * self.parameters.targets()["shear_viscosity"], 1e-6, 3))
    monkeypatch.setattr(Calibration, "steady_viscosity", lambda self: Measured(
        viscosity_ratio * self.parameters.targets()["shear_viscosity"], 1e-6, 3))
    for name in ("thermal_conductivity", "steady_conductivity"):
        monkeypatch.setattr(Calibration, name, lambda self: Measured(
            self.parameters.targets()["thermal_conductivity"], 1e-6, 3))
    path = tmp_path / "calibration.json"
    arguments = ["calibrate", "--quick", "--json", str(path), "--plot", str(tmp_path / "figure")]
    if expected:
        with pytest.raises(SystemExit) as exit_:
            main(arguments)
        assert exit_.value.code == 1
    else:
        main(arguments)
    captured = capsys.readouterr()
    saved = json.loads(path.read_text())
    assert [line.split(":")[0] for line in saved["missed"]] == expected
    assert saved["missed_properties"] == [name.split(" (")[0] for name in expected]
    assert [run[0] for run in saved["friction_runs"]] == pytest.approx([gamma0 * f for f in frictions], rel=1e-12)
    assert (tmp_path / "figure.png").stat().st_size > 0 and (tmp_path / "figure.pdf").stat().st_size > 0
    if expected:
        assert ("the calibration failed, 3 judged properties missed (pressure, pi0 tuned; shear viscosity, wave; "
                "shear viscosity, Poiseuille flow;" in captured.err)
        assert all(line in captured.err for line in saved["missed"])
        assert "(P - P0) kappa_T = 0.0250" in captured.err and "(model/target = 0.039)" in captured.err
        assert len(saved["pressure_rounds"]) == 2
    else:
        assert "Every judged result within its tolerance" in captured.out and captured.err == ""


def test_calibrate_iterates_the_conductivity_of_a_fluid_that_expands_on_the_heat_flux(monkeypatch, tmp_path):
    """calibrate --fluid argon-expanding end to end, with the simulations replaced by made-up measurements: the heat
    flux reads the target times kappa/(2 kappa0), so the iteration must double kappa; the energy wave, which a fluid
    that expands turns partly into sound (it read 11x the target whatever kappa was, docs/thermal.md), must not be
    called, and its rows must be absent. Everything else reads its target."""
    from openmmgendpde.calibration import calibrate as calibrate_module
    from openmmgendpde.calibration.calibration import Calibration, Measured
    kappa0 = coarse_grain(ARGON_EXPANDING, 5, neighbors=20).heat_conduction

    def wave(self):
        raise AssertionError("the energy wave was read for a fluid that expands")

    monkeypatch.setattr(Calibration, "tune_cutoff_scaling",
                        lambda self, iterations=None: self.parameters.cutoff_scaling)
    monkeypatch.setattr(Calibration, "thermodynamics", made_up_thermodynamics())
    monkeypatch.setattr(Calibration, "bulk_modulus",
                        lambda self: (Measured(self.parameters.targets()["bulk_modulus"], 1.0), Measured(1.0, 0.01)))
    monkeypatch.setattr(Calibration, "thermal_pressure", made_up_thermal_pressure)
    for name in ("shear_viscosity", "steady_viscosity"):
        monkeypatch.setattr(Calibration, name, lambda self: Measured(
            self.parameters.targets()["shear_viscosity"], 1e-6, 3))
    monkeypatch.setattr(Calibration, "thermal_conductivity", wave)
    monkeypatch.setattr(Calibration, "steady_conductivity", lambda self: Measured(
        self.parameters.targets()["thermal_conductivity"] * self.parameters.heat_conduction / (2 * kappa0), 1e-6, 3))
    monkeypatch.setattr(calibrate_module, "thermal_expansion_rows", lambda *arguments: [])   # (runs of its own)
    path = tmp_path / "calibration.json"
    main(["calibrate", "--quick", "--fluid", "argon-expanding", "--molecules-per-particle", "5", "--neighbors", "20",
          "--json", str(path)])
    saved = json.loads(path.read_text())
    assert saved["missed"] == []
    assert [run[0] / kappa0 for run in saved["heat_conduction_runs"]] == pytest.approx([1, 2], rel=1e-12)
    results = saved["results"]
    assert not [name for name in results if name.startswith("thermal conductivity, wave")]
    assert results["thermal conductivity, heat flux, kappa as mapped (W/(m K))"]["model"] == pytest.approx(
        0.5 * results["thermal conductivity, heat flux, kappa as mapped (W/(m K))"]["target"], rel=1e-9)
    assert results["thermal conductivity, heat flux (W/(m K))"]["model"] == pytest.approx(
        results["thermal conductivity, heat flux (W/(m K))"]["target"], rel=1e-9)


@pytest.mark.parametrize("arguments, message", [
    (["--particles", "1000"], "argument --particles: 1000 is not allowed; it must be 4 m^3 for an integer m from 1 "
                              "to 100 (500, 864, 2048, 4000, ..."),
    (["--particles", "0"], "argument --particles: 0 is not allowed"),
    (["--molecules-per-particle", "-1"], "argument --molecules-per-particle: -1 is not allowed; it must be a finite "
                                         "number > 0"),
    (["--neighbors", "1e6"], "is less than twice the cutoff 30.599 nm across; use more --particles, or fewer "
                             "--neighbors (a smaller --cutoff)"),
    (["--cutoff", "100"], "is less than twice the cutoff 100.000 nm across"),
    (["--neighbors", "0"], "argument --neighbors: 0 is not allowed; it must be a finite number > 0"),
    (["--platform", "Nope"], "argument --platform: invalid choice: 'Nope'"),
])
def test_calibrate_refuses_bad_arguments_in_one_line(arguments, message):
    """Bad arguments: a one-line error naming the option (not the Python argument behind it) and the value on stderr
    (after argparse's usage for an option it checks itself), exit status non-zero, no traceback, nothing run."""
    result = subprocess.run([sys.executable, "-m", "openmmgendpde", "calibrate", "--quick"] + arguments,
                            capture_output=True, text=True, timeout=120)
    assert result.returncode != 0 and result.stdout == ""
    assert "Traceback" not in result.stderr
    last = result.stderr.splitlines()[-1]
    assert message in last
    assert not any(name in last for name in ("num_particles", "molecules_per_particle", "give cells", "more cells"))


@pytest.mark.validation
def test_calibrate_quick_on_water(tmp_path):
    """`calibrate --quick` sets water up and measures it back (a functional check: 500 particles, short runs).
    What is asserted is what the run controls: f_cut tuned so that n-bar is within 2% of n0 (two secant steps on
    ~1% statistical errors), the isoenergetic runs start at T0 and conserve energy (harmonic mean of theta_i within
    1%), every measured property finite with a finite error."""
    path = tmp_path / "water.json"
    try:
        results = main(["calibrate", "--quick", "--fluid", "water", "--platform", "CPU", "--json", str(path)])
    except SystemExit as exit_:
        assert exit_.code == 1
        results = None
    saved = json.loads(path.read_text())
    # --quick's transport coefficients are functional checks (boxes too small for their targets: QUICK_CRITERIA);
    # what it controls, the thermodynamics, must be within the criteria.
    assert all(line.startswith(("shear viscosity", "thermal conductivity", "bulk modulus"))
               for line in saved["missed"])
    # The first pressure round starts at the mapping, and the friction moves towards the target (the model's
    # viscosity is below its target as mapped).
    assert len(saved["pressure_rounds"]) >= 1 and len(saved["friction_runs"]) >= 1
    saved = saved["results"]
    results = results or saved
    assert saved.keys() == results.keys()
    for name, entry in results.items():
        assert saved[name] == pytest.approx(entry), name
    density = results["density n-bar (nm^-3)"]
    assert density["model"] == pytest.approx(density["target"], rel=0.02)
    temperature = results["harmonic mean of theta_i (K)"]
    assert temperature["model"] == pytest.approx(temperature["target"], rel=0.01)
    for entry in results.values():
        assert math.isfinite(entry["model"]) and math.isfinite(entry["error"]) and entry["error"] >= 0


def made_up_model(mapped):
    """A made-up equation of state of the model: what each of calibrate's equilibrium measurements reads for
    parameters p, exactly (no noise), as a function of f_cut, pi0, B_T and beta, so that a measurement of any model
    can be computed here: n-bar = n0 f_cut/1.35; P = P0 + 0.5 (pi0 - pi0 mapped) + 0.3 K (f_cut - 1.35) + 0.02 K
    (beta/beta mapped - 1) (K = 1/kappa_T); n dP/dn = 0.5 K (B_T/B_T mapped) (f_cut/1.35)^4; (dP/dT)_n = n0 k_B (2 +
    f_cut) (1 + beta/beta mapped); c_U = 0.5 k_B."""
    from openmmgendpde.models.fluid import KB

    def measure(p):
        t = p.targets()
        beta = p.thermal_pressure / mapped.thermal_pressure if mapped.thermal_pressure else 1.0
        return {"density": t["density"] * p.cutoff_scaling / 1.35,
                "pressure": t["pressure"] + 0.5 * (p.reference_pressure - mapped.reference_pressure)
                + 0.3 * t["bulk_modulus"] * (p.cutoff_scaling - 1.35) + 0.02 * t["bulk_modulus"] * (beta - 1),
                "bulk_modulus": 0.5 * t["bulk_modulus"] * p.bulk_modulus / mapped.bulk_modulus
                * (p.cutoff_scaling / 1.35) ** 4,
                "thermal_pressure": p.density * KB * (2 + p.cutoff_scaling) * (1 + beta),
                "heat_capacity": p.heat_capacity + KB + 1.5 * KB + 0.5 * KB}
    return measure


@pytest.mark.parametrize("fluid, molecules", [("water", 4), ("argon-expanding", 5)])
def test_the_report_is_a_measurement_of_the_written_model(fluid, molecules, monkeypatch, tmp_path):
    """Every equilibrium number of calibrate's report (density, pressure, c_v, n dP/dn and the particle-density
    response, the speed of sound) is a measurement of the model it writes (--output), issue 54: water's report said
    n dP/dn = 0.996 of the target where its written model measured 0.969 +- 0.007 (the bulk modulus was measured before
    the last round of f_cut and pi0). The simulations are replaced by a made-up equation of state of the model
    (made_up_model: each measurement an exact function of f_cut, pi0, B_T and beta), so that the measurement of the
    written model is computed here, from the file, independently of the run. Water: the B_T iteration (0.5 of the
    target as mapped) moves B_T, then two more rounds of f_cut (each tuning moves it by +0.01) and pi0 move n dP/dn
    by ~3% (thousands of its made-up error, 1 kJ/mol/nm^3). argon-expanding: the thermal-expansion stage (made up:
    beta x 1.5) comes after the thermodynamics and the bulk modulus, and moves the pressure by 0.01 K. Expected:
    equal to 1e-9 (the made-up measurements have no noise). The speed of sound: sqrt(K_S/rho), K_S = K_T + T
    (dP/dT)_n^2/(n c_v), computed here in SI."""
    from openmmgendpde.calibration import calibrate as calibrate_module
    from openmmgendpde.calibration import expansion
    from openmmgendpde.calibration.calibration import Calibration, Measured
    from openmmgendpde.calibration.report import mpa
    from openmmgendpde.models.fluid_files import load_parameters
    mapped = coarse_grain({"water": WATER, "argon-expanding": ARGON_EXPANDING}[fluid], molecules, neighbors=20)
    measure = made_up_model(mapped)

    def thermodynamics(self, density=None, pressure_error=None):
        m = measure(self.parameters)
        self.configurational_heat_capacity = Measured(0.5 * KB, 0.01 * KB, 50)
        t = self.parameters.targets()
        return {"density": Measured(m["density"], 1e-3), "pressure": Measured(m["pressure"], 1e-3),
                "kinetic_temperature": Measured(t["temperature"], 0.1),
                "harmonic_temperature": Measured(t["temperature"], 0.1), "self_diffusion": Measured(1e-3, 1e-5),
                "heat_capacity": self.heat_capacity(), "configurational_heat_capacity": Measured(0.5 * KB, 0.01 * KB)}

    def tune(self, iterations=None):
        self.parameters = self.parameters.with_cutoff_scaling(self.parameters.cutoff_scaling + 0.01)
        return self.parameters.cutoff_scaling

    def expansion_rows(calibration, plan, platform, seed, report=print, history=None):
        calibration.parameters = calibration.parameters.with_thermal_pressure(1.5 * mapped.thermal_pressure)
        slope = measure(calibration.parameters)["thermal_pressure"] * expansion.MPA_PER_OPENMM_PRESSURE
        if history is not None:
            history.append(dataclasses.replace(expansion.ThermalExpansion(*[0.0] * 11), slope=slope,
                                               slope_error=0.0))
        return []

    monkeypatch.setattr(Calibration, "tune_cutoff_scaling", tune)
    monkeypatch.setattr(Calibration, "thermodynamics", thermodynamics)
    monkeypatch.setattr(Calibration, "bulk_modulus", lambda self: (
        Measured(measure(self.parameters)["bulk_modulus"], 1.0), Measured(0.9 * self.parameters.cutoff_scaling, 0.01)))
    monkeypatch.setattr(Calibration, "thermal_pressure",
                        lambda self, seed=None: Measured(measure(self.parameters)["thermal_pressure"], 0.0),
                        raising=False)   # (raising: the test runs on the code before Calibration.thermal_pressure too)
    for name, target in (("shear_viscosity", "shear_viscosity"), ("steady_viscosity", "shear_viscosity"),
                         ("thermal_conductivity", "thermal_conductivity"),
                         ("steady_conductivity", "thermal_conductivity")):
        monkeypatch.setattr(Calibration, name, lambda self, target=target: Measured(
            self.parameters.targets()[target], 1e-6, 3))
    monkeypatch.setattr(calibrate_module, "thermal_expansion_rows", expansion_rows)
    path, output = tmp_path / "calibration.json", tmp_path / "model.toml"
    try:
        main(["calibrate", "--quick", "--fluid", fluid, "--molecules-per-particle", str(molecules), "--neighbors",
              "20", "--json", str(path), "--output", str(output)])
    except SystemExit as exit_:
        assert exit_.code == 1   # (a miss: the made-up pressure need not reach its target)
    written = load_parameters(str(output))
    assert written.cutoff_scaling > mapped.cutoff_scaling + 0.015 and written.bulk_modulus != mapped.bulk_modulus
    if fluid == "argon-expanding":
        assert written.thermal_pressure == pytest.approx(1.5 * mapped.thermal_pressure, rel=1e-9)
    expected = measure(written)
    results = json.loads(path.read_text())["results"]
    assert results[Property.DENSITY.label]["model"] == pytest.approx(expected["density"], rel=1e-9)
    assert results[Property.PRESSURE.label]["model"] == pytest.approx(mpa(expected["pressure"]), rel=1e-9)
    assert results[Property.BULK_MODULUS.label]["model"] == pytest.approx(mpa(expected["bulk_modulus"]), rel=1e-9)
    assert results["particle-density response (n/n-bar) dn-bar/dn"]["model"] == pytest.approx(
        0.9 * written.cutoff_scaling, rel=1e-9)
    assert results[Property.HEAT_CAPACITY.label]["model"] == pytest.approx(
        expected["heat_capacity"] * 1e3 / (written.mass * 1e-3), rel=1e-9)
    # The speed of sound in SI: K (Pa) = kJ/mol/nm^3 x 1e3 x 1e27 / N_A; rho (kg/m^3) = n0 (nm^-3) x 1e27 x m (amu)
    # x 1e-3/N_A; c_v per particle (J/K) = kJ/mol/K x 1e3/N_A.
    n, temperature = written.density * 1e27, written.temperature
    modulus = expected["bulk_modulus"] * 1e30 / N_A
    thermal = expected["thermal_pressure"] * 1e30 / N_A
    heat = expected["heat_capacity"] * 1e3 / N_A
    sound = math.sqrt((modulus + temperature * thermal**2 / (n * heat)) / (n * written.mass * 1e-3 / N_A))
    row = next(name for name in results if name.startswith("not fitted: speed of sound"))
    assert results[row]["model"] == pytest.approx(sound, rel=1e-9)
    assert json.loads(path.read_text())["thermal_pressure_mpa_per_k"][0] == pytest.approx(
        mpa(expected["thermal_pressure"]), rel=1e-9)


@pytest.mark.parametrize("quick", [False, True])
def test_calibrate_reports_the_sound_wave_beside_the_derived_speed(monkeypatch, tmp_path, quick):
    """calibrate on made-up measurements (helpers.fake_calibration), the sound wave made up to read 1.02 x the speed it
    is given: without --quick the row "measured: speed of sound, sound wave (m/s)" follows the derived row and reads
    1.02 x it (so the wave runs on the derived speed, in m/s like it), its samples the replicas (4, Plan's); with
    --quick the wave is not run and its row is absent. The derived speed is independent of the wave: sqrt(K_S/rho)
    from the made-up K_T (the target), (dP/dT)_n = 3 n0 k_B and c_v, computed here in SI."""
    from helpers import fake_calibration

    from openmmgendpde.calibration.calibration import Calibration, Measured
    from openmmgendpde.calibration.report import SOUND_ROW, SOUND_WAVE_ROW
    mapped = coarse_grain(WATER, 4, neighbors=20)
    fake_calibration(monkeypatch, mapped)
    given = []

    def sound_speed(self, estimate):
        assert not quick, "the sound wave ran with --quick"
        given.append(estimate)
        return Measured(1.02 * estimate, 0.01 * estimate, self.plan.replicas)

    monkeypatch.setattr(Calibration, "sound_speed", sound_speed)
    path = tmp_path / "calibration.json"
    main(["calibrate", "--fluid", "water", "--json", str(path)] + (["--quick"] if quick else []))
    results = json.loads(path.read_text())["results"]
    names = list(results)
    derived = results[SOUND_ROW]["model"]
    t = mapped.targets()
    n, temperature, mass = t["density"] * 1e27, t["temperature"], mapped.mass * 1e-3 / N_A
    modulus = t["bulk_modulus"] * 1e3 * 1e27 / N_A                       # Pa
    thermal, heat = 3 * n * K_B, results[Property.HEAT_CAPACITY.label]["model"] * mass   # Pa/K; J/K per particle
    assert derived == pytest.approx(math.sqrt((modulus + temperature * thermal**2 / (n * heat)) / (n * mass)), rel=1e-9)
    if quick:
        assert SOUND_WAVE_ROW not in results and given == []
        return
    assert given == [pytest.approx(derived * 1e-3, rel=1e-12)]
    assert names.index(SOUND_WAVE_ROW) == names.index(SOUND_ROW) + 1
    assert results[SOUND_WAVE_ROW]["model"] == pytest.approx(1.02 * derived, rel=1e-12)
    assert results[SOUND_WAVE_ROW]["error"] == pytest.approx(0.01 * derived, rel=1e-12)
    assert results[SOUND_WAVE_ROW]["samples"] == 4
    assert results[SOUND_WAVE_ROW]["target"] == results[SOUND_ROW]["target"] == pytest.approx(1496.7)
