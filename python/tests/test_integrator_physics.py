# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""Physics of GenDPDEIntegrator against exact predictions (docs/theory.md section 5). Statistical tests state the exact
expected value, the tolerance and why; every run uses fixed seeds, so the tests are deterministic."""

import math

import numpy as np
import openmm
import pytest
from openmm import unit
from scipy import integrate, stats

from openmmgendpde import GenDPDEIntegrator
from openmmgendpde.analysis.statistics import block_average
from openmmgendpde.models.argon import liquid_argon
from openmmgendpde.units import BOLTZMANN

KB = BOLTZMANN.value_in_unit(unit.kilojoule_per_mole / unit.kelvin)
ENERGY = unit.kilojoule_per_mole

#: Blocks of 25 samples (5 time units) for the standard errors of the 500 equilibrium samples.
BLOCKS = 20


def _sample_equilibrium(simulation, integrator, equilibration_steps, count, every=40):
    """``equilibration_steps`` steps, then ``count`` samples ``every`` steps apart: (kinetic energies in kJ/mol,
    count x N particle temperatures in K) as arrays."""
    integrator.step(equilibration_steps)
    kinetic, temperatures = [], []
    for _ in range(count):
        integrator.step(every)
        kinetic.append(simulation.context.getState(getEnergy=True).getKineticEnergy().value_in_unit(ENERGY))
        temperatures.append(integrator.getParticleTemperatures().value_in_unit(unit.kelvin))
    return np.array(kinetic), np.array(temperatures)


@pytest.fixture(scope="module", params=["Tait", "TaitThermalExpansion"])
def equilibrium_samples(request):
    """Liquid argon (500 particles, VB, R* = 1.6839, the published gamma*, kappa*, C_V*) with dt* = 0.005:
    20 time units of equilibration, then 500 samples 0.2 time units apart (kinetic energy, particle temperatures).
    The internal energies decorrelate within ~2 time units (autocorrelation 0.59, 0.12, 0.02 at lags 0.2, 1, 2).
    Twice: with the Tait law, and with liquid argon's thermal expansion (TaitThermalExpansion, beta = alpha gamma_T
    B_T with alpha = 2.64e-3 1/K, theta0 = T0): the conservative motion then changes each theta_i with its density
    (isentropically), and the identities below still hold exactly, because at fixed positions the stationary law of
    the internal energies is the same (docs/theory.md section 11: the new factor prod_i exp(sigma(n_i)/C) depends on
    the positions alone)."""
    argon = liquid_argon(500, 1.6839, "VB", time_step=0.005, seed=11)
    if request.param == "TaitThermalExpansion":
        _, _, bulk_modulus, gamma = argon.force.getTaitParameters()
        beta = 2.64e-3 * gamma * bulk_modulus.value_in_unit(unit.kilojoule_per_mole / unit.nanometer**3)
        argon.force.setEquationOfState(argon.force.TaitThermalExpansion, [beta, argon.temperature])
    simulation = argon.simulation(velocity_seed=11)
    integrator = argon.integrator
    kinetic, temperatures = _sample_equilibrium(simulation, integrator, 4000, 500)
    heat_capacity = integrator.getHeatCapacity().value_in_unit(ENERGY / unit.kelvin)
    return kinetic, temperatures, heat_capacity


@pytest.mark.validation
def test_kinetic_temperature_equals_harmonic_mean_temperature(equilibrium_samples):
    """Exact expected value: at fixed positions the stationary state is microcanonical in E = K + U + sum eps with
    density prod_i eps_i^c (c = C_V/k_B), so (K, eps_1..eps_N)/(E - U) is Dirichlet(d/2, c+1, ..., c+1) with
    d = 3N - 3 (momentum is conserved) and A = d/2 + N (c + 1). Then 2<K>/(d k_B) = (E - U)/(A k_B) and
    <1/theta_i> = k_B (A - 1)/(E - U): T_kin/T_harm = 1 - 1/A = 0.99987. Tolerance: 5 block standard errors
    (~0.3% each, from the fluctuations of K for 500 particles); the time-step bias at dt* = 0.005 is within one.
    Without the Ito term of the friction (Physics::pairTemperatures) this ratio is 1.040, 12 standard errors off."""
    kinetic, temperatures, heat_capacity = equilibrium_samples
    n = temperatures.shape[1]
    c = heat_capacity / KB
    a = (3 * n - 3) / 2 + n * (c + 1)
    kinetic_temperature = 2 * kinetic / ((3 * n - 3) * KB)
    harmonic = 1 / np.mean(1 / temperatures, axis=1)
    ratio = kinetic_temperature / harmonic
    error = block_average(ratio, BLOCKS, name="T_kin/T_harm").standard_error
    assert abs(ratio.mean() - (1 - 1 / a)) < 5 * error


def test_mean_temperature_exceeds_harmonic_mean_by_kb_over_cv(equilibrium_samples):
    """Exact expected value (same Dirichlet law): <theta>/T_harm = (1 + k_B/C_V)(1 - 1/A) = 1.07979 for argon.
    Tolerance: 5 block standard errors (~0.03% each)."""
    _, temperatures, heat_capacity = equilibrium_samples
    n = temperatures.shape[1]
    c = heat_capacity / KB
    a = (3 * n - 3) / 2 + n * (c + 1)
    ratio = temperatures.mean(axis=1) * np.mean(1 / temperatures, axis=1)
    error = block_average(ratio, BLOCKS, name="<theta>/T_harm").standard_error
    assert abs(ratio.mean() - (1 + 1 / c) * (1 - 1 / a)) < 5 * error


def test_internal_energies_follow_the_gamma_law(equilibrium_samples):
    """eps_i/(k_B T_harm) is Gamma-distributed with shape C_V/k_B + 1 = 13.51 (scale 1), up to O(1/A) = 1e-4
    corrections. Kolmogorov-Smirnov on samples 5 time units apart (independent: the autocorrelation is 0.02 at
    2 time units): 20 snapshots x 500 particles; reject below p = 0.001. A shape off by one (Gamma(C_V/k_B), the
    law without the density of states of the particle itself) gives D ~ 0.1, p ~ 0."""
    _, temperatures, heat_capacity = equilibrium_samples
    c = heat_capacity / KB
    harmonic = 1 / np.mean(1 / temperatures, axis=1)
    reduced = (heat_capacity * temperatures / (KB * harmonic[:, None]))[::25].ravel()
    assert stats.kstest(reduced, stats.gamma(c + 1).cdf).pvalue > 1e-3
    assert stats.kstest(reduced, stats.gamma(c).cdf).pvalue < 1e-6


@pytest.fixture(scope="module")
def mixture_samples():
    """A two-type mixture of the argon model (500 particles; docs/types.md): odd particles have type 1 with C_V = 6 k_B
    (argon's is 12.51 k_B), n0 1.2 times and B_T 0.7 times argon's; pairs (0, 1) have 2 gamma and kappa/2, pairs
    (1, 1) gamma/2 and 2 kappa. dt* = 0.005: 10 time units of equilibration, then 300 samples 0.2 time units apart
    on the CPU platform (bitwise the Reference dynamics)."""
    argon = liquid_argon(500, 1.6839, "VB", time_step=0.005, seed=13)
    integrator, force = argon.integrator, argon.force
    n0, pi0, bulk_modulus, exponent = force.getTaitParameters()
    friction, conduction = integrator.getFriction(), integrator.getHeatConduction()
    for i in range(1, 500, 2):
        force.setParticleType(i, 1)
        integrator.setParticleType(i, 1)
    force.addTypeParameters(1, 1.2 * n0, pi0, 0.7 * bulk_modulus, exponent)
    integrator.addTypeHeatCapacity(1, 6 * KB)
    integrator.addTypePair(0, 1, 2 * friction, 0.5 * conduction)
    integrator.addTypePair(1, 1, 0.5 * friction, 2 * conduction)
    simulation = argon.simulation(platform="CPU", velocity_seed=13)
    kinetic, temperatures = _sample_equilibrium(simulation, integrator, 2000, 300)
    capacity = np.where(np.arange(500) % 2 == 1, 6 * KB,
                        integrator.getHeatCapacity().value_in_unit(ENERGY / unit.kelvin))
    return kinetic, temperatures, capacity


@pytest.mark.validation
def test_mixture_equilibrium_identities_hold_per_type(mixture_samples):
    """docs/types.md: with per-type C_V the stationary law on the shell is Dirichlet(d/2, c_1 + 1, ..., c_N + 1)
    (c_i = C_i/k_B), so A = d/2 + sum_i (c_i + 1), <1/theta_i> = k_B (A - 1)/(E - U) for every particle whatever
    its type, hence for each type T_kin/T_harm = 1 - 1/A and <theta>/T_harm = (1 + k_B/C_type)(1 - 1/A): 1.0797 for
    argon's C_V and 1.1665 for 6 k_B. Tolerance: 5 block standard errors (15 blocks of 20 samples, 4 time units;
    ~0.5% for T_kin/T_harm, ~0.1% for <theta>/T_harm). Measured: T_kin/T_harm 1.0020 and 1.0052 (expected 0.9998),
    <theta>/T_harm 1.1691 +- 0.0012 (6 k_B) and 1.0801 +- 0.0007 (argon). A sweep that gave both particles of a pair
    the first one's C_V (tried) misses T_kin/T_harm by 0.25, 68 standard errors."""
    kinetic, temperatures, capacity = mixture_samples
    n = temperatures.shape[1]
    a = (3 * n - 3) / 2 + np.sum(capacity / KB + 1)
    kinetic_temperature = 2 * kinetic / ((3 * n - 3) * KB)
    for heat_capacity in np.unique(capacity):
        theta = temperatures[:, capacity == heat_capacity]
        harmonic = 1 / np.mean(1 / theta, axis=1)
        ratio = kinetic_temperature / harmonic
        error = block_average(ratio, 15, name="T_kin/T_harm").standard_error
        assert abs(ratio.mean() - (1 - 1 / a)) < 5 * error, heat_capacity / KB
        mean_ratio = theta.mean(axis=1) / harmonic
        error = block_average(mean_ratio, 15, name="<theta>/T_harm").standard_error
        assert abs(mean_ratio.mean() - (1 + KB / heat_capacity) * (1 - 1 / a)) < 5 * error, heat_capacity / KB


