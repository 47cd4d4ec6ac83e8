"""calibrate (openmmgendpde.calibration): the judgement of a calibration, its iterations, its stages on made-up
measurements and in short runs, and the measurements it rests on (heat capacity, thermal expansion, stability)."""

import dataclasses
import json
import math
import subprocess
import sys

import numpy as np
import pytest
from openmm import unit

from openmmgendpde.__main__ import main
from openmmgendpde.calibration.results import Property
from openmmgendpde.models.fluid import (
    ARGON,
    ARGON_EXPANDING,
    WATER,
    coarse_grain,
    set_temperature_field,
)
from openmmgendpde.models.lattice import fcc_box

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


def _calibration(plan=None):
    from openmmgendpde.calibration.calibration import QUICK, Calibration
    return Calibration(coarse_grain(WATER, 4, neighbors=20), "VB", plan or QUICK, "Reference", report=lambda _: None)


def test_transport_iteration_reaches_a_linear_response_by_secant_steps():
    """A made-up response eta(gamma) = target (0.1 + 0.3 gamma/gamma0) (a floor of 0.1 target; 0.4 of the target as
    mapped): the proportional first step gives gamma0/0.4 (0.85 of the target), then the secant through the two
    measurements (errors tiny) lands exactly on gamma = 3 gamma0: three measurements, the friction 3 gamma0 and the
    viscosity the target to 1e-12."""
    from openmmgendpde.calibration.calibration import Measured, Plan
    calibration = _calibration(Plan(transport_runs=4))
    gamma0, target = calibration.parameters.friction, 1.0

    def measure():
        return Measured(target * (0.1 + 0.3 * calibration.parameters.friction / gamma0), 1e-6)

    measured, history, failure = calibration.iterate("friction", measure, target, "shear viscosity", 4)
    assert failure is None and len(history) == 3
    assert history[1][0] == pytest.approx(gamma0 / 0.4, rel=1e-12)
    assert calibration.parameters.friction == pytest.approx(3 * gamma0, rel=1e-12)
    assert measured.value == pytest.approx(target, rel=1e-12)


def test_an_iteration_steps_on_a_miss_beyond_one_standard_error():
    """Water's first energy wave read 1.74 +- 0.27 (relative, 4 replicas) of the target: inside the 95% interval
    that judges a result (3.18 standard errors for 4 replicas), but a miss of 2.7 standard errors, so the iteration
    steps (proportional: kappa / 1.74) instead of stopping there; the next reading, 1.03 +- 0.02, is within 5% and
    stops it. A reading of 1.08 +- 0.10 (within one standard error) stops it at once."""
    from openmmgendpde.calibration.calibration import Measured, Plan, _reached, _settled
    first = Measured(1.74, 0.27, 4)
    assert _reached(first, 1.0) and not _settled(first, 1.0)
    assert _settled(Measured(1.08, 0.10, 4), 1.0) and not _settled(Measured(1.08, 0.07, 4), 1.0)
    calibration = _calibration(Plan(transport_runs=4))
    kappa0 = calibration.parameters.heat_conduction
    readings = iter([first, Measured(1.03, 0.02, 4)])
    measured, history, failure = calibration.iterate("heat_conduction", lambda: next(readings), 1.0,
                                                     "thermal conductivity", 4)
    assert failure is None and len(history) == 2 and measured.value == 1.03
    assert calibration.parameters.heat_conduction == pytest.approx(kappa0 / 1.74, rel=1e-12)
    readings = iter([Measured(1.08, 0.10, 4)])
    _, history, _ = calibration.iterate("heat_conduction", lambda: next(readings), 1.0, "thermal conductivity", 4)
    assert len(history) == 1


def test_transport_iteration_stops_at_the_floor_of_the_model():
    """eta(gamma) = target (1.3 + 0.5 gamma/gamma0): no friction >= 0 reaches the target; after the proportional
    step the secant's intercept (1.3 target) is above it, and the iteration stops naming the floor."""
    from openmmgendpde.calibration.calibration import Measured, Plan
    calibration = _calibration(Plan(transport_runs=4))
    gamma0 = calibration.parameters.friction

    def measure():
        return Measured(1.3 + 0.5 * calibration.parameters.friction / gamma0, 1e-6)

    _, history, failure = calibration.iterate("friction", measure, 1.0, "shear viscosity", 4)
    assert len(history) == 2
    assert failure.startswith("shear viscosity: the model's shear viscosity without its friction is 1.3 (the "
                              "secant's intercept), above the target 1: no friction reaches it; friction kept at")
    assert "coarse-grain differently" in failure   # and the friction is the better of the two runs
    assert calibration.parameters.friction == pytest.approx(gamma0 / 1.8, rel=1e-12)


