# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""ProfileReporter (openmmgendpde.analysis.profiles) against a direct computation of the same bins."""

import io

import numpy as np
import openmm
import pytest
from openmm import app, unit

from openmmgendpde import GenDPDEForce, GenDPDEIntegrator
from openmmgendpde.analysis.profiles import ProfileReporter, profile
from openmmgendpde.models.argon import liquid_argon
from openmmgendpde.models.fluid import WATER, coarse_grain, set_temperature_field
from openmmgendpde.units import BOLTZMANN


def direct_bins(positions, velocities, masses, length, bins, theta):
    """Particle by particle into slices of [0, length) along z, with plain loops."""
    kb = BOLTZMANN.value_in_unit(unit.kilojoule_per_mole / unit.kelvin)
    members = [[] for _ in range(bins)]
    for i, r in enumerate(positions):
        z = r[2] % length
        members[min(int(z / length * bins), bins - 1)].append(i)
    rows = []
    for b in range(bins):
        idx = members[b]
        total_mass = sum(masses[i] for i in idx)
        mean_v = [sum(masses[i] * velocities[i][k] for i in idx) / total_mass for k in range(3)]
        kinetic = sum(masses[i] * sum((velocities[i][k] - mean_v[k]) ** 2 for k in range(3)) for i in idx)
        harmonic_theta = len(idx) / sum(1 / theta[i] for i in idx)
        rows.append((len(idx), kinetic / (3 * (len(idx) - 1) * kb), harmonic_theta, mean_v))
    return rows


def test_profile_reporter_against_direct_bins():
    """A water model in a 3 x 3 x 8-cell box with a temperature step and a shear flow, run a few steps with a
    Simulation and the reporter; its last report against direct bins of the same State (counts exact, the rest
    to 1e-9 relative)."""
    parameters = coarse_grain(WATER, 4, neighbors=10)
    model = parameters.liquid(cells=(3, 3, 8))
    simulation = app.Simulation(model.topology, model.system, model.integrator,
                                openmm.Platform.getPlatformByName("Reference"))
    simulation.context.setPositions(model.positions)
    length = model.system.getDefaultPeriodicBoxVectors()[2][2].value_in_unit(unit.nanometer)
    simulation.context.setVelocitiesToTemperature(parameters.temperature, 3)
    state = simulation.context.getState(getVelocities=True)
    velocities = state.getVelocities(asNumpy=True).value_in_unit(unit.nanometer / unit.picosecond)
    velocities[:, 0] += 0.5 * np.sin(2 * np.pi * model.positions[:, 2] / length)
    simulation.context.setVelocities(velocities)
    set_temperature_field(model.integrator, model.positions, lambda r: 280.0 if r[2] < length / 2 else 320.0)
    out = io.StringIO()
    bins = 8
    simulation.reporters.append(ProfileReporter(out, 5, axis=2, bins=bins, force=model.force))
    simulation.step(5)
    rows = [line.split(",") for line in out.getvalue().strip().splitlines()[2:]]   # (the header, the units)
    assert len(rows) == bins and all(int(row[0]) == 5 for row in rows)
    state = simulation.context.getState(getPositions=True, getVelocities=True)
    positions = state.getPositions(asNumpy=True).value_in_unit(unit.nanometer)
    velocities = state.getVelocities(asNumpy=True).value_in_unit(unit.nanometer / unit.picosecond)
    masses = [model.system.getParticleMass(i).value_in_unit(unit.amu) for i in range(model.num_particles)]
    theta = model.integrator.getParticleTemperatures().value_in_unit(unit.kelvin)
    expected = direct_bins(positions, velocities, masses, length, bins, theta)
    volume = model.volume / bins
    for row, (count, kinetic, harmonic_theta, mean_v) in zip(rows, expected):
        assert int(row[4]) == count
        assert float(row[5]) == pytest.approx(count / volume, rel=1e-5)
        assert float(row[6]) == pytest.approx(harmonic_theta, rel=1e-5)
        assert float(row[7]) == pytest.approx(kinetic, rel=1e-5)
        assert [float(x) for x in row[8:11]] == pytest.approx(mean_v, rel=1e-5, abs=1e-6)
    # The slices' pressure tensors: the traces of their virial parts add up to GenDPDEForce.getVirial (the C++ sum
    # over pairs), once each slice's kinetic part (its direct kinetic temperature) is taken off. 1e-4: the CSV's six
    # digits of P, K and the kinetic temperature.
    kb = BOLTZMANN.value_in_unit(unit.kilojoule_per_mole / unit.kelvin)
    virial_trace = 0.0
    for row, (count, kinetic, harmonic_theta, mean_v) in zip(rows, expected):
        pxx, pyy, pzz = (float(x) for x in row[11:14])
        virial_trace += (pxx + pyy + pzz) * volume - 3 * (count - 1) * kb * kinetic
    scalar = model.force.getVirial(simulation.context).value_in_unit(unit.kilojoule_per_mole)
    assert virial_trace == pytest.approx(scalar, rel=1e-4)
    # The step of theta and the shear wave show up where they were put.
    assert float(rows[0][6]) < 300 < float(rows[-1][6])
    assert float(rows[1][8]) > 0.2 and float(rows[5][8]) < -0.2


