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


def virial_tensor(force, context, per_particle=False):
    """W (3 x 3, kJ/mol) of ``force`` (a GenDPDEForce in the Context's System) at the Context's positions; with
    ``per_particle``, N x 3 x 3: each particle's half of its pairs' tensors (they sum to W)."""
    virials = GenDPDEForce.cast(force).getParticleVirials(context).value_in_unit(unit.kilojoule_per_mole)
    return virials if per_particle else virials.sum(axis=0)


def pressure_tensor(force, context, state=None):
    """P (3 x 3, kJ/mol/nm^3) of the System in the Context (periodic boundaries): kinetic part plus the virial tensor
    of ``force``. The velocities are those at the time of the positions (for a GenDPDEIntegrator, whose stored
    velocities are half a step behind, v + (dt/2) F/m, as its kinetic energy uses them), in the centre-of-mass frame.
    Other forces are not included (use it for Systems whose only force is this one). ``state``: a State with
    velocities and forces."""
    if not GenDPDEForce.cast(force).usesPeriodicBoundaryConditions():
        raise ValueError("pressure_tensor: the pressure of a box needs periodic boundaries (CutoffPeriodic); "
                         "virial_tensor works for open ones too")
    state = state or context.getState(getVelocities=True, getForces=True)
    system = context.getSystem()
    masses = np.array([system.getParticleMass(i).value_in_unit(unit.amu) for i in range(system.getNumParticles())])
    velocities = state.getVelocities(asNumpy=True).value_in_unit(unit.nanometer / unit.picosecond)
    integrator = context.getIntegrator()
    if GenDPDEIntegrator.isinstance(integrator):
        step = integrator.getStepSize().value_in_unit(unit.picosecond)
        forces = state.getForces(asNumpy=True).value_in_unit(unit.kilojoule_per_mole / unit.nanometer)
        velocities = velocities + 0.5 * step * forces / masses[:, None]
    velocities = velocities - (masses @ velocities) / masses.sum()
    kinetic = np.einsum("i,ia,ib->ab", masses, velocities, velocities)
    box = state.getPeriodicBoxVectors(asNumpy=True).value_in_unit(unit.nanometer)
    return (kinetic + virial_tensor(force, context)) / abs(np.linalg.det(box))
