# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""The sweep's order is made at builds and kept between them (docs/theory.md section 6): the rule that decides a
build, checked against the trajectory itself. A State carries the positions of the order's last build
(``sweepBuild``); they must be the positions of the last step at which some particle had moved more than half the
skin (0.05 R) from its position at the build before, computed here from the positions of every step."""

import re

import numpy as np
import openmm
import pytest
from conftest import GPU_PLATFORMS
from helpers import TEMPERATURE, argon_integrator, lattice_liquid
from openmm import unit

#: The skin of the candidates as a fraction of R, and the displacement^2 that makes a build: (skin/2)^2, computed as
#: the definition computes it (gendpde/GenDPDESweepDefinition.h), so that the comparison below is exact.
SKIN_FRACTION = 0.1


def sweep_build(context, num_particles):
    """(box (3 x 3), positions (N x 3)) of the sweep order's last build, from a State's integrator parameters."""
    state = context.getState(getIntegratorParameters=True)
    text = re.search(r'sweepBuild="([^"]*)"', openmm.XmlSerializer.serialize(state)).group(1)
    values = np.array([float.fromhex(token) for token in text.split()])
    assert values.size == 9 + 3 * num_particles
    return values[:9].reshape(3, 3), values[9:].reshape(-1, 3)


@pytest.mark.parametrize("name", ["Reference", "CPU"] + [pytest.param(name, marks=pytest.mark.gpu)
                                                         for name in GPU_PLATFORMS])
def test_the_order_is_built_when_a_particle_has_moved_half_the_skin(name):
    system, force, positions = lattice_liquid(5, seed=3)
    cutoff = force.getCutoffDistance().value_in_unit(unit.nanometer)
    skin = SKIN_FRACTION * cutoff
    limit = 0.25 * skin * skin
    integrator = argon_integrator(0.01 * unit.picosecond)
    integrator.setRandomNumberSeed(17)
    integrator.setParticleTemperatures([TEMPERATURE] * system.getNumParticles())
    platform = openmm.Platform.getPlatformByName(name)
    context = openmm.Context(system, integrator, platform)
    context.setPositions(positions)
    context.setVelocitiesToTemperature(3 * TEMPERATURE * unit.kelvin, 18)   # hot: builds every few steps
    build, builds = None, 0
    for _ in range(60):
        x = context.getState(getPositions=True).getPositions(asNumpy=True).value_in_unit(unit.nanometer)
        if build is not None:
            d = x - build
            moved = (d[:, 0] * d[:, 0] + d[:, 1] * d[:, 1]) + d[:, 2] * d[:, 2]
        if build is None or np.any(moved > limit):
            build, builds = x, builds + 1
        integrator.step(1)
    box, positions_at_build = sweep_build(context, system.getNumParticles())
    assert 3 <= builds <= 30   # the rule is exercised: neither every step nor once
    assert np.array_equal(positions_at_build, build)
    expected_box = context.getState().getPeriodicBoxVectors(asNumpy=True).value_in_unit(unit.nanometer)
    assert np.array_equal(box, expected_box)


@pytest.mark.parametrize("name", ["Reference", "CPU"])
def test_a_force_evaluated_elsewhere_between_steps_changes_nothing(name):
    """The host sweep takes the candidates of the GenDPDEForce's list when that list was built at the positions of
    the order's build (the same candidates), but its builds follow the rule alone: an evaluation at other positions
    between steps (which rebuilds the force's list there, and again when the positions come back) leaves the
    trajectory bit for bit that of the undisturbed run."""
    def run(disturb):
        system, force, positions = lattice_liquid(5, seed=3)
        integrator = argon_integrator(0.01 * unit.picosecond)
        integrator.setRandomNumberSeed(17)
        integrator.setParticleTemperatures([TEMPERATURE] * system.getNumParticles())
        context = openmm.Context(system, integrator, openmm.Platform.getPlatformByName(name))
        context.setPositions(positions)
        context.setVelocitiesToTemperature(3 * TEMPERATURE * unit.kelvin, 18)
        for step in range(40):
            if disturb and step % 7 == 3:
                here = context.getState(getPositions=True).getPositions(asNumpy=True)
                context.setPositions(here[np.random.default_rng(step).permutation(len(here))])
                context.getState(getEnergy=True)
                context.setPositions(here)
                context.getState(getEnergy=True)
            integrator.step(1)
        state = context.getState(getPositions=True, getVelocities=True)
        return (state.getPositions(asNumpy=True)._value, state.getVelocities(asNumpy=True)._value,
                np.asarray(integrator.getInternalEnergies()._value))

    for undisturbed, disturbed in zip(run(False), run(True)):
        assert np.array_equal(undisturbed, disturbed)


@pytest.mark.gpu
@pytest.mark.parametrize("name", GPU_PLATFORMS)
@pytest.mark.parametrize("precision", ["mixed", "double"])
def test_the_force_sharing_the_orders_build_changes_no_bit(name, precision, monkeypatch):
    """On the GPU platforms a GenDPDEForce with the sweep's pair range makes its neighbour list from the sweep order's
    build during the integrator's runs of steps (one check, one grid); GENDPDE_NO_SHARED_BUILD (read at each run)
    makes each keep its own. The force sums by original index over the pairs closer than R whatever its list holds, so
    the two trajectories must be the same to the last bit (the potential energy, summed in the cells' order, to its
    rounding), through builds, runs of several lengths, evaluations between runs (the force's own list) and atom
    reordering."""
    system, force, positions = lattice_liquid(5, seed=3)
    # A zero CustomNonbondedForce with a cutoff makes OpenMM reorder the atoms (every 250 steps).
    spacer = openmm.CustomNonbondedForce("0")
    spacer.setNonbondedMethod(openmm.CustomNonbondedForce.CutoffPeriodic)
    spacer.setCutoffDistance(0.5 * force.getCutoffDistance())
    for _ in range(system.getNumParticles()):
        spacer.addParticle([])
    system.addForce(spacer)
    platform = openmm.Platform.getPlatformByName(name)
    results = []
    for shared in (True, False):
        if shared:
            monkeypatch.delenv("GENDPDE_NO_SHARED_BUILD", raising=False)
        else:
            monkeypatch.setenv("GENDPDE_NO_SHARED_BUILD", "1")
        integrator = argon_integrator(0.01 * unit.picosecond)
        integrator.setRandomNumberSeed(17)
        integrator.setParticleTemperatures([TEMPERATURE] * system.getNumParticles())
        context = openmm.Context(system, integrator, platform, {"Precision": precision})
        context.setPositions(positions)
        context.setVelocitiesToTemperature(3 * TEMPERATURE * unit.kelvin, 18)   # hot: builds every few steps
        energies = []
        for count in (1, 7, 20, 3, 29, 250):
            integrator.step(count)
            state = context.getState(getEnergy=True, getForces=True)   # an evaluation of the force's own
            energies.append(state.getPotentialEnergy().value_in_unit(unit.kilojoule_per_mole))
        state = context.getState(getPositions=True, getVelocities=True, getForces=True)
        results.append((np.array(energies), state.getPositions(asNumpy=True)._value,
                        state.getVelocities(asNumpy=True)._value, state.getForces(asNumpy=True)._value,
                        np.array(integrator.getInternalEnergies().value_in_unit(unit.kilojoule_per_mole)),
                        sweep_build(context, system.getNumParticles())[1]))
        del context
    # The potential energy is summed per thread in the order of the cells the list was last built from (the order's
    # or the force's own): its last bits may differ; nothing that moves the particles reads it.
    np.testing.assert_allclose(results[0][0], results[1][0], rtol=1e-12)
    for a, b in zip(results[0][1:], results[1][1:]):
        assert np.array_equal(a, b)
