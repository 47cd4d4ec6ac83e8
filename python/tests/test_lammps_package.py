# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""The LAMMPS package (lammps/: pair_style gendpde, fix gendpde) against OpenMM's Reference platform.

LAMMPS runs in its lj units with OpenMM's numbers written as they are (nm, kJ/mol, amu, ps): lengths, energies, masses
and times then need no conversion, so the two engines compute with the same values. Only the temperature scale
differs (k_B = 1 in lj units): temperatures and theta0 are given as k_B T, heat capacities as C/k_B, heat conductions
as k_B kappa and thermal pressure coefficients as beta/k_B (exact up to one rounding each). The inputs are written by
the project's one LAMMPS writer, models.lammps_files.lammps_input(units="lj"), from the OpenMM System and integrator
each test compares with; a test adds only its own output and run commands.

Needs the package built (lammps/build.sh, which scripts/run-tests.sh runs first): build/lammps/lammps/lmp and
build/lammps/plugin/gendpdeplugin.so, or the paths in GENDPDE_LMP and GENDPDE_LAMMPS_PLUGIN. Ranks: mpirun with
--oversubscribe (4 ranks on 2 cores is fine for correctness).
"""

import os
import pathlib
import subprocess

import numpy as np
import openmm
import pytest
from helpers import MASS, TEMPERATURE, argon_integrator, lattice_liquid, load_file

from openmmgendpde import GenDPDEForce, GenDPDEIntegrator
from openmmgendpde.models.fluid_files import load_parameters
from openmmgendpde.models.lammps_files import (
    SECTIONS,
    lammps_input,
    round_up,
    thermo_table,
    write_lammps_input,
)
from openmmgendpde.models.lammps_units import ENERGY

pytestmark = pytest.mark.lammps

ROOT = pathlib.Path(__file__).resolve().parents[2]
LMP = pathlib.Path(os.environ.get("GENDPDE_LMP", ROOT / "build/lammps/lammps/lmp"))
PLUGIN = pathlib.Path(os.environ.get("GENDPDE_LAMMPS_PLUGIN", ROOT / "build/lammps/plugin/gendpdeplugin.so"))
#: The same LAMMPS and plugin built with -DLAMMPS_SIZES=bigbig (64-bit atom IDs): lammps/build.sh --bigbig.
BIGBIG_LMP = pathlib.Path(os.environ.get("GENDPDE_BIGBIG_LMP", ROOT / "build/lammps-bigbig/lammps/lmp"))
BIGBIG_PLUGIN = pathlib.Path(os.environ.get("GENDPDE_BIGBIG_LAMMPS_PLUGIN",
                                            ROOT / "build/lammps-bigbig/plugin/gendpdeplugin.so"))
#: OpenMM's Boltzmann constant, kJ/(mol K) (k_B N_A, exact SI values)
KB = 1.380649e-23 * 6.02214076e23 / 1000
#: A second type's law and thermal parameters (a liquid with thermal expansion, OpenMM units): beta (kJ/mol/nm^3/K),
#: theta0 (K), C_V (kJ/mol/K), and its pairs' friction (amu/ps) and heat conduction (kJ K/(mol ps)) with type 0.
BETA, THETA0, SECOND_HEAT_CAPACITY, MIXED_FRICTION, MIXED_CONDUCTION = 0.9, 130.0, 0.2, 20.0, 3.0


@pytest.fixture(scope="module")
def lammps():
    if not (LMP.exists() and PLUGIN.exists()):
        pytest.fail(f"the LAMMPS package is not built ({LMP}, {PLUGIN}): run lammps/build.sh")
    return LMP


def run_lammps(directory, script, ranks=1, check=True, lmp=None):
    """Run lmp on ``script`` (text) in ``directory`` with ``ranks`` MPI ranks; returns the CompletedProcess."""
    (directory / "in.test").write_text(script)
    command = ["mpirun", "--allow-run-as-root", "--oversubscribe", "-np", str(ranks), str(lmp or LMP), "-in",
               "in.test", "-log", "log.lammps", "-echo", "none"] + (["-screen", "none"] if check else [])
    result = subprocess.run(command, cwd=directory, capture_output=True, text=True, timeout=300)
    if check and result.returncode != 0:
        log = (directory / "log.lammps").read_text() if (directory / "log.lammps").exists() else ""
        raise AssertionError(f"lmp failed ({result.returncode}):\n{log[-3000:]}\n{result.stdout[-2000:]}")
    return result


def read_dump(path):
    """(ids sorted) columns of a LAMMPS custom dump of one frame."""
    table = np.loadtxt(path, skiprows=9, ndmin=2)
    return table[np.argsort(table[:, 0])]


def neighbour_list_builds(log):
    """LAMMPS's count of neighbour-list builds in a run (its log's "Neighbor list builds = N")."""
    return int(log.split("Neighbor list builds = ")[1].split()[0])


class Scene:
    """A liquid in OpenMM (System, force, positions) and its LAMMPS input in lj units (see the module docstring)."""

    def __init__(self, estimator=GenDPDEForce.VB, slab=False, two_types=False, cells=8, seed=1,
                 mixed_friction=MIXED_FRICTION):
        system, force, positions = lattice_liquid(cells, estimator=estimator, seed=seed)
        self.mixed_friction = mixed_friction
        edges = [system.getDefaultPeriodicBoxVectors()[k][k]._value for k in range(3)]
        if slab:
            # A slab: the box twice as tall, so the liquid has two free surfaces (V-C's moment terms act there).
            edges[2] *= 2
            system.setDefaultPeriodicBoxVectors(openmm.Vec3(edges[0], 0, 0), openmm.Vec3(0, edges[1], 0),
                                                openmm.Vec3(0, 0, edges[2]))
        self.positions = np.mod(positions, edges)
        self.system, self.force, self.edges = system, force, edges
        self.types = np.zeros(len(positions), dtype=int)
        if two_types:
            self.types[1::3] = 1
            for i in np.flatnonzero(self.types):
                force.setParticleType(int(i), 1)
            force.addTypeEquationOfState(1, GenDPDEForce.TaitThermalExpansion, [BETA, THETA0])

    @property
    def num_types(self):
        return int(self.types.max()) + 1

    def integrator(self, mode, step_size=0.004, seed=1234):
        integrator = argon_integrator(step_size)
        integrator.setMode(mode)
        integrator.setRandomNumberSeed(seed)
        integrator.setTemperature(TEMPERATURE)
        if self.num_types > 1:
            integrator.addTypeHeatCapacity(1, SECOND_HEAT_CAPACITY)
            integrator.addTypePair(0, 1, self.mixed_friction, MIXED_CONDUCTION)
        return integrator

    def lammps(self, directory, integrator=None, velocities=None, **options):
        """The LAMMPS input of this scene in lj units (lammps_files.lammps_input: data file, script sections, any
        atomfile), written into ``directory``; ``integrator``: the fix's (default an Isoenergetic one), ``options``:
        lammps_input's (temperatures, restart, skin)."""
        options.setdefault("plugin", PLUGIN)
        texts = lammps_input(self.system, integrator or self.integrator(GenDPDEIntegrator.Isoenergetic),
                             self.positions, velocities, units="lj", **options)
        write_lammps_input(directory, texts)
        return texts