def test_mixture_internal_energies_follow_the_gamma_law_of_their_type(mixture_samples):
    """Each type's eps_i/(k_B T_harm) is Gamma-distributed with shape C_type/k_B + 1 (7 for the 6 k_B type, 13.51
    for argon's), tested as in test_internal_energies_follow_the_gamma_law on samples 5 time units apart (12
    snapshots x 250 particles per type); the other type's shape is rejected."""
    _, temperatures, capacity = mixture_samples
    harmonic = 1 / np.mean(1 / temperatures, axis=1)
    shapes = {value: value / KB + 1 for value in np.unique(capacity)}
    for heat_capacity, shape in shapes.items():
        reduced = (heat_capacity * temperatures[:, capacity == heat_capacity] / (KB * harmonic[:, None]))[::25]
        assert stats.kstest(reduced.ravel(), stats.gamma(shape).cdf).pvalue > 1e-3
        other = [s for value, s in shapes.items() if value != heat_capacity][0]
        assert stats.kstest(reduced.ravel(), stats.gamma(other).cdf).pvalue < 1e-6


def _pair(mode, heat_capacity, temperature):
    """Two particles (2 and 3 amu) 0.5 nm apart along x, cutoff 1 nm, no conservative force, separating at
    0.1 nm/ps, with a common perpendicular velocity (so that e_ij stays exactly along x)."""
    system = openmm.System()
    system.addParticle(2.0)
    system.addParticle(3.0)
    if mode == "DPDIntegrator":
        # OpenMM's DPDIntegrator damps the relative velocity at 2 f (1 - r/R)^2: the same dynamics for
        # f = gamma (1/m_i + 1/m_j)/2 (the mapping benchmark-integrator relies on), here at 0 K.
        integrator = openmm.DPDIntegrator(0.0, 10.0 * (1 / 2.0 + 1 / 3.0) / 2, 1.0, 0.0005)
    else:
        integrator = GenDPDEIntegrator(0.0005, 10.0, 0.0, heat_capacity)
        integrator.setCutoffDistance(1.0)
        integrator.setMode(mode)
        integrator.setTemperature(temperature)
    integrator.setRandomNumberSeed(3)
    context = openmm.Context(system, integrator, openmm.Platform.getPlatformByName("Reference"))
    context.setPositions([openmm.Vec3(0, 0, 0), openmm.Vec3(0.5, 0, 0)])
    context.setVelocities([openmm.Vec3(-0.05, 0.2, 0.3), openmm.Vec3(0.05, 0.2, 0.3)])
    return context, integrator


