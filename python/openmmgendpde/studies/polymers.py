# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""The polymer-solution study (docs/soft-matter.md, "A polymer solution"; examples/polymer_solution.py): chains of
several lengths N in a fluid's liquid (models.polymers), each run with the DPD thermostat at T0 (Isothermal: the chains'
conformations sample the canonical distribution of the model at T0), their mean-square radius of gyration sampled and
averaged with its correlation accounted for, and the Flory exponent nu of <R_g^2>^(1/2) ~ N^nu fitted
(analysis.polymers.flory_fit).

Each N in its own cube (box_cells: an edge of at least BOX_OVER_CHAIN b0 N^0.6, 1.5-1.6 times the end-to-end distance of
the longest chains measured, so that a chain rarely meets its own image), with as many chains as give the bead fraction
``bead_fraction`` (at least one): dilute (the default 0.04 is a quarter or less of the overlap fraction N/(4 pi R_g^3/3)
n0^-1 of N <= 40), so that chains rarely meet. The bonded beads' mean density against the solvent's
(GenDPDEForce.getParticleDensities) is sampled too (docs/soft-matter.md, "Bonded beads and the many-body density")."""

import dataclasses
import math

import numpy as np
from openmm import unit

from ..analysis.polymers import bond_lengths, flory_fit, radii_of_gyration_squared
from ..analysis.statistics import correlated_mean
from ..api import GenDPDEIntegrator
from ..models.polymers import lattice_bond_length, polymer_solution

#: The box edge over b0 N^0.6 (box_cells).
BOX_OVER_CHAIN = 1.5


@dataclasses.dataclass(frozen=True)
class ChainSize:
    """What one run of chains of ``chain_length`` beads measured (lengths in nm): the root of the mean-square radius of
    gyration with its standard error (analysis.statistics.correlated_mean of the chains' mean R_g^2, sqrt(g s^2/n),
    propagated to the root), the samples taken and their statistical inefficiency g (samples / g: the independent
    ones, which make the error itself uncertain by ~1/sqrt(2 samples/g)), the mean bond length over the bond's rest
    length, and the bonded beads' and the solvent's mean density over n0."""
    chain_length: int
    num_chains: int
    radius_of_gyration: float
    error: float
    samples: int
    statistical_inefficiency: float
    bond_stretch: float
    bead_density: float
    solvent_density: float


def box_cells(parameters, chain_length, bond_length=None, smallest=5):
    """(m, m, m): the fewest cubic FCC cells at n0 (at least ``smallest``) whose edge is at least BOX_OVER_CHAIN b0
    N^0.6 (b0: ``bond_length``, nm, default the lattice's nearest-neighbour distance)."""
    b0 = lattice_bond_length(parameters.density) if bond_length is None else bond_length
    cell = (4 / parameters.density) ** (1 / 3)
    return (max(smallest, math.ceil(BOX_OVER_CHAIN * b0 * chain_length**0.6 / cell - 1e-9)),) * 3


def chains_for(chain_length, sites, bead_fraction):
    """The number of chains of ``chain_length`` beads that make ``bead_fraction`` of ``sites`` particles (>= 1)."""
    return max(1, round(bead_fraction * sites / chain_length))


def chain_size(parameters, chain_length, num_chains, cells, time_step=0.05, melt_steps=2000, steps=20000,
               sample_every=20, platform="CPU", properties=None, seed=1, estimator=None, **bonds):
    """One run (ChainSize): ``num_chains`` chains of ``chain_length`` beads in ``cells`` FCC cells of the liquid of
    ``parameters`` (models.polymers.polymer_solution, with ``bonds``: bond_length, bond_stiffness, angle_stiffness),
    Isothermal at dt* = ``time_step``, ``melt_steps`` steps to leave the lattice, then ``steps`` steps sampled every
    ``sample_every``."""
    model = polymer_solution(parameters, chain_length, num_chains, cells, estimator, GenDPDEIntegrator.Isothermal,
                             time_step, seed, placement_seed=seed, **bonds)
    context = model.context(platform, seed=seed, properties=properties)
    model.integrator.step(melt_steps)
    box, pairs = model.box_edges, model.bond_pairs
    bonded = num_chains * chain_length
    radii, stretch, beads, solvent = [], [], [], []
    for _ in range(steps // sample_every):
        model.integrator.step(sample_every)
        x = context.getState(getPositions=True).getPositions(asNumpy=True).value_in_unit(unit.nanometer)
        radii.append(radii_of_gyration_squared(x, box, model.chains).mean())
        stretch.append(bond_lengths(x, box, pairs).mean() / model.bond_length)
        density = model.force.getParticleDensities(context).value_in_unit(unit.nanometer**-3) / parameters.density
        beads.append(density[:bonded].mean())
        solvent.append(density[bonded:].mean() if len(density) > bonded else np.nan)
    mean = correlated_mean(radii)
    root = float(np.sqrt(mean.mean))
    return ChainSize(chain_length, num_chains, root, float(mean.standard_error / (2 * root)), len(radii),
                     mean.inefficiency, float(np.mean(stretch)), float(np.mean(beads)), float(np.mean(solvent)))


def flory_study(parameters, chain_lengths, bead_fraction=0.04, progress=None, **options):
    """chain_size for each of ``chain_lengths``, each in its box (box_cells) with ``bead_fraction`` of its particles
    in chains (chains_for; ``options`` as chain_size's), then the Flory fit. Returns (list of ChainSize,
    analysis.polymers.FloryFit); ``progress(row)`` is called after each run."""
    rows = []
    for length in chain_lengths:
        cells = box_cells(parameters, length, options.get("bond_length"))
        sites = 4 * int(np.prod(cells))
        rows.append(chain_size(parameters, length, chains_for(length, sites, bead_fraction), cells, **options))
        if progress is not None:
            progress(rows[-1])
    fit = flory_fit([r.chain_length for r in rows], [r.radius_of_gyration for r in rows], [r.error for r in rows])
    return rows, fit


__all__ = ["BOX_OVER_CHAIN", "ChainSize", "box_cells", "chain_size", "chains_for", "flory_study"]
