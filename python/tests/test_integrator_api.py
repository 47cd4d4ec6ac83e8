# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""GenDPDEIntegrator from Python: an openmm.Integrator that works with Context, Simulation, reporters,
XmlSerializer, checkpoints and States."""

import copy
import pickle

import numpy as np
import openmm
import pytest
from helpers import MIDDLE_CUTOFF, TEMPERATURE, argon_integrator, assert_rejected_without_change
from openmm import app, unit
from scipy import stats

from openmmgendpde import GenDPDEForce, GenDPDEIntegrator
from openmmgendpde.models.argon import ARGON_STATE, ARGON_UNITS, liquid_argon

ENERGY = unit.kilojoule_per_mole


def make_integrator():
    return argon_integrator(0.009 * unit.picosecond)


def test_is_an_openmm_integrator_with_quantity_getters():
    integrator = make_integrator()
    assert isinstance(integrator, openmm.Integrator)
    assert integrator.getStepSize() == 0.009 * unit.picosecond
    assert integrator.getFriction() == ARGON_UNITS.to_openmm(MIDDLE_CUTOFF.friction, "friction")
    assert integrator.getHeatCapacity().value_in_unit(ENERGY / unit.kelvin) == \
        ARGON_UNITS.to_openmm(ARGON_STATE.heat_capacity, "heat_capacity").value_in_unit(ENERGY / unit.kelvin)
    assert integrator.getMode() == GenDPDEIntegrator.Isoenergetic
    assert integrator.getCutoffDistance() == 0 * unit.nanometer
    integrator.setTemperature(TEMPERATURE)
    assert integrator.getTemperature() == TEMPERATURE * unit.kelvin
    integrator.setStepSize(5 * unit.femtosecond)
    assert integrator.getStepSize().value_in_unit(unit.picosecond) == pytest.approx(0.005)
    integrator.setHeatConduction(heatConduction=0.0)
    assert "Isoenergetic" in repr(integrator)


@pytest.mark.parametrize("call, fragments", [
    # Every setter, below and above its documented range (docs/integrator.md) and with non-finite values.
    (lambda i: GenDPDEIntegrator(-0.001, 1, 1, 1), ["step size", "-0.001", "(0, 1000] ps"]),
    (lambda i: i.setStepSize(2 * unit.nanosecond), ["step size", "2000"]),
    (lambda i: i.setFriction(-1.0), ["friction", "-1"]),
    (lambda i: i.setFriction(1e300), ["friction", "1e+300", "[0, 1e+12] amu/ps"]),
    (lambda i: i.setHeatConduction(float("nan")), ["heat conduction", "nan"]),
    (lambda i: i.setHeatCapacity(0.0), ["heat capacity", "[1e-20, 1e+20] kJ/(mol K)"]),
    (lambda i: i.setTemperature(-5 * unit.kelvin), ["temperature", "-5"]),
    (lambda i: i.setTemperature(1e-200), ["temperature", "1e-200", "[1e-50, 1e+50] K"]),
    (lambda i: i.setParticleTemperatures([300.0, 0.0]), ["temperature of particle 1", "0"]),
    (lambda i: i.setParticleTemperatures([300.0, 1e153]), ["temperature of particle 1", "1e+153"]),
    (lambda i: i.setParticleTemperatures([]), ["number of particle temperatures", "= 0"]),
    (lambda i: i.setInternalEnergies([30.0, 0.0]), ["internal energy of particle 1", "= 0 kJ/mol",
                                                    "[1e-100, 1e+100] kJ/mol"]),
    (lambda i: i.setInternalEnergies([30.0, float("nan")]), ["internal energy of particle 1", "nan"]),
    (lambda i: i.setInternalEnergies([]), ["number of internal energies", "= 0"]),
    (lambda i: i.setCutoffDistance(-1.0), ["cutoff", "-1"]),
    (lambda i: i.setMode(7), ["mode", "7"]),
    (lambda i: i.getConservedEnergy(), ["not bound to a Context"]),
    (lambda i: i.setInternalEnergiesToTemperature(300, 1), ["needs a Context"]),
    (lambda i: i.getParticleTemperatures(), ["none are set"]),
])
def test_bad_input_raises_openmm_exception(call, fragments):
    assert_rejected_without_change(make_integrator(), call, fragments)


def test_copy_pickle_and_xml_round_trips():
    integrator = make_integrator()
    integrator.setMode(GenDPDEIntegrator.Isothermal)
    integrator.setTemperature(300)
    integrator.setRandomNumberSeed(17)
    integrator.setCutoffDistance(1.1)
    xml = openmm.XmlSerializer.serialize(integrator)
    for duplicate in [copy.copy(integrator), copy.deepcopy(integrator), pickle.loads(pickle.dumps(integrator))]:
        assert isinstance(duplicate, GenDPDEIntegrator) and duplicate.thisown
        assert openmm.XmlSerializer.serialize(duplicate) == xml
    assert openmm.XmlSerializer.serialize(GenDPDEIntegrator.cast(openmm.XmlSerializer.deserialize(xml))) == xml


def test_temperatures_before_and_after_the_context_exists():
    argon = liquid_argon(500, 1.6839, "VB")
    integrator = argon.integrator
    temperatures = np.linspace(100, 150, 500)
    integrator.setParticleTemperatures(temperatures * unit.kelvin)
    assert np.array_equal(integrator.getParticleTemperatures().value_in_unit(unit.kelvin), temperatures)
    context = openmm.Context(argon.system, integrator, openmm.Platform.getPlatformByName("Reference"))
    found = integrator.getParticleTemperatures()
    assert unit.is_quantity(found) and found.unit == unit.kelvin
    found = found.value_in_unit(unit.kelvin)
    assert isinstance(found, np.ndarray) and np.allclose(found, temperatures, rtol=1e-15)
    heat_capacity = integrator.getHeatCapacity().value_in_unit(ENERGY / unit.kelvin)
    energies = integrator.getInternalEnergies()
    assert unit.is_quantity(energies) and energies.unit == ENERGY
    assert np.allclose(energies.value_in_unit(ENERGY), heat_capacity * temperatures, rtol=1e-15)
    # The bath temperature is not the particles' state: setting it leaves every theta_i as it is.
    integrator.setTemperature(200)
    assert np.allclose(integrator.getParticleTemperatures().value_in_unit(unit.kelvin), temperatures, rtol=1e-15)
    integrator.setParticleTemperatures([200.0] * 500)
    assert np.all(integrator.getParticleTemperatures().value_in_unit(unit.kelvin) == 200.0)
    assert GenDPDEIntegrator.isinstance(context.getIntegrator())
    assert GenDPDEIntegrator.cast(context.getIntegrator()) is integrator   # the user's object, still owning it
    assert integrator.thisown and integrator.getSeedInUse() != 0
    with pytest.raises(openmm.OpenMMException, match="number of particle temperatures"):
        integrator.setParticleTemperatures([300.0] * 3)


def test_kinetic_and_conserved_energy_use_on_step_velocities():
    """K = sum m |v + (dt/2) F/m|^2 / 2 (velocities are half a step behind), and the conserved energy is
    K + U + sum eps, both recomputed here from the State."""
    argon = liquid_argon(500, 1.6839, "VB", seed=4)
    simulation = argon.simulation()
    argon.integrator.step(20)
    state = simulation.context.getState(getVelocities=True, getForces=True, getEnergy=True)
    dt = argon.integrator.getStepSize().value_in_unit(unit.picosecond)
    mass = ARGON_UNITS.unit("mass").value_in_unit(unit.amu)
    v = state.getVelocities(asNumpy=True).value_in_unit(unit.nanometer / unit.picosecond)
    f = state.getForces(asNumpy=True).value_in_unit(ENERGY / unit.nanometer)
    kinetic = 0.5 * mass * np.sum((v + 0.5 * dt * f / mass) ** 2)
    assert state.getKineticEnergy().value_in_unit(ENERGY) == pytest.approx(kinetic, rel=1e-10)
    internal = argon.integrator.getInternalEnergies().value_in_unit(ENERGY).sum()
    expected = kinetic + state.getPotentialEnergy().value_in_unit(ENERGY) + internal
    assert argon.integrator.getConservedEnergy().value_in_unit(ENERGY) == pytest.approx(expected, rel=1e-12)


def test_simulation_with_reporters_save_state_and_checkpoints(tmp_path):
    """Simulation, StateDataReporter, DCDReporter, CheckpointReporter; a run continued from saveState or from a
    checkpoint reproduces the uninterrupted run bit for bit, internal energies included."""
    argon = liquid_argon(500, 1.6839, "VB", seed=21)
    simulation = argon.simulation()
    log = tmp_path / "log.csv"
    simulation.reporters.append(app.StateDataReporter(str(log), 10, step=True, temperature=True, totalEnergy=True))
    simulation.reporters.append(app.DCDReporter(str(tmp_path / "trajectory.dcd"), 10))
    simulation.reporters.append(app.CheckpointReporter(str(tmp_path / "checkpoint.chk"), 30))
    simulation.step(30)
    simulation.saveState(str(tmp_path / "state.xml"))
    simulation.saveCheckpoint(str(tmp_path / "mine.chk"))
    simulation.step(40)
    final = simulation.context.getState(getPositions=True, getVelocities=True)
    energies = argon.integrator.getInternalEnergies().value_in_unit(ENERGY)
    assert len(log.read_text().splitlines()) == 8

    for restore in ("loadState", "loadCheckpoint"):
        other = liquid_argon(500, 1.6839, "VB", seed=99)       # another seed: the saved seed must win
        other.integrator.setTemperature(50)                     # other temperatures: the saved ones must win
        resumed = other.simulation()
        if restore == "loadState":
            resumed.loadState(str(tmp_path / "state.xml"))
        else:
            resumed.loadCheckpoint(str(tmp_path / "mine.chk"))
        resumed.step(40)
        state = resumed.context.getState(getPositions=True, getVelocities=True)
        assert np.array_equal(state.getPositions(asNumpy=True), final.getPositions(asNumpy=True)), restore
        assert np.array_equal(state.getVelocities(asNumpy=True), final.getVelocities(asNumpy=True)), restore
        assert np.array_equal(other.integrator.getInternalEnergies().value_in_unit(ENERGY), energies), restore


def test_force_group_not_integrated_gives_own_pair_list():
    """The integrator takes pairs from the GenDPDEForce only when that force is integrated; otherwise it finds its
    own, and the step still works (here: the force is in group 1, only group 0 is integrated)."""
    argon = liquid_argon(500, 1.6839, "VB", seed=6)
    argon.force.setForceGroup(1)
    argon.integrator.setIntegrationForceGroups({0})
    _simulation = argon.simulation()   # (kept alive: the Context the integrator is bound to)
    argon.integrator.step(10)
    assert np.all(np.isfinite(argon.integrator.getInternalEnergies().value_in_unit(ENERGY)))
    assert GenDPDEForce.isinstance(argon.system.getForce(0))


def test_internal_energies_drawn_at_a_temperature_follow_the_gamma_law():
    """setInternalEnergiesToTemperature(T) draws eps_i from Gamma(C_V/k_B + 1, k_B T). For 4000 draws with shape
    a = 13.51: the harmonic mean of theta_i estimates T with relative standard error 1/sqrt((a - 2) N) = 0.47%, the
    mean estimates T (1 + k_B/C_V) with 1/sqrt(a N) = 0.43%; tolerance 4 standard errors each; KS test p > 0.001."""
    argon = liquid_argon(4000, 1.6839, "VB")
    simulation = argon.simulation()   # noqa: F841  (the Context must stay alive)
    t = TEMPERATURE
    argon.integrator.setInternalEnergiesToTemperature(t * unit.kelvin, 3)
    theta = argon.integrator.getParticleTemperatures().value_in_unit(unit.kelvin)
    c = ARGON_STATE.heat_capacity   # C_V/k_B
    assert abs(1 / np.mean(1 / theta) / t - 1) < 4 / np.sqrt((c + 1 - 2) * 4000)
    assert abs(np.mean(theta) / (t * (1 + 1 / c)) - 1) < 4 / np.sqrt((c + 1) * 4000)
    assert stats.kstest(theta * c / t, stats.gamma(c + 1).cdf).pvalue > 1e-3


def argon_with_two_heat_capacities(seed):
    """liquid_argon(500) with the odd particles of type 1 on the integrator, C_V = 0.125 kJ/(mol K) for type 0 and
    0.25 for type 1 (returned as an array, one per particle), in a Simulation after 3 steps."""
    argon = liquid_argon(500, 1.6839, "VB", seed=seed)
    argon.integrator.setHeatCapacity(0.125)
    argon.integrator.addTypeHeatCapacity(1, 0.25)
    for i in range(1, 500, 2):
        argon.integrator.setParticleType(i, 1)
    simulation = argon.simulation()
    argon.integrator.step(3)
    return argon, simulation, np.where(np.arange(500) % 2 == 1, 0.25, 0.125)


def test_set_internal_energies_is_set_particle_temperatures_in_energies():
    """setInternalEnergies(eps), eps_i = C_V(type of i) theta_i computed here, leaves the Context in the state that
    setParticleTemperatures(theta) leaves it in: the same energies (exactly: the same product), then the same
    trajectory bit for bit (Reference). The energies set come back exactly, as a Quantity in kJ/mol."""
    a, simulation_a, capacity = argon_with_two_heat_capacities(8)
    b, simulation_b, _ = argon_with_two_heat_capacities(8)
    theta = TEMPERATURE * (0.8 + 0.4 * np.random.default_rng(2).random(500))
    energies = capacity * theta
    a.integrator.setParticleTemperatures(theta)
    b.integrator.setInternalEnergies(energies * ENERGY)
    found = b.integrator.getInternalEnergies()
    assert unit.is_quantity(found) and found.unit == ENERGY
    assert np.array_equal(found.value_in_unit(ENERGY), energies)
    assert np.array_equal(a.integrator.getInternalEnergies().value_in_unit(ENERGY), energies)
    assert np.allclose(b.integrator.getParticleTemperatures().value_in_unit(unit.kelvin), theta, rtol=1e-15, atol=0)
    a.integrator.step(20)
    b.integrator.step(20)
    state_a = simulation_a.context.getState(getPositions=True, getVelocities=True)
    state_b = simulation_b.context.getState(getPositions=True, getVelocities=True)
    assert np.array_equal(state_a.getPositions(asNumpy=True), state_b.getPositions(asNumpy=True))
    assert np.array_equal(state_a.getVelocities(asNumpy=True), state_b.getVelocities(asNumpy=True))
    assert np.array_equal(a.integrator.getInternalEnergies().value_in_unit(ENERGY),
                          b.integrator.getInternalEnergies().value_in_unit(ENERGY))


def test_set_internal_energies_before_the_context_in_units_and_through_checkpoints():
    """Before a Context the energies set are the initial condition (through copy/pickle too); any energy unit is
    converted; a checkpoint taken after setInternalEnergies restores those energies exactly."""
    argon = liquid_argon(500, 1.6839, "VB", seed=9)
    energies = np.linspace(10.0, 20.0, 500) / 3   # kJ/mol
    argon.integrator.setInternalEnergies(energies * ENERGY)
    assert np.array_equal(argon.integrator.getInternalEnergies().value_in_unit(ENERGY), energies)
    assert np.array_equal(pickle.loads(pickle.dumps(argon.integrator)).getInternalEnergies().value_in_unit(ENERGY),
                          energies)
    simulation = argon.simulation()
    assert np.array_equal(argon.integrator.getInternalEnergies().value_in_unit(ENERGY), energies)
    argon.integrator.step(2)
    argon.integrator.setInternalEnergies(list(energies))   # plain numbers: kJ/mol
    checkpoint = simulation.context.createCheckpoint()
    argon.integrator.setInternalEnergies(energies / 4.184 * unit.kilocalorie_per_mole)
    assert np.allclose(argon.integrator.getInternalEnergies().value_in_unit(ENERGY), energies, rtol=1e-14, atol=0)
    argon.integrator.setInternalEnergies(2 * energies)
    simulation.context.loadCheckpoint(checkpoint)
    assert np.array_equal(argon.integrator.getInternalEnergies().value_in_unit(ENERGY), energies)
    with pytest.raises(TypeError, match="setInternalEnergies"):
        argon.integrator.setInternalEnergies(energies * unit.kelvin)


@pytest.mark.parametrize("last, fragments", [
    (0.0, ["internal energy of particle 499", "= 0 kJ/mol", "[1e-100, 1e+100] kJ/mol"]),
    (-2.5, ["internal energy of particle 499", "= -2.5 kJ/mol"]),
    (float("nan"), ["internal energy of particle 499", "nan"]),
    (float("inf"), ["internal energy of particle 499", "inf"]),
    (None, ["number of internal energies", "= 499", "the number of particles in the System, 500"]),
])
def test_set_internal_energies_refuses_bad_input_in_a_context_without_change(last, fragments):
    """A bad value (the last particle's) or a list one short is refused naming what is wrong; the Context's
    internal energies stay as they were."""
    argon = liquid_argon(500, 1.6839, "VB", seed=10)
    simulation = argon.simulation()   # noqa: F841  (the Context must stay alive)
    argon.integrator.step(2)
    before = argon.integrator.getInternalEnergies().value_in_unit(ENERGY)
    bad = list(2 * before[:-1]) + ([] if last is None else [last])
    with pytest.raises(openmm.OpenMMException) as error:
        argon.integrator.setInternalEnergies(bad)
    for fragment in fragments:
        assert fragment in str(error.value)
    assert np.array_equal(argon.integrator.getInternalEnergies().value_in_unit(ENERGY), before)
