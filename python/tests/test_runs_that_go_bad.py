# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""A run that goes bad stops, the same way on every platform, and stays stopped until a saved state is loaded
(docs/integrator.md, "When a run goes bad")."""

import functools
import re

import numpy as np
import openmm
import pytest
from helpers import TEMPERATURE, argon_integrator, lattice_liquid

from openmmgendpde import GenDPDEForce

STOPPED = "This Context takes no step from this state"


def pushed_liquid(platform_name):
    """216 argon particles with the thermal Tait law; particle 0 pushed along x by a constant force of 2e5 kJ/mol/nm,
    so that it is driven through its neighbours faster every step until the run goes bad (at step 11 with this seed:
    a neighbour's temperature changes by more than a factor 2 in one step). A fixed random seed: Reference and CPU
    give the same trajectory to the bit, OpenCL in double precision to rounding."""
    system, force, positions = lattice_liquid(6)
    force.setEquationOfState(GenDPDEForce.TaitThermalExpansion, [0.955, 125.7])
    push = openmm.CustomExternalForce("-f*x")
    push.addGlobalParameter("f", 2e5)
    push.addParticle(0, [])
    system.addForce(push)
    integrator = argon_integrator(0.01)
    integrator.setTemperature(TEMPERATURE)
    integrator.setRandomNumberSeed(5)
    context = openmm.Context(system, integrator, openmm.Platform.getPlatformByName(platform_name))
    context.setPositions(positions)
    context.setVelocitiesToTemperature(TEMPERATURE, 1)
    return integrator, context


def snapshot(context, integrator):
    state = context.getState(getPositions=True, getVelocities=True)
    return (state.getStepCount(), state.getPositions(asNumpy=True)._value.copy(),
            state.getVelocities(asNumpy=True)._value.copy(), integrator.getInternalEnergies()._value.copy())


def assert_same_snapshot(first, second):
    assert first[0] == second[0]
    for a, b in zip(first[1:], second[1:]):
        assert np.array_equal(a, b)


@functools.lru_cache
def reference_failure():
    """(step, particle) at which the pushed liquid's run stops on the Reference platform."""
    integrator, context = pushed_liquid("Reference")
    with pytest.raises(openmm.OpenMMException) as error:
        integrator.step(40)
    return failure_of(str(error.value))


def failure_of(message):
    particle = re.search(r"particle (\d+)", message)
    step = re.search(r"at step (\d+)", message)
    assert particle and step, message
    return int(step.group(1)), int(particle.group(1))


def test_a_run_that_goes_bad_stops_and_stays_stopped(platform):
    # Before: the failure (a temperature that changed by more than a factor 2 in one step) was raised, but a
    # setPositions() to the very same positions cleared it and the run went on past the instability; OpenCL ran two
    # more steps on the next call while Reference and CPU raised again. Now every platform stops at the same step,
    # naming the same particle, and refuses every later step, checkpoint and State until a saved state is loaded.
    integrator, context = pushed_liquid(platform.getName())
    saved = context.createCheckpoint()
    with pytest.raises(openmm.OpenMMException, match=STOPPED) as error:
        integrator.step(40)
    assert "went from" in str(error.value)
    assert failure_of(str(error.value)) == reference_failure()
    at_failure = snapshot(context, integrator)
    assert at_failure[0] == reference_failure()[0]   # the steps before the failure, none after
    for attempt in (lambda: integrator.step(1), lambda: integrator.step(5), context.createCheckpoint,
                    lambda: context.getState(getIntegratorParameters=True)):
        with pytest.raises(openmm.OpenMMException, match="the run stopped") as again:
            attempt()
        assert "went from" in str(again.value) and STOPPED in str(again.value)
        assert_same_snapshot(snapshot(context, integrator), at_failure)
    # A move does not clear it: the same positions set again.
    context.setPositions(context.getState(getPositions=True).getPositions())
    with pytest.raises(openmm.OpenMMException, match="the run stopped"):
        integrator.step(1)
    # The way on the message names: a checkpoint saved before the failure.
    context.loadCheckpoint(saved)
    integrator.step(3)
    assert context.getState().getStepCount() == 3


def test_a_saved_state_also_lets_the_run_go_on():
    integrator, context = pushed_liquid("Reference")
    state = context.getState(getPositions=True, getVelocities=True, getIntegratorParameters=True)
    with pytest.raises(openmm.OpenMMException, match=STOPPED):
        integrator.step(40)
    context.setState(state)
    integrator.step(2)
    assert context.getState().getStepCount() == 2


def test_a_refused_checkpoint_stops_the_run():
    # Before: OpenMM had already restored the damaged checkpoint's positions and velocities when the integrator
    # refused its part, and the next step went on from them silently (72 of 200 damaged checkpoints). Now the refusal
    # says the Context holds the refused checkpoint's state, and the run stays stopped until a good one is loaded.
    integrator, context = pushed_liquid("Reference")
    integrator.step(2)
    good = context.createCheckpoint()
    damaged = bytearray(good)
    damaged[len(damaged) // 3] ^= 0x01   # a byte of OpenMM's part (positions, velocities)
    with pytest.raises(openmm.OpenMMException, match="checksum") as error:
        context.loadCheckpoint(bytes(damaged))
    assert "now holds the refused checkpoint's positions" in str(error.value) and STOPPED in str(error.value)
    with pytest.raises(openmm.OpenMMException, match="the run stopped"):
        integrator.step(1)
    context.loadCheckpoint(good)
    integrator.step(1)
    assert context.getState().getStepCount() == 3


def test_reinitialize_keeping_the_state_is_refused_after_a_failure():
    # reinitialize(preserveState=True) goes through a checkpoint: it is refused before anything changes, so that a
    # failed state cannot come back as a fresh one; without the state, the Context starts anew.
    integrator, context = pushed_liquid("Reference")
    with pytest.raises(openmm.OpenMMException, match=STOPPED):
        integrator.step(40)
    at_failure = snapshot(context, integrator)
    with pytest.raises(openmm.OpenMMException, match="cannot create a checkpoint: the run stopped"):
        context.reinitialize(preserveState=True)
    assert_same_snapshot(snapshot(context, integrator), at_failure)
    context.reinitialize(preserveState=False)
    positions = lattice_liquid(6)[2]
    context.setPositions(positions)
    integrator.step(1)


def started_liquid(platform):
    system, force, positions = lattice_liquid(4)
    integrator = argon_integrator(0.01)
    integrator.setTemperature(TEMPERATURE)
    return force, integrator, openmm.Context(system, integrator, platform), positions


@pytest.mark.parametrize("bad", [1e30, 1001.5, np.nan])
def test_positions_no_platform_can_wrap_alike_are_refused(platform, bad):
    # Before: a position of 1e30 nm was accepted and gave particle 5 the density 5.645 nm^-3 on Reference and CPU and
    # 20.15 on OpenCL (each platform's periodic wrapping of 1e30 is a different number); a NaN position reached
    # OpenMM's CPU check, which names no particle. Now such positions are refused when set, naming the particle, and
    # no step starts from them; 1000 box lengths outside the box is the limit (1001.5 edges: 1001 outside).
    force, integrator, context, positions = started_liquid(platform)
    edge = context.getState().getPeriodicBoxVectors()[0][0].value_in_unit(openmm.unit.nanometer)
    bad_positions = positions.copy()
    bad_positions[5, 0] = bad * edge if bad == 1001.5 else bad
    with pytest.raises(openmm.OpenMMException, match="particle 5 ") as error:
        context.setPositions(bad_positions)
    assert ("not finite" if np.isnan(bad) else "box lengths outside the periodic box") in str(error.value)
    with pytest.raises(openmm.OpenMMException, match="cannot step from the positions set"):
        integrator.step(1)
    context.setPositions(positions)
    integrator.step(1)
    assert context.getState().getStepCount() == 1


def test_positions_within_the_limit_are_wrapped_alike(platform):
    # 999 box lengths out along each axis: the densities are those of the positions in the box (to rounding: the
    # shift by 999 edges costs ~1e3 ulp of the coordinate).
    force, integrator, context, positions = started_liquid(platform)
    context.setPositions(positions)
    inside = force.getParticleDensities(context).value_in_unit(openmm.unit.nanometer**-3)
    edge = context.getState().getPeriodicBoxVectors()[0][0].value_in_unit(openmm.unit.nanometer)
    shifted = positions + np.array([999.0, -999.0, 999.0]) * edge
    context.setPositions(shifted)
    outside = force.getParticleDensities(context).value_in_unit(openmm.unit.nanometer**-3)
    assert np.allclose(outside, inside, rtol=1e-8, atol=0)


def background_pressure_run(platform, background_pressure):
    system, force, positions = lattice_liquid(6)
    force.setBackgroundPressure(background_pressure)
    integrator = argon_integrator(0.01)
    integrator.setTemperature(TEMPERATURE)
    integrator.setRandomNumberSeed(3)
    context = openmm.Context(system, integrator, platform)
    context.setPositions(positions)
    context.setVelocitiesToTemperature(TEMPERATURE, 1)
    return integrator, context


def test_a_run_whose_step_no_longer_integrates_the_forces_stops(platform):
    # Before: a background pressure of 1e6 kJ/mol/nm^3 (allowed: it is a model parameter) at argon's step dt* = 0.01
    # ran on silently: in 300 steps the mean temperature rose from 137 K to ~1e5 K while the conserved energy fell by
    # ~1700 kJ/mol per particle in the first 20 steps (K + sum eps was 15 per particle): the step no longer resolves
    # the forces. Now the energy guard stops it at its first look, step 100 (the drift there: ~18% of K + sum eps).
    integrator, context = background_pressure_run(platform, 1e6)
    with pytest.raises(openmm.OpenMMException, match=r"the conserved energy K \+ U \+ sum eps changed by .* between "
                                                     r"step 0 and step 100, more than 10% .* particle \d+ has the "
                                                     r"largest kinetic energy") as error:
        integrator.step(300)
    assert STOPPED in str(error.value)
    assert context.getState().getStepCount() == 100
    with pytest.raises(openmm.OpenMMException, match="the run stopped"):
        integrator.step(1)


def test_heat_the_dynamics_integrates_does_not_stop_the_run():
    # The guard looks at the conserved energy, not the temperature: with a background pressure of 1e3 kJ/mol/nm^3
    # the lattice's structure releases p_b (V_box - sum V_i) as heat (the mean temperature rises from 137 K to ~207 K
    # in 300 steps, measured) while E drifts by 0.02% of K + sum eps, well integrated: it runs on, in calls of any
    # length (the looks fall at steps 100, 200, 300 either way).
    for calls in ([300], [7] * 43):
        integrator, context = background_pressure_run(openmm.Platform.getPlatformByName("Reference"), 1e3)
        start = integrator.getConservedEnergy().value_in_unit(openmm.unit.kilojoule_per_mole)
        for steps in calls:
            integrator.step(steps)
        drift = integrator.getConservedEnergy().value_in_unit(openmm.unit.kilojoule_per_mole) - start
        kinetic = context.getState(getEnergy=True).getKineticEnergy().value_in_unit(openmm.unit.kilojoule_per_mole)
        moved = kinetic + sum(integrator.getInternalEnergies().value_in_unit(openmm.unit.kilojoule_per_mole))
        assert abs(drift) < 1e-3 * moved   # (measured: 0.6 kJ/mol of ~3000)
        assert integrator.getParticleTemperatures().value_in_unit(openmm.unit.kelvin).mean() > 180
