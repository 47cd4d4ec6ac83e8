# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""A bonded force without periodic boundary conditions in a periodic GenDPDE System (docs/soft-matter.md, "Bonds and
periodic boundaries"): OpenMM measures its bonds as the positions are, which is right while every molecule is whole
(unwrapped positions, OpenMM's convention); positions that split a molecule across the box are refused when set, on
every platform, naming the pair and the force. Before this check, a chain wrapped into the box started at ~57,000
kJ/mol of bond energy and the run went on."""

import numpy as np
import openmm
import pytest
from helpers import TEMPERATURE, argon_integrator, lattice_liquid

#: The bond: rest length (nm) and stiffness (kJ/mol/nm^2).
BOND_LENGTH, BOND_STIFFNESS = 0.4, 1000.0


def chain_scene(periodic_bonds, angles=False):
    """(system, positions, chain): 4^3 argon particles; particles 0, 1, 2 form a chain along x across the box's
    boundary x = L (unwrapped: 1 and 2 beyond it), bonded by a HarmonicBondForce (and a HarmonicAngleForce) with or
    without periodic boundary conditions."""
    system, _, positions = lattice_liquid(4)
    edge = system.getDefaultPeriodicBoxVectors()[0][0].value_in_unit(openmm.unit.nanometer)
    chain = [0, 1, 2]
    start = np.array([edge - 0.2, 0.5 * edge, 0.5 * edge])
    for k, particle in enumerate(chain):
        positions[particle] = start + [k * BOND_LENGTH, 0, 0]
    bonds = openmm.HarmonicBondForce()
    for i, j in zip(chain, chain[1:]):
        bonds.addBond(i, j, BOND_LENGTH, BOND_STIFFNESS)
    bonds.setUsesPeriodicBoundaryConditions(periodic_bonds)
    system.addForce(bonds)
    if angles:
        angle = openmm.HarmonicAngleForce()
        angle.addAngle(*chain, np.pi, 50.0)
        angle.setUsesPeriodicBoundaryConditions(periodic_bonds)
        system.addForce(angle)
    return system, positions, edge


def context_of(system, platform):
    integrator = argon_integrator(0.002)
    integrator.setTemperature(TEMPERATURE)
    return openmm.Context(system, integrator, platform), integrator


def bond_energy(context, system):
    groups = {i for i in range(system.getNumForces()) if not system.getForce(i).getName().startswith("GenDPDE")}
    for i in groups:
        system.getForce(i).setForceGroup(1)
    context.reinitialize(preserveState=True)
    return context.getState(getEnergy=True, groups={1}).getPotentialEnergy().value_in_unit(
        openmm.unit.kilojoule_per_mole)


@pytest.mark.parametrize("angles", [False, True])
def test_a_molecule_split_by_the_box_is_refused_when_its_bonds_are_not_periodic(platform, angles):
    """The chain wrapped into the box (particle 1 and 2 moved back by one box edge): OpenMM's HarmonicBondForce would
    measure the bond 0-1 as ~L - 0.4 nm long. setPositions raises naming the particles, the force,
    and both ways on; the next step refuses; the whole (unwrapped) chain is then accepted and steps."""
    system, whole, edge = chain_scene(periodic_bonds=False, angles=angles)
    context, integrator = context_of(system, platform)
    split = whole.copy()
    split[1:3, 0] -= edge
    with pytest.raises(openmm.OpenMMException) as error:
        context.setPositions(split)
    message = str(error.value)
    for fragment in ("particles 0 and 1", "HarmonicBondForce (force 1", "does not use periodic boundary",
                     "keep each molecule whole", "setUsesPeriodicBoundaryConditions(true)"):
        assert fragment in message, message
    with pytest.raises(openmm.OpenMMException, match="cannot step from the positions set: .*particles 0 and 1"):
        integrator.step(1)
    context.setPositions(whole)
    context.setVelocitiesToTemperature(TEMPERATURE, 1)
    integrator.step(5)


def test_the_angle_alone_names_its_outer_pair(platform):
    """A HarmonicAngleForce without periodic boundaries and periodic bonds: the pair it bonds that crosses the
    boundary (OpenMM's angle names the pairs 0-1 and 1-2) is refused, naming the angle force."""
    system, whole, edge = chain_scene(periodic_bonds=False, angles=True)
    system.getForce(1).setUsesPeriodicBoundaryConditions(True)
    context, _ = context_of(system, platform)
    split = whole.copy()
    split[2, 0] -= edge
    with pytest.raises(openmm.OpenMMException, match="particles 1 and 2, bonded by HarmonicAngleForce \\(force 2"):
        context.setPositions(split)


def test_whole_molecules_and_periodic_bonds_are_accepted_alike(platform):
    """The independent check of what is accepted: the bond energy of the whole chain with non-periodic bonds, and of
    the split chain with periodic ones, both equal k (r - r0)^2/2 summed over the bonds at the lattice's unwrapped
    distances (here 0: each bond is at its rest length), to rounding; the split chain with periodic bonds is not
    refused."""
    system, whole, edge = chain_scene(periodic_bonds=False)
    context, _ = context_of(system, platform)
    context.setPositions(whole)
    assert bond_energy(context, system) == pytest.approx(0.0, abs=1e-9)
    system, whole, edge = chain_scene(periodic_bonds=True)
    context, _ = context_of(system, platform)
    split = whole.copy()
    split[1:3, 0] -= edge
    context.setPositions(split)
    assert bond_energy(context, system) == pytest.approx(0.0, abs=1e-9)


def test_the_refusal_is_what_the_old_run_went_on_with():
    """What the check prevents, measured on Reference with a VerletIntegrator (which does not check): the bond 0-1
    of the split chain is measured across the box, L - 0.4 nm = 2.065 nm long, an energy of k (L - 2 r0)^2/2 =
    1000 x 1.665^2/2 ~ 1386 kJ/mol for this bond alone, where the whole chain has 0."""
    system, whole, edge = chain_scene(periodic_bonds=False)
    context = openmm.Context(system, openmm.VerletIntegrator(0.001), openmm.Platform.getPlatformByName("Reference"))
    split = whole.copy()
    split[1:3, 0] -= edge
    context.setPositions(split)
    expected = BOND_STIFFNESS * (edge - 2 * BOND_LENGTH) ** 2 / 2
    assert bond_energy(context, system) == pytest.approx(expected, rel=1e-9)
