# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""Polymer chains in a GenDPDE liquid (docs/soft-matter.md, "A polymer solution"): linear chains of the fluid's own
particles (same mass, same type: an athermal, good solvent) held together by an openmm.HarmonicBondForce (periodic
boundaries), optionally stiffened by an openmm.HarmonicAngleForce. The chains start on the sites of the liquid's FCC
lattice, replacing solvent particles, so that the start is at the fluid's density: each chain is a self-avoiding walk
along the lattice's nearest-neighbour steps, whose length (sqrt(2)/n0)^(1/3) = 1.12 n0^(-1/3) is the default rest
length b0 of the bonds (the bonds start unstrained). The default stiffness k = 100 k_B T0/b0^2 keeps a bond's length
within sqrt(k_B T0/k) = 0.1 b0 (rms) of b0, so the chain is a string of beads at about the liquid's spacing, and the
step that the bonds' highest frequency 2 sqrt(k/m) allows (calibration.stability.bonded_frequency) is above the
fluid's own for argon and water (docs/soft-matter.md). GenDPDEForce keeps no exclusions: bonded beads count in each
other's density and feel the integrator's friction and heat conduction (docs/soft-matter.md, "Bonded beads and the
many-body density"). The model is built by ModelParameters.build, whose Topology holds the chains and their bonds
(PDB files show them); the chains are the first particles, in order, and the solvent follows."""

import dataclasses
import math
import numbers

import numpy as np
import openmm
from openmm import unit

from ..api import GenDPDEIntegrator, estimator_value
from ..units import BOLTZMANN
from .model import Model

#: The default bond stiffness in k_B T0/b0^2: an rms stretch of 0.1 b0.
BOND_STIFFNESS = 100.0
#: The twelve nearest-neighbour steps of the FCC lattice, in half cell edges.
_FCC_STEPS = np.array([(a, b, 0) for a in (-1, 1) for b in (-1, 1)] + [(a, 0, b) for a in (-1, 1) for b in (-1, 1)]
                      + [(0, a, b) for a in (-1, 1) for b in (-1, 1)])
#: How many times one chain is started again where its walk is trapped, before the placement gives up.
_PLACEMENT_TRIES = 1000


@dataclasses.dataclass
class PolymerSolution(Model):
    """A polymer solution (model.Model): ``chains``, the particle indices of each chain in bond order (a tuple of
    numpy arrays; the chains are the first particles), their HarmonicBondForce ``bonds`` (rest length
    ``bond_length`` nm, stiffness ``bond_stiffness`` kJ/mol/nm^2) and HarmonicAngleForce ``angles`` (None without)."""
    chains: tuple = ()
    bonds: openmm.HarmonicBondForce = None
    angles: openmm.HarmonicAngleForce = None
    bond_length: float = None
    bond_stiffness: float = None

    @property
    def bond_pairs(self):
        """The bonded pairs (i, j), an M x 2 integer array, chain by chain."""
        return np.array([(chain[k], chain[k + 1]) for chain in self.chains for k in range(len(chain) - 1)], dtype=int)


def lattice_bond_length(density):
    """The nearest-neighbour distance of an FCC lattice at ``density`` (nm^-3): (sqrt(2)/n)^(1/3) nm."""
    return (math.sqrt(2) / density) ** (1 / 3)


def _count(name, value, smallest):
    if isinstance(value, bool) or not isinstance(value, numbers.Integral) or value < smallest:
        raise ValueError(f"{name} = {value!r} is not allowed; it must be an integer >= {smallest}")
    return int(value)


def _positive(name, value, quantity_unit, allow_zero=False):
    if unit.is_quantity(value):
        value = value.value_in_unit(quantity_unit)
    if isinstance(value, bool) or not isinstance(value, numbers.Real) or not math.isfinite(value) or \
            not (value >= 0 if allow_zero else value > 0):
        raise ValueError(f"{name} = {value!r} is not allowed; it must be a finite number "
                         f"{'>= 0' if allow_zero else '> 0'} ({quantity_unit.get_symbol()})")
    return float(value)


def chain_sites(positions, box, chain_length, num_chains, seed=0):
    """Lattice sites for ``num_chains`` chains of ``chain_length`` beads on the FCC lattice ``positions`` (N x 3,
    nm, as lattice.fcc_box makes them) in the periodic ``box`` (three rows): each chain a self-avoiding walk of
    nearest-neighbour steps, the chains disjoint, drawn with numpy's generator seeded ``seed``. Returns a
    num_chains x chain_length integer array of indices into ``positions``. A ValueError where the walks do not fit."""
    positions = np.asarray(positions, dtype=float)
    edges = np.array([box[k][k] for k in range(3)], dtype=float)
    sites = len(positions)
    if chain_length * num_chains > sites:
        raise ValueError(f"{num_chains} chains of {chain_length} beads do not fit on the {sites} sites of the "
                         f"lattice; use more cells or fewer chains")
    cell = (4 * np.prod(edges) / sites) ** (1 / 3)   # the FCC cell's edge (4 sites a cell)
    counts = np.rint(2 * edges / cell).astype(int)   # the lattice's period in half cell edges
    keys = np.rint(2 * positions / cell - 0.5).astype(int)
    index = {tuple(key): i for i, key in enumerate(keys)}
    if len(index) != sites or not np.allclose((keys + 0.5) * cell / 2, positions, atol=1e-6 * cell):
        raise ValueError("positions is not an FCC lattice of lattice.fcc_box")
    rng = np.random.default_rng(seed)
    free = np.ones(sites, dtype=bool)
    chains = []
    for _ in range(num_chains):
        for _ in range(_PLACEMENT_TRIES):
            start = rng.choice(np.flatnonzero(free))
            walk = [start]
            taken = {start}
            while len(walk) < chain_length:
                here = keys[walk[-1]]
                options = [index[tuple((here + step) % counts)] for step in _FCC_STEPS]
                options = [site for site in options if free[site] and site not in taken]
                if not options:
                    break
                walk.append(options[rng.integers(len(options))])
                taken.add(walk[-1])
            if len(walk) == chain_length:
                break
        else:
            raise ValueError(f"could not place chain {len(chains)} of {chain_length} beads on the lattice's free "
                             f"sites; use more cells or fewer chains")
        free[walk] = False
        chains.append(walk)
    return np.array(chains, dtype=int)


def polymer_solution(parameters, chain_length, num_chains, cells, estimator=None, mode=GenDPDEIntegrator.Isoenergetic,
                     time_step=0.01, seed=0, bond_length=None, bond_stiffness=None, angle_stiffness=None,
                     angle=math.pi, placement_seed=0):
    """``num_chains`` linear chains of ``chain_length`` beads in the liquid of ``parameters`` (a
    parameters.GenDPDEParameters, e.g. fluid.coarse_grain(fluid.WATER, 4, neighbors=20)) on ``cells`` = (n_x, n_y,
    n_z) FCC cells at n0 (parameters.liquid: ``estimator``, ``mode``, reduced ``time_step``, ``seed`` as there).

    The beads are the fluid's particles (its mass and its one type: an athermal, good solvent) placed on lattice
    sites by chain_sites (seed ``placement_seed``), so the start is at n0; they come first, chain by chain. Bonds: an
    openmm.HarmonicBondForce with periodic boundaries, rest length ``bond_length`` (nm; default the lattice's
    nearest-neighbour distance (sqrt(2)/n0)^(1/3)) and stiffness ``bond_stiffness`` (kJ/mol/nm^2, or a Quantity;
    default BOND_STIFFNESS k_B T0/b0^2). With ``angle_stiffness`` (kJ/mol/rad^2, or a Quantity) an
    openmm.HarmonicAngleForce (periodic) holds each pair of consecutive bonds at ``angle`` (rad, default pi: a
    stiff chain). Returns a PolymerSolution. Bad arguments raise ValueError naming the argument, the value and what
    is allowed, before anything is built."""
    chain_length = _count("chain_length", chain_length, 2)
    num_chains = _count("num_chains", num_chains, 1)
    kt = (BOLTZMANN * parameters.temperature * unit.kelvin).value_in_unit(unit.kilojoule_per_mole)
    lattice_length = lattice_bond_length(parameters.density)
    bond_length = lattice_length if bond_length is None else _positive("bond_length", bond_length, unit.nanometer)
    if bond_length >= parameters.cutoff:
        raise ValueError(f"bond_length = {bond_length} nm is not allowed; it must be less than the cutoff "
                         f"{parameters.cutoff:.4g} nm (a bond longer than the pair range leaves its beads without "
                         f"friction between them)")
    stiffness = (BOND_STIFFNESS * kt / bond_length**2 if bond_stiffness is None
                 else _positive("bond_stiffness", bond_stiffness, unit.kilojoule_per_mole / unit.nanometer**2))
    if angle_stiffness is not None:
        angle_stiffness = _positive("angle_stiffness", angle_stiffness, unit.kilojoule_per_mole / unit.radian**2,
                                    allow_zero=True)
    angle = _positive("angle", angle, unit.radian)
    if angle > math.pi:
        raise ValueError(f"angle = {angle} rad is not allowed; it must be in (0, pi]")
    liquid = parameters.liquid(estimator=estimator, mode=mode, time_step=time_step, seed=seed, cells=cells)
    box = np.array([[v.value_in_unit(unit.nanometer) for v in row]
                    for row in liquid.system.getDefaultPeriodicBoxVectors()])
    sites = chain_sites(liquid.positions, box, chain_length, num_chains, placement_seed)
    rest = np.setdiff1d(np.arange(len(liquid.positions)), sites.ravel())
    positions = np.vstack([liquid.positions[sites.ravel()], liquid.positions[rest]])
    step = liquid.integrator.getStepSize()
    model = parameters.build(box, positions, estimator_value(parameters.checked_estimator(estimator)), step, seed, mode,
                             model_type=PolymerSolution, chains=[chain_length] * num_chains)
    chains = tuple(np.arange(c * chain_length, (c + 1) * chain_length) for c in range(num_chains))
    bonds = openmm.HarmonicBondForce()
    bonds.setUsesPeriodicBoundaryConditions(True)
    for chain in chains:
        for first, second in zip(chain[:-1], chain[1:]):
            bonds.addBond(int(first), int(second), bond_length, stiffness)
    model.system.addForce(bonds)
    angles = None
    if angle_stiffness is not None:
        angles = openmm.HarmonicAngleForce()
        angles.setUsesPeriodicBoundaryConditions(True)
        for chain in chains:
            for first, middle, last in zip(chain[:-2], chain[1:-1], chain[2:]):
                angles.addAngle(int(first), int(middle), int(last), angle, angle_stiffness)
        model.system.addForce(angles)
    model.chains, model.bonds, model.angles = chains, bonds, angles
    model.bond_length, model.bond_stiffness = bond_length, stiffness
    return model


__all__ = ["BOND_STIFFNESS", "PolymerSolution", "chain_sites", "lattice_bond_length", "polymer_solution"]
