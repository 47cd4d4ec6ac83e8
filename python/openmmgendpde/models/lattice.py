# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""The lattices that models start from (FCC positions in a rectangular box) and the volume of a System's box; the
model itself is built by model.ModelParameters.build."""

import numpy as np
from openmm import unit


def fcc_positions(cells, cell_edge):
    """Positions (N x 3, in the units of ``cell_edge``) of n_x x n_y x n_z cubic FCC cells of edge ``cell_edge``,
    4 particles each, starting a quarter cell from the origin."""
    nx, ny, nz = (int(c) for c in cells)
    basis = np.array([[0, 0, 0], [0.5, 0.5, 0], [0.5, 0, 0.5], [0, 0.5, 0.5]]) + 0.25
    grid = np.array([(x, y, z) for x in range(nx) for y in range(ny) for z in range(nz)], dtype=float)
    return (grid[:, None, :] + basis[None, :, :]).reshape(-1, 3) * cell_edge


def fcc_box(density, cells):
    """(positions, box): an FCC lattice at ``density`` (nm^-3) of n_x x n_y x n_z cubic cells (4 particles each,
    edge (4/density)^(1/3)) filling a rectangular periodic box; positions (nm) as an N x 3 array, the box as three
    rows (nm)."""
    nx, ny, nz = (int(c) for c in cells)
    if min(nx, ny, nz) < 1:
        raise ValueError(f"cells = {cells} is not allowed; each count must be >= 1")
    if not density > 0:
        raise ValueError(f"density = {density} is not allowed; it must be > 0")
    edge = (4 / density) ** (1 / 3)
    return fcc_positions((nx, ny, nz), edge), [[nx * edge, 0, 0], [0, ny * edge, 0], [0, 0, nz * edge]]


def box_volume(system):
    """The volume (nm^3) of ``system``'s default periodic box (a reduced triclinic box: the product of the diagonal)."""
    a, b, c = system.getDefaultPeriodicBoxVectors()
    nm = unit.nanometer
    return a[0].value_in_unit(nm) * b[1].value_in_unit(nm) * c[2].value_in_unit(nm)
