# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""Radial distribution function g(r) of particle frames (mdtraj), in reduced or OpenMM units."""

import numpy as np
from openmm import unit

from ..units import ARGON_UNITS

#: g(r) is computed up to this distance (reduced units) with bins of this width.
R_MAX, BIN_WIDTH = 3.0, 0.02


def radial_distribution(frames, box_edge, r_max=R_MAX, bin_width=BIN_WIDTH, length=None):
    """(r, g(r)) for frames (F x N x 3, nm) in a cubic box of edge box_edge (nm), by mdtraj in chunks of 5 frames; r,
    r_max and bin_width in units of ``length`` nm (default: the argon model's L, reduced units; 1.0: nm)."""
    import mdtraj  # optional dependency (the studies extra of pyproject.toml): only the studies need it
    frames = np.asarray(frames, dtype=np.float32)
    if length is None:
        length = ARGON_UNITS.unit("length").value_in_unit(unit.nanometer)
    topology = mdtraj.Topology()
    chain = topology.add_chain()
    for _ in range(frames.shape[1]):
        topology.add_atom("AR", mdtraj.element.argon, topology.add_residue("AR5", chain))
    pairs = topology.select_pairs("all", "all")
    sums, chunks = 0.0, 0
    for start in range(0, len(frames), 5):
        chunk = frames[start:start + 5]
        trajectory = mdtraj.Trajectory(chunk, topology, unitcell_lengths=np.full((len(chunk), 3), box_edge),
                                       unitcell_angles=np.full((len(chunk), 3), 90.0))
        r, g = mdtraj.compute_rdf(trajectory, pairs, r_range=(0.0, r_max * length), bin_width=bin_width * length)
        sums, chunks = sums + g * len(chunk), chunks + len(chunk)
    return r / length, sums / chunks