def openmm_energy_and_forces(scene, integrator=None):
    context = openmm.Context(scene.system, integrator or openmm.VerletIntegrator(0.001),
                             openmm.Platform.getPlatformByName("Reference"))
    context.setPositions(scene.positions)
    if integrator is not None:
        integrator.setParticleTemperatures([TEMPERATURE] * scene.system.getNumParticles())
    state = context.getState(getEnergy=True, getForces=True)
    return state.getPotentialEnergy()._value, np.array(state.getForces()._value)


def lammps_energy_and_forces(scene, directory, ranks, integrator=None):
    """U and the forces of the pair style alone, or with fix gendpde of ``integrator`` (the thermal state)."""
    texts = scene.lammps(directory, integrator)
    sections = ("header", "variables", "setup", "pair", "neighbors") + (("fix",) if integrator else ())
    script = texts.commands(*sections) + """
thermo_style custom step pe
thermo_modify norm no format float %.17g
dump forces all custom 1 forces.dump id fx fy fz
dump_modify forces format float %.17g sort id
run 0
"""
    run_lammps(directory, script, ranks)
    potential_energy = thermo_table((directory / "log.lammps").read_text())[0]["PotEng"]
    return potential_energy, read_dump(directory / "forces.dump")[:, 1:4]


@pytest.mark.parametrize("ranks", [1, 2, 4])
@pytest.mark.parametrize("case", ["va", "vb", "vc-slab", "two-types-thermal"])
def test_energy_and_forces_equal_reference(lammps, tmp_path, case, ranks):
    """U and every force as OpenMM's Reference platform computes them, to 1e-12 (relative to U and to the rms force;
    the sums run in other orders, so they differ by rounding, ~1e-15)."""
    estimator = {"va": GenDPDEForce.VA, "vc-slab": GenDPDEForce.VC}.get(case, GenDPDEForce.VB)
    scene = Scene(estimator, slab=case == "vc-slab", two_types=case == "two-types-thermal")
    integrator = None
    if case == "two-types-thermal":
        # A law that depends on temperature: its pressure and U read each particle's temperature, here T0
        integrator = scene.integrator(GenDPDEIntegrator.Isoenergetic)
    lammps_energy, lammps_forces = lammps_energy_and_forces(scene, tmp_path, ranks, integrator)
    energy, forces = openmm_energy_and_forces(scene, integrator)
    assert abs(lammps_energy - energy) <= 1e-12 * abs(energy)
    rms = np.sqrt(np.mean(forces**2))
    assert np.max(np.abs(lammps_forces - forces)) <= 1e-12 * rms
    if case == "vc-slab":
        # the moment terms act: V-C's forces differ from V-B's at the surfaces by far more than rounding
        scene.force.setDensityEstimator(GenDPDEForce.VB)
        assert np.max(np.abs(openmm_energy_and_forces(scene)[1] - forces)) > 1e-3 * rms


def openmm_trajectory(scene, mode, steps, velocities, step_size=0.004, temperatures=None):
    """Positions and internal energies after ``steps`` steps of GenDPDEIntegrator on Reference, starting from
    ``velocities`` at the time of the positions (OpenMM keeps velocities half a step behind: the first half kick is
    undone here)."""
    integrator = scene.integrator(mode, step_size)
    context = openmm.Context(scene.system, integrator, openmm.Platform.getPlatformByName("Reference"))
    context.setPositions(scene.positions)
    forces = np.array(context.getState(getForces=True).getForces()._value)
    context.setVelocities(velocities - forces * (0.5 * step_size / MASS))
    if mode != GenDPDEIntegrator.Isothermal:
        integrator.setParticleTemperatures(
            [TEMPERATURE] * scene.system.getNumParticles() if temperatures is None else temperatures)
    integrator.step(steps)
    positions = np.array(context.getState(getPositions=True).getPositions()._value)
    energies = np.array(integrator.getInternalEnergies()) if mode != GenDPDEIntegrator.Isothermal else None
    return positions, energies, integrator


def lammps_trajectory(scene, directory, mode, steps, velocities, ranks, step_size=0.004, restart_at=None,
                      temperatures=None, edit=lambda script: script):
    """Positions and internal energies (fix gendpde's per-atom vector) after ``steps`` steps of the fix in ``mode``;
    with ``restart_at``, the run stops there, writes a restart file (its log: log.first.lammps), and a second lmp
    reads it and runs the rest;
    ``temperatures``: each particle's initial temperature (K), through an atomfile variable (initial v_theta);
    ``edit``: what changes the written script (text) before it runs."""
    integrator = scene.integrator(mode, step_size)
    texts = scene.lammps(directory, integrator, velocities, temperatures=temperatures)
    output = """thermo_style custom step pe ke f_integrate
thermo 10
"""
    finish = """write_dump all custom final.dump id x y z f_integrate modify format float %.17g sort id
"""
    script = edit(texts.commands(*SECTIONS[:-2])) + output
    if restart_at is None:
        run_lammps(directory, script + f"run {steps}\n" + finish, ranks)
    else:
        run_lammps(directory, script + f"run {restart_at}\nwrite_restart state.restart\n", ranks)
        (directory / "log.lammps").rename(directory / "log.first.lammps")
        resumed = scene.lammps(directory, integrator, restart="state.restart")
        run_lammps(directory, resumed.commands(*SECTIONS[:-2]) + output + f"run {steps - restart_at}\n" + finish,
                   ranks)
    table = read_dump(directory / "final.dump")
    return table[:, 1:4], table[:, 4]


