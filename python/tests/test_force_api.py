# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""GenDPDEForce from Python: an openmm.Force that feels like OpenMM's own classes."""

import copy
import gc
import pickle

import numpy as np
import openmm
import pytest
from conftest import GPU_PLATFORMS
from helpers import (
    DENSITY,
    MIDDLE_CUTOFF,
    TEMPERATURE,
    assert_rejected_without_change,
    energy_and_forces,
    lattice_liquid,
    make_context,
)
from openmm import app, unit

from openmmgendpde import GenDPDEForce
from openmmgendpde.physics import particleVolumeVB, taitEquationOfState

PRESSURE = unit.kilojoule_per_mole / unit.nanometer**3
NUMBER_DENSITY = unit.nanometer**-3


def test_is_an_openmm_force_with_quantity_getters():
    force = GenDPDEForce(1.2 * unit.nanometer)
    assert isinstance(force, openmm.Force)
    assert force.getCutoffDistance() == 1.2 * unit.nanometer
    assert force.getDensityEstimator() == GenDPDEForce.VB
    assert force.getNonbondedMethod() == GenDPDEForce.CutoffPeriodic and force.usesPeriodicBoundaryConditions()
    n0, pi0, bulk, gamma = force.getTaitParameters()
    # Defaults: liquid argon of docs/theory.md section 9 (u = 94.5476 kJ/mol, L = 0.61616 nm), written out here in SI
    # so that the C++ defaults are checked independently of openmmgendpde.models.argon.
    length = 0.61616
    pressure_unit = 1.5700e-19 * 6.02214076e23 / 1000 / length**3
    assert n0.value_in_unit(unit.nanometer**-3) == pytest.approx(1 / length**3, rel=1e-14)
    assert pi0.value_in_unit(PRESSURE) == pytest.approx((0.12711 - 0.011054) * pressure_unit, rel=1e-14)
    assert bulk.value_in_unit(PRESSURE) == pytest.approx(pressure_unit / 6, rel=1e-14)
    assert gamma == 6.0
    assert force.getReferenceDensity() == n0 and force.getBulkModulus() == bulk
    assert "GenDPDEForce" in repr(force) and "estimator=VB" in repr(force)
    for estimator, name in ((GenDPDEForce.VA, "VA"), (GenDPDEForce.VC, "VC")):
        force.setDensityEstimator(estimator)
        assert f"estimator={name}" in repr(force)


def test_arguments_accept_quantities_in_any_compatible_unit():
    force = GenDPDEForce(12.0 * unit.angstrom)
    assert force.getCutoffDistance().value_in_unit(unit.nanometer) == pytest.approx(1.2)
    force.setTaitParameters(4.0e27 / unit.meter**3, 80 * unit.megapascal,
                            1 * unit.kilocalorie_per_mole / unit.angstrom**3, 7.0)
    n0, pi0, bulk, gamma = force.getTaitParameters()
    assert n0.value_in_unit(unit.nanometer**-3) == pytest.approx(4.0)
    # A pressure in MPa is converted per mole: 1 MPa = 0.602214 kJ/mol/nm^3.
    assert pi0.value_in_unit(PRESSURE) == pytest.approx(80 * 0.602214076)
    assert bulk.value_in_unit(PRESSURE) == pytest.approx(4184.0)
    force.setCutoffDistance(0.9)                # plain numbers are OpenMM units
    assert force.getCutoffDistance() == 0.9 * unit.nanometer
    force.setCutoffScaling(scaling=1.41)        # keyword arguments work
    assert force.getCutoffScaling() == 1.41
    with pytest.raises(TypeError, match="setCutoffDistance"):
        force.setCutoffDistance(3 * unit.kelvin)


