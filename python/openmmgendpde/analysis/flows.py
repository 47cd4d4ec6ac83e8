# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""The steady flows of analysis.transport in closed form: the shape of the flow profile that the periodic Poiseuille
body force (models.flows.poiseuille_body_force) drives, the fit of a binned profile to it, the heat flux's slab
profile, and the slowest modes' relaxation times of a periodic box (docs/transport.md)."""

import math

import numpy as np


def half_sign(z, box_length):
    """+1 where z wrapped into [0, L) is below L/2, else -1: the direction of the body force."""
    wrapped = np.mod(z, box_length)
    return np.where(wrapped < box_length / 2, 1.0, -1.0)


def poiseuille_shape(z, box_length):
    """h(z) = z (L/2 - z) for wrapped z in [0, L/2) and -(z - L/2)(L - z) in [L/2, L) (nm^2)."""
    wrapped = np.mod(z, box_length)
    half = box_length / 2
    inner = np.mod(wrapped, half)
    return half_sign(z, box_length) * inner * (half - inner)


def bin_shape(bins, box_length):
    """The mean of h over each of ``bins`` equal bins of [0, L) (Simpson's rule, exact for the parabola of each
    half: ``bins`` must be even so that no bin straddles L/2)."""
    if bins % 2:
        raise ValueError(f"bins = {bins} is not allowed; it must be even (no bin may straddle L/2)")
    edges = np.linspace(0, box_length, bins + 1)
    low, high = edges[:-1], edges[1:]
    # Evaluate each end inside its own bin: h at the right edge of the bin below L/2 is that of the first half.
    eps = 1e-12 * box_length
    return (poiseuille_shape(low, box_length) + 4 * poiseuille_shape((low + high) / 2, box_length)
            + poiseuille_shape(high - eps, box_length)) / 6


def fit_amplitude(velocities, shape):
    """(A, c): the least-squares fit of v_b = A s_b + c to a binned profile ``velocities`` (nm/ps) with the bins'
    shape ``shape`` (nm^2); A in 1/(nm ps), c the uniform drift (nm/ps). ``velocities`` may be one profile or one
    per row (frames)."""
    design = np.column_stack([shape, np.ones_like(shape)])
    solution = np.linalg.lstsq(design, np.asarray(velocities, float).T, rcond=None)[0]
    return solution[0], solution[1]


def viscosity_from_amplitude(amplitude, density, force):
    """eta = n F/(2 A) (amu/(nm ps)) from the amplitude A (1/(nm ps)) of v_x = A h(z), n in nm^-3, F in kJ/mol/nm."""
    return density * force / (2 * amplitude)


def momentum_diffusion_time(mass_density, viscosity, box_length):
    """rho (L/2)^2/(eta pi^2) (ps): the decay time of the slowest flow mode, sin(2 pi z/L), of a periodic box of
    length L (nm); rho in amu/nm^3, eta in amu/(nm ps)."""
    return mass_density * (box_length / 2) ** 2 / (viscosity * math.pi**2)


def thermal_diffusion_time(density, heat_capacity, conductivity, box_length):
    """n c (L/2)^2/(lambda pi^2) (ps): the decay time of the slowest temperature mode of a periodic box of length L
    (nm); n in nm^-3, c the heat capacity per particle at fixed density (kJ/mol/K), lambda in kJ/(mol ps nm K)."""
    return density * heat_capacity * (box_length / 2) ** 2 / (conductivity * math.pi**2)


def slab_profile(z, box_length, slab_width):
    """+1 in the hot slab (wrapped z in [0, w)), -1 in the cold one ([L/2, L/2 + w)), linear in between: the shape of
    the steady temperature profile, T0 (1 + e s(z))."""
    z = np.mod(z, box_length)
    half = box_length / 2
    gap = half - slab_width
    inner = np.mod(z, half)
    ramp = np.where(inner < slab_width, 1.0, 1 - 2 * (inner - slab_width) / gap)
    return np.where(z < half, ramp, -ramp)


def between_slabs(centre, box_length, slab_width, margin):
    """(lower, upper): boolean masks of the bins whose ``centre`` (nm) lies between the slab [0, w) and the slab
    [L/2, L/2 + w) at least ``margin`` (nm) from both, in the first half of the box and in the second: the bins a line
    is fitted through in a heat flux or a reverse shear flow between two slabs of width ``slab_width``. A ValueError
    where a half keeps fewer than 2 bins."""
    centre = np.asarray(centre, float)
    inside = np.mod(centre, box_length / 2)
    region = (inside > slab_width + margin) & (inside < box_length / 2 - margin)
    lower, upper = region & (centre < box_length / 2), region & (centre > box_length / 2)
    if lower.sum() < 2 or upper.sum() < 2:
        raise ValueError(f"the box (L = {box_length:.3g} nm) leaves fewer than 2 of {len(centre)} bins between the "
                         f"slabs (w = {slab_width:.3g} nm) at least {margin:.3g} nm from them: use a longer box or "
                         f"more bins")
    return lower, upper


def line_slopes(centre, profiles, mask):
    """The least-squares slope (per row of ``profiles``) of the bins in ``mask`` against ``centre``."""
    x = centre[mask] - centre[mask].mean()
    return (np.asarray(profiles)[:, mask] @ x) / (x @ x)