def start_velocities(scene, seed=7):
    rng = np.random.default_rng(seed)
    return rng.normal(0.0, np.sqrt(KB * TEMPERATURE / MASS), scene.positions.shape)


MODES = {"isoenergetic": GenDPDEIntegrator.Isoenergetic, "isothermal": GenDPDEIntegrator.Isothermal,
         "conservative": GenDPDEIntegrator.Conservative}


@pytest.mark.parametrize("ranks", [1, 2, 4])
@pytest.mark.parametrize("mode_name", ["isoenergetic", "isothermal"])
def test_trajectory_follows_reference(lammps, tmp_path, mode_name, ranks):
    """fix gendpde's sweep across subdomains is GenDPDEIntegrator's (same order of pair updates, built at the same
    steps, same random numbers): after 60 steps (the order built at the start and once more on the way, when an atom
    has moved 0.05 R) every position and internal energy is OpenMM's to rounding, 1e-12 nm and 1e-12 relative, with 1,
    2 or 4 ranks. A pair updated out of order, twice, never, or with another random number moves particles by ~1e-5
    nm in one step."""
    scene = Scene(GenDPDEForce.VB)
    velocities = start_velocities(scene)
    positions, energies, _ = openmm_trajectory(scene, MODES[mode_name], 60, velocities)
    lammps_positions, lammps_energies = lammps_trajectory(scene, tmp_path, MODES[mode_name], 60, velocities, ranks)
    assert neighbour_list_builds((tmp_path / "log.lammps").read_text()) >= 1   # (the order was built again)
    assert np.max(np.abs(lammps_positions - positions)) <= 1e-12
    if energies is not None:
        assert np.max(np.abs(lammps_energies / energies - 1)) <= 1e-12
        assert np.max(np.abs(energies / (scene.integrator(MODES[mode_name]).getHeatCapacity()._value * TEMPERATURE)
                             - 1)) > 1e-4   # (the energies did change)



def bonded_scene_energy_and_forces(scene, directory, special):
    """U and the forces of the pair style in LAMMPS (lj units, 1 rank) with the scene's particles in molecules:
    atom_style bond, every particle i < j in a chain bonded to the next (bond_style zero: the bonds add no force of
    their own), with ``special`` as the special_bonds line (None: LAMMPS's default, lj 0 0 0)."""
    script = scene.lammps(directory).commands("header", "variables", "setup", "pair", "neighbors")
    data = (directory / "gendpde.data").read_text().split("\n")
    atoms = data.index("Atoms # atomic")
    data[atoms] = "Atoms # bond"
    count = scene.system.getNumParticles()
    for k in range(atoms + 2, atoms + 2 + count):
        fields = data[k].split()
        data[k] = " ".join([fields[0], "1"] + fields[1:])   # molecule 1
    bonds = [(i, i + 1) for i in range(0, count - 1, 2)]
    data[2:2] = [f"{len(bonds)} bonds", "1 bond types"]
    data += ["", "Bonds", ""] + [f"{k + 1} 1 {i + 1} {j + 1}" for k, (i, j) in enumerate(bonds)] + [""]
    (directory / "gendpde.data").write_text("\n".join(data))
    script = script.replace("atom_style atomic", "atom_style bond\nbond_style zero")
    script = script.replace("read_data gendpde.data", "read_data gendpde.data\nbond_coeff 1")
    if special is not None:
        script = script.replace("pair_style", special + "\npair_style", 1)
    script += ("thermo_style custom step pe\nthermo_modify norm no format float %.17g\n"
               "dump forces all custom 1 forces.dump id fx fy fz\ndump_modify forces format float %.17g sort id\n"
               "run 0\n")
    result = run_lammps(directory, script, 1, check=False)
    if result.returncode != 0:
        return result.stdout
    potential_energy = thermo_table((directory / "log.lammps").read_text())[0]["PotEng"]
    return potential_energy, read_dump(directory / "forces.dump")[:, 1:4]


def test_bonded_pairs_count_in_the_density_as_in_openmm(lammps, tmp_path):
    """Bonded particles count in each other's density in OpenMM's GenDPDEForce (no exclusions) and in the fix's
    sweep; LAMMPS's default special_bonds (lj 0 0 0) would drop them from the pair style's neighbour list. With
    molecules, pair_style gendpde refuses any special_bonds lj weight other than 1, naming it; with lj/coul 1 1 1,
    U and every force equal OpenMM's Reference for the same particles without bonds, to 1e-12 (as
    test_energy_and_forces_equal_reference), so the bonded pairs are counted."""
    scene = Scene(GenDPDEForce.VB)
    refused = bonded_scene_energy_and_forces(scene, tmp_path / "default", None)
    assert isinstance(refused, str) and "special_bonds lj 0 0 0 is not allowed" in refused, refused[-2000:]
    refused = bonded_scene_energy_and_forces(scene, tmp_path / "half", "special_bonds lj/coul 1.0 0.5 1.0")
    assert isinstance(refused, str) and "special_bonds lj 1 0.5 1 is not allowed" in refused, refused[-2000:]
    lammps_energy, lammps_forces = bonded_scene_energy_and_forces(scene, tmp_path / "all",
                                                                  "special_bonds lj/coul 1.0 1.0 1.0")
    energy, forces = openmm_energy_and_forces(scene)
    assert abs(lammps_energy - energy) <= 1e-12 * abs(energy)
    assert np.max(np.abs(lammps_forces - forces)) <= 1e-12 * np.sqrt(np.mean(forces**2))

@pytest.mark.parametrize("mode_name", ["isoenergetic", "conservative"])
def test_two_types_with_thermal_law_follow_reference(lammps, tmp_path, mode_name):
    """Two types, one with a temperature-dependent law (TaitThermalExpansion): per-type laws, heat capacities and pair
    parameters, and the thermal state the pair style keeps in the fix (Conservative: isentropic temperatures only), on
    2 ranks: OpenMM's trajectory to rounding after 20 steps."""
    scene = Scene(GenDPDEForce.VB, two_types=True)
    velocities = start_velocities(scene)
    positions, energies, _ = openmm_trajectory(scene, MODES[mode_name], 20, velocities)
    lammps_positions, lammps_energies = lammps_trajectory(scene, tmp_path, MODES[mode_name], 20, velocities, 2)
    assert np.max(np.abs(lammps_positions - positions)) <= 1e-12
    assert np.max(np.abs(lammps_energies / energies - 1)) <= 1e-12


