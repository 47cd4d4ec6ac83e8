# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""Reverse non-equilibrium shear flow (models.shear.ReverseShearFlow, analysis.shear, studies.shear; docs/flows.md):
the momentum exchange against the conservation laws it must keep, its bookkeeping as a reporter and on a Context, the
viscosity analysis on synthetic profiles, and (validation) the viscosity against the transport study's and the
xz pressure against the momentum flux."""

import math

import numpy as np
import openmm
import pytest
from openmm import app, unit

from openmmgendpde import GenDPDEIntegrator
from openmmgendpde.analysis import shear
from openmmgendpde.analysis.pressure import virial_tensor
from openmmgendpde.analysis.profiles import profile
from openmmgendpde.analysis.statistics import correlated_mean
from openmmgendpde.models.fluid import ARGON, coarse_grain
from openmmgendpde.models.model import Equilibration
from openmmgendpde.models.shear import ReverseShearFlow
from openmmgendpde.studies.shear import maximum_of_normals, shear_run

ARGON_MODEL = coarse_grain(ARGON, 5, neighbors=20)
_VELOCITY = unit.nanometer / unit.picosecond


def _liquid(cells=(3, 3, 6), mode=GenDPDEIntegrator.Isoenergetic, platform="Reference", seed=4, properties=None):
    """(model, context): the mapped argon model (216 particles by default) melted briefly and run in ``mode``."""
    model = ARGON_MODEL.liquid(cells=cells, mode=GenDPDEIntegrator.Isothermal, seed=seed)
    return model, model.equilibrate(platform, Equilibration(100, 20, mode, seed=seed), properties)


def _on_step(model, context):
    """(positions, stored velocities, on-step velocities v + (dt/2) F/m) of ``context`` now, nm and nm/ps."""
    state = context.getState(getPositions=True, getVelocities=True, getForces=True)
    step = model.integrator.getStepSize().value_in_unit(unit.picosecond)
    v = state.getVelocities(asNumpy=True).value_in_unit(_VELOCITY)
    f = state.getForces(asNumpy=True).value_in_unit(unit.kilojoule_per_mole / unit.nanometer)
    return state.getPositions(asNumpy=True).value_in_unit(unit.nanometer), v, v + 0.5 * step * f / ARGON_MODEL.mass


def test_exchange_swaps_the_on_step_x_velocities_of_the_extreme_particles_keeping_momentum_and_energy():
    """One exchange: the particle with the most negative on-step v_x among those with wrapped z in [0, L/20) and the one
    with the most positive among [L/2, L/2 + L/20) (found here by hand from the box edge) swap their on-step v_x, to
    rounding; every other velocity component is bitwise unchanged; the total on-step momentum stays within 1e-12 of
    the particles' momentum scale, the on-step kinetic energy and the integrator's conserved energy K + U + sum eps
    within 1e-12 relative (rounding); the momentum moved into slab 0 is m (u_j - u_i) > 0."""
    model, context = _liquid()
    m = ARGON_MODEL.mass
    x, v, u = _on_step(model, context)
    length = model.box_edges[2]
    z = np.mod(x[:, 2], length)
    low, high = np.flatnonzero(z < length / 20), np.flatnonzero((z >= length / 2) & (z < length / 2 + length / 20))
    i, j = low[np.argmin(u[low, 0])], high[np.argmax(u[high, 0])]
    energy = model.integrator.getConservedEnergy().value_in_unit(unit.kilojoule_per_mole)
    flow = ReverseShearFlow(10)
    moved = flow.exchange(context)
    _, v_after, u_after = _on_step(model, context)
    assert moved == pytest.approx(m * (u[j, 0] - u[i, 0]), rel=1e-14) and moved > 0
    assert u_after[i, 0] == pytest.approx(u[j, 0], rel=1e-13) and u_after[j, 0] == pytest.approx(u[i, 0], rel=1e-13)
    others = np.ones(v.shape, bool)
    others[[i, j], 0] = False
    assert np.array_equal(v_after[others], v[others])
    scale = m * np.abs(u).sum()
    assert np.abs(m * (u_after.sum(axis=0) - u.sum(axis=0))).max() < 1e-12 * scale
    kinetic, kinetic_after = 0.5 * m * (u**2).sum(), 0.5 * m * (u_after**2).sum()
    assert kinetic_after == pytest.approx(kinetic, rel=1e-12)
    assert model.integrator.getConservedEnergy().value_in_unit(unit.kilojoule_per_mole) == pytest.approx(
        energy, rel=1e-12)
    assert list(flow.momenta) == [moved] and flow.area == pytest.approx(model.box_edges[0] * model.box_edges[1])
    assert flow.getExchangedMomentum().value_in_unit(unit.amu * _VELOCITY) == moved


def test_the_half_kick_is_that_of_the_forces_the_integrator_integrates():
    """A force the integrator leaves out (a harmonic well 2000 x^2 kJ/mol along x, in force group 5, with
    setIntegrationForceGroups({0})) is in a State's forces but not in the on-step velocities v + (dt/2) F/m of the
    integrator's kinetic and conserved energies: an exchange keeps the conserved energy within 1e-12 relative. With
    the State's forces of every group the swapped pair's half kicks would differ by (dt/2) 4000 (x_j - x_i)/m (a
    uniform push would cancel between them), and the conserved energy would move far beyond rounding."""
    model = ARGON_MODEL.liquid(cells=(3, 3, 6), mode=GenDPDEIntegrator.Isothermal, seed=4)
    push = openmm.CustomExternalForce("2000*x^2")
    push.setForceGroup(5)
    for i in range(model.num_particles):
        push.addParticle(i, [])
    model.system.addForce(push)
    model.integrator.setIntegrationForceGroups({0})
    context = model.equilibrate("Reference", Equilibration(100, 20, GenDPDEIntegrator.Isoenergetic, seed=4))
    energy = model.integrator.getConservedEnergy().value_in_unit(unit.kilojoule_per_mole)
    assert ReverseShearFlow(10).exchange(context) > 0
    assert model.integrator.getConservedEnergy().value_in_unit(unit.kilojoule_per_mole) == pytest.approx(
        energy, rel=1e-12)


def test_swapping_the_stored_velocities_instead_would_change_the_conserved_energy():
    """Why the exchange swaps on-step velocities: swapping the stored (half-step-behind) v_x of the same two particles
    keeps the momentum but changes the integrator's conserved energy by m (v_j - v_i)(a_i - a_j), a = (dt/2) F_x/m
    (worked out by hand: K uses v + a), which is measured here to 1e-9 kJ/mol and is not zero."""
    model, context = _liquid()
    x, v, u = _on_step(model, context)
    length = model.box_edges[2]
    z = np.mod(x[:, 2], length)
    low, high = np.flatnonzero(z < length / 20), np.flatnonzero((z >= length / 2) & (z < length / 2 + length / 20))
    i, j = low[np.argmin(u[low, 0])], high[np.argmax(u[high, 0])]
    a = u - v
    energy = model.integrator.getConservedEnergy().value_in_unit(unit.kilojoule_per_mole)
    swapped = v.copy()
    swapped[i, 0], swapped[j, 0] = v[j, 0], v[i, 0]
    context.setVelocities(swapped)
    change = model.integrator.getConservedEnergy().value_in_unit(unit.kilojoule_per_mole) - energy
    expected = ARGON_MODEL.mass * (v[j, 0] - v[i, 0]) * (a[i, 0] - a[j, 0])
    assert change == pytest.approx(expected, abs=1e-9) and abs(expected) > 1e-4


def test_a_run_with_exchanges_keeps_the_momentum_and_the_conserved_energy():
    """300 Isoenergetic steps with an exchange every 10 (step() on a Context): 30 exchanges at steps 10, 20, ...
    (counted from the Context's step count), each moving momentum into slab 0; the total momentum stays at its start
    within 1e-12 of its scale, and E = K + U + sum eps within 1e-5 relative to K + sum eps (the integrator's drift
    over 300 steps; the exchanges add rounding only)."""
    model, context = _liquid()
    _, _, u = _on_step(model, context)
    start_step = context.getStepCount()
    energy = model.integrator.getConservedEnergy().value_in_unit(unit.kilojoule_per_mole)
    moved = (0.5 * ARGON_MODEL.mass * (u**2).sum()
             + model.integrator.getInternalEnergies().value_in_unit(unit.kilojoule_per_mole).sum())
    flow = ReverseShearFlow(10)
    flow.step(context, 300)
    _, _, u_after = _on_step(model, context)
    assert context.getStepCount() == start_step + 300
    assert list(flow.steps) == [s for s in range(start_step + 1, start_step + 301) if s % 10 == 0]
    assert len(flow.times) == 30 and np.all(flow.momenta >= 0) and np.count_nonzero(flow.momenta) > 20
    scale = ARGON_MODEL.mass * np.abs(u).sum()
    assert np.abs(ARGON_MODEL.mass * (u_after.sum(axis=0) - u.sum(axis=0))).max() < 1e-12 * scale
    assert model.integrator.getConservedEnergy().value_in_unit(unit.kilojoule_per_mole) == pytest.approx(
        energy, abs=1e-5 * moved)


def test_as_a_simulation_reporter_it_exchanges_at_multiples_of_its_interval():
    """Appended to an openmm.app.Simulation, it exchanges at steps 7, 14, 21 of 25 (OpenMM's reporter protocol), and
    the moved momenta add up to getExchangedMomentum."""
    model = ARGON_MODEL.liquid(cells=(3, 3, 6), mode=GenDPDEIntegrator.Isothermal, seed=2)
    simulation = app.Simulation(model.topology, model.system, model.integrator,
                                openmm.Platform.getPlatformByName("Reference"))
    simulation.context.setPositions(model.positions)
    simulation.context.setVelocitiesToTemperature(ARGON_MODEL.temperature * unit.kelvin, 3)
    flow = ReverseShearFlow(7)
    simulation.reporters.append(flow)
    simulation.step(25)
    assert list(flow.steps) == [7, 14, 21]
    assert flow.getExchangedMomentum().value_in_unit(unit.amu * _VELOCITY) == pytest.approx(flow.momenta.sum())


@pytest.mark.parametrize("arguments, named", [((0,), "exchangeInterval = 0"), ((2.5,), "exchangeInterval = 2.5"),
                                              ((True,), "exchangeInterval = True"), ((5, 21), "slabs = 21"),
                                              ((5, 2), "slabs = 2"), ((5, "20"), "slabs = '20'")])
def test_bad_arguments_are_refused_naming_them(arguments, named):
    with pytest.raises(openmm.OpenMMException, match=f"ReverseShearFlow: {named} is not allowed; it must be"):
        ReverseShearFlow(*arguments)


def test_systems_it_cannot_shear_are_refused_before_anything_changes():
    """Unequal masses (a swap would not keep momentum and energy), another integrator, and a System without periodic
    boundaries are refused at the exchange, naming what is wrong, with the velocities unchanged."""
    model, context = _liquid()
    before = context.getState(getVelocities=True).getVelocities(asNumpy=True)
    model.system.setParticleMass(5, 2 * ARGON_MODEL.mass)
    context.reinitialize(preserveState=True)
    with pytest.raises(openmm.OpenMMException, match="moving particles have the masses 200.*one mass"):
        ReverseShearFlow(5).exchange(context)
    assert np.array_equal(context.getState(getVelocities=True).getVelocities(asNumpy=True), before)
    system = openmm.System()
    for _ in range(4):
        system.addParticle(1.0)
    verlet = openmm.Context(system, openmm.VerletIntegrator(0.001), openmm.Platform.getPlatformByName("Reference"))
    with pytest.raises(openmm.OpenMMException, match="integrator = a VerletIntegrator is not allowed; it must be a "
                                                     "GenDPDEIntegrator"):
        ReverseShearFlow(5).exchange(verlet)
    integrator = GenDPDEIntegrator(0.001, 1.0, 0.0, 1.0)
    integrator.setCutoffDistance(1.0)
    integrator.setMode(GenDPDEIntegrator.Conservative)
    open_context = openmm.Context(system, integrator, openmm.Platform.getPlatformByName("Reference"))
    open_context.setPositions(np.arange(12.0).reshape(4, 3))
    with pytest.raises(openmm.OpenMMException, match="does not use periodic boundaries"):
        ReverseShearFlow(5).exchange(open_context)


def test_the_viscosity_of_a_synthetic_zigzag_flow_is_recovered():
    """Frames of a zig-zag v_x(z) with slopes -/+ gamma_dot between the slabs (the bins in the slabs themselves off
    the line) plus independent noise, and exchanges whose momenta give J = eta gamma_dot: eta, gamma_dot and J come
    back within 3 of their standard errors, and the error of gamma_dot is within 30% of the noise's propagated one
    (independent frames: statistical inefficiency 1)."""
    rng = np.random.default_rng(7)
    length, slabs, rate, eta, area, duration = 7.8, 20, 0.015, 125.0, 61.0, 80.0
    centre = (np.arange(slabs) + 0.5) * length / slabs
    width = length / slabs
    inner = np.mod(centre, length / 2)
    line = np.where(centre < length / 2, 1, -1) * rate * ((length / 2 - width) / 2 - (inner - width))
    line[[0, slabs // 2]] *= 1.3                                          # the slabs themselves: off the line
    noise = 0.003
    frames = line + rng.normal(0, noise, (400, slabs))
    momenta = rng.normal(1.0, 0.3, 300)
    momenta *= eta * rate * 2 * area * duration / momenta.sum()         # J = eta gamma_dot exactly
    result = shear.shear_viscosity(momenta, area, duration, centre, frames, length, slabs, margin=0.5)
    lower, upper = shear.fitted_bins(centre, length, slabs, 0.5)
    x = centre[lower] - centre[lower].mean()
    propagated = noise / math.sqrt(x @ x) / math.sqrt(2) / math.sqrt(len(frames))
    assert result.shear_rate == pytest.approx(rate, abs=3 * result.shear_rate_error)
    assert result.shear_rate_error == pytest.approx(propagated, rel=0.3)
    assert result.momentum_flux == pytest.approx(eta * rate, rel=1e-12)
    assert result.viscosity == pytest.approx(eta, abs=3 * result.error)
    assert list(np.flatnonzero(lower)) == [2, 3, 4, 5, 6, 7, 8] and list(np.flatnonzero(upper)) == list(
        range(12, 19))


def test_too_short_a_box_for_the_margin_is_refused():
    with pytest.raises(ValueError, match="fewer than 2 of 10 bins between the slabs"):
        shear.fitted_bins((np.arange(10) + 0.5) * 0.4, 4.0, 10, 1.0)
    with pytest.raises(ValueError, match="area = 0"):
        shear.momentum_flux([1.0], 0, 1.0)


def test_expected_maximum_of_normals_against_its_closed_forms():
    """E[max of 1] = 0, of 2 = 1/sqrt(pi), of 3 = 3/(2 sqrt(pi)) (closed forms for 2 and 3 normals)."""
    assert maximum_of_normals(1) == pytest.approx(0, abs=1e-10)
    assert maximum_of_normals(2) == pytest.approx(1 / math.sqrt(math.pi), rel=1e-8)
    assert maximum_of_normals(3) == pytest.approx(1.5 / math.sqrt(math.pi), rel=1e-8)


@pytest.mark.validation
def test_reverse_shear_viscosity_agrees_with_the_wave_decay_and_poiseuille_flow():
    """The mapped argon model (5 molecules per particle, 20 neighbours, V-B, dt* = 0.01, Isoenergetic) in 8 x 8 x 8
    FCC cells (2048 particles), a swap every 25 steps (peak flow ~0.4 v_th, in the Newtonian range of the flow curve in
    docs/flows.md), 2 momentum diffusion times to develop, 4 to measure (~12 s on one core). Expected: the viscosity
    that docs/transport.md measured on the same model and box by two other methods, the wave decay 0.206 +- 0.011 mPa s
    and Poiseuille flow 0.1946 +- 0.0046 (f = 0.25) and 0.2055 +- 0.0029 (f = 0.4) mPa s; their mean, 0.202 mPa s =
    121.6 amu/(nm ps), with the spread of the three, +- 0.006 mPa s (3.6 amu/(nm ps)), as its error. Tolerance: 3
    combined standard errors, this run's at least 6%: its own error comes from a statistical inefficiency estimated
    on ~6 correlation times and is itself uncertain (measured: 4 seeds of 8 tau scattered by 4.2% while reporting
    2.0-6.8%, docs/flows.md; 4 tau: ~6%)."""
    run = shear_run(ARGON_MODEL, 25, cells=(8, 8, 8), developed=2.0, measured=4.0, seed=5, properties={"Threads": "1"},
                    report=lambda _: None)
    reference, reference_error = 121.6, 3.6
    assert run.result.error < 0.1 * run.result.viscosity
    error = max(run.result.error, 0.06 * run.result.viscosity)
    assert run.result.viscosity == pytest.approx(reference, abs=3 * math.hypot(error, reference_error))
    assert 0.2 < run.peak_fraction < 0.7


@pytest.mark.validation
def test_the_xz_pressure_between_the_slabs_is_the_momentum_flux():
    """Irving-Kirkwood: in the steady state the x momentum the exchanges move into slab 0 flows back through both
    halves as the xz pressure, P_xz = +J in the first half and -J in the second. In the Conservative mode (velocity
    Verlet: no pair friction or noise, whose momentum transfer profiles.profile's pressure tensor does not hold) the
    pressure tensor of each bin (kinetic part with the on-step velocities about the bin's mean, and the GenDPDEForce's
    per-particle virial tensors) averaged over the bins at least R/2 from the slabs (analysis.shear.shear_stress) must
    equal J, which is counted from the swaps alone: independent. The mapped argon model in 4 x 4 x 8 cells (512
    particles), a swap every 20 steps, 27500 steps (2.5 momentum diffusion times of this viscosity, ~17 amu/(nm ps)
    without friction) to develop, 18000 to measure (~12 s). Tolerance: 3 combined standard errors (each ~5%)."""
    model, context = _liquid(cells=(4, 4, 8), mode=GenDPDEIntegrator.Conservative, platform="CPU", seed=3,
                             properties={"Threads": "1"})
    flow = ReverseShearFlow(20)
    flow.step(context, 27500)
    flow.reset()
    start = context.getState().getTime().value_in_unit(unit.picosecond)
    masses = np.full(model.num_particles, ARGON_MODEL.mass)
    stresses = []
    length = model.box_edges[2]
    for _ in range(180):
        flow.step(context, 100)
        x, _, u = _on_step(model, context)
        box = np.diag(model.box_edges)
        binned = profile(x, u, masses, box, bins=20, virials=virial_tensor(model.force, context, per_particle=True))
        stresses.append(binned["pressure"][:, 0, 2])
    duration = context.getState().getTime().value_in_unit(unit.picosecond) - start
    lower, upper = shear.fitted_bins(binned["centre"], length, 20, ARGON_MODEL.cutoff / 2)
    stress = correlated_mean(shear.shear_stress(stresses, lower, upper))
    flux = shear.momentum_flux(flow.momenta, flow.area, duration)
    flux_error = correlated_mean(flow.momenta).standard_error * len(flow.momenta) / (2 * flow.area * duration)
    assert stress.standard_error < 0.1 * flux and flux_error < 0.1 * flux
    assert stress.mean == pytest.approx(flux, abs=3 * math.hypot(stress.standard_error, flux_error))


@pytest.mark.parametrize("arguments, message", [
    (["--slabs", "21"], "argument --slabs: 21 is not allowed; it must be an even integer from 4 to 1000"),
    (["--intervals", "0"], "argument --intervals: 0 is not allowed; it must be an integer >= 1"),
    (["--measured", "0"], "argument --measured: 0 is not allowed; it must be a finite number > 0"),
    (["--mode", "conservative"], "argument --mode: invalid choice: 'conservative'"),
])
def test_flow_curve_refuses_bad_arguments_before_running(arguments, message, capsys, monkeypatch):
    """Usage errors (status 2) naming the option, the value and what is allowed; nothing runs."""
    from openmmgendpde.cli import flow_curve
    from openmmgendpde.cli.main import main
    monkeypatch.setattr(flow_curve.study, "flow_curve", lambda *a, **k: pytest.fail("the study ran"))
    with pytest.raises(SystemExit) as exit_:
        main(["flow-curve"] + arguments)
    assert exit_.value.code == 2 and message in capsys.readouterr().err


def test_flow_curve_refuses_a_box_without_room_between_the_slabs(monkeypatch):
    """A margin that leaves fewer than 2 bins in a half: a one-line error naming the options, before any run."""
    from openmmgendpde.cli import flow_curve
    from openmmgendpde.cli.main import main
    monkeypatch.setattr(flow_curve.study, "flow_curve", lambda *a, **k: pytest.fail("the study ran"))
    with pytest.raises(SystemExit, match="error: flow-curve: the box .* leaves fewer than 2 of 20 bins between the "
                                         "slabs .* at least 2 nm from them.*--margin"):
        main(["flow-curve", "--cells", "4", "4", "4", "--margin", "2"])


@pytest.mark.validation
def test_flow_curve_quick_prints_the_table_and_writes_json(tmp_path, capsys):
    """flow-curve --quick end to end (512 particles, one interval, ~4 s): a table row for interval 25 and a JSON record
    whose viscosity is J/gamma_dot of its own numbers (rounding)."""
    import json

    from openmmgendpde.cli.main import main
    main(["flow-curve", "--quick", "--json", str(tmp_path / "flow.json")])
    out = capsys.readouterr().out
    assert "| 25 | " in out and "eta (mPa s)" in out
    record = json.loads((tmp_path / "flow.json").read_text())["runs"][0]
    assert record["interval"] == 25 and record["viscosity"] > 0
    assert record["viscosity"] == pytest.approx(record["momentum_flux"] / record["shear_rate"], rel=1e-12)


def test_the_normal_stress_study_s_chains_are_polymer_solution_s_in_their_own_force_group(monkeypatch):
    """polymer_normal_stresses builds its liquid with models.polymers.polymer_solution (the package's one chain
    builder): round(0.3 x 216/6) = 11 chains of 6 beads in 3 x 3 x 6 cells, their bonds in BOND_GROUP (the group
    whose numerical virial tensor the study adds). The run itself is stopped at the equilibration."""
    from openmmgendpde.studies import shear as study
    built = {}

    def stop(parameters, cells, estimator, time_step, mode, platform, properties, seed, build=None):
        built["model"] = build()
        raise RuntimeError("stopped")
    monkeypatch.setattr(study, "_equilibrated", stop)
    with pytest.raises(RuntimeError, match="stopped"):
        study.polymer_normal_stresses(ARGON_MODEL, 12, study.Chains(6, 0.3), cells=(3, 3, 6))
    model = built["model"]
    assert len(model.chains) == 11 and all(len(chain) == 6 for chain in model.chains)
    assert model.bonds.getNumBonds() == 55 and model.bonds.getForceGroup() == study.BOND_GROUP
    assert model.integrator.getMode() == GenDPDEIntegrator.Isothermal


@pytest.mark.validation
def test_the_shear_flow_example_runs_the_openmm_way_and_measures_the_viscosity():
    """examples/shear_flow.py at a small size (512 particles, 3500 steps to develop, ~3 tau, 4000 measured; ~10 s):
    160 swaps in the measured 4000 steps, the profile falling in the first half and rising in the second, and eta
    within 3 combined standard errors of the viscosity of docs/transport.md's two methods on the same model (121.6 +-
    3.6 amu/(nm ps), as in test_reverse_shear_viscosity_agrees_with_the_wave_decay_and_poiseuille_flow; the box has
    the same length along z, so the same k = 2 pi/L), the run's error at least 6.5% (the scatter expected of 3.4 tau,
    from the 4.2% of 8 tau measured in docs/flows.md)."""
    import pathlib
    import re
    import subprocess
    import sys
    script = pathlib.Path(__file__).resolve().parents[2] / "examples" / "shear_flow.py"
    result = subprocess.run([sys.executable, str(script), "--cells", "4", "4", "8", "--develop", "3500", "--steps",
                             "4000"], capture_output=True, text=True, check=True, timeout=600)
    assert "160 swaps" in result.stdout
    rows = [line.split() for line in result.stdout.splitlines() if re.match(r"^\s*\d+\.\d+\s+[+-]", line)]
    v = np.array([float(row[1]) for row in rows])
    assert len(v) == 20 and v[2] > v[5] > v[8] and v[12] < v[15] < v[18]
    eta, error = (float(x) for x in re.search(r"eta = (\S+) \+- (\S+) amu", result.stdout).groups())
    assert eta == pytest.approx(121.6, abs=3 * math.hypot(max(error, 0.065 * eta), 3.6))