def test_bulk_modulus_iteration_stops_when_b_t_does_not_raise_it():
    """What water does with 20 neighbours (docs/fluids.md): n dP/dn = 531 MPa at B_T as mapped and 425 at 5 B_T.
    A made-up response K(B_T) = 0.24 target - 0.024 target (B_T/B_T0 - 1) (falls as B_T rises): after the
    proportional step (B_T0/0.24, limited to 3 B_T0 by MAX_STEP) the measured response has the wrong sign, and the
    iteration stops saying so and naming the remedy (more neighbours), B_T back at B_T0 (the better of the two)."""
    from openmmgendpde.calibration.calibration import Measured, Plan
    calibration = _calibration(Plan(bulk_runs=3))
    b0 = calibration.parameters.bulk_modulus

    def measure():
        return Measured(0.24 - 0.024 * (calibration.parameters.bulk_modulus / b0 - 1), 1e-4)

    _, history, failure = calibration.iterate("bulk_modulus", measure, 1.0, "bulk modulus n dP/dn", 3)
    assert [x for x, _ in history] == pytest.approx([b0, 3 * b0], rel=1e-12)
    assert calibration.parameters.bulk_modulus == b0
    assert "a response of the wrong sign, no bulk_modulus reaches the target" in failure
    assert "use more neighbours within the cutoff" in failure


def test_an_iteration_out_of_runs_keeps_the_best_parameter():
    """Two runs on a flat response (K = 0.18 target +- 0.01 whatever B_T): the proportional step multiplies B_T by
    1/0.18 and moves nothing; the iteration keeps B_T0 (the measurement closest to the target, the first) and says
    that B_T did not move n dP/dn. On a response that moves but needs more runs, it keeps the best, no failure."""
    from openmmgendpde.calibration.calibration import Measured, Plan
    calibration = _calibration(Plan())
    b0 = calibration.parameters.bulk_modulus
    values = iter([0.18, 0.17])
    _, history, failure = calibration.iterate("bulk_modulus", lambda: Measured(next(values), 0.01), 1.0,
                                              "bulk modulus n dP/dn", 2)
    assert calibration.parameters.bulk_modulus == b0 and len(history) == 2
    assert "did not move it" in failure and "use more neighbours" in failure
    # Closer to the target but within 2 standard errors of the first (0.158 +- 0.04 against 0.092 +- 0.02, water's
    # B_T x 9): not a measured effect, the mapped B_T is kept.
    values = iter([0.092, 0.158])
    _, history, failure = calibration.iterate("bulk_modulus", lambda: Measured(next(values), 0.02 + 0.02 * (
        calibration.parameters.bulk_modulus != b0)), 1.0, "bulk modulus n dP/dn", 2)
    assert history[1][0] == pytest.approx(3 * b0) and calibration.parameters.bulk_modulus == b0
    assert "did not move it" in failure
    gamma0 = calibration.parameters.friction
    best, history, failure = calibration.iterate(
        "friction", lambda: Measured(0.5 * calibration.parameters.friction / gamma0 + 0.2,
                                     1e-3), 1.0, "shear viscosity", 2)
    assert failure is None and best.value == pytest.approx(0.2 + 0.5 / 0.7)
    assert calibration.parameters.friction == pytest.approx(gamma0 / 0.7)


def test_an_iteration_out_of_runs_after_a_small_step_is_no_failure():
    """Water's friction: 8855 -> 8059 (a step of 9%) read 593 +- 52 -> 596 +- 11 (target 536): a proportional
    response would have moved it by 53, within 2 standard errors of the difference (106), so the step says nothing
    about the friction's effect and the iteration keeps the better parameter without a failure."""
    from openmmgendpde.calibration.calibration import Measured, Plan
    calibration = _calibration(Plan())
    gamma0 = calibration.parameters.friction
    readings = iter([Measured(592.8, 52.0, 4), Measured(596.1, 11.0, 4)])
    _, history, failure = calibration.iterate("friction", lambda: next(readings), 536.0, "shear viscosity", 2)
    assert len(history) == 2 and history[1][0] == pytest.approx(gamma0 * 536.0 / 592.8, rel=1e-12)
    assert failure is None


