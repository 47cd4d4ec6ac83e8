# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""The numerical virial tensor of any force group (analysis.pressure.numerical_virial_tensor: strains of positions and
box by central differences) against exact ones: GenDPDEForce's own per-particle tensors (its kernels' pair sums) on a
GenDPDE-only System, and the analytic virial of harmonic bonds across the periodic boundaries, in rectangular and
triclinic boxes; and pressure_tensor with the bonds' group added."""

import numpy as np
import openmm
import pytest
from helpers import lattice_liquid, make_context
from openmm import unit

from openmmgendpde import GenDPDEForce
from openmmgendpde.analysis.pressure import numerical_virial_tensor, pressure_tensor, virial_tensor
from openmmgendpde.analysis.thermodynamics import numerical_virial


def _triclinic(system):
    """The System's cubic box sheared into a reduced triclinic one (the liquid's positions are then another liquid)."""
    edge = system.getDefaultPeriodicBoxVectors()[0][0].value_in_unit(unit.nanometer)
    system.setDefaultPeriodicBoxVectors(openmm.Vec3(edge, 0, 0), openmm.Vec3(0.3 * edge, edge, 0),
                                        openmm.Vec3(-0.4 * edge, 0.2 * edge, edge))


@pytest.mark.parametrize("estimator", [GenDPDEForce.VA, GenDPDEForce.VB, GenDPDEForce.VC], ids=["VA", "VB", "VC"])
@pytest.mark.parametrize("triclinic", [False, True], ids=["rectangular", "triclinic"])
def test_numerical_tensor_equals_gendpde_s_exact_one(estimator, triclinic):
    """On a System whose only force is a GenDPDEForce (216 particles, jittered lattice): every element of the
    numerical tensor within 1e-6 of the largest |W_ab| of the exact one (virial_tensor, the kernels' sum of F_ij,a
    r_ij,b; central differences of step 1e-5 are good to ~1e-10 relative, rounding of energies ~1e3 kJ/mol over 2e-5
    to ~1e-9 kJ/mol); the positions and the box are back exactly afterwards."""
    system, force, positions = lattice_liquid(6, estimator=estimator, seed=3, jitter=0.2)
    if triclinic:
        _triclinic(system)
    context = make_context(system, positions, openmm.Platform.getPlatformByName("Reference"))
    state = context.getState(getPositions=True)
    exact = virial_tensor(force, context)
    numerical = numerical_virial_tensor(context, {0})
    assert np.abs(numerical - exact).max() < 1e-6 * np.abs(exact).max()
    after = context.getState(getPositions=True)
    assert np.array_equal(after.getPositions(asNumpy=True), state.getPositions(asNumpy=True))
    assert np.array_equal(after.getPeriodicBoxVectors(asNumpy=True), state.getPeriodicBoxVectors(asNumpy=True))


def _bonded(triclinic):
    """(system, positions, bonds): 30 particles in a 2 nm box, chains of harmonic bonds (k = 500 kJ/mol/nm^2,
    r0 = 0.3 nm) of random lengths 0.15-0.5 nm, each particle wrapped into the box so that many bonds cross its faces
    (OpenMM's minimum image), in force group 1."""
    rng = np.random.default_rng(11)
    edge = 2.0
    system = openmm.System()
    system.setDefaultPeriodicBoxVectors(openmm.Vec3(edge, 0, 0), openmm.Vec3(0.3 * edge if triclinic else 0, edge, 0),
                                        openmm.Vec3(-0.4 * edge if triclinic else 0, 0.2 * edge if triclinic else 0,
                                                    edge))
    positions = [rng.uniform(-1, 3, 3)]
    bonds = openmm.HarmonicBondForce()
    bonds.setUsesPeriodicBoundaryConditions(True)
    bonds.setForceGroup(1)
    for i in range(30):
        system.addParticle(10.0)
        if i:
            step = rng.normal(size=3)
            positions.append(positions[-1] + step / np.linalg.norm(step) * rng.uniform(0.15, 0.5))
            bonds.addBond(i - 1, i, 0.3, 500.0)
    system.addForce(bonds)
    box = np.array([v.value_in_unit(unit.nanometer) for v in system.getDefaultPeriodicBoxVectors()])
    positions = np.array(positions)
    positions -= np.floor(positions @ np.linalg.inv(box)) @ box   # each wrapped into the box: bonds cross its faces
    return system, positions, bonds


