"""The virial and pressure tensors of a GenDPDEForce (docs/fluids.md): what shear flows, surface tension or
anisotropic boxes need beyond the scalar virial that GenDPDEForce.getVirial returns.

    W_ab = sum_{i<j} F_ij,a r_ij,b = sum_{i<j} [pi_i V'_i + pi_j V'_j] w'(r_ij) r_ij,a r_ij,b / r_ij

with V'_i = dV_i/dn0_i (docs/theory.md section 4). The per-particle pressures pi_i and primitive densities n0_i come
from the Context (GenDPDEForce's observables, on any platform); V'_i from the model's own estimator
(openmmgendpde.physics); the pairs from scipy's k-d tree in the periodic box. The trace equals the scalar virial
(tested against GenDPDEForce.getVirial). The pressure tensor of the system adds the kinetic part:

    P_ab = (sum_i m_i v_i,a v_i,b + W_ab) / V          (velocities at the positions' time, centre-of-mass frame)

Rectangular periodic boxes only (the k-d tree's periodic mode); an analysis tool, not a per-step one.
"""

import numpy as np
from openmm import unit
from scipy.spatial import cKDTree

from . import GenDPDEForce, GenDPDEIntegrator
from .physics import particleVolumeVA, particleVolumeVB


def virial_tensor(force, context, per_particle=False):
    """W (3 x 3, kJ/mol) of ``force`` (a GenDPDEForce in the Context's System) at the Context's positions; with
    ``per_particle``, N x 3 x 3: each pair's term split equally between its two particles (they sum to W)."""
    force = GenDPDEForce.cast(force)
    state = context.getState(getPositions=True)
    box = state.getPeriodicBoxVectors(asNumpy=True).value_in_unit(unit.nanometer)
    if not force.usesPeriodicBoundaryConditions() or np.count_nonzero(box - np.diag(np.diag(box))):
        raise ValueError("virial_tensor: only a GenDPDEForce with periodic boundaries in a rectangular box")
    edges = np.diag(box)
    positions = state.getPositions(asNumpy=True).value_in_unit(unit.nanometer)
    cutoff = force.getCutoffDistance().value_in_unit(unit.nanometer)
    n0 = np.asarray(force.getPrimitiveDensities(context).value_in_unit(unit.nanometer**-3))
    pressure = np.asarray(force.getParticlePressures(context).value_in_unit(unit.kilojoule_per_mole / unit.nanometer**3))
    if force.getDensityEstimator() == GenDPDEForce.VA:
        derivative = np.array([particleVolumeVA(n)[1] for n in n0])
    else:
        reduced_range = cutoff / force.getCutoffScaling()
        derivative = np.array([particleVolumeVB(n, reduced_range)[1] if n > 0 else 0.0 for n in n0])
    coefficient = pressure * derivative                               # pi_i dV_i/dn0_i (kJ/mol nm^3)
    wrapped = positions - edges * np.floor(positions / edges)
    tree = cKDTree(wrapped, boxsize=edges)
    pairs = tree.query_pairs(cutoff, output_type="ndarray")
    i, j = pairs[:, 0], pairs[:, 1]
    delta = wrapped[i] - wrapped[j]
    delta -= edges * np.round(delta / edges)
    r = np.sqrt((delta**2).sum(axis=1))
    keep = (r > 0) & (r < cutoff)
    i, j, delta, r = i[keep], j[keep], delta[keep], r[keep]
    weight_derivative = -15.0 / (np.pi * cutoff**4) * (1 - r / cutoff)   # w'(r)
    scale = (coefficient[i] + coefficient[j]) * weight_derivative / r    # F_ij = scale r_ij
    if not per_particle:
        return np.einsum("p,pa,pb->ab", scale, delta, delta)
    terms = 0.5 * np.einsum("p,pa,pb->pab", scale, delta, delta)
    result = np.zeros((len(positions), 3, 3))
    np.add.at(result, i, terms)
    np.add.at(result, j, terms)
    return result


def pressure_tensor(force, context, state=None):
    """P (3 x 3, kJ/mol/nm^3) of the System in the Context: kinetic part plus the virial tensor of ``force``. The
    velocities are those at the time of the positions (for a GenDPDEIntegrator, whose stored velocities are half a
    step behind, v + (dt/2) F/m, as its kinetic energy uses them), in the centre-of-mass frame. Other forces are not
    included (use it for Systems whose only force is this one). ``state``: a State with velocities and forces."""
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