def test_profile_refuses_bad_arguments():
    with pytest.raises(ValueError, match="axis = 3"):
        profile(np.zeros((2, 3)), np.zeros((2, 3)), np.ones(2), np.eye(3), axis=3)
    with pytest.raises(openmm.OpenMMException, match="ProfileReporter: axis = 3"):
        ProfileReporter(io.StringIO(), 1, axis=3)


@pytest.mark.parametrize("interval", [0, -3, 2.7, True, "10"])
def test_profile_reporter_refuses_a_report_interval_as_gendpde_reporter_does(interval):
    """The same check and error as GenDPDEReporter's (test_reporter.py): an integer >= 1, else OpenMMException."""
    with pytest.raises(openmm.OpenMMException, match=f"ProfileReporter: reportInterval = {interval!r}.*integer >= 1"):
        ProfileReporter(io.StringIO(), interval)


def test_profile_by_type_against_direct_counts():
    """Two types in alternating halves of the particles, with different temperatures: each type's density in a
    bin is its count over the bin volume, and its harmonic-mean theta the harmonic mean of its particles there
    (written out here); the per-type densities add up to the bin's."""
    rng = np.random.default_rng(4)
    positions = rng.uniform(0, 2.0, (200, 3))
    types = np.where(np.arange(200) % 2 == 0, 5, -1)
    theta = np.where(types == 5, 300.0, 100.0) * rng.uniform(0.8, 1.2, 200)
    box = np.diag([2.0, 2.0, 2.0])
    values = profile(positions, np.zeros((200, 3)), np.ones(200), box, axis=2, bins=4, temperatures=theta,
                     types=types)
    assert list(values["types"]) == [-1, 5]
    volume = 8.0 / 4
    for b in range(4):
        members = (positions[:, 2] * 2).astype(int) == b
        for k, t in enumerate([-1, 5]):
            chosen = members & (types == t)
            assert values["type_density"][b, k] == pytest.approx(chosen.sum() / volume)
            assert values["type_theta"][b, k] == pytest.approx(len(theta[chosen]) / np.sum(1 / theta[chosen]))
        assert values["type_density"][b].sum() == pytest.approx(values["density"][b])


def particles_in_a_box(force=None, integrator=None, positions=None):
    """A Simulation of particles of 1 amu in a periodic 2 nm cube: 50 at random positions unless ``positions`` are
    given, with ``force`` in its System if given, with ``integrator`` (by default a VerletIntegrator)."""
    system = openmm.System()
    system.setDefaultPeriodicBoxVectors(openmm.Vec3(2, 0, 0), openmm.Vec3(0, 2, 0), openmm.Vec3(0, 0, 2))
    if positions is None:
        positions = np.random.default_rng(5).uniform(0, 2.0, (50, 3))
    for _ in range(len(positions)):
        system.addParticle(1.0)
    if force is not None:
        system.addForce(force)
    topology = app.Topology()
    chain = topology.addChain()
    for _ in range(len(positions)):
        topology.addAtom("X", None, topology.addResidue("X", chain))
    simulation = app.Simulation(topology, system, integrator or openmm.VerletIntegrator(0.001),
                                openmm.Platform.getPlatformByName("Reference"))
    simulation.context.setPositions(positions)
    return simulation