@pytest.mark.parametrize("mode, heat_capacity, temperature", [
    (GenDPDEIntegrator.Isothermal, 1.0, 1e-16),        # bath at ~0 K: no noise
    (GenDPDEIntegrator.Isoenergetic, 1e9, 1e-13),       # theta stays ~1e-11 K: no noise; k_B/C_V ~ 1e-11
    ("DPDIntegrator", None, 0.0),                       # OpenMM's own DPD, an independent implementation
])
def test_relative_velocity_relaxes_at_the_predicted_rate(mode, heat_capacity, temperature):
    """Without noise, docs/theory.md section 6 gives du/dt = -gamma (1 - r/R)^2 (1/m_i + 1/m_j) u and dr/dt = u for
    the relative velocity u along e_ij; solved here with scipy to 1e-12. The integrator (dt = 0.5 fs, rate ~2/ps)
    follows it up to the O(dt) error of the splitting in the r-u coupling (the pair update acts at fixed r, then the
    drift): measured 3e-6 = 3e-5 u0; tolerance 1e-4 u0. Velocities perpendicular to e_ij are untouched."""
    context, integrator = _pair(mode, heat_capacity, temperature)
    mu = 1 / 2.0 + 1 / 3.0
    solution = integrate.solve_ivp(lambda t, y: [y[1], -10.0 * (1 - y[0]) ** 2 * mu * y[1]], (0, 1.5), [0.5, 0.1],
                                   rtol=1e-12, atol=1e-14, dense_output=True)
    for steps in (500, 1000, 1000, 500):
        integrator.step(steps)
        state = context.getState(getVelocities=True, getPositions=True)
        time = state.getTime().value_in_unit(unit.picosecond)
        v = state.getVelocities(asNumpy=True).value_in_unit(unit.nanometer / unit.picosecond)
        # The state's velocities are half a step behind; with no forces they are the on-step velocities.
        u = -(v[0, 0] - v[1, 0])
        assert abs(u - solution.sol(time)[1]) < 1e-4 * 0.1
        assert v[0, 1] == v[1, 1] == 0.2 and v[0, 2] == v[1, 2] == 0.3
    assert solution.sol(1.5)[1] < 0.1 * math.exp(-2)   # the test spans more than two relaxation times


