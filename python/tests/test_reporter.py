# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""GenDPDEReporter and the thermodynamic probe behind it: consistent values, what is reported when something cannot
be measured, validated input, and the pressure of every force (exact virials, numerical where needed)."""

import copy
import io
import math

import numpy as np
import openmm
import pytest
from helpers import TEMPERATURE, argon_integrator
from openmm import app, unit

from openmmgendpde import GenDPDEForce, GenDPDEIntegrator, GenDPDEReporter
from openmmgendpde.analysis.thermodynamics import ThermodynamicProbe, numerical_virial
from openmmgendpde.models.argon import ARGON_UNITS, liquid_argon
from openmmgendpde.units import BOLTZMANN

ENERGY = unit.kilojoule_per_mole
REFERENCE = "Reference"


def rows_of(stream):
    lines = stream.getvalue().splitlines()
    return lines[0], [[float(x) for x in line.split(",")] for line in lines[1:]]


def test_values_are_consistent():
    argon = liquid_argon(500, 1.6839, "VB", seed=5)
    simulation = argon.simulation()
    stream = io.StringIO()
    simulation.reporters.append(GenDPDEReporter(stream, 25, units=ARGON_UNITS))
    simulation.step(100)
    header, rows = rows_of(stream)
    assert header.startswith('#"Step"') and "Harmonic-mean theta*" in header
    assert [row[0] for row in rows] == [25, 50, 75, 100]
    for step, time, kinetic, mean_theta, harmonic, density, pressure, energy, drift in rows:
        assert time == pytest.approx(step * 0.01)
        assert harmonic <= mean_theta
        assert 0.9 < density < 1.1 and 0.005 < kinetic < 0.02 and 0 < pressure < 0.3
        assert abs(drift) < 1e-5
    assert rows[0][-1] == 0.0


@pytest.mark.parametrize("interval", [0, -3, 2.7, True, "10"])
def test_report_interval_is_validated(interval):
    with pytest.raises(openmm.OpenMMException, match=f"reportInterval = {interval!r}.*integer >= 1"):
        GenDPDEReporter(io.StringIO(), interval)


def test_what_cannot_be_measured_is_nan_not_an_error():
    """With another integrator there are no particle temperatures and no conserved energy; without a GenDPDEForce
    no density; without periodic boundaries no virial pressure. The simulation runs and the rest is reported."""
    argon = liquid_argon(500, 1.6839, "VB", seed=7)
    verlet = openmm.VerletIntegrator(argon.integrator.getStepSize())
    simulation = app.Simulation(argon.topology, argon.system, verlet, openmm.Platform.getPlatformByName(REFERENCE))
    simulation.context.setPositions(argon.positions)
    simulation.context.setVelocitiesToTemperature(TEMPERATURE, 1)
    stream = io.StringIO()
    simulation.reporters.append(GenDPDEReporter(stream, 5))
    simulation.step(10)
    _, rows = rows_of(stream)
    for _, _, kinetic, mean_theta, harmonic, density, pressure, energy, drift in rows:
        assert all(math.isnan(x) for x in (mean_theta, harmonic, energy, drift))
        assert kinetic > 0 and density > 0 and not math.isnan(pressure)

    system = openmm.System()   # no force at all: not periodic, no density
    for _ in range(8):
        system.addParticle(1.0)
    integrator = argon_integrator(0.001)
    integrator.setTemperature(100)
    integrator.setCutoffDistance(1.0)
    bare = app.Simulation(app.Topology(), system, integrator, openmm.Platform.getPlatformByName(REFERENCE))
    bare.context.setPositions([openmm.Vec3(0.3 * i, 0.1 * (i % 2), 0) for i in range(8)])
    stream = io.StringIO()
    bare.reporters.append(GenDPDEReporter(stream, 1))
    bare.step(2)
    _, rows = rows_of(stream)
    assert math.isnan(rows[-1][5]) and math.isnan(rows[-1][6])   # density, pressure
    assert rows[-1][3] > 0 and not math.isnan(rows[-1][7])   # mean theta, conserved energy


def test_drift_only_where_the_energy_is_conserved():
    argon = liquid_argon(500, 1.6839, "VB", seed=8, mode=GenDPDEIntegrator.Isothermal)
    simulation = argon.simulation()
    stream = io.StringIO()
    simulation.reporters.append(GenDPDEReporter(stream, 5))
    simulation.step(10)
    _, rows = rows_of(stream)
    assert all(math.isnan(row[-1]) for row in rows) and not math.isnan(rows[-1][7])


def test_kinetic_temperature_is_measured_in_the_centre_of_mass_frame():
    """Adding a uniform velocity to every particle changes K but not the temperature: expected value
    sum m |v - v_com|^2/((3N - 3) k_B), computed here from the velocities."""
    argon = liquid_argon(500, 1.6839, "VB", seed=9, mode=GenDPDEIntegrator.Conservative)
    simulation = argon.simulation()
    context = simulation.context
    velocities = context.getState(getVelocities=True).getVelocities(asNumpy=True).value_in_unit(
        unit.nanometer / unit.picosecond)
    context.setVelocities(velocities + np.array([3.0, -1.0, 0.5]))
    state = context.getState(getVelocities=True, getEnergy=True)
    sample = ThermodynamicProbe(argon.system).sample(state, context, argon.integrator)
    # The State's K uses on-step velocities v + (dt/2) F/m; so does the expected value.
    forces = context.getState(getForces=True).getForces(asNumpy=True).value_in_unit(ENERGY / unit.nanometer)
    mass = argon.system.getParticleMass(0).value_in_unit(unit.amu)
    dt = argon.integrator.getStepSize().value_in_unit(unit.picosecond)
    velocities = state.getVelocities(asNumpy=True).value_in_unit(unit.nanometer / unit.picosecond)
    on_step = velocities + 0.5 * dt * forces / mass
    internal = on_step - on_step.mean(axis=0)
    expected = mass * np.sum(internal**2) / ((3 * 500 - 3) * BOLTZMANN.value_in_unit(ENERGY / unit.kelvin))
    assert sample.kinetic_temperature.value_in_unit(unit.kelvin) == pytest.approx(expected, rel=1e-10)


def test_pressure_counts_every_force():
    """Two GenDPDEForces: W is the sum of their exact virials, P = (2K + W1 + W2)/(3V) (velocities with zero total
    momentum, so K is the internal kinetic energy; tolerance 1e-10, rounding). Both forces share group 0, so the
    numerical path is checked too: -dU/dlambda of group 0 equals W1 + W2 to O(h^2) (relative h^2 = 1e-10;
    tolerance 1e-7), and the Context's positions come back bit for bit."""
    argon = liquid_argon(500, 1.6839, "VB", seed=10)
    second = copy.deepcopy(argon.force)   # an owning copy, which System.addForce can take over
    second.setCutoffScaling(1.2)
    argon.system.addForce(second)
    simulation = argon.simulation()
    context = simulation.context
    simulation.step(5)
    velocities = context.getState(getVelocities=True).getVelocities(asNumpy=True).value_in_unit(
        unit.nanometer / unit.picosecond)
    context.setVelocities(velocities - velocities.mean(axis=0))
    state = context.getState(getVelocities=True, getEnergy=True, getPositions=True)
    kinetic = state.getKineticEnergy().value_in_unit(ENERGY)
    forces = [GenDPDEForce.cast(argon.system.getForce(i)) for i in range(2)]
    w1, w2 = (f.getVirial(context).value_in_unit(ENERGY) for f in forces)

    probe = ThermodynamicProbe(argon.system)
    assert probe.numerical_virial_groups == [] and len(probe.exact_virial_forces) == 2
    pressure = probe.sample(state, context, argon.integrator).pressure.value_in_unit(ENERGY / unit.nanometer**3)
    assert pressure == pytest.approx((2 * kinetic + w1 + w2) / (3 * argon.box_volume), rel=1e-10)

    numerical = numerical_virial(context, {0})
    assert numerical == pytest.approx(w1 + w2, rel=1e-7)
    after = context.getState(getPositions=True)
    assert np.array_equal(after.getPositions(asNumpy=True), state.getPositions(asNumpy=True))
    assert after.getPeriodicBoxVectors() == state.getPeriodicBoxVectors()

    # Another force in that group: the probe switches group 0 to the numerical virial.
    other = openmm.XmlSerializer.clone(argon.system)
    other.addForce(openmm.CustomBondForce("0"))
    assert ThermodynamicProbe(other).numerical_virial_groups == [0]
    # An external field in that group is left out of the virial (test_flows.py), not a reason to switch.
    field = openmm.XmlSerializer.clone(argon.system)
    field.addForce(openmm.CustomExternalForce("0"))
    probe = ThermodynamicProbe(field)
    assert probe.numerical_virial_groups == [] and len(probe.exact_virial_forces) == 2 and probe.external_fields == [2]


