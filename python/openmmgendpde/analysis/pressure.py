# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""The virial and pressure tensors of a GenDPDEForce (docs/fluids.md): what shear flows, surface tension or
anisotropic boxes need beyond the scalar virial that GenDPDEForce.getVirial returns.

    W_ab = sum over pairs i<j of F_ij,a r_ij,b = -dU/d epsilon_ab,

F_ij the pair force on i (with V-C's moment term, which is not along r_ij) and epsilon the strain r -> (1 + epsilon) r
of positions and box. The force's own kernels compute it on every platform, for every estimator and any box
(GenDPDEForce.getParticleVirials: each particle's half of its pairs' tensors); this module only sums them and adds
the kinetic part of the pressure tensor:

    P_ab = (sum_i m_i v_i,a v_i,b + W_ab) / V          (velocities at the positions' time, centre-of-mass frame)
"""

import numpy as np
from openmm import unit

from ..api import GenDPDEForce, GenDPDEIntegrator
from .thermodynamics import VIRIAL_SCALING_STEP, is_external_field, particle_masses, strain_derivatives


def virial_tensor(force, context, per_particle=False):
    """W (3 x 3, kJ/mol) of ``force`` (a GenDPDEForce in the Context's System) at the Context's positions; with
    ``per_particle``, N x 3 x 3: each particle's half of its pairs' tensors (they sum to W)."""
    virials = GenDPDEForce.cast(force).getParticleVirials(context).value_in_unit(unit.kilojoule_per_mole)
    return virials if per_particle else virials.sum(axis=0)


def pressure_tensor(force, context, state=None, numerical_groups=()):
    """P (3 x 3, kJ/mol/nm^3) of the System in the Context (periodic boundaries): kinetic part plus the virial tensor
    of ``force``. The velocities are those at the time of the positions (for a GenDPDEIntegrator, whose stored
    velocities are half a step behind, v + (dt/2) F/m, as its kinetic energy uses them), in the centre-of-mass frame.
    Other forces are included only through ``numerical_groups``: force groups (not holding ``force``) whose
    numerical_virial_tensor is added (bonds, external fields). ``state``: a State with velocities and forces."""
    if not GenDPDEForce.cast(force).usesPeriodicBoundaryConditions():
        raise ValueError("pressure_tensor: the pressure of a box needs periodic boundaries (CutoffPeriodic); "
                         "virial_tensor works for open ones too")
    state = state or context.getState(getVelocities=True, getForces=True)
    system = context.getSystem()
    masses = particle_masses(system)
    velocities = state.getVelocities(asNumpy=True).value_in_unit(unit.nanometer / unit.picosecond)
    integrator = context.getIntegrator()
    if GenDPDEIntegrator.isinstance(integrator):
        step = integrator.getStepSize().value_in_unit(unit.picosecond)
        forces = state.getForces(asNumpy=True).value_in_unit(unit.kilojoule_per_mole / unit.nanometer)
        velocities = velocities + 0.5 * step * forces / masses[:, None]
    velocities = velocities - (masses @ velocities) / masses.sum()
    kinetic = np.einsum("i,ia,ib->ab", masses, velocities, velocities)
    box = state.getPeriodicBoxVectors(asNumpy=True).value_in_unit(unit.nanometer)
    virial = virial_tensor(force, context)
    if numerical_groups:
        virial = virial + numerical_virial_tensor(context, set(numerical_groups))
    return (kinetic + virial) / abs(np.linalg.det(box))


#: The strains (a, b) of numerical_virial_tensor, r_a -> r_a + epsilon r_b: the three stretches and the three shears
#: that keep a box in OpenMM's reduced form (box vectors as the rows of a lower-triangular matrix).
STRAINS = ((0, 0), (1, 1), (2, 2), (0, 1), (0, 2), (1, 2))


def numerical_virial_tensor(context, groups, step=VIRIAL_SCALING_STEP):
    """W (3 x 3, kJ/mol) of the energy U of the force ``groups`` (a set of force group numbers) at the Context's
    positions: W_ab = -dU/d epsilon_ab under the strain r_a -> r_a + epsilon r_b of the positions and the periodic box
    (the pair form sum F_ij,a r_ij,b for pair forces), by central differences at epsilon = +-``step``
    (thermodynamics.strain_derivatives: two energy evaluations per strain, error O(step^2)). The strains are those of
    STRAINS, which keep the box in OpenMM's reduced form: the diagonal and W_xy, W_xz, W_yz; W_yx, W_zx, W_zy are set
    equal to them (the virial of an energy that does not change under rotations is symmetric; for a GenDPDEForce
    virial_tensor gives it exactly). For any force without a virial of its own (bonds, OpenMM's forces), e.g. the
    normal stress differences of a polymer solution. An external field (thermodynamics.is_external_field: its energy
    reads absolute positions, and it carries no momentum across a surface in the fluid, docs/flows.md) has no place in
    it: a group holding one is refused (ValueError naming the force) before anything changes. The Context's positions
    and box are restored exactly (a GenDPDEIntegrator treats it as a move: docs/integrator.md)."""
    system = context.getSystem()
    for index in range(system.getNumForces()):
        force = system.getForce(index)
        if force.getForceGroup() in set(groups) and is_external_field(force):
            raise ValueError(f"numerical_virial_tensor: groups = {sorted(set(groups))} holds force {index}, a "
                             f"{type(force).__name__}, an external field (its energy reads absolute positions); give "
                             f"the groups of interactions only (an external field in a force group of its own)")
    strains = []
    for a, b in STRAINS:
        strain = np.zeros((3, 3))
        strain[a, b] = 1.0
        strains.append(strain)
    virial = np.zeros((3, 3))
    for (a, b), derivative in zip(STRAINS, strain_derivatives(context, set(groups), strains, step)):
        virial[a, b] = virial[b, a] = derivative
    return virial