def test_a_step_on_the_steady_flow_supersedes_the_wave_iteration_s_failure():
    """Water's energy waves read kappa 12367 -> 22526 as no move (a failure that keeps 22526); the heat flux then
    read 0.72 of the target and moved kappa, and both methods were measured again: the failure no longer describes
    the kappa calibrate ends with, which CRITERIA judges by both methods, so it is dropped. Where the steady flow is
    within 5% no step is taken and the iteration's failure stands."""
    from openmmgendpde.calibration.calibration import Measured, Plan
    calibration = _calibration(Plan())
    kappa = calibration.parameters.heat_conduction
    history = [(kappa / 2, Measured(0.274, 0.034, 4)), (kappa, Measured(0.310, 0.047, 4))]
    failure = "thermal conductivity: heat_conduction did not move it; heat_conduction kept at ..."
    steady = iter([Measured(0.262, 0.011, 4), Measured(0.364, 0.013, 4)])
    result, wave, kept = calibration.steady_correction(
        "heat_conduction", lambda: next(steady), lambda: Measured(0.370, 0.04, 4), history, 0.365,
        "thermal conductivity", failure)
    assert kept is None and result.value == 0.364 and wave.value == 0.370
    assert calibration.parameters.heat_conduction > kappa and len(history) == 3
    result, wave, kept = calibration.steady_correction(
        "heat_conduction", lambda: Measured(0.360, 0.013, 4), lambda: pytest.fail("no step expected"), history,
        0.365, "thermal conductivity", failure)
    assert kept == failure and wave is None


def test_elasticity_of_an_iteration():
    """d ln(m)/d ln(x) from the last two runs: 0.5 for m ~ sqrt(x); 1 when the difference is not measured (within 2
    standard errors) or of the wrong sign; limited to [1/3, 3]."""
    from openmmgendpde.calibration.calibration import Measured, _elasticity
    assert _elasticity([(1.0, Measured(1.0, 1e-4)), (4.0, Measured(2.0, 1e-4))]) == pytest.approx(0.5)
    assert _elasticity([(1.0, Measured(1.0, 0.5)), (4.0, Measured(2.0, 0.5))]) == 1.0
    assert _elasticity([(1.0, Measured(2.0, 1e-4)), (4.0, Measured(1.0, 1e-4))]) == 1.0
    assert _elasticity([(1.0, Measured(1.0, 1e-4)), (1.01, Measured(2.0, 1e-4))]) == 3.0
    assert _elasticity([(1.0, Measured(1.0, 1e-4))]) == 1.0


def test_pressure_step_is_a_secant_on_measured_responses():
    from openmmgendpde.calibration.calibration import Measured, pressure_step
    assert pressure_step([(-20.0, Measured(10.0, 1.0))], 0.0) == -10.0
    # A response of 0.5 measured (P moved by -5 for pi0 moved by -10), errors small: the step is (0 - 5)/0.5.
    assert pressure_step([(-20.0, Measured(10.0, 1.0)), (-30.0, Measured(5.0, 1.0))], 0.0) == pytest.approx(-10.0)
    # Not a measured response (a difference within 2 standard errors): the step is P0 - P.
    assert pressure_step([(-20.0, Measured(10.0, 3.0)), (-30.0, Measured(5.0, 3.0))], 0.0) == -5.0
    # A response beyond [0.25, 4] is clipped.
    assert pressure_step([(-20.0, Measured(10.0, 0.01)), (-21.0, Measured(9.9, 0.01))], 0.0) == pytest.approx(-39.6)


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


@pytest.mark.validation
def test_stability_criterion_separates_a_good_step_from_a_blow_up():
    """The step-size test of openmmgendpde.calibration.stability on argon (V-B, Isoenergetic, 500 particles): dt* = 0.01
    (the step of every argon study here, 10^5-step runs without a failure, docs/argon.md) passes; dt* = 1 (a particle
    crosses a neighbour's range in a few steps) fails."""
    from openmmgendpde.calibration.stability import _passes
    parameters = coarse_grain(ARGON, 5, neighbors=20)
    assert _passes(parameters, "VB", "Isoenergetic", 0.01, 1000, 500, "CPU", 1)
    assert not _passes(parameters, "VB", "Isoenergetic", 1.0, 1000, 500, "CPU", 1)