@pytest.mark.parametrize("call, fragments", [
    # Every setter, below and above its documented range (docs/force.md) and with non-finite values.
    (lambda f: GenDPDEForce(-1.0), ["cutoff distance", "-1", "[0.001, 10000] nm"]),
    (lambda f: GenDPDEForce(1e-320 * unit.nanometer), ["cutoff distance", "e-321"]),
    (lambda f: f.setCutoffDistance(float("nan")), ["cutoff distance", "nan"]),
    (lambda f: f.setCutoffDistance(3e4 * unit.nanometer), ["cutoff distance", "30000"]),
    (lambda f: f.setCutoffScaling(0.9), ["f_cut", "0.9", "[1, 100]"]),
    (lambda f: f.setCutoffScaling(1e100), ["f_cut", "1e+100"]),
    (lambda f: f.setTaitParameters(-1, 1, 1, 2), ["reference density", "-1"]),
    (lambda f: f.setTaitParameters(1e-300, 1, 1, 2), ["reference density", "1e-300", "[1e-12, 1e+12] nm^-3"]),
    (lambda f: f.setTaitParameters(1, float("inf"), 1, 2), ["reference pressure", "inf"]),
    (lambda f: f.setTaitParameters(1, 1e20 * unit.bar, 1, 2), ["reference pressure"]),
    (lambda f: f.setTaitParameters(1, 1, 0, 2), ["bulk modulus", "0"]),
    (lambda f: f.setTaitParameters(1, 1, 1e300, 2), ["bulk modulus", "1e+300"]),
    (lambda f: f.setTaitParameters(1, 1, 1, 0.5), ["gamma_T", "0.5", "(1, 100]"]),
    (lambda f: f.setTaitParameters(1, 1, 1, 1000), ["gamma_T", "1000"]),
    (lambda f: f.setDensityEstimator(5), ["estimator", "5"]),
    (lambda f: f.setNonbondedMethod(-1), ["method", "-1"]),
])
def test_bad_input_raises_openmm_exception_and_changes_nothing(call, fragments):
    assert_rejected_without_change(GenDPDEForce(1.0), call, fragments)


def test_cast_never_takes_ownership():
    """cast() of a Force that something else owns leaves the ownership where it was (no double free, no dangling
    object), and a cast of a deserialized Force keeps the owning original alive."""
    system, force, _ = lattice_liquid(3)
    generic = system.getForce(0)
    cast = GenDPDEForce.cast(generic)
    assert not cast.thisown and not generic.thisown
    assert GenDPDEForce.cast(force) is force
    loaded = GenDPDEForce.cast(openmm.XmlSerializer.deserialize(openmm.XmlSerializer.serialize(force)))
    gc.collect()
    assert loaded.getCutoffScaling() == force.getCutoffScaling()
    system.addForce(copy.copy(force))           # copies own their object, so System.addForce accepts them


def test_cast_and_isinstance_on_forces_from_a_system():
    system, force, _ = lattice_liquid(3)
    system.addForce(openmm.CMMotionRemover())
    generic = system.getForce(0)
    assert type(generic) is openmm.Force
    assert GenDPDEForce.isinstance(generic) and not GenDPDEForce.isinstance(system.getForce(1))
    cast = GenDPDEForce.cast(generic)
    assert cast.getCutoffScaling() == MIDDLE_CUTOFF.cutoff_scaling
    with pytest.raises(openmm.OpenMMException, match="not a GenDPDEForce"):
        GenDPDEForce.cast(system.getForce(1))


def test_copy_deepcopy_pickle_and_xml_round_trips():
    force = GenDPDEForce(1.1)
    force.setDensityEstimator(GenDPDEForce.VA)
    force.setCutoffScaling(1.33)
    force.setTaitParameters(4.5, 40.0, 70.0, 6.5)
    force.setForceGroup(4)
    for duplicate in [copy.copy(force), copy.deepcopy(force), pickle.loads(pickle.dumps(force))]:
        assert isinstance(duplicate, GenDPDEForce)
        assert duplicate.thisown  # the copy owns its C++ object, so it can go into a System and is freed once
        assert repr(duplicate) == repr(force)
        assert duplicate.getForceGroup() == 4
        duplicate.setCutoffScaling(2.0)         # independent of the original
        assert force.getCutoffScaling() == 1.33


def test_system_with_the_force_round_trips_through_xml(platform):
    system, force, positions = lattice_liquid(4)
    restored = openmm.XmlSerializer.deserialize(openmm.XmlSerializer.serialize(system))
    energy, forces = energy_and_forces(make_context(system, positions, platform))
    energy2, forces2 = energy_and_forces(make_context(restored, positions, platform))
    assert energy2 == energy
    assert np.array_equal(forces, forces2)


