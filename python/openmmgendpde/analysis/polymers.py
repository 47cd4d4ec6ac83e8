# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""What chains in a periodic box measure: their bond lengths, their radius of gyration (each chain made whole across
the periodic boundaries by following its bonds), and the Flory exponent nu of <R_g^2>^(1/2) ~ N^nu fitted to several
chain lengths (docs/soft-matter.md, "A polymer solution"). Rectangular boxes; positions and edges in one length unit."""

import math
from typing import NamedTuple

import numpy as np


def _minimum_image(vectors, box_edges):
    box_edges = np.asarray(box_edges, dtype=float)
    return vectors - box_edges * np.round(vectors / box_edges)


def bond_lengths(positions, box_edges, pairs):
    """The lengths of the bonds ``pairs`` (M x 2 particle indices) at ``positions`` (N x 3) in the periodic
    rectangular box of edges ``box_edges`` (minimum image), an array of M."""
    positions = np.asarray(positions, dtype=float)
    pairs = np.asarray(pairs, dtype=int).reshape(-1, 2)
    return np.linalg.norm(_minimum_image(positions[pairs[:, 1]] - positions[pairs[:, 0]], box_edges), axis=1)


def whole_chains(positions, box_edges, chains):
    """Each chain (a sequence of particle indices in bond order) made whole: bead k+1 placed at bead k plus the
    minimum image of their separation, so that a chain split by the periodic boundaries is one object (bonds shorter
    than half the box, as the models' are). A list of (length x 3) arrays."""
    positions = np.asarray(positions, dtype=float)
    whole = []
    for chain in chains:
        steps = _minimum_image(np.diff(positions[np.asarray(chain, dtype=int)], axis=0), box_edges)
        whole.append(positions[chain[0]] + np.vstack([np.zeros(3), np.cumsum(steps, axis=0)]))
    return whole


def radii_of_gyration_squared(positions, box_edges, chains):
    """R_g^2 = (1/N) sum_k |r_k - r_cm|^2 of each chain (made whole, whole_chains), an array of len(chains)."""
    return np.array([((beads - beads.mean(axis=0)) ** 2).sum(axis=1).mean()
                     for beads in whole_chains(positions, box_edges, chains)])


class FloryFit(NamedTuple):
    """<R_g^2>^(1/2) = prefactor N^nu, fitted by weighted least squares in logarithms: nu with its standard error
    (from the radii's errors, scaled by sqrt(chi^2/dof) where that exceeds 1), the prefactor, and chi^2/dof."""
    nu: float
    nu_error: float
    prefactor: float
    reduced_chi_squared: float


def flory_fit(chain_lengths, radii, errors):
    """FloryFit of radii of gyration ``radii`` (with standard errors ``errors``, > 0) against ``chain_lengths``
    (at least two different ones). A ValueError for fewer than two lengths or a radius or error <= 0."""
    lengths = np.asarray(chain_lengths, dtype=float)
    radii = np.asarray(radii, dtype=float)
    errors = np.asarray(errors, dtype=float)
    if len(lengths) < 2 or len(set(lengths.tolist())) < 2 or not (len(radii) == len(errors) == len(lengths)):
        raise ValueError(f"chain_lengths = {list(chain_lengths)} is not allowed; a fit needs at least two different "
                         f"chain lengths, each with a radius and an error")
    if np.any(radii <= 0) or np.any(errors <= 0) or np.any(lengths <= 0):
        raise ValueError(f"radii = {list(radii)} and errors = {list(errors)} are not allowed; each must be > 0")
    x, y, sigma = np.log(lengths), np.log(radii), errors / radii
    weights = 1 / sigma**2
    matrix = np.array([[weights.sum(), (weights * x).sum()], [(weights * x).sum(), (weights * x * x).sum()]])
    covariance = np.linalg.inv(matrix)
    intercept, slope = covariance @ np.array([(weights * y).sum(), (weights * x * y).sum()])
    dof = len(x) - 2
    chi2 = float((weights * (y - intercept - slope * x) ** 2).sum() / dof) if dof > 0 else float("nan")
    scale = math.sqrt(chi2) if dof > 0 and chi2 > 1 else 1.0
    return FloryFit(float(slope), float(math.sqrt(covariance[1, 1]) * scale), float(math.exp(intercept)), chi2)


__all__ = ["FloryFit", "bond_lengths", "flory_fit", "radii_of_gyration_squared", "whole_chains"]
