# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""The measurements calibrate rests on, against what is known: the stability of a time step, V-C's step at a free
surface, the decay of a conduction wave on a lattice, the speed of sound of an ideal gas, the fit of a sound wave and
its speed against the one derived from the equation of state, and the model's heat capacity from its fluctuations
against the energy a temperature change takes."""

import dataclasses
import math

import numpy as np
import pytest
from openmm import unit

from openmmgendpde.models.fluid import ARGON, WATER, coarse_grain, set_temperature_field
from openmmgendpde.models.lattice import fcc_box


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
    """calibrate.speed_of_sound with K_T = n k_B T, (dP/dT)_n = n k_B and the heat capacity of the motion alone
    (c = 3 k_B/2): the ideal
    monatomic gas, c = sqrt(5 k_B T/(3 m)) (argon atoms at 300 K: 322.6 m/s, computed here in SI)."""
    from openmmgendpde.calibration.calibration import Measured
    from openmmgendpde.calibration.report import speed_of_sound
    from openmmgendpde.models.fluid import KB
    gas = dataclasses.replace(coarse_grain(ARGON, 1, neighbors=20), heat_capacity=0.0, temperature=300.0,
                              mass=39.948)
    result = speed_of_sound(gas, Measured(gas.density * KB * 300.0, 0.0), Measured(gas.density * KB, 0.0), 1.5 * KB)
    expected = math.sqrt(5 * 1.380649e-23 * 300.0 / (3 * 39.948 * 1.66053906660e-27))   # m/s
    assert result.value * 1e3 == pytest.approx(expected, rel=1e-6)
    assert expected == pytest.approx(322.6, abs=0.1)


@pytest.mark.parametrize("thermal", [0.0, 1.0, 5.0])
def test_the_adiabatic_modulus_is_the_slope_of_the_pressure_along_an_adiabat(thermal):
    """thermodynamics.adiabatic_bulk_modulus (and the speed of sound calibrate derives from it) against finite
    differences on an equation of state made from a free energy, so that its adiabats are known exactly: per
    particle f(n, T) = c_v T (1 - ln T) + phi(n) - T psi(n), with the Tait energy phi (the model's law at T0:
    n^2 phi' = B_T ((n/n0)^gamma_T - 1) + pi0) and psi(n) = -k_B ln n - b n/n0^2 (the kinetic n k_B T and a thermal
    pressure b T (n/n0)^2 of the structure's or the law's kind; b = ``thermal`` n0 k_B). P = n^2 df/dn, s = -df/dT =
    c_v ln T + psi(n): along the adiabat through (n0, T0), T(n) = T0 exp((psi(n0) - psi(n))/c_v), and n dP/dn there
    (a central difference of 1e-5 n0) is K_S. Water's model (n0, T0, B_T, gamma_T, pi0; c_v of 4 molecules, 74.44
    J/(mol K) each). Expected to 1e-7 (the difference's truncation ~1e-10 of K_S, its rounding ~1e-9). K_T and
    (dP/dT)_n given to the code are finite differences of P too."""
    from openmmgendpde.analysis.thermodynamics import adiabatic_bulk_modulus
    from openmmgendpde.calibration.calibration import Measured
    from openmmgendpde.calibration.report import speed_of_sound
    from openmmgendpde.models.fluid import KB, WATER
    water = coarse_grain(WATER, 4, neighbors=20)
    n0, t0, gamma, modulus, pi0 = (water.density, water.temperature, water.tait_exponent, water.bulk_modulus,
                                   water.reference_pressure)
    c_v, b = 4 * 74.44e-3, thermal * n0 * KB   # kJ/mol/K per particle; kJ/mol/nm^3/K

    def psi(n):
        return -KB * math.log(n) - b * n / n0**2

    def pressure(n, t):
        return modulus * ((n / n0) ** gamma - 1) + pi0 + n * KB * t + b * t * (n / n0) ** 2

    def adiabat(n):
        return t0 * math.exp((psi(n0) - psi(n)) / c_v)

    h = 1e-5 * n0
    expected = n0 * (pressure(n0 + h, adiabat(n0 + h)) - pressure(n0 - h, adiabat(n0 - h))) / (2 * h)
    isothermal = n0 * (pressure(n0 + h, t0) - pressure(n0 - h, t0)) / (2 * h)
    slope = (pressure(n0, t0 + 1e-3) - pressure(n0, t0 - 1e-3)) / 2e-3
    assert slope == pytest.approx(n0 * KB + b, rel=1e-8)
    assert adiabatic_bulk_modulus(n0, t0, isothermal, slope, c_v) == pytest.approx(expected, rel=1e-7)
    sound = speed_of_sound(water, Measured(isothermal, 0.0), Measured(slope, 0.0), c_v)
    assert sound.value == pytest.approx(math.sqrt(expected / (n0 * water.mass)), rel=1e-7)
    if thermal:   # (the thermal pressure matters here: with the kinetic n k_B alone, K_S falls short)
        assert abs(adiabatic_bulk_modulus(n0, t0, isothermal, n0 * KB, c_v) / expected - 1) > 1e-4


@pytest.mark.parametrize("guess", [1.0, 0.6, 1.7])
def test_damped_cosine_recovers_the_frequency_and_damping_it_was_made_with(guess):
    """waves.damped_cosine on exp(-a t) (cos(omega t) - 0.3 sin(omega t)) sampled 40 times a period over two periods
    (the sound wave's sampling), a = 0.1 omega (the damping per period 2 pi a/omega = 0.63, water's in its box), the
    search started at ``guess`` x omega (the derived speed may miss the wave's by tens of %): omega and a to 1e-6 (the
    grid refined to ~1e-8 of omega; the curve is exact). Then with noise of 0.03 of the amplitude (a standard
    deviation, independent samples; the thermal noise of sound_speed's mode is ~0.07 of its amplitude but averaged
    over the replicas): omega within 1% (4 times the fit's scatter over 200 noise draws, 0.24%)."""
    from openmmgendpde.calibration.waves import damped_cosine
    omega, rate = 0.25, 0.025
    times = np.arange(81) * (2 * math.pi / omega) / 40
    values = np.exp(-rate * times) * (np.cos(omega * times) - 0.3 * np.sin(omega * times))
    fitted_omega, fitted_rate = damped_cosine(times, values, guess * omega)
    assert fitted_omega == pytest.approx(omega, rel=1e-6)
    assert fitted_rate == pytest.approx(rate, rel=1e-6)
    noisy = values + np.random.default_rng(7).normal(0.0, 0.03, times.shape)
    assert damped_cosine(times, noisy, guess * omega)[0] == pytest.approx(omega, rel=0.01)


def test_the_sound_box_is_widened_for_a_long_cutoff():
    """waves.sound_cells: plan.sound_cells where its width holds twice the cutoff (argon, 20 neighbours: (3, 3, 48)),
    else as many cells across as needed and the length alike (water at 80 neighbours, R = 2.67 n0^(-1/3) > 1.5 cells
    of 4^(1/3) n0^(-1/3)): each edge more than twice the cutoff, L_z = 16 L_x; the box is one that liquid() builds."""
    from openmmgendpde.calibration.calibration import Plan
    from openmmgendpde.calibration.waves import sound_cells
    assert sound_cells(coarse_grain(ARGON, 5, neighbors=20), Plan()) == (3, 3, 48)
    wide = coarse_grain(WATER, 4, neighbors=80)
    cells = sound_cells(wide, Plan())
    edge = (4 / wide.density) ** (1 / 3)
    assert cells[0] == cells[1] > 3 and cells[2] == 16 * cells[0]
    assert (cells[0] - 1) * edge <= 2 * wide.cutoff < cells[0] * edge
    wide.liquid(None, "VB", cells=cells)


@pytest.mark.parametrize("dampings, warned", [((0.4, 1.2), False), ((0.4, 2.5), True)])
def test_the_sound_wave_says_when_it_dies_out_too_fast_to_be_read(dampings, warned):
    """Calibration.sound_speed on made-up replicas (speed, damping per period): the mean and the standard error of the
    speeds (0.65 and 0.67 nm/ps: 0.66 +- 0.01), each replica's speed (m/s) and damping in its line, and a warning
    naming the box when a damping exceeds waves.SOUND_DAMPING (1.5), where water's replicas scattered by 8%."""
    from openmmgendpde.calibration.calibration import QUICK, Calibration
    lines = []
    calibration = Calibration(coarse_grain(ARGON, 5, neighbors=20), "VB", QUICK, "CPU", report=lines.append)
    calibration.replicas = lambda cells: lambda one: [(0.65, dampings[0]), (0.67, dampings[1])]
    measured = calibration.sound_speed(0.66)
    assert (measured.value, measured.error, measured.samples) == (pytest.approx(0.66), pytest.approx(0.01), 2)
    assert lines[0].startswith("  sound wave in 3 x 3 x 48 cells: c = 650.0, 670.0 m/s (damping per period 0.40, ")
    assert ("a longer box is needed (Plan.sound_cells)" in lines[0]) == warned


@pytest.mark.validation
@pytest.mark.parametrize("fluid, molecules", [(ARGON, 5)], ids=["argon"])
def test_a_sound_wave_travels_at_the_speed_derived_from_the_equation_of_state(fluid, molecules):
    """Calibration.sound_speed (a standing sound wave followed over two periods; 6 replicas) against the adiabatic
    speed sqrt(K_S/rho) derived (report.speed_of_sound) from the same model's measured n dP/dn (boxes at n0 (1 -+ 5%)),
    thermal pressure (dP/dT)_n (runs at T0 -+ 8%) and c_v (C_V + 2.5 k_B + c_U, c_U from the fluctuation of U), in
    500-particle cubes (--quick's runs): the equation of state, measured without any wave. Liquid argon, the published
    model (5 atoms per particle, R* = 1.6839: 20 neighbours), in 3 x 3 x 24 FCC cells (864 particles): half the length
    of calibrate's box (Plan.sound_cells, 3 x 3 x 48, chosen for water's damping), so that the test costs ~45 s
    instead of ~150 s; argon's wave still damps by only 0.5-1.1 per period there. Expected: equal within t(0.995, 5) =
    4.03 combined standard errors (the wave's from its 6 replicas' scatter, whose standard error is itself uncertain,
    so Student's t; the derived one's from n dP/dn and (dP/dT)_n), about a 1% chance of failing if both are right.
    Measured here (seed 3, the CPU platform): 645.3 +- 4.2 m/s (wave) against 645.9 +- 2.4 (derived): the tolerance,
    19.5 m/s, is 3.0%, so a wave that read a wavelength or a period 3% off fails. In calibrate's box: 648.5 +- 1.8
    (argon) and water (WATER, 4) 1445.3 +- 14.4 against 1444.6 +- 7.3 (docs/fluids.md). What this cannot tell
    apart: the adiabatic speed from the isothermal sqrt(K_T/rho), 0.5% (argon) and 0.09% (water) below it
    (K_S - K_T = T (dP/dT)_n^2/(n c_v) is small in a liquid)."""
    from scipy.stats import t

    from openmmgendpde.calibration.calibration import QUICK, Calibration
    from openmmgendpde.calibration.report import speed_of_sound
    parameters = coarse_grain(fluid, molecules, neighbors=20)
    plan = dataclasses.replace(QUICK, replicas=6, sound_wave=True, sound_cells=(3, 3, 24))
    calibration = Calibration(parameters, "VB", plan, "CPU", seed=3, report=print)
    bulk, _ = calibration.bulk_modulus()
    derived = speed_of_sound(parameters, bulk, calibration.thermal_pressure(5),
                             calibration.heat_capacity().value)
    measured = calibration.sound_speed(derived.value)
    combined = math.hypot(measured.error, derived.error)
    print(f"{fluid.name}: sound wave {1e3 * measured.value:.1f} +- {1e3 * measured.error:.1f} m/s, derived "
          f"{1e3 * derived.value:.1f} +- {1e3 * derived.error:.1f} m/s")
    assert abs(measured.value - derived.value) < t.ppf(0.995, measured.samples - 1) * combined


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