def _analytic_bond_virial(positions, box):
    """W = sum over bonds of F_ij,a r_ij,b = -k (|d| - r0) d_a d_b/|d|, d the minimum image of r_i+1 - r_i in the
    reduced box (rows), k = 500, r0 = 0.3: worked out by hand from U = (k/2)(|d| - r0)^2."""
    virial = np.zeros((3, 3))
    for i in range(len(positions) - 1):
        d = positions[i + 1] - positions[i]
        for k in (2, 1, 0):   # minimum image in a reduced box: the last vector first
            d -= box[k] * np.round(d[k] / box[k][k])
        r = np.linalg.norm(d)
        virial -= 500.0 * (r - 0.3) * np.outer(d, d) / r
    return virial


@pytest.mark.parametrize("triclinic", [False, True], ids=["rectangular", "triclinic"])
def test_numerical_tensor_equals_the_analytic_virial_of_periodic_bonds(triclinic):
    """Harmonic bonds (OpenMM's HarmonicBondForce, periodic) in group 1: the numerical tensor of group 1 equals the
    analytic bond virial within 1e-6 of its largest element, its trace equals thermodynamics.numerical_virial's scalar
    (the uniform scaling: another strain) to 1e-6, and a GenDPDE-free group 0 adds nothing. Some bonds cross the box's
    faces (their particles' difference is longer than half the box before the minimum image)."""
    system, positions, _ = _bonded(triclinic)
    context = make_context(system, positions, openmm.Platform.getPlatformByName("Reference"))
    box = context.getState().getPeriodicBoxVectors(asNumpy=True).value_in_unit(unit.nanometer)
    assert np.abs(np.diff(positions, axis=0)).max() > 1.0
    exact = _analytic_bond_virial(positions, box)
    numerical = numerical_virial_tensor(context, {1})
    assert np.abs(numerical - exact).max() < 1e-6 * np.abs(exact).max()
    assert np.trace(numerical) == pytest.approx(numerical_virial(context, {1}), abs=1e-6 * np.abs(exact).max())
    assert np.abs(numerical_virial_tensor(context, {0})).max() == 0


def test_pressure_tensor_adds_the_bonds_numerical_virial():
    """A GenDPDE liquid with harmonic bonds between neighbours along a chain in group 1: pressure_tensor with
    numerical_groups={1} is the one without plus the analytic bond virial over the volume (to 1e-6 relative)."""
    system, force, positions = lattice_liquid(6, seed=3, jitter=0.2)
    bonds = openmm.HarmonicBondForce()
    bonds.setUsesPeriodicBoundaryConditions(True)
    bonds.setForceGroup(1)
    for i in range(0, 40, 2):
        bonds.addBond(i, i + 1, 0.3, 500.0)
    system.addForce(bonds)
    context = make_context(system, positions, openmm.Platform.getPlatformByName("Reference"))
    context.setVelocitiesToTemperature(100.0, 1)
    state = context.getState(getVelocities=True, getForces=True, getPositions=True)
    box = state.getPeriodicBoxVectors(asNumpy=True).value_in_unit(unit.nanometer)
    x = state.getPositions(asNumpy=True).value_in_unit(unit.nanometer)
    expected_bonds = np.zeros((3, 3))
    for i in range(0, 40, 2):
        d = x[i + 1] - x[i]
        d -= np.diag(box) * np.round(d / np.diag(box))
        r = np.linalg.norm(d)
        expected_bonds -= 500.0 * (r - 0.3) * np.outer(d, d) / r
    without = pressure_tensor(force, context, state)
    with_bonds = pressure_tensor(force, context, state, numerical_groups={1})
    assert with_bonds - without == pytest.approx(expected_bonds / np.prod(np.diag(box)),
                                                 abs=1e-6 * np.abs(expected_bonds).max())


def test_a_group_holding_an_external_field_is_refused():
    """A CustomExternalForce (a body force) in the group asked for: a ValueError naming the force, positions and box
    untouched."""
    system, positions, _ = _bonded(False)
    field = openmm.CustomExternalForce("-0.5*x")
    field.addParticle(0, [])
    field.setForceGroup(1)
    system.addForce(field)
    context = make_context(system, positions, openmm.Platform.getPlatformByName("Reference"))
    before = context.getState(getPositions=True).getPositions(asNumpy=True)
    with pytest.raises(ValueError, match=r"groups = \[1\] holds force 1, a CustomExternalForce, an external field"):
        numerical_virial_tensor(context, {1})
    assert np.array_equal(context.getState(getPositions=True).getPositions(asNumpy=True), before)