@pytest.mark.validation
def test_suggested_vc_step_drifts_at_a_free_surface_as_little_as_vb_at_its_own(monkeypatch):
    """suggest_time_step for V-C against the measured energy drift at a free surface (docs/interfaces.md, "V-C's
    energy error"). The stability limits (measured on a bulk liquid, where V-C is V-B) are set to V-B's measured
    Isoenergetic limit 0.134 (docs/fluids.md) so that only the estimator's own rule differs. Then a 1000-particle
    argon droplet in vacuum runs 10 time units from the lattice with each estimator at its suggested step, and the
    change of K + U + sum eps per N k_B T0 is compared: measured -2.1e-4 (V-B at 0.067) and -2.1e-4 (V-C at 0.0067);
    at V-B's step V-C's is -2.1e-2, a hundred times more, as it was before V-C had its own step. Tolerance: V-C's
    error within a factor 2 of V-B's either way (over seeds 5-7 the ratio was 1.0-1.25)."""
    from openmmgendpde.calibration import stability
    from openmmgendpde.studies.slab import argon_model, droplet_positions
    monkeypatch.setattr(stability, "largest_stable_step", lambda *arguments, **options: 0.134)
    parameters = coarse_grain(ARGON, 5, neighbors=20)
    errors, steps = {}, {}
    for estimator in ("VB", "VC"):
        steps[estimator], step = stability.suggest_time_step(parameters, estimator)
        positions, box, _ = droplet_positions()
        model, _context = argon_model(positions, box, estimator, platform="CPU", seed=5)
        model.integrator.setStepSize(step)
        kt = (unit.MOLAR_GAS_CONSTANT_R * model.temperature).value_in_unit(unit.kilojoule_per_mole) * len(positions)
        start = model.integrator.getConservedEnergy().value_in_unit(unit.kilojoule_per_mole)
        model.integrator.step(int(round(10.0 / steps[estimator])))
        errors[estimator] = (model.integrator.getConservedEnergy().value_in_unit(unit.kilojoule_per_mole) - start) / kt
    assert steps["VB"] == pytest.approx(0.067)
    assert 0.5 < errors["VC"] / errors["VB"] < 2, (steps, errors)


def test_conduction_wave_decays_at_the_rate_of_the_lattice_sum():
    """A case with a known answer for the wave-decay measurement that calibrate uses for the conductivity: particles
    on an FCC lattice too heavy to move (1e9 amu: they drift 1e-5 of a spacing), no conservative force, no friction,
    only heat conduction (a GenDPDEForce is in the System only to make it periodic: OpenMM's System is periodic when
    a force is; its forces move nothing here). A wave theta_i = T0 (1 + e sin(k z_i)) (e = 0.1) then obeys, to first
    order in e, d theta_i/dt = kappa/(C_V T0^2) sum_j omega_q(r_ij) (theta_j - theta_i), so its amplitude decays at
    exactly
        Gamma = kappa/(C_V T0^2) sum_j omega_q(r_0j) (1 - cos(k z_0j))
    (every lattice site alike; the sum over one site's neighbours, computed here with numpy). Measured: the mean of
    4 replicas (the conductive noise averages out) fitted by calibrate's decay fit, dt small against 1/Gamma (50
    steps per decay time, Shardlow error ~1%); tolerance 5% (second order in e ~1%, the noise left ~2%)."""
    import openmm

    from openmmgendpde import GenDPDEForce, GenDPDEIntegrator
    from openmmgendpde.calibration.calibration import _decay_rate
    density, temperature, heat_capacity, kappa = 8.0, 300.0, 0.3, 2.0e4
    positions, box = fcc_box(density, (4, 4, 8))
    cutoff = 0.9
    edges = np.diag(box)
    k = 2 * np.pi / edges[2]
    delta = positions - positions[0]
    delta -= edges * np.round(delta / edges)
    r = np.sqrt((delta**2).sum(axis=1))
    near = (r > 0) & (r < cutoff)
    omega = (1 - r[near] / cutoff) ** 2
    expected = kappa / (heat_capacity * temperature**2) * np.sum(omega * (1 - np.cos(k * delta[near, 2])))
    curves = []
    dt = 1 / (50 * expected)
    for seed in range(1, 5):
        system = openmm.System()
        system.setDefaultPeriodicBoxVectors(*[openmm.Vec3(*row) for row in box])
        for _ in positions:
            system.addParticle(1e9)
        periodic = GenDPDEForce(cutoff)
        periodic.setNonbondedMethod(GenDPDEForce.CutoffPeriodic)
        system.addForce(periodic)
        integrator = GenDPDEIntegrator(dt, 0.0, kappa, heat_capacity)
        integrator.setCutoffDistance(cutoff)
        integrator.setRandomNumberSeed(seed)
        context = openmm.Context(system, integrator, openmm.Platform.getPlatformByName("CPU"))
        context.setPositions(positions)
        set_temperature_field(integrator, positions, lambda p: temperature * (1 + 0.1 * np.sin(k * p[2])))
        amplitudes = []
        for n in range(41):
            if n:
                integrator.step(5)
            theta = integrator.getParticleTemperatures().value_in_unit(unit.kelvin)
            amplitudes.append(2 * np.mean(theta * np.sin(k * positions[:, 2])))
        curves.append(amplitudes)
    times = dt * 5 * np.arange(41)
    measured = _decay_rate(times, np.mean(curves, axis=0))
    print(f"lattice-sum decay rate {expected:.5f}/ps, measured {measured:.5f}/ps")
    assert measured == pytest.approx(expected, rel=0.05)


