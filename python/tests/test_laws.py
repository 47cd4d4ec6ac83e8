# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""Any law of the table in a model (models.laws, model.ModelParameters): its parameters fitted to a reference state
(pi0 and n dpi/dn = gamma_T B_T at n0, the thermal pressure at the particles' mean temperature), checked against the
laws' closed forms (docs/theory.md section 11), and a van der Waals fluid mapped, saved to a model file, loaded and
calibrated (issue 51): the calibration's handles pi0, B_T and beta act on it as on the Tait laws."""

import dataclasses
import math

import pytest
from helpers import fake_calibration

from openmmgendpde import GenDPDEForce
from openmmgendpde.calibration import calibrate as calibrate_module
from openmmgendpde.calibration.calibration import QUICK
from openmmgendpde.calibration.results import QUICK_CRITERIA, Property
from openmmgendpde.models import laws
from openmmgendpde.models.fluid import ARGON, ARGON_EXPANDING, KB, SUPERCRITICAL_ARGON, coarse_grain
from openmmgendpde.models.fluid_files import load_parameters, save_parameters

VDW = GenDPDEForce.VanDerWaals


def van_der_waals(state):
    """(a, b, k) of pi = k theta n/(1 - b n) - a n^2 with pi, n dpi/dn and dpi/dtheta of ``state`` at (n0, theta),
    solved by hand: dpi/dtheta = k n0/(1 - x) = beta (x = b n0), pi = beta theta - a n0^2, and
    n dpi/dn = beta theta/(1 - x) - 2 a n0^2, so 1/(1 - x) = (n dpi/dn + 2 (beta theta - pi))/(beta theta)."""
    n0, theta, beta = state.density, state.temperature, state.thermal_pressure
    x = 1 - beta * theta / (state.modulus + 2 * (beta * theta - state.pressure))
    return (beta * theta - state.pressure) / n0**2, x / n0, beta * (1 - x) / n0


@pytest.mark.parametrize("fluid", [ARGON_EXPANDING, SUPERCRITICAL_ARGON])
def test_a_fluid_maps_onto_each_law_as_its_closed_form_says(fluid):
    """The thermal Tait law: beta and theta0 of thermal_expansion_law, to the bit; van der Waals: the closed form
    (van_der_waals) to 1e-8 (the fit's modulus is a central difference); each law then gives the state it was fitted
    to (the physics core evaluates it)."""
    thermal = coarse_grain(fluid, 5, neighbors=20)
    state = thermal.reference_state()
    assert thermal.law == GenDPDEForce.TaitThermalExpansion
    assert thermal.law_parameters == (state.thermal_pressure, thermal.particle_temperature)
    assert thermal.law_parameters[1] == pytest.approx(thermal.temperature * (1 + KB / thermal.heat_capacity), rel=1e-15)
    vdw = coarse_grain(fluid, 5, neighbors=20, law="VanDerWaals")
    assert vdw.equation_of_state == "VanDerWaals" and vdw.tait == thermal.tait
    assert vdw.law_parameters == pytest.approx(van_der_waals(state), rel=1e-8)
    got = laws.state_of(VDW, vdw.law_parameters, vdw.tait, vdw.density, state.temperature)
    assert (got.pressure, got.modulus, got.thermal_pressure) == pytest.approx(
        (state.pressure, state.modulus, state.thermal_pressure), rel=1e-8)
    assert vdw.thermal_pressure == pytest.approx(thermal.thermal_pressure, rel=1e-12)
    assert vdw.thermal_reference_temperature == pytest.approx(thermal.particle_temperature, rel=1e-8)


def test_the_handles_move_a_law_that_does_not_extend_tait():
    """pi0 and B_T (replace) and beta (with_thermal_pressure) refit the van der Waals parameters: the law then gives
    the new pi0 and gamma_T B_T at n0 with the beta it had (or the new beta with the pi0 it had), at the same particle
    temperature; on the thermal Tait law pi0 and B_T are the Tait parameters alone and beta its own, theta0 kept."""
    vdw = coarse_grain(ARGON_EXPANDING, 5, neighbors=20, law=VDW)
    theta = vdw.thermal_reference_temperature
    moved = vdw.replace(reference_pressure=1.2 * vdw.reference_pressure, bulk_modulus=0.8 * vdw.bulk_modulus)
    assert moved.law_parameters != vdw.law_parameters
    assert moved.law_parameters == pytest.approx(van_der_waals(laws.ReferenceState(
        vdw.density, theta, 1.2 * vdw.reference_pressure, 0.8 * vdw.tait_exponent * vdw.bulk_modulus,
        vdw.thermal_pressure)), rel=1e-8)
    hotter = vdw.with_thermal_pressure(1.3 * vdw.thermal_pressure)
    assert hotter.thermal_pressure == pytest.approx(1.3 * vdw.thermal_pressure, rel=1e-10)
    assert hotter.law_parameters == pytest.approx(van_der_waals(vdw.reference_state(1.3 * vdw.thermal_pressure)),
                                                  rel=1e-8)
    thermal = coarse_grain(ARGON_EXPANDING, 5, neighbors=20)
    assert thermal.replace(reference_pressure=50.0).law_parameters == thermal.law_parameters
    beta, theta0 = thermal.with_thermal_pressure(2.0).law_parameters
    assert beta == pytest.approx(2.0, rel=1e-15) and theta0 == pytest.approx(thermal.law_parameters[1], rel=1e-15)


def test_a_law_that_depends_on_temperature_follows_the_heat_capacity():
    """A new C_V moves the particles' mean temperature at T0, theta_r = T0 (1 + k_B/C_V) (docs/theory.md section 11):
    the thermal Tait law's theta0 becomes the new theta_r exactly (beta kept), and van der Waals is fitted again to
    give pi0, gamma_T B_T and beta there; the Tait law is left as it is."""
    thermal = coarse_grain(ARGON_EXPANDING, 5, neighbors=20)
    colder = thermal.replace(heat_capacity=0.75 * thermal.heat_capacity)
    assert colder.law_parameters == (thermal.law_parameters[0], colder.particle_temperature)
    assert colder.particle_temperature == pytest.approx(thermal.temperature * (1 + KB / (0.75 * thermal.heat_capacity)))
    vdw = coarse_grain(ARGON_EXPANDING, 5, neighbors=20, law=VDW).replace(heat_capacity=0.75 * thermal.heat_capacity)
    assert vdw.law_parameters == pytest.approx(van_der_waals(colder.reference_state()), rel=1e-8)
    tait = coarse_grain(ARGON, 5, neighbors=20)
    assert tait.replace(heat_capacity=0.75 * tait.heat_capacity).law_parameters == ()


def test_a_law_that_cannot_give_the_state_is_refused_naming_it():
    """A fluid without a thermal expansion has no thermal pressure for a law with parameters of its own; van der
    Waals cannot give a pressure above beta theta (its attraction a would be negative): both refused in one
    ValueError naming the law."""
    with pytest.raises(ValueError, match="law = 'VanDerWaals' is not allowed for liquid argon .*no thermal_expansion"):
        coarse_grain(ARGON, 5, neighbors=20, law="VanDerWaals")
    vdw = coarse_grain(ARGON_EXPANDING, 5, neighbors=20, law=VDW)
    too_high = 2 * vdw.thermal_pressure * vdw.thermal_reference_temperature
    with pytest.raises(ValueError, match=r"no parameters of the law VanDerWaals \(a, b, k\) give pi = "):
        vdw.replace(reference_pressure=too_high)
    with pytest.raises(ValueError, match="equation of state must be one of"):
        coarse_grain(ARGON_EXPANDING, 5, neighbors=20, law="Waals")


def test_a_van_der_waals_fluid_is_mapped_saved_loaded_and_calibrated(monkeypatch, tmp_path):
    """Map -> model file -> load -> calibrate (calibrate.calibrate from Python, --quick's plan and criteria), the
    simulations replaced by made-up measurements (helpers.fake_calibration: the pressure reads 0.02/kappa_T above P0
    until pi0 has moved, f_cut 'tunes' to 1.3, the rest read their targets): the file holds the law by name with its
    parameters, loads to the same parameters, and the calibration moves pi0 by -0.02/kappa_T (one round, a response of
    1) and refits the van der Waals parameters to it, so that the law gives the calibrated pi0 at n0 with its modulus
    and thermal pressure; saved and loaded again, the calibrated model builds a force with that law."""
    mapped = coarse_grain(ARGON_EXPANDING, 5, neighbors=20, law="VanDerWaals")
    path = tmp_path / "vdw.toml"
    save_parameters(mapped, str(path))
    text = path.read_text()
    a, b, k = mapped.law_parameters
    assert 'equation_of_state = "VanDerWaals"' in text
    assert f"equation_of_state_parameters = {{a = {a!r}, b = {b!r}, k = {k!r}}}" in text
    loaded = load_parameters(str(path))
    assert loaded == dataclasses.replace(mapped, fluid=loaded.fluid)
    fake_calibration(monkeypatch, loaded, pressure_offset=0.02)
    result = calibrate_module.calibrate(loaded, "VB", QUICK, "Reference", criteria=QUICK_CRITERIA,
                                        report=lambda line: None)
    calibrated = result.parameters
    bulk = loaded.targets()["bulk_modulus"]
    assert result.succeeded and calibrated.equation_of_state == "VanDerWaals" and calibrated.cutoff_scaling == 1.3
    assert calibrated.reference_pressure == pytest.approx(loaded.reference_pressure - 0.02 * bulk, rel=1e-12)
    assert calibrated.law_parameters != loaded.law_parameters
    assert calibrated.heat_capacity != loaded.heat_capacity   # (c_U reads 0.5 k_B: C_V matched to c_v)
    assert calibrated.thermal_reference_temperature == pytest.approx(calibrated.particle_temperature, rel=1e-10)
    state = laws.state_of(VDW, calibrated.law_parameters, calibrated.tait, calibrated.density,
                          calibrated.particle_temperature)
    assert state.pressure == pytest.approx(calibrated.reference_pressure, rel=1e-8)
    assert state.modulus == pytest.approx(calibrated.tait_exponent * calibrated.bulk_modulus, rel=1e-8)
    assert state.thermal_pressure == pytest.approx(loaded.thermal_pressure, rel=1e-8)
    save_parameters(calibrated, str(tmp_path / "calibrated.json"))
    again = load_parameters(str(tmp_path / "calibrated.json"))
    assert again == dataclasses.replace(calibrated, fluid=again.fluid)
    law, parameters = again.liquid(500).force.getEquationOfState()
    assert law == VDW and [p._value for p in parameters] == list(calibrated.law_parameters)


@pytest.mark.validation
def test_a_van_der_waals_argon_calibrates_within_the_quick_criteria():
    """The same fluid calibrated for real (calibrate.calibrate with --quick's plan and criteria, 500 particles, CPU):
    every judged property within QUICK_CRITERIA (density 2%, pressure 0.01/kappa_T, c_v and the temperatures 2%,
    transport within a factor 2, thermal expansion 5%, each widened by its 95% interval) but the temperatures, the
    known miss of the thermal laws (below), the law still van der Waals with its parameters refitted. Measured (111 s
    on 2 shared cores, the report measured on the written model since issue 54): n-bar 1.001, (P - P0) kappa_T
    0.0055, n dP/dn 0.993, c_v 0.992, T_kin 0.965 and T_harm 0.959 (the temperature of the thermal laws,
    docs/thermal.md "Not done yet"; measured before beta's last correction, as the report did before issue 54, they
    read 0.975 and 0.976-0.979), viscosity 0.87 and 0.91, conductivity 1.09, alpha 0.996; a, b, k from 4.528, 0.1807,
    0.05085 to 4.937, 0.1791, 0.05415."""
    mapped = coarse_grain(ARGON_EXPANDING, 5, neighbors=20, law=VDW)
    lines = []
    result = calibrate_module.calibrate(mapped, "VB", QUICK, "CPU", criteria=QUICK_CRITERIA, report=lines.append)
    # Every judged property within its criterion but the ones the thermal laws are known to miss (docs/thermal.md,
    # "Not done yet"): the temperatures, 2.1-2.2% below T0 in the full calibration (2048 particles) as its report
    # measured them, before beta's last correction; the written model, measured since issue 54, is colder: in this
    # quick run T_harm 120.59 +- 0.35 K and T_kin 121.24 +- 0.70 K (4.1% and 3.5% below T0). They may miss, but not
    # by more than 5% (that deficit plus 3 standard errors): a model colder than that is a new fault.
    known = (Property.HARMONIC_TEMPERATURE, Property.KINETIC_TEMPERATURE)
    others = [miss for miss in result.missed if miss.property not in known]
    assert others == [], "\n".join(lines + [str(miss) for miss in result.missed])
    for temperature in (result.results[property.label] for property in known):
        assert temperature["target"] == pytest.approx(125.7, rel=1e-3), temperature
        assert temperature["model"] > 0.95 * 125.7, temperature
    assert result.parameters.law == VDW and result.parameters.law_parameters != mapped.law_parameters
    assert all(math.isfinite(value) for value in result.parameters.law_parameters)