def assert_type_columns(simulation, text, types):
    """The last four columns of the reporter's CSV ``text`` against the two types of ``types`` (one per particle):
    one density and one theta column per type, in ascending type order, each density the type's count in the
    slice (counted here particle by particle) over the slice volume (NaN theta without a GenDPDEIntegrator)."""
    low, high = sorted(set(types))
    header, units, *rows = [line.split(",") for line in text.strip().splitlines()]
    label = {t: f"type{t}" if t >= 0 else f"typeminus{-t}" for t in (low, high)}
    assert header[-4:] == [f"density_{label[low]}", f"theta_harmonic_{label[low]}", f"density_{label[high]}",
                           f"theta_harmonic_{label[high]}"]
    assert units[-4:] == [f" density_{label[low]}=nm^-3", f" theta_harmonic_{label[low]}=K",
                          f" density_{label[high]}=nm^-3", f" theta_harmonic_{label[high]}=K"]
    state = simulation.context.getState(getPositions=True)
    counts = {(b, t): 0 for b in range(2) for t in (low, high)}
    for r, t in zip(state.getPositions(asNumpy=True).value_in_unit(unit.nanometer), types):
        counts[(min(int((r[2] % 2.0) / 2.0 * 2), 1), t)] += 1
    slice_volume = 8.0 / 2
    assert len(rows) == 2
    for b, row in enumerate(rows):
        assert float(row[-4]) == pytest.approx(counts[(b, low)] / slice_volume, rel=1e-5)
        assert float(row[-2]) == pytest.approx(counts[(b, high)] / slice_volume, rel=1e-5)
        assert row[-3] == "nan" and row[-1] == "nan"
    assert sum(counts.values()) == 50 and min(counts.values()) > 0


def test_profile_reporter_writes_the_type_columns():
    """The reporter with types, one integer per particle."""
    simulation = particles_in_a_box()
    types = [3 if i < 20 else 1 for i in range(50)]
    out = io.StringIO()
    simulation.reporters.append(ProfileReporter(out, 1, axis=2, bins=2, types=types))
    simulation.step(1)
    assert_type_columns(simulation, out.getvalue(), types)


def test_profile_reporter_takes_the_types_of_the_force():
    """The types set on a GenDPDEForce (particles 0-19 type -3, the rest left at type 0): the reporter's default
    with ``force``, and the dict of force.getParticleTypes() as ``types``, both give the columns of types -3 and 0."""
    force = GenDPDEForce(0.6)
    for i in range(20):
        force.setParticleType(i, -3)
    simulation = particles_in_a_box(force)
    by_default, by_dict = io.StringIO(), io.StringIO()
    simulation.reporters.append(ProfileReporter(by_default, 1, axis=2, bins=2, force=force))
    simulation.reporters.append(ProfileReporter(by_dict, 1, axis=2, bins=2, types=force.getParticleTypes()))
    simulation.step(1)
    types = [-3 if i < 20 else 0 for i in range(50)]
    assert_type_columns(simulation, by_default.getvalue(), types)
    assert_type_columns(simulation, by_dict.getvalue(), types)


@pytest.mark.parametrize("types", [{0: 1.5}, {-1: 2}, {"a": 1}, [1.0, 2.0], [[1, 2]], ["a", "b"], 3],
                         ids=str)
def test_profile_reporter_refuses_bad_types_when_made(types):
    out = io.StringIO()
    with pytest.raises(openmm.OpenMMException, match="types = .* is not allowed; it must be one integer per particle"):
        ProfileReporter(out, 1, types=types)
    assert out.getvalue() == ""


@pytest.mark.parametrize("types, message", [
    ([1] * 49, "types has 49 entries, but the System has 50 particles"),
    ({50: 1}, "types names particle 50, but the System has 50 particles"),
])
def test_profile_reporter_refuses_types_that_do_not_fit_the_system(types, message):
    """A length or a particle that only the System can check: refused at the first report, before it writes."""
    simulation = particles_in_a_box()
    out = io.StringIO()
    simulation.reporters.append(ProfileReporter(out, 1, types=types))
    with pytest.raises(openmm.OpenMMException, match=message):
        simulation.step(1)
    assert out.getvalue() == ""


def test_profile_theta_is_the_harmonic_mean():
    """A slice holding one particle at 100 K and one at 300 K has theta_harmonic 1/((1/100 + 1/300)/2) = 150 K (the
    arithmetic mean would be 200 K), from profile() and in the reporter's CSV (a GenDPDEIntegrator in a Simulation,
    the report made before any step, so that the temperatures are the ones set)."""
    positions = [[0.1, 0.1, 0.1], [1.1, 1.1, 0.2]]
    values = profile(positions, np.zeros((2, 3)), np.ones(2), np.diag([2.0, 2.0, 2.0]), axis=2, bins=1,
                     temperatures=[100.0, 300.0])
    assert values["theta_harmonic"][0] == pytest.approx(150.0, rel=1e-14)
    integrator = GenDPDEIntegrator(0.001, 1.0, 1.0, 0.1)
    integrator.setCutoffDistance(0.5)
    integrator.setParticleTemperatures([100.0, 300.0])
    simulation = particles_in_a_box(integrator=integrator, positions=positions)
    out = io.StringIO()
    reporter = ProfileReporter(out, 1, axis=2, bins=1)
    reporter.report(simulation, simulation.context.getState(getPositions=True, getVelocities=True))
    header, units, row = out.getvalue().strip().splitlines()
    assert float(row.split(",")[header.split(",").index("theta_harmonic")]) == pytest.approx(150.0, rel=1e-6)