def test_a_pair_without_friction_reads_its_stream_as_openmm_does(lammps, tmp_path):
    """Unlike pairs without friction (but with heat conduction) in a run with friction: a pair's stream is read the
    same way whatever its own parameters (the impulse's variate, then the heat's; core/include/gendpde/
    GenDPDESweepPair.h), so LAMMPS follows OpenMM's trajectory to rounding after 20 steps on 2 ranks. (Before the two
    engines shared the pair step, LAMMPS drew no impulse variate for such a pair and gave its heat the impulse's.)"""
    scene = Scene(GenDPDEForce.VB, two_types=True, mixed_friction=0.0)
    velocities = start_velocities(scene)
    positions, energies, _ = openmm_trajectory(scene, GenDPDEIntegrator.Isoenergetic, 20, velocities)
    lammps_positions, lammps_energies = lammps_trajectory(scene, tmp_path, GenDPDEIntegrator.Isoenergetic, 20,
                                                          velocities, 2)
    assert np.max(np.abs(lammps_positions - positions)) <= 1e-12
    assert np.max(np.abs(lammps_energies / energies - 1)) <= 1e-12


@pytest.mark.parametrize("steps, restart_at", [(20, 10), (60, 56)])
def test_restart_continues_the_run(lammps, tmp_path, steps, restart_at):
    """A run written to a restart file after ``restart_at`` steps and continued by another lmp (read_restart:
    positions, velocities, internal energies and entropies, the step, and each atom's position at the sweep order's
    last build, from which the continued run makes the same order again) ends where OpenMM's uninterrupted run ends,
    to rounding: after 10 steps (the order of step 0 kept) and after 56 (one built again on the way, at step 51-54:
    an order made anew from the positions at the restart would move particles by ~1e-5 nm)."""
    scene = Scene(GenDPDEForce.VB, two_types=True)
    velocities = start_velocities(scene)
    positions, energies, _ = openmm_trajectory(scene, GenDPDEIntegrator.Isoenergetic, steps, velocities)
    lammps_positions, lammps_energies = lammps_trajectory(scene, tmp_path, GenDPDEIntegrator.Isoenergetic, steps,
                                                          velocities, 2, restart_at=restart_at)
    if restart_at > 50:
        assert neighbour_list_builds((tmp_path / "log.first.lammps").read_text()) >= 1
    assert np.max(np.abs(lammps_positions - positions)) <= 1e-12
    assert np.max(np.abs(lammps_energies / energies - 1)) <= 1e-12


def test_a_second_run_command_continues_the_order(lammps, tmp_path):
    """run 30 then run 30 in one input: the second run's first step makes the order of the first run's last build
    again (from each atom's position at that build) rather than a new one from its own positions, as OpenMM's
    integrator keeps its order between step() calls: the 60 steps end where OpenMM's end, to rounding."""
    scene = Scene(GenDPDEForce.VB)
    velocities = start_velocities(scene)
    positions, energies, _ = openmm_trajectory(scene, GenDPDEIntegrator.Isoenergetic, 60, velocities)
    lammps_positions, lammps_energies = lammps_trajectory(scene, tmp_path, GenDPDEIntegrator.Isoenergetic, 30,
                                                          velocities, 2, edit=lambda script: script + "run 30\n")
    assert np.max(np.abs(lammps_positions - positions)) <= 1e-12
    assert np.max(np.abs(lammps_energies / energies - 1)) <= 1e-12


@pytest.mark.parametrize("change, words", [
    (("pair_style gendpde", "pair_style gendpde 1.0375518240000001 vd 1.35 #"), "density estimator 'vd'"),
    (("pair_coeff 1 1 Tait", "pair_coeff 1 1 Tait 1.0 #"), "law Tait takes 4 parameters"),
    (("pair_coeff 1 1 Tait", "pair_coeff 1 1 Murnaghan"), "law 'Murnaghan' is not allowed"),
    (("pair_coeff 1 1 Tait", "#"), "All pair coeffs are not set"),
    (("comm_modify cutoff", "comm_modify cutoff 1.2 #"), "the ghost cutoff 1.2 is below what the sweep needs"),
    (("variable mode index isoenergetic", "variable mode index adiabatic"), "mode 'adiabatic'"),
    (("initial ${initial}", ""), "the internal energies are not set"),
    # GenDPDEForce's range of f_cut, [1, 100] (ParameterRanges.h), not merely > 0
    (("pair_style gendpde", "pair_style gendpde 1.0375518240000001 vb 0.5 #"),
     "cutoff scaling f_cut = 0.5 is not allowed: it must be in [1, 100]"),
    (("pair_style gendpde", "pair_style gendpde 1.0375518240000001 vb 100.5 #"),
     "cutoff scaling f_cut = 100.5 is not allowed: it must be in [1, 100]"),
    # the fix integrates every atom: a group would leave the others frozen and out of the sweep
    (("fix integrate all gendpde", "group some id <= 256\nfix integrate some gendpde"),
     "fix gendpde: group 'some' is not allowed: it must be all"),
])
def test_bad_input_gives_a_lammps_error(lammps, tmp_path, change, words):
    """Bad input stops LAMMPS with its ERROR line naming the problem (exit status 1), not a crash."""
    scene = Scene(GenDPDEForce.VB)
    script = scene.lammps(tmp_path).commands(*SECTIONS[:-1]) + "run 1\n"
    assert change[0] in script
    result = run_lammps(tmp_path, script.replace(change[0], change[1], 1), check=False)
    assert result.returncode == 1, result.stdout[-2000:]
    assert "ERROR" in result.stdout and words in result.stdout, result.stdout[-2000:]