@pytest.mark.validation
def test_conserved_energy_error_is_second_order_in_the_step():
    """Full GenDPDE on liquid argon from 4 equilibrated states, dt* = 0.01, 0.005, 0.0025 over 10 time units: the
    root-mean-square change of K + U + sum eps over windows of 0.5 time units (80 windows per step size). Velocity
    Verlet's energy error is O(dt^2) and the pair updates conserve energy exactly, so the expected order is 2.
    The estimate of each RMS has a standard error of ~7.5% (scatter of the squared increments), hence ~0.075 on
    the fitted order; tolerance +-0.3 (4 standard errors). Measured: 1.96."""
    states = []
    for seed in range(11, 15):
        argon = liquid_argon(500, 1.6839, "VB", time_step=0.005, seed=seed)
        simulation = argon.simulation(velocity_seed=seed)
        argon.integrator.step(2000)
        states.append(simulation.context.getState(getPositions=True, getVelocities=True, getIntegratorParameters=True))
    steps, errors = [0.01, 0.005, 0.0025], []
    for time_step in steps:
        squares = []
        for state in states:
            argon = liquid_argon(500, 1.6839, "VB", time_step=time_step, seed=7)
            context = openmm.Context(argon.system, argon.integrator, openmm.Platform.getPlatformByName("Reference"))
            context.setState(state)
            energies = [argon.integrator.getConservedEnergy().value_in_unit(ENERGY)]
            for _ in range(20):
                argon.integrator.step(round(0.5 / time_step))
                energies.append(argon.integrator.getConservedEnergy().value_in_unit(ENERGY))
            squares += list(np.diff(energies) ** 2)
        errors.append(math.sqrt(np.mean(squares)))
    order = np.polyfit(np.log(steps), np.log(errors), 1)[0]
    assert abs(order - 2) < 0.3, f"errors {errors}, order {order}"