def test_speed_of_sound_of_an_ideal_monatomic_gas():
    """calibrate.speed_of_sound with K_T = n k_B T and the heat capacity of the motion alone (c = 3 k_B/2): the ideal
    monatomic gas, c = sqrt(5 k_B T/(3 m)) (argon atoms at 300 K: 322.6 m/s, computed here in SI)."""
    from openmmgendpde.calibration.calibration import Measured
    from openmmgendpde.calibration.report import speed_of_sound
    from openmmgendpde.models.fluid import KB
    gas = dataclasses.replace(coarse_grain(ARGON, 1, neighbors=20), heat_capacity=0.0, temperature=300.0,
                              mass=39.948)
    result = speed_of_sound(gas, Measured(gas.density * KB * 300.0, 0.0), 1.5 * KB)
    expected = math.sqrt(5 * 1.380649e-23 * 300.0 / (3 * 39.948 * 1.66053906660e-27))   # m/s
    assert result.value * 1e3 == pytest.approx(expected, rel=1e-6)
    assert expected == pytest.approx(322.6, abs=0.1)


@pytest.mark.validation
def test_model_heat_capacity_from_fluctuations_equals_the_energy_it_takes():
    """Calibration.heat_capacity (C_V + k_B + 3 k_B/2 + c_U, c_U from the fluctuation of U in an Isoenergetic run at
    T0) against what a temperature change at fixed volume costs: the conserved energy E = K + U + sum eps_i of
    Isoenergetic runs started at T0 (1 -+ 10%), over the change of their harmonic-mean temperatures, per particle.
    Argon, 5 atoms per particle, 500 particles. Expected: the same c within 3 standard errors of the difference
    (c_U's error from the fluctuation, ~0.1 k_B of c ~ 15.4 k_B; the temperatures' means, ~0.3% of the 25 K
    difference). Leaving out the k_B of the internal energies' Gamma law (6% of c) fails it."""
    from openmmgendpde.analysis.statistics import correlated_mean
    from openmmgendpde.analysis.thermodynamics import ThermodynamicProbe
    from openmmgendpde.calibration.calibration import QUICK, Calibration
    from openmmgendpde.models.fluid import KB
    u = unit
    parameters = coarse_grain(ARGON, 5, neighbors=20)
    plan = dataclasses.replace(QUICK, frames=300, interval=20)
    calibration = Calibration(parameters, "VB", plan, "CPU", seed=3, report=lambda *a: None)
    measured = calibration.heat_capacity()
    energies, temperatures = [], []
    for factor in (0.9, 1.1):
        run = Calibration(dataclasses.replace(parameters, temperature=factor * parameters.temperature), "VB", plan,
                          "CPU", seed=5, report=lambda *a: None)
        model, context = run._equilibrated()
        probe = ThermodynamicProbe(model.system)
        samples = []
        for _ in range(100):
            model.integrator.step(20)
            samples.append(probe.sample(context.getState(getEnergy=True, getVelocities=True), context,
                                        model.integrator))
        energies.append(np.mean([s.conserved_energy.value_in_unit(u.kilojoule_per_mole) for s in samples]))
        temperatures.append(correlated_mean([s.harmonic_temperature.value_in_unit(u.kelvin) for s in samples]))
    n = model.system.getNumParticles()
    difference = (energies[1] - energies[0]) / n / (temperatures[1].mean - temperatures[0].mean)
    error = difference * math.hypot(temperatures[0].standard_error, temperatures[1].standard_error) / (
        temperatures[1].mean - temperatures[0].mean)
    print(f"c = {measured.value / KB:.3f} +- {measured.error / KB:.3f} k_B from fluctuations, "
          f"{difference / KB:.3f} +- {error / KB:.3f} k_B from the energy")
    assert abs(measured.value - difference) < 3 * math.hypot(measured.error, error)


