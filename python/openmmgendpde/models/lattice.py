"""The one builder of ready GenDPDE liquids, for the argon model (openmmgendpde.models.argon) and any fluid
(openmmgendpde.models.fluid): FCC positions, and a System with one GenDPDEForce, its GenDPDEIntegrator and a
Topology."""

import numpy as np
import openmm
from openmm import app, unit


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


def build_liquid(box, num_particles, mass, cutoff, estimator, cutoff_scaling, tait, step_size, friction,
                 heat_conduction, heat_capacity, temperature, seed, mode, atom_name="CG", element=None,
                 residue_name="CG"):
    """(system, force, integrator, topology) of ``num_particles`` identical particles in the periodic ``box`` (three
    Vec3, nm): a GenDPDEForce of ``cutoff`` (nm), ``estimator`` (an enum value), f_cut ``cutoff_scaling`` and the
    Tait parameters ``tait`` = (n0, pi0, B_T, gamma_T), and a GenDPDEIntegrator of step ``step_size`` (ps),
    ``friction``, ``heat_conduction`` and ``heat_capacity``, bath temperature ``temperature`` (K), random seed
    ``seed`` and ``mode``; every value in OpenMM units. The topology's atoms are named for PDB files and viewers.
    The force holds a reference to the System, which owns it, so that it stays valid as long as it is used."""
    from ..api import GenDPDEForce, GenDPDEIntegrator
    system = openmm.System()
    system.setDefaultPeriodicBoxVectors(*box)
    for _ in range(num_particles):
        system.addParticle(mass)
    force = GenDPDEForce(cutoff)
    force.setDensityEstimator(estimator)
    force.setCutoffScaling(cutoff_scaling)
    force.setTaitParameters(*tait)
    system.addForce(force)
    force._system = system   # the System owns the C++ force (addForce): the force, once returned, keeps it alive
    integrator = GenDPDEIntegrator(step_size, friction, heat_conduction, heat_capacity)
    integrator.setTemperature(temperature)
    integrator.setRandomNumberSeed(seed)
    integrator.setMode(mode)
    topology = app.Topology()
    chain = topology.addChain()
    for _ in range(num_particles):
        topology.addAtom(atom_name, element, topology.addResidue(residue_name, chain))
    topology.setPeriodicBoxVectors(unit.Quantity(box, unit.nanometer))   # as PDBFile and PDBReporter expect
    return system, force, integrator, topology


def box_volume(system):
    """The volume (nm^3) of ``system``'s default periodic box (a reduced triclinic box: the product of the diagonal)."""
    a, b, c = system.getDefaultPeriodicBoxVectors()
    nm = unit.nanometer
    return a[0].value_in_unit(nm) * b[1].value_in_unit(nm) * c[2].value_in_unit(nm)