@pytest.mark.parametrize("mode_name", ["isoenergetic", "conservative"])
@pytest.mark.parametrize("other, style", [
    ("fix again all nve", "nve"),
    ("fix again all npt temp 1.0 1.0 0.4 iso 0.0 0.0 4.0", "npt"),
    ("fix again all gendpde isothermal 5 temperature 1.0", "gendpde"),
])
def test_a_second_time_integrator_is_refused(lammps, tmp_path, mode_name, other, style):
    """Another fix that integrates the same atoms (fix nve, a thermostat-barostat such as npt, a second fix gendpde)
    would move each atom twice per step, which LAMMPS only warns about: fix gendpde stops before the run with an
    error naming that fix, on 2 ranks, in a mode with the sweep and in one without."""
    scene = Scene(GenDPDEForce.VB)
    script = scene.lammps(tmp_path, velocities=start_velocities(scene)).commands(*SECTIONS[:-1])
    assert "variable mode index isoenergetic" in script
    script = script.replace("variable mode index isoenergetic", f"variable mode index {mode_name}")
    script += other + "\nrun 5\n"
    result = run_lammps(tmp_path, script, ranks=2, check=False)
    assert result.returncode == 1, result.stdout[-2000:]
    assert f"fix gendpde: fix again (style {style}) also integrates" in result.stdout, result.stdout[-2000:]


@pytest.mark.parametrize("other, style", [("fix baro all press/berendsen iso 0.0 0.0 1.0", "press/berendsen"),
                                          ("fix stretch all deform 1 x scale 1.01", "deform")])
def test_a_box_that_changes_during_a_run_is_refused(lammps, tmp_path, other, style):
    """A barostat or fix deform changes the box during the run; the sweep's cells and ghost cutoff are those of the
    box at the run's start, so fix gendpde stops before the run with an error naming that fix (it used to stop at
    the first step with a message about the ghost cutoff). A fix that moves only the subdomains (fix balance) runs:
    test_subdomains_that_move_during_the_run."""
    scene = Scene(GenDPDEForce.VB)
    script = scene.lammps(tmp_path, velocities=start_velocities(scene)).commands(*SECTIONS[:-1])
    result = run_lammps(tmp_path, script + other + "\nrun 5\n", check=False)
    assert result.returncode == 1, result.stdout[-2000:]
    name = other.split()[1]
    assert f"fix gendpde: fix {name} (style {style}) changes the box during a run" in result.stdout, \
        result.stdout[-2000:]
    assert "is below what the sweep needs" not in result.stdout


def test_a_restart_read_under_another_fix_id_is_refused(lammps, tmp_path):
    """read_restart then fix gendpde under another ID than the fix that wrote the file: LAMMPS matches a fix's
    restart data by ID, so the internal energies saved would be left unused and set again from ``initial`` (the
    conserved energy jumps). The fix stops at its definition with an error naming the ID of the saved state (2 ranks);
    under that ID the run continues (test_restart_continues_the_run)."""
    scene = Scene(GenDPDEForce.VB)
    integrator = scene.integrator(GenDPDEIntegrator.Isoenergetic)
    texts = scene.lammps(tmp_path, integrator, start_velocities(scene))
    run_lammps(tmp_path, texts.commands(*SECTIONS[:-1]) + "run 10\nwrite_restart state.restart\n", ranks=2)
    resumed = scene.lammps(tmp_path, integrator, restart="state.restart").commands(*SECTIONS[:-1])
    assert "fix integrate all gendpde" in resumed and "read_restart state.restart" in resumed
    renamed = resumed.replace("fix integrate all gendpde", "fix other all gendpde").replace("f_integrate", "f_other")
    result = run_lammps(tmp_path, renamed + "run 10\n", ranks=2, check=False)
    assert result.returncode == 1, result.stdout[-2000:]
    assert ("fix gendpde: the restart file holds the state of fix integrate (style gendpde)" in result.stdout
            and "fix other" in result.stdout), result.stdout[-2000:]



def test_the_written_ghost_cutoff_is_the_fix_s_need(lammps, tmp_path):
    """The writer's comm_modify cutoff is the ghost cutoff fix gendpde requires (both from the core's
    sweepGhostCutoff: 1.5 widths of the widest sweep cell + the skin), rounded up to 4 digits: in a slab box (4 cells
    across x and y, 8 along z: the cells differ) the fix, given less, names what it needs, and the writer's value is
    that need rounded up."""
    scene = Scene(GenDPDEForce.VB, slab=True)
    texts = scene.lammps(tmp_path)
    script = texts.commands(*SECTIONS[:-1]).replace(f"comm_modify cutoff {texts.ghost!r}", "comm_modify cutoff 0.5")
    result = run_lammps(tmp_path, script + "run 1\n", check=False)
    assert result.returncode == 1, result.stdout[-2000:]
    need = float(result.stdout.split("is below what the sweep needs, ")[1].split()[0])
    assert need <= texts.ghost == round_up(need) < need * (1 + 1e-3)
    assert need == pytest.approx(1.5 * scene.edges[0] / 4 + texts.skin, rel=1e-15)


def test_each_particle_s_initial_temperature_from_an_atomfile(lammps, tmp_path):
    """initial v_name: every particle's starting temperature from an atom-style variable (here an atomfile, as an
    OpenMM run's GenDPDEIntegrator.getParticleTemperatures would be written): 20 isoenergetic steps on 2 ranks end
    where OpenMM's end after setParticleTemperatures with the same temperatures, to rounding (a uniform start would
    differ by ~10% in eps_i)."""
    scene = Scene(GenDPDEForce.VB)
    velocities = start_velocities(scene)
    temperatures = TEMPERATURE * np.random.default_rng(11).uniform(0.8, 1.2, len(scene.positions))
    positions, energies, _ = openmm_trajectory(scene, GenDPDEIntegrator.Isoenergetic, 20, velocities,
                                               temperatures=temperatures)
    lammps_positions, lammps_energies = lammps_trajectory(scene, tmp_path, GenDPDEIntegrator.Isoenergetic, 20,
                                                          velocities, 2, temperatures=temperatures)
    assert np.max(np.abs(lammps_positions - positions)) <= 1e-12
    assert np.max(np.abs(lammps_energies / energies - 1)) <= 1e-12


def test_a_skin_below_a_tenth_of_the_range_is_refused(lammps, tmp_path):
    """The sweep's candidates reach 0.1 R beyond R and the order is built again once an atom has moved 0.05 R: with
    a skin of 0.001 nm (< 0.1 R) LAMMPS's lists and ghosts would miss pairs before that, so fix gendpde stops at the
    start with an error naming the skin and the least it takes."""
    scene = Scene(GenDPDEForce.VB)
    texts = scene.lammps(tmp_path, velocities=start_velocities(scene), skin=0.001)
    script = texts.commands(*SECTIONS[:-1]) + "run 50\n"
    assert "neighbor 0.001 bin\nneigh_modify every 1 delay 0 check yes" in script
    result = run_lammps(tmp_path, script, check=False)
    assert result.returncode != 0
    least = 0.1 * texts.cutoff
    assert f"the neighbour skin 0.001 is below {least!r} = 0.1 R" in result.stdout, result.stdout[-2000:]