def test_profile_reporter_csv_reads_by_name_with_genfromtxt(tmp_path):
    """Liquid argon with types -2 and 3 on its force, with the pressure and type columns: numpy.genfromtxt(names=True,
    comments='#') finds every column (names written out here) and reads the units line as a comment; the rows of the
    last report are profile() of the final State, column by column (to the CSV's 6 digits), and in one slice the
    count, density and theta_harmonic are recomputed here particle by particle."""
    argon = liquid_argon(500, 1.6839, "VB", seed=12)
    types = np.where(np.arange(500) % 3 == 0, -2, 3)
    for i, t in enumerate(types):
        argon.force.setParticleType(i, int(t))
    simulation = argon.simulation()
    path = tmp_path / "profile.csv"
    bins = 4
    reporter = ProfileReporter(str(path), 5, axis=2, bins=bins, force=argon.force)
    simulation.reporters.append(reporter)
    simulation.step(10)   # (the reporter flushes every report)
    names = ["step", "time", "bin", "centre", "particles", "density", "theta_harmonic", "kinetic_temperature", "vx",
             "vy", "vz", "Pxx", "Pyy", "Pzz", "Pxy", "Pxz", "Pyz", "density_typeminus2", "theta_harmonic_typeminus2",
             "density_type3", "theta_harmonic_type3"]
    lines = path.read_text().splitlines()
    assert lines[0] == ",".join(names)
    assert lines[1].startswith("# units: step=1, time=ps, bin=1, centre=nm, particles=1, density=nm^-3, "
                               "theta_harmonic=K, kinetic_temperature=K, vx=nm/ps")
    table = np.genfromtxt(path, delimiter=",", names=True, comments="#")
    assert list(table.dtype.names) == names
    assert len(table) == 2 * bins and list(table["step"]) == [5] * bins + [10] * bins

    state = simulation.context.getState(getPositions=True, getVelocities=True, enforcePeriodicBox=False)
    positions = state.getPositions(asNumpy=True).value_in_unit(unit.nanometer)
    velocities = state.getVelocities(asNumpy=True).value_in_unit(unit.nanometer / unit.picosecond)
    box = state.getPeriodicBoxVectors(asNumpy=True).value_in_unit(unit.nanometer)
    masses = np.array([argon.system.getParticleMass(i).value_in_unit(unit.amu) for i in range(500)])
    theta = argon.integrator.getParticleTemperatures().value_in_unit(unit.kelvin)
    virials = argon.force.getParticleVirials(simulation.context).value_in_unit(unit.kilojoule_per_mole)
    expected = profile(positions, velocities, masses, box, 2, bins, theta, virials, types)
    last = table[bins:]
    columns = {"bin": np.arange(bins), "centre": expected["centre"], "particles": expected["count"],
               "density": expected["density"], "theta_harmonic": expected["theta_harmonic"],
               "kinetic_temperature": expected["kinetic_temperature"], "vx": expected["velocity"][:, 0],
               "vy": expected["velocity"][:, 1], "vz": expected["velocity"][:, 2],
               "density_typeminus2": expected["type_density"][:, 0], "theta_harmonic_typeminus2":
               expected["type_theta"][:, 0], "density_type3": expected["type_density"][:, 1],
               "theta_harmonic_type3": expected["type_theta"][:, 1]}
    for k, (a, b) in enumerate([(0, 0), (1, 1), (2, 2), (0, 1), (0, 2), (1, 2)]):
        columns[names[11 + k]] = expected["pressure"][:, a, b]
    for name, values in columns.items():
        assert last[name] == pytest.approx(values, rel=1e-5, abs=1e-6), name
    assert last["time"] == pytest.approx([state.getTime().value_in_unit(unit.picosecond)] * bins, rel=1e-5)
    # Slice 1 by hand: which particles lie in it, their count, density and harmonic-mean theta.
    edge = box[2][2]
    members = [i for i in range(500) if min(int((positions[i][2] % edge) / edge * bins), bins - 1) == 1]
    assert last["particles"][1] == len(members)
    assert last["density"][1] == pytest.approx(len(members) / (edge**3 / bins), rel=1e-5)
    assert last["theta_harmonic"][1] == pytest.approx(len(members) / sum(1 / theta[i] for i in members), rel=1e-5)
