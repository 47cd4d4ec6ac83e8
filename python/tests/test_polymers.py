# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""Polymer chains in a GenDPDE liquid (docs/soft-matter.md): the builder (models.polymers), the bound on the bonds'
frequency and the time step with bonds (calibration.stability), the chain measurements (analysis.polymers), energy
conservation and the equipartition of the bonds, and the example at a small size."""

import math
import pathlib
import subprocess
import sys

import numpy as np
import openmm
import pytest
from openmm import unit

from openmmgendpde import GenDPDEIntegrator
from openmmgendpde.analysis.polymers import bond_lengths, flory_fit, radii_of_gyration_squared, whole_chains
from openmmgendpde.calibration import stability
from openmmgendpde.models import fluid
from openmmgendpde.models.melting import melt_then_switch
from openmmgendpde.models.model import MONOMER_RESIDUE
from openmmgendpde.models.polymers import BOND_STIFFNESS, chain_sites, lattice_bond_length, polymer_solution

EXAMPLES = pathlib.Path(__file__).resolve().parents[2] / "examples"
SOFT_MATTER = pathlib.Path(__file__).resolve().parents[2] / "docs" / "soft-matter.md"
ARGON = fluid.coarse_grain(fluid.ARGON, 5, neighbors=20)
KB = unit.MOLAR_GAS_CONSTANT_R.value_in_unit(unit.kilojoule_per_mole / unit.kelvin)


def _kt(parameters=ARGON):
    return KB * parameters.temperature


def test_chains_start_on_lattice_sites_at_the_bonds_rest_length_and_the_topology_holds_them():
    model = polymer_solution(ARGON, 10, 5, (5, 5, 5), seed=1)
    liquid = ARGON.liquid(cells=(5, 5, 5))
    # the same lattice sites, reordered: the start is at the fluid's density
    assert model.num_particles == 500
    assert np.allclose(np.sort(model.positions, axis=0), np.sort(liquid.positions, axis=0))
    b0 = lattice_bond_length(ARGON.density)
    assert model.bond_length == pytest.approx(b0) and b0 == pytest.approx(1.1225 * ARGON.density ** (-1 / 3), 1e-4)
    assert np.allclose(bond_lengths(model.positions, model.box_edges, model.bond_pairs), b0, rtol=1e-9)
    assert model.bond_stiffness == pytest.approx(BOND_STIFFNESS * _kt() / b0**2)
    assert model.bonds.usesPeriodicBoundaryConditions() and model.bonds.getNumBonds() == 45
    assert model.angles is None
    assert {model.system.getParticleMass(i).value_in_unit(unit.amu) for i in range(500)} == {ARGON.mass}
    assert [model.force.getParticleType(i) for i in range(500)] == [0] * 500
    chains = list(model.topology.chains())
    assert len(chains) == 6 and [len(list(c.atoms())) for c in chains] == [10] * 5 + [450]
    assert {r.name for c in chains[:5] for r in c.residues()} == {MONOMER_RESIDUE}
    topology_bonds = sorted((b[0].index, b[1].index) for b in model.topology.bonds())
    force_bonds = sorted(tuple(model.bonds.getBondParameters(i)[:2]) for i in range(45))
    assert topology_bonds == force_bonds == sorted(map(tuple, model.bond_pairs.tolist()))


def test_angles_are_periodic_and_hold_consecutive_bonds():
    model = polymer_solution(ARGON, 4, 2, (5, 5, 5), angle_stiffness=3.0, angle=2.0)
    assert model.angles.usesPeriodicBoundaryConditions() and model.angles.getNumAngles() == 4
    i, j, k, angle, stiffness = model.angles.getAngleParameters(1)
    assert (i, j, k) == (1, 2, 3) and angle.value_in_unit(unit.radian) == 2.0
    assert stiffness.value_in_unit(unit.kilojoule_per_mole / unit.radian**2) == 3.0


def test_chain_sites_are_disjoint_self_avoiding_walks_of_nearest_neighbour_steps():
    liquid = ARGON.liquid(cells=(4, 4, 4))
    box = np.diag(liquid.box_edges)
    sites = chain_sites(liquid.positions, box, 20, 6, seed=5)
    assert sites.shape == (6, 20) and len(set(sites.ravel().tolist())) == 120
    steps = bond_lengths(liquid.positions, liquid.box_edges, np.stack([sites[:, :-1], sites[:, 1:]], -1))
    assert np.allclose(steps, lattice_bond_length(ARGON.density))


@pytest.mark.parametrize("arguments, words", [
    ({"chain_length": 1}, "chain_length = 1 is not allowed"),
    ({"num_chains": 0}, "num_chains = 0 is not allowed"),
    ({"num_chains": 60}, "do not fit on the 500 sites"),
    ({"bond_length": 1.2}, "bond_length = 1.2 nm is not allowed; it must be less than the cutoff"),
    ({"bond_stiffness": -1.0}, "bond_stiffness = -1.0 is not allowed"),
    ({"angle_stiffness": float("nan")}, "angle_stiffness = nan is not allowed"),
    ({"angle": 4.0}, "angle = 4.0 rad is not allowed"),
])
def test_bad_arguments_are_refused_by_name(arguments, words):
    options = {"chain_length": 10, "num_chains": 2, **arguments}
    with pytest.raises(ValueError, match=words):
        polymer_solution(ARGON, cells=(5, 5, 5), **options)


def _system(positions, masses, bonds=(), angles=(), box=None):
    """A System of point masses with harmonic bonds (i, j, r0, k) and angles (i, j, k, theta0, k_theta); with ``box``
    (a cube's edge) the bonds are periodic."""
    system = openmm.System()
    for mass in masses:
        system.addParticle(mass)
    bond_force = openmm.HarmonicBondForce()
    if box is not None:
        system.setDefaultPeriodicBoxVectors(*(openmm.Vec3(*(box * np.eye(3)[k])) for k in range(3)))
        bond_force.setUsesPeriodicBoundaryConditions(True)
    for bond in bonds:
        bond_force.addBond(*bond)
    system.addForce(bond_force)
    if angles:
        angle_force = openmm.HarmonicAngleForce()
        for angle in angles:
            angle_force.addAngle(*angle)
        system.addForce(angle_force)
    return system, np.asarray(positions, dtype=float)


def _frequencies(system, positions, h=1e-5):
    """The vibrational angular frequencies (rad/ps) from the mass-weighted Hessian of the System's forces, by central
    differences of OpenMM's own forces (independent of bonded_frequency)."""
    context = openmm.Context(system, openmm.VerletIntegrator(0.001), openmm.Platform.getPlatformByName("Reference"))
    n = len(positions)
    hessian = np.zeros((3 * n, 3 * n))
    for a in range(3 * n):
        columns = []
        for sign in (1, -1):
            x = positions.copy()
            x[a // 3, a % 3] += sign * h
            context.setPositions(x)
            columns.append(context.getState(getForces=True).getForces(asNumpy=True)._value.ravel())
        hessian[:, a] = -(columns[0] - columns[1]) / (2 * h)
    root = np.repeat([1 / math.sqrt(system.getParticleMass(i)._value) for i in range(n)], 3)
    eigenvalues = np.linalg.eigvalsh(0.5 * (hessian + hessian.T) * np.outer(root, root))
    return np.sqrt(np.clip(eigenvalues, 0, None))


def test_bonded_frequency_is_exact_for_a_dimer_and_a_ring_and_bounds_the_rest():
    """Analytic cases of Gershgorin's bound on the mass-weighted Hessian: a dimer of equal masses vibrates at
    sqrt(2k/m) and a straight ring (a chain closed through a periodic box) of an even number of equal masses has its
    highest mode (neighbours in opposite phase along it) at 2 sqrt(k/m): the bound is exact for both. Unequal masses
    (exact sqrt(k (1/m1 + 1/m2))), a chain with angles: the bound is above the highest frequency of the Hessian of
    OpenMM's forces (central differences, to 1e-6)."""
    k, m, r0 = 5000.0, 40.0, 0.3
    dimer, x = _system([[0, 0, 0], [r0, 0, 0]], [m, m], [(0, 1, r0, k)])
    assert stability.bonded_frequency(dimer) == pytest.approx(math.sqrt(2 * k / m), rel=1e-12)
    assert _frequencies(dimer, x).max() == pytest.approx(math.sqrt(2 * k / m), rel=1e-5)
    ring_x = [[r0 * i, 1.0, 1.0] for i in range(6)]   # closed through the box of edge 6 r0
    ring, x = _system(ring_x, [m] * 6, [(i, (i + 1) % 6, r0, k) for i in range(6)], box=6 * r0)
    assert stability.bonded_frequency(ring) == pytest.approx(2 * math.sqrt(k / m), rel=1e-12)
    assert _frequencies(ring, x).max() == pytest.approx(2 * math.sqrt(k / m), rel=1e-5)
    uneven, x = _system([[0, 0, 0], [r0, 0, 0]], [10.0, 90.0], [(0, 1, r0, k)])
    exact = math.sqrt(k * (1 / 10 + 1 / 90))
    assert _frequencies(uneven, x).max() == pytest.approx(exact, rel=1e-5)
    assert exact <= stability.bonded_frequency(uneven) <= 2 * exact
    bent_x = [[0, 0, 0], [r0, 0, 0], [r0 + r0 * math.cos(1.0), r0 * math.sin(1.0), 0], [2 * r0, r0, 0.1]]
    bent, x = _system(bent_x, [m, 2 * m, m, 3 * m],
                      [(0, 1, r0, k), (1, 2, r0, k), (2, 3, float(np.linalg.norm(np.subtract(bent_x[3], bent_x[2]))),
                                                      k)],
                      [(0, 1, 2, math.pi - 1.0, 200.0)])
    assert _frequencies(bent, x).max() <= stability.bonded_frequency(bent) * (1 + 1e-6)


def test_bonded_frequency_refuses_forces_it_cannot_bound():
    system, _ = _system([[0, 0, 0], [0.3, 0, 0], [0.6, 0, 0.1]], [40.0] * 3, [(0, 1, 0.3, 100.0)])
    torsion = openmm.PeriodicTorsionForce()
    system.addForce(torsion)
    with pytest.raises(ValueError, match=r"force 1 \(PeriodicTorsionForce\) is not allowed"):
        stability.bonded_frequency(system)
    system.removeForce(1)
    angle = openmm.HarmonicAngleForce()
    angle.addAngle(0, 1, 2, 2.0, 10.0)   # its arm (2, 1) is no bond
    system.addForce(angle)
    with pytest.raises(ValueError, match=r"angle 0 \(0, 1, 2\) of a HarmonicAngleForce is not allowed"):
        stability.bonded_frequency(system)
    assert stability.bonded_frequency(ARGON.liquid(500).system) == 0.0
    barostat = ARGON.liquid(500).system
    barostat.addForce(openmm.MonteCarloBarostat(1.0, 100.0))   # exerts no force: passed by
    assert stability.bonded_frequency(barostat) == 0.0


def test_suggest_time_step_takes_the_bonds_limit_where_it_is_below_the_fluids(monkeypatch):
    """The fluid's measured limit replaced by a constant (dt* = 0.134: the suggestion without bonds is half of it);
    with soft bonds (the default, omega_max dt* ~ 0.25 at 0.134) the fluid sets the step, with bonds 1000 times
    stiffer (omega_max* ~ 59) they do: 0.5 BONDED_STEP_LIMIT/omega_max, in reduced time and in ps."""
    monkeypatch.setattr(stability, "largest_stable_step", lambda *arguments, **options: 0.134)
    soft = polymer_solution(ARGON, 10, 5, (5, 5, 5))
    assert stability.suggest_time_step(ARGON, "VB", soft.system)[0] == pytest.approx(0.067)
    stiff = polymer_solution(ARGON, 10, 5, (5, 5, 5), bond_stiffness=1000 * soft.bond_stiffness)
    omega = 2 * math.sqrt(stiff.bond_stiffness / ARGON.mass)   # rad/ps: two bonds per bead, equal masses
    time_unit = ARGON.units.unit("time").value_in_unit(unit.picosecond)
    step, step_ps = stability.suggest_time_step(ARGON, "VB", stiff.system)
    assert step == pytest.approx(0.5 * stability.BONDED_STEP_LIMIT / omega / time_unit, rel=1e-9) and step < 0.03
    assert step_ps.value_in_unit(unit.picosecond) == pytest.approx(step * time_unit)
    torsion = openmm.PeriodicTorsionForce()
    stiff.system.addForce(torsion)
    with pytest.raises(ValueError, match="PeriodicTorsionForce"):
        stability.suggest_time_step(ARGON, "VB", stiff.system)


def test_chain_measurements_on_known_shapes():
    """A straight chain of N beads spaced b has R_g^2 = b^2 (N^2 - 1)/12, also when the box splits it; the fit of
    exact power laws returns their exponent."""
    box = np.array([3.0, 3.0, 3.0])
    beads = np.array([[2.5 + 0.4 * k, 1.0, 1.0] for k in range(5)]) % box   # split by the boundary at x = 3
    chains = [np.arange(5)]
    assert radii_of_gyration_squared(beads, box, chains)[0] == pytest.approx(0.4**2 * 24 / 12)
    assert np.allclose(np.diff(whole_chains(beads, box, chains)[0][:, 0]), 0.4)
    assert np.allclose(bond_lengths(beads, box, [[0, 1], [1, 2]]), 0.4)
    fit = flory_fit([5, 10, 20, 40], [2 * n**0.6 for n in (5, 10, 20, 40)], [0.01] * 4)
    assert fit.nu == pytest.approx(0.6) and fit.prefactor == pytest.approx(2.0)
    with pytest.raises(ValueError, match="at least two different chain lengths"):
        flory_fit([5, 5], [1.0, 1.0], [0.1, 0.1])


def test_isoenergetic_chains_conserve_the_energy_with_their_bonds():
    """Chains in argon (20 chains of 10 beads among 500 particles, the default bonds), melted 300 steps with the
    thermostat, then 1000 Isoenergetic steps at dt* = 0.01 (10 time units). Expected: the conserved energy
    K + U + sum eps (U with the bonds' energy) constant to the O(dt^2) error of the splitting, measured 5e-6 N k_B T0
    at most (2.3e-6 without the chains, 1.2e-5 with bonds 4 times stiffer); required < 5e-5 N k_B T0. The bonds' energy
    itself fluctuates by ~sqrt(180/2) k_B T0 = 0.019 N k_B T0, so a conserved energy that left it out, or bond forces
    that did not derive from it, would miss by ~400 times the tolerance."""
    model = polymer_solution(ARGON, 10, 20, (5, 5, 5), mode=GenDPDEIntegrator.Isothermal, time_step=0.01, seed=3)
    context = model.context("CPU", properties={"Threads": "1"})   # (kept: the integrator lives while it does)
    melt_then_switch(model.integrator, 300, ARGON.temperature, 3)
    scale = model.num_particles * _kt()
    start = model.integrator.getConservedEnergy().value_in_unit(unit.kilojoule_per_mole)
    deviations = []
    for _ in range(10):
        model.integrator.step(100)
        deviations.append(model.integrator.getConservedEnergy().value_in_unit(unit.kilojoule_per_mole) - start)
    assert max(abs(d) for d in deviations) / scale < 5e-5, deviations
    assert context.getState().getTime().value_in_unit(unit.picosecond) > 0


def _isolated_spring_variance(k_over_kt, b0):
    """The variance of r for a harmonic spring in three dimensions with no other force: P(r) ~ r^2
    exp(-k (r - b0)^2/(2 k_B T)), by quadrature."""
    sigma = 1 / math.sqrt(k_over_kt)
    r = np.linspace(max(0.0, b0 - 12 * sigma), b0 + 12 * sigma, 200001)
    weight = r**2 * np.exp(-0.5 * k_over_kt * (r - b0) ** 2)
    mean = (r * weight).sum() / weight.sum()
    return ((r - mean) ** 2 * weight).sum() / weight.sum(), mean


@pytest.mark.validation
def test_bond_lengths_fluctuate_as_equipartition_says():
    """20 chains of 10 beads among 500 argon particles, bonds of k = 400 k_B T0/b0^2 (an rms stretch of b0/20), the
    DPD thermostat at T0 (Isothermal: the canonical distribution at T0 up to the O(dt^2) error of the splitting),
    dt* = 0.05, 10000 steps sampled every 10. A harmonic spring alone in three dimensions has P(r) ~ r^2
    exp(-k (r - b0)^2/(2 k_B T0)): var(r) = k_B T0/k (1 - 2 k_B T0/(k b0^2) + ...) = 0.995 k_B T0/k here (by
    quadrature). Expected: var(r) k/(k_B T0) at that value, within 2.5%: the standard error of the run is 0.4% (block
    averages), and the liquid's own force between the bonded beads (their potential of mean force, which stiffens or
    softens the bond by its curvature W'') shifts it by -W''/k: measured at k = 100 k_B T0/b0^2, where it weighs 4
    times more, var k/(k_B T0) = 0.970 +- 0.008 against the isolated spring's 0.980, so |W''|/k < 0.5% at 400. The
    mean bond length is the spring's b0 (1 + 2 k_B T0/(k b0^2)) = 1.005 b0 to 0.5% (measured 1.0072 b0: the liquid
    pushes the bonded beads apart by 0.2% of b0)."""
    kt = _kt()
    b0 = lattice_bond_length(ARGON.density)
    model = polymer_solution(ARGON, 10, 20, (5, 5, 5), mode=GenDPDEIntegrator.Isothermal, time_step=0.05, seed=3,
                             bond_stiffness=400 * kt / b0**2)
    context = model.context("CPU", properties={"Threads": "1"})
    model.integrator.step(1000)
    samples = []
    for _ in range(1000):
        model.integrator.step(10)
        x = context.getState(getPositions=True).getPositions(asNumpy=True).value_in_unit(unit.nanometer)
        samples.append(bond_lengths(x, model.box_edges, model.bond_pairs))
    r = np.array(samples)
    expected, mean = _isolated_spring_variance(model.bond_stiffness / kt, b0)
    assert expected * model.bond_stiffness / kt == pytest.approx(0.995, abs=0.001)
    variance = ((r - r.mean()) ** 2).mean()
    assert abs(variance / expected - 1) < 0.025, variance * model.bond_stiffness / kt
    assert abs(r.mean() / mean - 1) < 0.005, (r.mean() / b0, mean / b0)


def test_the_polymer_example_runs_at_a_small_size():
    """examples/polymer_solution.py with two short lengths and a few hundred steps (seconds): a table row per length
    and a fitted nu. The chains are too short and the runs too short for the exponent to mean much (the measured
    table is in docs/soft-matter.md); required: the rows in order, R_g of 6 beads above that of 3, nu finite."""
    result = subprocess.run([sys.executable, str(EXAMPLES / "polymer_solution.py"), "--lengths", "3", "6",
                             "--steps", "400", "--melt-steps", "100", "--sample-every", "20", "--threads", "1"],
                            capture_output=True, text=True, check=True, timeout=300)
    rows = [line.split() for line in result.stdout.splitlines() if line[:4].strip().isdigit()]
    assert [int(row[0]) for row in rows] == [3, 6]
    assert float(rows[1][2]) > float(rows[0][2])
    nu = float(result.stdout.split("nu = ")[1].split()[0])
    assert math.isfinite(nu)


def test_the_polymer_solution_snippet_of_the_docs_runs(tmp_path):
    """The Python block of docs/soft-matter.md, "A polymer solution", as a user would paste it (200 thermostatted
    steps of 500 water particles): it prints a radius of gyration of 10 beads between the fully folded and the
    straight chain's (b0 sqrt(99/12) = 2.87 b0), and writes a PDB file that holds the chains' bonds (CONECT)."""
    section = SOFT_MATTER.read_text().split("## A polymer solution")[1]
    code = section.split("```python\n")[1].split("```")[0]
    result = subprocess.run([sys.executable, "-c", code], cwd=tmp_path, capture_output=True, text=True, check=True,
                            timeout=300)
    radius, b0 = (float(part.split()[0]) for part in result.stdout.split(": ")[1].split("b0 = "))
    assert 0.3 * b0 < radius < math.sqrt(99 / 12) * b0, result.stdout
    assert (tmp_path / "chains.pdb").read_text().count("CONECT") >= 45
