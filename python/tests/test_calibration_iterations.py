# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""calibrate's iterations (calibration.iteration, and beta's by calibration.expansion): a parameter moved on its
measured response, on made-up responses whose answer is known, until the target, the floor of the model, or the end of
its runs."""

import math

import pytest

from openmmgendpde.calibration.results import Property
from openmmgendpde.models.fluid import WATER, coarse_grain

#: Avogadro's and Boltzmann's constants (SI, exact), written out.
N_A = 6.02214076e23
K_B = 1.380649e-23


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