@pytest.mark.parametrize("settings, builds", [("every 1 delay 0 check yes", "some"),
                                              ("every 1 delay 0 check no", "every step"),
                                              ("every 1000 delay 0 check no", "some")])
def test_the_order_is_built_by_its_rule_whatever_lammps_lists_do(lammps, tmp_path, settings, builds):
    """The sweep's order is built at the start and when an atom has moved 0.05 R since its build (the rule OpenMM's
    platforms follow), whenever LAMMPS builds its lists: with LAMMPS's check (skin/2 = 0.05 R: its lists are built
    at the order's builds), with lists built at every step (the order kept, its atoms found again by ID) and with
    lists LAMMPS would build every 1000 steps only (the fix makes it build them at the order's builds), 60 isoenergetic
    steps on 2 ranks end where OpenMM's end, to rounding. The run does build the order again (some atom moves 0.05 R
    in 60 steps): an order built at another step would move particles by ~1e-5 nm."""
    scene = Scene(GenDPDEForce.VB)
    velocities = start_velocities(scene)
    positions, energies, _ = openmm_trajectory(scene, GenDPDEIntegrator.Isoenergetic, 60, velocities)

    def lists(script):
        assert "neigh_modify every 1 delay 0 check yes" in script
        return script.replace("neigh_modify every 1 delay 0 check yes", f"neigh_modify {settings}")
    lammps_positions, lammps_energies = lammps_trajectory(scene, tmp_path, GenDPDEIntegrator.Isoenergetic, 60,
                                                          velocities, 2, edit=lists)
    count = neighbour_list_builds((tmp_path / "log.lammps").read_text())
    assert count == 60 if builds == "every step" else 1 <= count < 60
    assert np.max(np.abs(lammps_positions - positions)) <= 1e-12
    assert np.max(np.abs(lammps_energies / energies - 1)) <= 1e-12


def test_subdomains_that_move_during_the_run(lammps, tmp_path):
    """fix balance moving the boundary between 2 ranks every 5 steps (atoms weighted by x, so there is always an
    imbalance to correct): the sweep's blocks go to the ranks that now hold their centres, its order stays the one of
    its build (made again from the positions of the build for the new subdomains), and 60 isoenergetic steps end where
    OpenMM's end, to rounding."""
    scene = Scene(GenDPDEForce.VB)
    velocities = start_velocities(scene)
    positions, energies, _ = openmm_trajectory(scene, GenDPDEIntegrator.Isoenergetic, 60, velocities)

    def balanced(script):
        return script + ("variable weight atom 1.0+2.0*x/lx\n"
                         "fix balance all balance 5 1.0 shift x 10 1.0 weight var weight\n"
                         'fix report all print 5 "rebalanced $(f_balance[2])"\n')
    lammps_positions, lammps_energies = lammps_trajectory(scene, tmp_path, GenDPDEIntegrator.Isoenergetic, 60,
                                                          velocities, 2, edit=balanced)
    reports = [line for line in (tmp_path / "log.lammps").read_text().splitlines() if line.startswith("rebalanced")]
    assert len(reports) == 13 and all(line.split()[1] != "0" for line in reports[1:])
    assert np.max(np.abs(lammps_positions - positions)) <= 1e-12
    assert np.max(np.abs(lammps_energies / energies - 1)) <= 1e-12


def test_subdomains_thinner_than_the_ghost_cutoff(lammps, tmp_path):
    """4 ranks as slabs along z (processors 1 1 4), each 1.23 nm thick against a ghost cutoff of 1.95 nm (1.5 sweep
    cells + the skin): the sweep's exchanges then reach past the neighbouring rank (two hops), and the trajectory is
    still OpenMM's to rounding."""
    scene = Scene(GenDPDEForce.VB)
    velocities = start_velocities(scene)
    positions, energies, _ = openmm_trajectory(scene, GenDPDEIntegrator.Isoenergetic, 30, velocities)

    def slabs(script):
        return script.replace("boundary p p p\n", "boundary p p p\nprocessors 1 1 4\n")
    lammps_positions, lammps_energies = lammps_trajectory(scene, tmp_path, GenDPDEIntegrator.Isoenergetic, 30,
                                                          velocities, 4, edit=slabs)
    assert "1 by 1 by 4 MPI processor grid" in (tmp_path / "log.lammps").read_text()
    assert np.max(np.abs(lammps_positions - positions)) <= 1e-12
    assert np.max(np.abs(lammps_energies / energies - 1)) <= 1e-12


@pytest.fixture(scope="module")
def bigbig():
    if not (BIGBIG_LMP.exists() and BIGBIG_PLUGIN.exists()):
        pytest.fail(f"the bigbig build of the package is missing ({BIGBIG_LMP}, {BIGBIG_PLUGIN}): run lammps/build.sh "
                    f"--bigbig")
    return BIGBIG_LMP


def with_atom_id(data, old, new):
    """A data file's text with atom ID ``old`` renamed ``new`` (in its Atoms and Velocities sections)."""
    lines = data.splitlines()
    start = lines.index("Atoms # atomic")
    for k in range(start, len(lines)):
        if lines[k].split(" ", 1)[0] == str(old):
            lines[k] = f"{new} {lines[k].split(' ', 1)[1]}"
    return "\n".join(lines) + "\n"