def test_observables_are_quantity_arrays_consistent_with_the_model(platform):
    system, force, positions = lattice_liquid(4)
    context = make_context(system, positions, platform)
    n0 = force.getPrimitiveDensities(context)
    volumes = force.getParticleVolumes(context)
    densities = force.getParticleDensities(context)
    pressures = force.getParticlePressures(context)
    for quantity, expected_unit in ((n0, NUMBER_DENSITY), (volumes, unit.nanometer**3), (densities, NUMBER_DENSITY),
                                    (pressures, PRESSURE)):
        # One Quantity holding a numpy array, like State.getPositions(asNumpy=True).
        assert unit.is_quantity(quantity) and quantity.unit == expected_unit
        array = quantity.value_in_unit(expected_unit)
        assert isinstance(array, np.ndarray) and array.dtype == np.float64 and array.shape == (64,)
    n0 = n0.value_in_unit(NUMBER_DENSITY)
    volumes = volumes.value_in_unit(unit.nanometer**3)
    densities = densities.value_in_unit(NUMBER_DENSITY)
    pressures = pressures.value_in_unit(PRESSURE)
    reduced_range = force.getCutoffDistance().value_in_unit(unit.nanometer) / force.getCutoffScaling()
    tait = [value.value_in_unit(value.unit) if unit.is_quantity(value) else value
            for value in force.getTaitParameters()]
    # The host platforms call the model's own function (the same bits); the GPU platforms evaluate it on the device,
    # where the compiler fuses multiply-adds (a few ulp).
    exact = platform.getName() not in GPU_PLATFORMS
    for i in range(64):
        expected_volume = particleVolumeVB(n0[i], reduced_range)[0]
        assert volumes[i] == (expected_volume if exact else pytest.approx(expected_volume, rel=1e-15))
        assert densities[i] == pytest.approx(1 / volumes[i], rel=1e-15)
        assert pressures[i] == pytest.approx(taitEquationOfState(densities[i], *tait)[0], rel=1e-14)
    energy, _ = energy_and_forces(context)
    assert energy == pytest.approx(sum(taitEquationOfState(n, *tait)[1] for n in densities), rel=1e-13)
    virial = force.getVirial(context)
    assert unit.is_quantity(virial) and virial.unit == unit.kilojoule_per_mole


def test_reference_and_cpu_agree():
    if "CPU" not in [openmm.Platform.getPlatform(i).getName() for i in range(openmm.Platform.getNumPlatforms())]:
        pytest.skip("no CPU platform")
    system, force, positions = lattice_liquid(5)
    energy, forces = energy_and_forces(make_context(system, positions, openmm.Platform.getPlatformByName("Reference")))
    energy2, forces2 = energy_and_forces(make_context(system, positions, openmm.Platform.getPlatformByName("CPU")))
    assert energy2 == pytest.approx(energy, rel=1e-12)
    assert np.allclose(forces2, forces, rtol=0, atol=1e-9 * np.abs(forces).max())


def test_update_parameters_in_context_from_python(platform):
    system, force, positions = lattice_liquid(4, estimator=GenDPDEForce.VA)
    context = make_context(system, positions, platform)
    force.setDensityEstimator(GenDPDEForce.VB)
    force.setCutoffScaling(1.41)
    force.updateParametersInContext(context)
    energy, _ = energy_and_forces(context)
    fresh, _ = energy_and_forces(make_context(system, positions, platform))
    assert energy == fresh


def test_runs_in_a_simulation_with_reporters(platform, tmp_path):
    system, force, positions = lattice_liquid(4, density=DENSITY)
    topology = app.Topology()
    chain = topology.addChain()
    for _ in range(system.getNumParticles()):
        topology.addAtom("AR", app.element.argon, topology.addResidue("AR", chain))
    topology.setPeriodicBoxVectors(system.getDefaultPeriodicBoxVectors())
    simulation = app.Simulation(topology, system, openmm.VerletIntegrator(0.005), platform)
    simulation.context.setPositions(positions)
    simulation.context.setVelocitiesToTemperature(TEMPERATURE)
    log = tmp_path / "log.csv"
    simulation.reporters.append(app.StateDataReporter(str(log), 5, step=True, potentialEnergy=True, temperature=True))
    simulation.reporters.append(app.DCDReporter(str(tmp_path / "traj.dcd"), 5))
    simulation.step(20)
    lines = log.read_text().splitlines()
    assert len(lines) == 5 and all(np.isfinite(float(v)) for v in lines[-1].split(",")[1:])


def test_nan_position_is_reported(platform):
    system, force, positions = lattice_liquid(4)
    positions[9, 2] = np.nan
    context = make_context(system, positions, platform)
    with pytest.raises(openmm.OpenMMException, match="particle 9|nan"):
        context.getState(getForces=True)


def test_isolated_particle_under_va_names_the_particle(platform):
    system, force, positions = lattice_liquid(4, estimator=GenDPDEForce.VA)
    force.setNonbondedMethod(GenDPDEForce.CutoffNonPeriodic)
    positions[13] = [100.0, 100.0, 100.0]
    context = make_context(system, positions, platform)
    with pytest.raises(openmm.OpenMMException, match="particle 13 has no neighbor"):
        context.getState(getEnergy=True)
