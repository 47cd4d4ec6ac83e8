# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""Particle types from Python: per-particle types, per-type Tait parameters (GenDPDEForce), per-type heat capacities
and per-type-pair friction and heat conduction (GenDPDEIntegrator), with units, copies and error messages."""

import copy
import pickle

import numpy as np
import openmm
import pytest
from helpers import assert_rejected_without_change, lattice_liquid, make_context
from openmm import unit

from openmmgendpde import GenDPDEForce, GenDPDEIntegrator

PRESSURE = unit.kilojoule_per_mole / unit.nanometer**3
NUMBER_DENSITY = unit.nanometer**-3
FRICTION = unit.amu / unit.picosecond
HEAT_CONDUCTION = unit.kilojoule_per_mole * unit.kelvin / unit.picosecond
HEAT_CAPACITY = unit.kilojoule_per_mole / unit.kelvin
#: 1 MPa per particle is 0.602214076 kJ/mol/nm^3.
MEGAPASCAL = 0.602214076


def make_integrator():
    return GenDPDEIntegrator(0.005, 1.0, 2.0, 0.1)


def typed_force():
    """A force with particle types and two type-parameter entries (in OpenMM units)."""
    force = GenDPDEForce(0.95)
    for particle, particle_type in [(0, 3), (2, -1), (7, 3), (100, 42)]:
        force.setParticleType(particle, particle_type)
    force.addTypeParameters(3, 4.0, 50.0, 70.0, 6.5)
    force.addTypeParameters(-1, 5.0, 10.0, 20.0, 3.0)
    return force


def typed_integrator():
    """An integrator with particle types, two heat capacities and two type pairs (in OpenMM units)."""
    integrator = make_integrator()
    for particle, particle_type in [(1, 5), (4, -2), (9, 5)]:
        integrator.setParticleType(particle, particle_type)
    integrator.addTypeHeatCapacity(5, 0.3)
    integrator.addTypeHeatCapacity(-2, 0.05)
    integrator.addTypePair(5, -2, 3.0, 4.0)
    integrator.addTypePair(0, 5, 0.5, 0.25)
    return integrator


def test_particle_types_are_a_dict_of_plain_ints():
    for obj in (GenDPDEForce(0.95), make_integrator()):
        assert obj.getParticleTypes() == {}
        obj.setParticleType(10, -7)
        obj.setParticleType(3, 1000)
        obj.setParticleType(0, 0)
        obj.setParticleType(3, 2)               # a second call replaces the type
        types = obj.getParticleTypes()
        assert type(types) is dict
        assert types == {0: 0, 3: 2, 10: -7}
        assert all(type(key) is int and type(value) is int for key, value in types.items())
        assert obj.getParticleType(10) == -7 and obj.getParticleType(3) == 2
        assert obj.getParticleType(5) == 0      # never set: type 0
        types[4] = 9                            # a copy: changing it changes nothing
        assert obj.getParticleTypes() == {0: 0, 3: 2, 10: -7}


def test_type_parameters_round_trip_with_units():
    force = GenDPDEForce(0.95)
    assert force.getNumTypeParameters() == 0
    assert force.addTypeParameters(3, 4.0e27 / unit.meter**3, 100 * unit.bar, 80 * unit.megapascal, 7.0) == 0
    assert force.addTypeParameters(-4, 5.5, 12.5, 30.0, 2.5) == 1   # plain numbers are OpenMM units
    assert force.getNumTypeParameters() == 2
    entry_type, n0, pi0, bulk, gamma = force.getTypeParameters(0)
    assert type(entry_type) is int and entry_type == 3
    assert n0.unit == NUMBER_DENSITY and n0.value_in_unit(NUMBER_DENSITY) == pytest.approx(4.0, rel=1e-14)
    # Pressures in bar or MPa come back per mole, in kJ/mol/nm^3: 100 bar = 10 MPa.
    assert pi0.unit == PRESSURE and pi0.value_in_unit(PRESSURE) == pytest.approx(10 * MEGAPASCAL, rel=1e-14)
    assert bulk.unit == PRESSURE and bulk.value_in_unit(PRESSURE) == pytest.approx(80 * MEGAPASCAL, rel=1e-14)
    assert type(gamma) is float and gamma == 7.0
    assert force.getTypeParameters(1) == [-4, 5.5 * NUMBER_DENSITY, 12.5 * PRESSURE, 30.0 * PRESSURE, 2.5]
    # Keyword arguments, and pressures in other energy and length units.
    force.setTypeParameters(1, type=8, referenceDensity=6.0 / unit.angstrom**3 / 1000,
                            referencePressure=1 * unit.kilocalorie_per_mole / unit.angstrom**3,
                            bulkModulus=2 * unit.megapascal, exponent=4.0)
    entry_type, n0, pi0, bulk, gamma = force.getTypeParameters(1)
    assert (entry_type, gamma) == (8, 4.0)
    assert n0.value_in_unit(NUMBER_DENSITY) == pytest.approx(6.0, rel=1e-14)
    assert pi0.value_in_unit(PRESSURE) == pytest.approx(4184.0, rel=1e-14)
    assert bulk.value_in_unit(PRESSURE) == pytest.approx(2 * MEGAPASCAL, rel=1e-14)
    assert force.getTypeParameters(0)[0] == 3   # the other entry is untouched
    with pytest.raises(TypeError, match=r"addTypeParameters\(referencePressure\)"):
        force.addTypeParameters(9, 4.0, 3 * unit.kelvin, 1.0, 2.0)


def test_type_heat_capacities_round_trip_with_units():
    integrator = make_integrator()
    assert integrator.getNumTypeHeatCapacities() == 0
    assert integrator.addTypeHeatCapacity(2, 1 * unit.kilocalorie_per_mole / unit.kelvin) == 0
    assert integrator.addTypeHeatCapacity(-3, 0.25) == 1
    assert integrator.getNumTypeHeatCapacities() == 2
    entry_type, capacity = integrator.getTypeHeatCapacity(0)
    assert type(entry_type) is int and entry_type == 2
    assert capacity.unit == HEAT_CAPACITY and capacity.value_in_unit(HEAT_CAPACITY) == pytest.approx(4.184, rel=1e-14)
    assert integrator.getTypeHeatCapacity(1) == [-3, 0.25 * HEAT_CAPACITY]
    integrator.setTypeHeatCapacity(1, 6, 500 * unit.joule / unit.mole / unit.kelvin)
    entry_type, capacity = integrator.getTypeHeatCapacity(1)
    assert entry_type == 6 and capacity.value_in_unit(HEAT_CAPACITY) == pytest.approx(0.5, rel=1e-14)
    with pytest.raises(TypeError, match=r"addTypeHeatCapacity\(heatCapacity\)"):
        integrator.addTypeHeatCapacity(7, 1 * unit.kelvin)


def test_type_pairs_round_trip_with_units():
    integrator = make_integrator()
    assert integrator.getNumTypePairs() == 0
    assert integrator.addTypePair(1, 2, 0.5 * unit.amu / unit.femtosecond,
                                  1 * unit.kilocalorie_per_mole * unit.kelvin / unit.picosecond) == 0
    assert integrator.addTypePair(-1, -1, 3.0, 4.0) == 1
    assert integrator.getNumTypePairs() == 2
    type1, type2, friction, conduction = integrator.getTypePairParameters(0)
    assert type(type1) is int and type(type2) is int and (type1, type2) == (1, 2)
    assert friction.unit == FRICTION and friction.value_in_unit(FRICTION) == pytest.approx(500.0, rel=1e-14)
    assert conduction.unit == HEAT_CONDUCTION
    assert conduction.value_in_unit(HEAT_CONDUCTION) == pytest.approx(4.184, rel=1e-14)
    assert integrator.getTypePairParameters(1) == [-1, -1, 3.0 * FRICTION, 4.0 * HEAT_CONDUCTION]
    integrator.setTypePairParameters(1, type1=0, type2=7, friction=2 * unit.amu / unit.nanosecond,
                                     heatConduction=5 * unit.kilojoule_per_mole * unit.kelvin / unit.femtosecond)
    type1, type2, friction, conduction = integrator.getTypePairParameters(1)
    assert (type1, type2) == (0, 7)
    assert friction.value_in_unit(FRICTION) == pytest.approx(0.002, rel=1e-14)
    assert conduction.value_in_unit(HEAT_CONDUCTION) == pytest.approx(5000.0, rel=1e-14)
    assert integrator.getTypePairParameters(0)[:2] == [1, 2]
    with pytest.raises(TypeError, match=r"addTypePair\(friction\)"):
        integrator.addTypePair(3, 4, 1 * unit.kelvin, 1.0)


def test_copies_and_pickles_keep_the_types():
    force, integrator = typed_force(), typed_integrator()
    for duplicate in [copy.copy(force), copy.deepcopy(force), pickle.loads(pickle.dumps(force))]:
        assert isinstance(duplicate, GenDPDEForce) and duplicate.thisown
        assert duplicate.getParticleTypes() == {0: 3, 2: -1, 7: 3, 100: 42}
        assert duplicate.getNumTypeParameters() == 2
        assert duplicate.getTypeParameters(0) == [3, 4.0 * NUMBER_DENSITY, 50.0 * PRESSURE, 70.0 * PRESSURE, 6.5]
        assert duplicate.getTypeParameters(1) == [-1, 5.0 * NUMBER_DENSITY, 10.0 * PRESSURE, 20.0 * PRESSURE, 3.0]
        duplicate.setParticleType(0, 9)         # independent of the original
        assert force.getParticleType(0) == 3
    for duplicate in [copy.copy(integrator), copy.deepcopy(integrator), pickle.loads(pickle.dumps(integrator))]:
        assert isinstance(duplicate, GenDPDEIntegrator) and duplicate.thisown
        assert duplicate.getParticleTypes() == {1: 5, 4: -2, 9: 5}
        assert duplicate.getNumTypeHeatCapacities() == 2 and duplicate.getNumTypePairs() == 2
        assert duplicate.getTypeHeatCapacity(0) == [5, 0.3 * HEAT_CAPACITY]
        assert duplicate.getTypeHeatCapacity(1) == [-2, 0.05 * HEAT_CAPACITY]
        assert duplicate.getTypePairParameters(0) == [5, -2, 3.0 * FRICTION, 4.0 * HEAT_CONDUCTION]
        assert duplicate.getTypePairParameters(1) == [0, 5, 0.5 * FRICTION, 0.25 * HEAT_CONDUCTION]
        duplicate.setTypeHeatCapacity(0, 5, 1.0)
        assert integrator.getTypeHeatCapacity(0) == [5, 0.3 * HEAT_CAPACITY]


def with_pair(integrator):
    integrator.addTypePair(1, 2, 1.0, 1.0)
    return integrator


@pytest.mark.parametrize("make, call, fragments", [
    (make_integrator, lambda i: i.addTypePair(1, 2, -1.0, 1.0), ["type pair 0 (types 1, 2)", "friction = -1"]),
    (make_integrator, lambda i: i.addTypePair(1, 2, 1.0, float("nan")), ["heat conduction = nan"]),
    (lambda: with_pair(make_integrator()), lambda i: i.addTypePair(2, 1, 1.0, 1.0),
     ["type pair 1 (types 2, 1)", "already has parameters (entry 0)"]),
    (lambda: with_pair(make_integrator()), lambda i: i.getTypePairParameters(1), ["type pair index = 1"]),
    (make_integrator, lambda i: i.getTypeHeatCapacity(0), ["type heat capacity index = 0"]),
    (make_integrator, lambda i: i.addTypeHeatCapacity(4, 0.0), ["type heat capacity 0 (type 4)",
                                                                "heat capacity = 0"]),
    (make_integrator, lambda i: i.setParticleType(-3, 1), ["GenDPDEIntegrator", "particle index", "-3"]),
    (lambda: GenDPDEForce(0.95), lambda f: f.addTypeParameters(2, 0.0, 1.0, 1.0, 2.0),
     ["type parameters 0 (type 2)", "reference density n0 = 0"]),
    (lambda: GenDPDEForce(0.95), lambda f: f.addTypeParameters(2, -4.0, 1.0, 1.0, 2.0),
     ["type parameters 0 (type 2)", "reference density n0 = -4"]),
    (typed_force, lambda f: f.addTypeParameters(3, 1.0, 1.0, 1.0, 2.0),
     ["type parameters 2 (type 3)", "type 3 already has parameters (entry 0)"]),
    (typed_force, lambda f: f.getTypeParameters(2), ["type parameters index = 2"]),
    (lambda: GenDPDEForce(0.95), lambda f: f.setParticleType(-1, 4), ["GenDPDEForce", "particle index", "-1"]),
])
def test_bad_input_raises_openmm_exception_naming_the_value(make, call, fragments):
    assert_rejected_without_change(make(), call, fragments)


def small_liquid():
    """27 argon particles in a periodic box of 2.0 nm, cutoff 0.95 nm (at most half the box)."""
    return lattice_liquid(3, density=27 / 2.0**3, cutoff=0.95)


@pytest.mark.parametrize("on_integrator", [False, True], ids=["types on the force", "types on both"])
def test_types_reach_the_context(on_integrator):
    """The per-type heat capacities apply to the particles of each type, u_i = C_V(type of i) T, whether the types are
    set on the force alone (the integrator takes them) or on both alike."""
    system, force, positions = small_liquid()
    integrator = make_integrator()
    integrator.setTemperature(100.0)
    for particle, type_ in ((4, 7), (20, -2)):
        force.setParticleType(particle, type_)
        if on_integrator:
            integrator.setParticleType(particle, type_)
    integrator.addTypeHeatCapacity(7, 0.3)
    integrator.addTypeHeatCapacity(-2, 0.02)
    integrator.addTypePair(7, -2, 5.0, 6.0)
    force.addTypeParameters(7, 5.0, 10.0, 20.0, 3.0)
    context = make_context(system, positions, openmm.Platform.getPlatformByName("Reference"), integrator)
    expected = np.full(27, 0.1 * 100.0)
    expected[4], expected[20] = 0.3 * 100.0, 0.02 * 100.0
    energies = integrator.getInternalEnergies().value_in_unit(unit.kilojoule_per_mole)
    np.testing.assert_allclose(energies, expected, rtol=1e-14)
    integrator.step(2)
    del context


def test_types_that_differ_between_force_and_integrator_are_refused():
    """A particle's type is one setting: the Context is refused, naming the particle and both types."""
    system, force, positions = small_liquid()
    integrator = make_integrator()
    force.setParticleType(20, -2)
    integrator.setParticleType(4, 7)
    with pytest.raises(openmm.OpenMMException, match="particle 4 has type 7 on the GenDPDEIntegrator but type 0 on "
                                                     "the GenDPDEForce"):
        make_context(system, positions, openmm.Platform.getPlatformByName("Reference"), integrator)


@pytest.mark.parametrize("configure, fragments", [
    (lambda f, i: i.addTypePair(0, 5, 1.0, 1.0), ["GenDPDEIntegrator", "type pair 0 names type 5",
                                                   "types are 0, 3"]),
    (lambda f, i: i.addTypeHeatCapacity(-6, 0.2), ["GenDPDEIntegrator", "type heat capacity 0 names type -6"]),
    (lambda f, i: f.addTypeParameters(11, 4.0, 1.0, 1.0, 2.0), ["GenDPDEForce", "type parameters 0 names type 11"]),
    (lambda f, i: i.setParticleType(27, 3), ["setParticleType() was given particle 27", "has 27 particles"]),
])
def test_context_refuses_an_entry_for_a_type_no_particle_has(configure, fragments):
    system, force, positions = small_liquid()
    integrator = make_integrator()
    integrator.setParticleType(1, 3)
    force.setParticleType(1, 3)
    configure(force, integrator)
    with pytest.raises(openmm.OpenMMException) as error:
        make_context(system, positions, openmm.Platform.getPlatformByName("Reference"), integrator)
    for fragment in fragments:
        assert fragment in str(error.value)
