# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""The virial and pressure tensors (GenDPDEForce.getParticleVirials, openmmgendpde.analysis.pressure) against the scalar
virial and the energy's response to deformations of the box, for every estimator (V-C's pair forces are not central) and
platform, in cubic and triclinic boxes and a slab. (The C++ tests check each particle's tensor against the
brute-force evaluator and every element by finite differences on every platform and precision.)"""

import numpy as np
import openmm
import pytest
from conftest import PLATFORM_PARAMETERS
from helpers import DENSITY, lattice_liquid, make_context
from openmm import unit

from openmmgendpde import ESTIMATOR_NAMES
from openmmgendpde.analysis.pressure import pressure_tensor, virial_tensor

ESTIMATORS = list(ESTIMATOR_NAMES)


def triclinic(system, positions):
    """The lattice liquid's box sheared into a reduced triclinic one (positions unchanged: a different liquid)."""
    a, b, c = (np.array(v.value_in_unit(unit.nanometer)) for v in system.getDefaultPeriodicBoxVectors())
    edge = a[0]
    system.setDefaultPeriodicBoxVectors(openmm.Vec3(edge, 0, 0), openmm.Vec3(0.3 * edge, edge, 0),
                                        openmm.Vec3(-0.4 * edge, 0.2 * edge, edge))
    return system, positions


@pytest.mark.parametrize("estimator", ESTIMATORS, ids=[ESTIMATOR_NAMES[e] for e in ESTIMATORS])
@pytest.mark.parametrize("name", PLATFORM_PARAMETERS)
def test_trace_is_the_scalar_virial(name, estimator):
    """The per-particle tensors (N x 3 x 3, kJ/mol) add up to W with trace W = GenDPDEForce.getVirial (the
    platform's own sum over pairs): 1e-10 relative to the sum of the particles' |trace| (the same sums in another
    order); W is symmetric (the energy is invariant under rotations) to the same tolerance, in a cubic and a triclinic
    box."""
    for shear in (False, True):
        system, force, positions = lattice_liquid(6, estimator=estimator, seed=12, jitter=0.2)
        if shear:
            system, positions = triclinic(system, positions)
        context = make_context(system, positions, openmm.Platform.getPlatformByName(name))
        particles = force.getParticleVirials(context)
        assert particles.unit == unit.kilojoule_per_mole and particles.shape == (system.getNumParticles(), 3, 3)
        w = virial_tensor(force, context)
        scale = np.abs(np.trace(particles.value_in_unit(unit.kilojoule_per_mole), axis1=1, axis2=2)).sum()
        assert np.trace(w) == pytest.approx(force.getVirial(context).value_in_unit(unit.kilojoule_per_mole),
                                            abs=1e-10 * scale)
        assert np.abs(w - w.T).max() <= 1e-10 * scale


def energy_after(context, positions, box, deform):
    """U (kJ/mol) with positions and box vectors (rows) mapped by the matrix ``deform`` (r -> deform r)."""
    context.setPeriodicBoxVectors(*[openmm.Vec3(*(deform @ np.array(v))) for v in box])
    context.setPositions(positions @ deform.T)
    return context.getState(getEnergy=True).getPotentialEnergy().value_in_unit(unit.kilojoule_per_mole)


@pytest.mark.parametrize("estimator", ESTIMATORS, ids=[ESTIMATOR_NAMES[e] for e in ESTIMATORS])
@pytest.mark.parametrize("geometry", ["bulk", "slab"])
def test_components_are_the_energys_response_to_strain(estimator, geometry):
    """W_ab = -dU/d epsilon for the strain r_a -> r_a + epsilon r_b of positions and box: stretching along x gives
    W_xx, shearing x by z gives W_xz (the sheared box is triclinic, which GenDPDEForce supports), in a bulk liquid
    and in a slab with two free surfaces (where V-C's moment forces act). Central differences with epsilon = 1e-6:
    truncation ~1e-12 relative, rounding eps |U|/1e-6 ~ 1e-9 of |W|: 1e-6 relative to the largest component."""
    system, force, positions = lattice_liquid(6, estimator=estimator, seed=13, jitter=0.2,
                                              density=(0.82 if geometry == "slab" else 1.0) * DENSITY)
    if geometry == "slab":   # the liquid in the middle third of a box three times as long along z
        a, b, c = system.getDefaultPeriodicBoxVectors()
        edge = c[2].value_in_unit(unit.nanometer)
        system.setDefaultPeriodicBoxVectors(a, b, openmm.Vec3(0, 0, 3 * edge))
        positions = positions + np.array([0, 0, edge])
    context = make_context(system, positions, openmm.Platform.getPlatformByName("Reference"))
    w = virial_tensor(force, context)
    box = [np.array(v.value_in_unit(unit.nanometer)) for v in system.getDefaultPeriodicBoxVectors()]
    epsilon = 1e-6
    for a, b in ((0, 0), (1, 1), (2, 2), (0, 2), (0, 1), (1, 2)):
        strain = np.zeros((3, 3))
        strain[a, b] = epsilon
        plus = energy_after(context, positions, box, np.eye(3) + strain)
        minus = energy_after(context, positions, box, np.eye(3) - strain)
        derivative = (plus - minus) / (2 * epsilon)
        assert -derivative == pytest.approx(w[a, b], abs=1e-6 * np.abs(w).max()), (a, b)
    if geometry == "slab":   # the free surfaces: the normal virial differs from the tangential ones
        assert abs(w[2, 2] - 0.5 * (w[0, 0] + w[1, 1])) > 1e-3 * np.abs(w).max()


def test_pressure_tensor_trace_is_the_virial_pressure():
    """trace P / 3 = (2 K_int + W)/(3V), the scalar virial pressure of the reporters
    (openmmgendpde.analysis.thermodynamics, from the integrator's kinetic energy and GenDPDEForce.getVirial): the same
    sums, 1e-10 relative."""
    from helpers import TEMPERATURE, argon_integrator

    from openmmgendpde.analysis.thermodynamics import ThermodynamicProbe
    system, force, positions = lattice_liquid(6, seed=14)
    integrator = argon_integrator(0.01 * unit.picosecond)
    integrator.setTemperature(TEMPERATURE * unit.kelvin)
    context = make_context(system, positions, openmm.Platform.getPlatformByName("Reference"), integrator)
    context.setVelocitiesToTemperature(TEMPERATURE * unit.kelvin, 3)
    integrator.setInternalEnergiesToTemperature(TEMPERATURE * unit.kelvin, 4)
    integrator.step(20)
    state = context.getState(getEnergy=True, getVelocities=True, getForces=True)
    p = pressure_tensor(force, context, state)
    scalar = ThermodynamicProbe(system).sample(state, context, integrator).pressure
    assert np.trace(p) / 3 == pytest.approx(scalar.value_in_unit(unit.kilojoule_per_mole / unit.nanometer**3),
                                            rel=1e-10)


def test_pressure_tensor_needs_periodic_boundaries():
    system, force, positions = lattice_liquid(5, periodic=False)
    context = make_context(system, positions, openmm.Platform.getPlatformByName("Reference"))
    with pytest.raises(ValueError, match="periodic"):
        pressure_tensor(force, context)
    assert virial_tensor(force, context).shape == (3, 3)