def _force_free_dpd_run(kind, seed, steps=1500, every=5, lag=20):
    """A force-free DPD fluid (500 particles of 1 amu at 3 nm^-3, R = 1 nm, gamma = 6.75 amu/ps, k_B T = 1 kJ/mol,
    dt = 0.04 ps) in a periodic box, started in its equilibrium (uniform positions, Maxwell-Boltzmann velocities
    with zero total momentum). Returns (kinetic temperatures / T, self-diffusion estimates D in nm^2/ps from the
    displacement over `lag` samples at every time origin). kind: GenDPDE's Isothermal mode or OpenMM's
    DPDIntegrator with f = gamma/m."""
    temperature, length, dt = 1 / KB, (500 / 3.0) ** (1 / 3), 0.04
    rng = np.random.default_rng(seed)
    system = openmm.System()
    system.setDefaultPeriodicBoxVectors(*(openmm.Vec3(*row) for row in np.eye(3) * length))
    for _ in range(500):
        system.addParticle(1.0)
    # A System is periodic only if a force uses periodic boundaries (as OpenMM's DPDIntegrator reads it too);
    # this one acts on no particle and costs nothing.
    system.addForce(openmm.CustomExternalForce("0*periodicdistance(x, y, z, 0, 0, 0)"))
    if kind == "DPDIntegrator":
        integrator = openmm.DPDIntegrator(temperature, 6.75, 1.0, dt)
    else:
        integrator = GenDPDEIntegrator(dt, 6.75, 0.0, 1.0)
        integrator.setMode(GenDPDEIntegrator.Isothermal)
        integrator.setTemperature(temperature)
        integrator.setCutoffDistance(1.0)
    integrator.setRandomNumberSeed(seed)
    context = openmm.Context(system, integrator, openmm.Platform.getPlatformByName("Reference"))
    context.setPositions(rng.uniform(0, length, (500, 3)))
    velocities = rng.normal(0, math.sqrt(KB * temperature), (500, 3))
    context.setVelocities(velocities - velocities.mean(axis=0))
    temperatures, positions = [], []
    for _ in range(steps // every):
        integrator.step(every)
        state = context.getState(getEnergy=True, getPositions=True)
        temperatures.append(2 * state.getKineticEnergy().value_in_unit(ENERGY) / ((3 * 500 - 3) * KB * temperature))
        positions.append(state.getPositions(asNumpy=True).value_in_unit(unit.nanometer))
    positions = np.array(positions)
    displacement2 = np.sum((positions[lag:] - positions[:-lag]) ** 2, axis=2).mean(axis=1)
    return np.array(temperatures), displacement2 / (6 * lag * every * dt)


@pytest.mark.validation
def test_force_free_dpd_fluid_against_equipartition_and_openmm():
    """Plain DPD (no GenDPDEForce; the integrator's own pair list). Expected: kinetic temperature = T exactly (each
    pair update and the drift preserve uniform positions x Maxwell-Boltzmann velocities, so the start is stationary
    for any dt), for GenDPDE and for OpenMM's DPDIntegrator; and the same self-diffusion coefficient for both, the
    same dynamics (measured 0.449 +- 0.004 and 0.454 +- 0.005 nm^2/ps). Tolerances: 5 standard errors of block
    means, 10 blocks for T and 5 for D (the D estimates of overlapping windows are correlated over ~15 samples; the
    blocks must hold at least twice that, which the plateau check of block_average verifies). In a non-periodic System
    the same fluid is an expanding gas, and both integrators read ~1.5 kT there (docs/integrator.md)."""
    results = {kind: _force_free_dpd_run(kind, 3) for kind in ("GenDPDE", "DPDIntegrator")}
    diffusion = {}
    for kind, (temperatures, estimates) in results.items():
        mean, error = block_average(temperatures, blocks=10)
        assert abs(mean - 1) < 5 * error, f"{kind}: T_kin/T = {mean} +- {error}"
        diffusion[kind] = block_average(estimates[:len(estimates) // 5 * 5], blocks=5)
    (d1, e1), (d2, e2) = diffusion["GenDPDE"], diffusion["DPDIntegrator"]
    assert abs(d1 - d2) < 5 * math.hypot(e1, e2), f"D = {d1} +- {e1} (GenDPDE), {d2} +- {e2} (DPDIntegrator)"