def test_the_package_in_a_bigbig_build(bigbig, tmp_path):
    """LAMMPS and the plugin built with -DLAMMPS_SIZES=bigbig (64-bit atom IDs, as LAMMPS asks every contribution to
    build and run): the energy and forces (2 ranks) and 20 isoenergetic steps (2 ranks) are OpenMM's to rounding, as
    in the default build; the last atom renumbered 2^32, the largest ID the random streams index, runs; renumbered
    2^32 + 1 it is refused with an error naming the ID, not truncated to another particle's streams."""
    scene = Scene(GenDPDEForce.VB)
    energy, forces = openmm_energy_and_forces(scene)
    texts = scene.lammps(tmp_path, plugin=BIGBIG_PLUGIN)
    script = texts.commands("header", "variables", "setup", "pair", "neighbors") + """
thermo_style custom step pe
thermo_modify norm no format float %.17g
dump forces all custom 1 forces.dump id fx fy fz
dump_modify forces format float %.17g sort id
run 0
"""
    run_lammps(tmp_path, script, 2, lmp=bigbig)
    assert abs(thermo_table((tmp_path / "log.lammps").read_text())[0]["PotEng"] - energy) <= 1e-12 * abs(energy)
    rms = np.sqrt(np.mean(forces**2))
    assert np.max(np.abs(read_dump(tmp_path / "forces.dump")[:, 1:4] - forces)) <= 1e-12 * rms

    velocities = start_velocities(scene)
    positions, energies, _ = openmm_trajectory(scene, GenDPDEIntegrator.Isoenergetic, 20, velocities)
    integrator = scene.integrator(GenDPDEIntegrator.Isoenergetic)
    texts = scene.lammps(tmp_path, integrator, velocities, plugin=BIGBIG_PLUGIN)
    finish = "run 20\nwrite_dump all custom final.dump id x y z f_integrate modify format float %.17g sort id\n"
    run_lammps(tmp_path, texts.commands(*SECTIONS[:-1]) + finish, 2, lmp=bigbig)
    table = read_dump(tmp_path / "final.dump")
    assert np.max(np.abs(table[:, 1:4] - positions)) <= 1e-12
    assert np.max(np.abs(table[:, 4] / energies - 1)) <= 1e-12

    last = len(scene.positions)
    for atom_id, allowed in ((2**32, True), (2**32 + 1, False)):
        (tmp_path / "gendpde.data").write_text(with_atom_id(texts.data, last, atom_id))
        result = run_lammps(tmp_path, texts.commands(*SECTIONS[:-1]) + "run 2\n", 2, check=False, lmp=bigbig)
        if allowed:
            assert result.returncode == 0, result.stdout[-2000:]
        else:
            assert result.returncode != 0
            assert f"atom ID {atom_id} is not allowed" in result.stdout and "1 ... 4294967296" in result.stdout, \
                result.stdout[-2000:]


EXAMPLE = ROOT / "lammps" / "examples" / "in.gendpde"


def test_the_example_deck(lammps, tmp_path):
    """lammps/examples/in.gendpde, the package's example (the calibrated argon model in metal units, 864 particles
    made by create_atoms): at step 0 its potential energy is what OpenMM's Reference platform computes for the model
    file at LAMMPS's positions and box, to 1e-12 (so the deck's numbers are the model's); its IDs are reset in
    spatial order, so 100 steps on 1 and on 2 ranks print the same thermo output (to the rounding of the force sums,
    1e-9); and the conserved energy etotal + f_1 holds to 1e-6."""
    deck = EXAMPLE.read_text().replace("thermo_modify   format float %.10g", "thermo_modify   format float %.17g")
    assert "%.17g" in deck
    first = deck + "write_dump all custom start.dump id x y z modify format float %.17g sort id\n"
    run_lammps(tmp_path, f"variable plugin index {PLUGIN}\nvariable steps index 0\n" + first)
    start = thermo_table((tmp_path / "log.lammps").read_text())[0]
    lines = (tmp_path / "start.dump").read_text().splitlines()
    edge = [float(lines[5 + k].split()[1]) - float(lines[5 + k].split()[0]) for k in range(3)]
    table = read_dump(tmp_path / "start.dump")
    model = load_parameters(ROOT / "docs" / "figures" / "calibrated-argon-model.toml").liquid(len(table))
    box = [openmm.Vec3(*(0.1 * edge[k] if k == axis else 0 for k in range(3))) for axis in range(3)]
    context = openmm.Context(model.system, openmm.VerletIntegrator(0.001),
                             openmm.Platform.getPlatformByName("Reference"))
    context.setPeriodicBoxVectors(*box)
    context.setPositions(0.1 * table[:, 1:4])
    energy = context.getState(getEnergy=True).getPotentialEnergy()._value   # kJ/mol
    assert start["PotEng"] == pytest.approx(energy * ENERGY, rel=1e-12)

    runs = []
    for ranks in (1, 2):
        run_lammps(tmp_path, f"variable plugin index {PLUGIN}\nvariable steps index 100\n" + deck, ranks)
        runs.append(thermo_table((tmp_path / "log.lammps").read_text()))
    assert sorted(runs[0]) == sorted(runs[1]) == list(range(0, 101, 20))
    for step, row in runs[0].items():
        for column, value in row.items():
            assert runs[1][step][column] == pytest.approx(value, rel=1e-9, abs=1e-9), (step, column)
    assert runs[0][100]["v_conserved"] == pytest.approx(runs[0][0]["v_conserved"], rel=1e-6)
    assert runs[0][100]["Temp"] != pytest.approx(runs[0][0]["Temp"], rel=1e-3)   # (the run did move)


UNITTEST = ROOT / "lammps" / "unittest"
#: LAMMPS's force-style test inputs (in.metal, data.metal), from the source tree lammps/build.sh fetched.
FORCE_STYLE_INPUTS = next((ROOT / "build" / "lammps" / "source").glob("lammps-*/unittest/force-styles/tests"), None)
#: LAMMPS's metal units: pressure = virial x nktv2p / V (update.cpp).
NKTV2P = 1.6021765e6


def read_force_style_yaml(path):
    """A force-styles YAML file (LAMMPS's unittest/force-styles layout, as yaml_writer.cpp writes it): {key: text}
    with block values ("! |", "! |-", "! |2") joined by newlines."""
    entries, key = {}, None
    for line in pathlib.Path(path).read_text().splitlines():
        if line in ("---", "..."):
            continue
        if line.startswith(" ") and key is not None:
            entries[key].append(line.strip())
            continue
        key, _, value = line.partition(":")
        value = value.strip()
        entries[key] = [] if value.startswith("! |") else [value.strip('"').replace('! ""', "").replace('!', "")]
    return {k: "\n".join(v).strip() for k, v in entries.items()}


def fp_error(value, reference):
    """test_pair_style's EXPECT_FP_LE_WITH_EPS: the difference relative to the smaller magnitude (absolute at 0)."""
    value, reference = np.asarray(value, dtype=float), np.asarray(reference, dtype=float)
    smaller = np.minimum(np.abs(value), np.abs(reference))
    difference = np.abs(value - reference)
    return np.max(np.where(smaller == 0, difference, difference / np.where(smaller == 0, 1, smaller)))