def test_one_correction_of_beta_scales_the_thermal_part_of_the_slope():
    """expansion.corrected: (dP/dT)_V = n0 k_B + X beta (1 + k_B/C), linear in beta with the estimator's response X,
    so beta' = beta (target - n0 k_B)/(measured - n0 k_B). A measured slope equal to the target leaves beta as it is;
    one whose thermal part is half the target's doubles it."""
    from openmmgendpde.calibration.expansion import MPA_PER_OPENMM_PRESSURE, ThermalExpansion, corrected, mapped
    parameters = mapped()
    kinetic = parameters.density * K_B * N_A / 1000 * MPA_PER_OPENMM_PRESSURE   # n0 k_B in MPa/K
    target = 1.7718

    def result(slope):
        return ThermalExpansion(temperatures=(0, 0), temperature_errors=(0, 0), pressures=(0, 0),
                                pressure_errors=(0, 0), slope=slope,
                                slope_error=0, target_slope=target, alpha=0, alpha_error=0, target_alpha=0,
                                thermal_pressure=parameters.thermal_pressure)
    assert corrected(parameters, result(target)).thermal_pressure == pytest.approx(parameters.thermal_pressure,
                                                                                   rel=1e-12)
    half = kinetic + (target - kinetic) / 2
    assert corrected(parameters, result(half)).thermal_pressure == pytest.approx(2 * parameters.thermal_pressure,
                                                                                 rel=1e-12)


def test_beta_is_iterated_on_the_measured_slope_until_alpha_reaches_the_target(monkeypatch):
    """calibrate's thermal-expansion stage with made-up measurements whose slope is not proportional to beta:
    (dP/dT)_V = n0 k_B + 0.4 g(beta/beta0) s_t with g(x) = x^0.5 (a structure that absorbs part of each shift), s_t
    the target's thermal part, with a standard error of 1% of the target. One proportional correction (the old rule)
    leaves the thermal part at 0.4 sqrt(2.5) = 0.63 of the target's; the iteration's secant steps must reach alpha
    within 5% in at most EXPANSION_RUNS measurements, and keep the last beta. Expected from the law:
    beta -> 6.25 beta0 (g = 2.5), within 10% (the secant approaches it from below: 1, 2.5, 4.9, 6.0)."""
    from openmmgendpde.calibration import calibrate as calibrate_module
    from openmmgendpde.calibration import expansion
    from openmmgendpde.calibration.calibrate import EXPANSION_RUNS
    from openmmgendpde.calibration.calibration import QUICK, Calibration
    from openmmgendpde.calibration.expansion import MPA_PER_OPENMM_PRESSURE, ThermalExpansion
    parameters = expansion.mapped()
    beta0 = parameters.thermal_pressure
    kinetic = parameters.density * K_B * N_A / 1000 * MPA_PER_OPENMM_PRESSURE
    target_slope, target_alpha = 1.7718, 2.64e-3
    thermal = target_slope - kinetic
    calls = []

    def measure(model, **_):
        slope = kinetic + 0.4 * math.sqrt(model.thermal_pressure / beta0) * thermal
        calls.append(model.thermal_pressure)
        alpha = target_alpha * slope / target_slope
        return ThermalExpansion(temperatures=(0, 0), temperature_errors=(0, 0), pressures=(0, 0),
                                pressure_errors=(0, 0), slope=slope, slope_error=0.01 * target_slope,
                                target_slope=target_slope, alpha=alpha, alpha_error=0.01 * target_alpha,
                                target_alpha=target_alpha, thermal_pressure=model.thermal_pressure)
    monkeypatch.setattr(expansion, "measure", measure)
    calibration = Calibration(parameters, "VB", QUICK, "CPU", report=lambda _: None)
    rows = calibrate_module.thermal_expansion_rows(calibration, QUICK, "CPU", 1)
    assert rows[1][0] is Property.THERMAL_EXPANSION and 2 <= len(calls) <= EXPANSION_RUNS
    assert abs(rows[1][2].value / rows[1][1] - 1) <= 0.05
    assert calibration.parameters.thermal_pressure == calls[-1]
    assert calibration.parameters.thermal_pressure == pytest.approx(6.25 * beta0, rel=0.1)