def _reporters():
    from openmmgendpde.analysis.profiles import ProfileReporter
    return {"GenDPDEReporter": GenDPDEReporter, "ProfileReporter": ProfileReporter}


@pytest.mark.parametrize("reporter, options, fragments", [
    ("GenDPDEReporter", {"file": None}, ["file = None is not allowed", "a path to a file"]),
    ("ProfileReporter", {"file": 3}, ["file = 3 is not allowed", "a path to a file"]),
    ("GenDPDEReporter", {"file": "missing/log.csv"}, ["missing/log.csv", "does not exist"]),
    ("GenDPDEReporter", {"units": "nonsense"}, ["units = 'nonsense' is not allowed", "ReducedUnits"]),
    ("GenDPDEReporter", {"separator": ""}, ["separator = '' is not allowed", "non-empty string"]),
    ("GenDPDEReporter", {"append": "yes"}, ["append = 'yes' is not allowed", "True or False"]),
    ("ProfileReporter", {"bins": 2.5}, ["bins = 2.5 is not allowed", "an integer from 1 to 100000"]),
    ("ProfileReporter", {"bins": 10**9}, ["bins = 1000000000 is not allowed", "exhaust the memory"]),
    ("ProfileReporter", {"bins": 0}, ["bins = 0 is not allowed"]),
    ("ProfileReporter", {"axis": "z"}, ["axis = 'z' is not allowed", "0, 1 or 2"]),
    ("ProfileReporter", {"axis": 1.0}, ["axis = 1.0 is not allowed"]),
    ("ProfileReporter", {"force": openmm.NonbondedForce()}, ["force = a NonbondedForce is not allowed",
                                                             "a GenDPDEForce"]),
])
def test_reporters_refuse_bad_arguments_when_made_before_creating_the_file(reporter, options, fragments, tmp_path,
                                                                           monkeypatch):
    """Every argument of a reporter is checked when it is made: OpenMMException naming the parameter, the value and
    what is allowed, and no file created (the file is the last thing made). bins is bounded (each report computes and
    writes every bin: 10^9 would exhaust the memory at the first report)."""
    monkeypatch.chdir(tmp_path)
    arguments = {"file": "out.csv", "reportInterval": 10, **options}
    with pytest.raises(openmm.OpenMMException) as error:
        _reporters()[reporter](**arguments)
    for fragment in [f"{reporter}: "] + fragments:
        assert fragment in str(error.value)
    assert list(tmp_path.iterdir()) == []


def test_profile_reporter_takes_a_gendpde_force_from_the_system():
    """A GenDPDEForce as System.getForce returns it (an openmm.Force) is taken, cast to GenDPDEForce."""
    from openmmgendpde.analysis.profiles import ProfileReporter
    argon = liquid_argon(500, 1.6839, "VB", seed=5)
    ProfileReporter(io.StringIO(), 10, force=argon.system.getForce(0))