def force_style_run(directory, config, script_tail, ranks=1, start=None):
    """Run LAMMPS as test_pair_style sets it up (newton_pair, input_dir, the YAML's pre_commands, its input file,
    pair_style, pair_coeff, post_commands), or from ``start`` (commands that replace all that, e.g. read_restart),
    then ``script_tail``; (thermo rows, forces by ID, virial from the pair's pressure tensor)."""
    setup = start or "\n".join([
        "variable newton_pair index on", f"variable input_dir index {FORCE_STYLE_INPUTS}",
        f"variable gendpde_plugin index {PLUGIN}", config["pre_commands"],
        f"include {FORCE_STYLE_INPUTS / config['input_file']}", f"pair_style {config['pair_style']}",
        *(f"pair_coeff {line}" for line in config["pair_coeff"].splitlines()),
        "pair_modify table 0", "pair_modify table/disp 0", config["post_commands"]])
    output = """
compute virial all pressure NULL pair
thermo_style custom step pe vol c_virial[1] c_virial[2] c_virial[3] c_virial[4] c_virial[5] c_virial[6]
thermo_modify format float %.17g
"""
    finish = "write_dump all custom forces.dump id fx fy fz modify format float %.17g sort id\n"
    run_lammps(directory, setup + output + script_tail + finish, ranks)
    rows = thermo_table((directory / "log.lammps").read_text())
    return rows, read_dump(directory / "forces.dump")[:, 1:4], pair_virial(rows[max(rows)])


def pair_virial(row):
    """The pair's virial (xx, yy, zz, xy, xz, yz; energy units, LAMMPS's pair->virial) of a thermo row with the
    pair's pressure tensor (compute pressure NULL pair) and the volume."""
    return [row[f"c_virial[{k}]"] * row["Volume"] / NKTV2P for k in range(1, 7)]


@pytest.mark.parametrize("name", sorted(path.name for path in UNITTEST.glob("manybody-pair-gendpde*.yaml")))
def test_the_force_styles_yaml(lammps, tmp_path, name):
    """lammps/unittest/NAME, a YAML test of LAMMPS's force-styles kind with OpenMM's Reference values
    (lammps/unittest/pair_gendpde_yaml.py), checked as LAMMPS's test_pair_style checks one: on LAMMPS's own test
    system (in.metal, data.metal) the energy, the pair virial and every force component at the start, after 4 steps
    of fix nve (forces to 5 epsilon, as the tester), after write_restart/read_restart and after write_data/read_data
    (in new processes: the plugin's styles do not survive LAMMPS's clear), each to the YAML's epsilon relative to the
    smaller of the two values; newton pair on (the style requires it); per-atom energies sum to the total. The YAML
    still holds what the script computes now."""
    if FORCE_STYLE_INPUTS is None:
        pytest.fail("LAMMPS's source tree (unittest/force-styles/tests) is missing: run lammps/build.sh")
    config = read_force_style_yaml(UNITTEST / name)
    epsilon = float(config["epsilon"])
    init_forces = np.array([[float(x) for x in line.split()[1:]] for line in config["init_forces"].splitlines()])
    run_forces = np.array([[float(x) for x in line.split()[1:]] for line in config["run_forces"].splitlines()])
    init_stress = [float(x) for x in config["init_stress"].split()]
    run_stress = [float(x) for x in config["run_stress"].split()]

    tail = """run 0 post no
write_restart yaml.restart
write_data yaml.data pair ii
write_dump all custom init.dump id fx fy fz modify format float %.17g sort id
fix 1 all nve
compute pe all pe/atom pair
compute sum all reduce sum c_pe
thermo_style custom step pe vol c_virial[1] c_virial[2] c_virial[3] c_virial[4] c_virial[5] c_virial[6] c_sum
thermo_modify format float %.17g
thermo 2
run 4 post no
"""
    rows, forces, virial = force_style_run(tmp_path, config, tail)
    assert fp_error(rows[0]["PotEng"], float(config["init_vdwl"])) <= epsilon
    assert fp_error(pair_virial(rows[0]), init_stress) <= epsilon
    assert fp_error(read_dump(tmp_path / "init.dump")[:, 1:4], init_forces) <= epsilon
    assert fp_error(rows[4]["PotEng"], float(config["run_vdwl"])) <= epsilon
    assert fp_error(forces, run_forces) <= 5 * epsilon
    assert fp_error(virial, run_stress) <= epsilon
    assert fp_error(rows[4]["c_sum"], rows[4]["PotEng"]) <= epsilon
    assert int(config["natoms"]) == len(forces)

    for start in ("plugin load {plugin}\nread_restart yaml.restart",
                  "variable newton_pair index on\n{pre}\nvariable pair_style index '{style}'\n"
                  "variable data_file index yaml.data\ninclude {inputs}/{input}"):
        setup = start.format(plugin=PLUGIN, pre=config["pre_commands"], style=config["pair_style"],
                             inputs=FORCE_STYLE_INPUTS, input=config["input_file"])
        if "read_restart" in setup:
            setup += f"\npair_style {config['pair_style']}"
        setup += "\n" + "\n".join(f"pair_coeff {line}" for line in config["pair_coeff"].splitlines())
        setup = f"variable gendpde_plugin index {PLUGIN}\n" + setup
        rows, forces, virial = force_style_run(tmp_path, config, "run 0 post no\n", start=setup)
        assert fp_error(rows[0]["PotEng"], float(config["init_vdwl"])) <= epsilon, setup
        assert fp_error(forces, init_forces) <= epsilon, setup
        assert fp_error(virial, init_stress) <= epsilon, setup

    # the YAML holds OpenMM's values as the script computes them now (not edited by hand, not stale)
    writer = load_file(UNITTEST / "pair_gendpde_yaml.py")
    case = writer.CASES[name]
    expected = writer.yaml_text(name, case, writer.reference_values(case, FORCE_STYLE_INPUTS / "data.metal"), "")
    written = (UNITTEST / name).read_text()
    assert [line for line in written.splitlines() if not line.startswith("date_generated")] == \
        [line for line in expected.splitlines() if not line.startswith("date_generated")]
