# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""The local equations of state that depend on temperature (docs/theory.md section 11), from Python: the API with
units, copies, and what is refused, and OpenCL against Reference. Their physics is tested in C++
(tests/TestGenDPDEThermal.h) on every platform."""

import copy
import pickle

import numpy
import openmm
import pytest
from openmm import unit

from openmmgendpde import GenDPDEForce, GenDPDEIntegrator

AVOGADRO = 6.02214076e23


def test_laws_round_trip_with_units():
    force = GenDPDEForce(1.0)
    assert force.getEquationOfState() == [GenDPDEForce.Tait, []]
    assert not force.dependsOnTemperature()
    # beta given per molecule in MPa/K: converted per mole, as Tait pressures are (1 MPa = 1e-21 J/nm^3).
    force.setEquationOfState(GenDPDEForce.TaitThermalExpansion, [1.77 * unit.megapascal / unit.kelvin, 125.7])
    law, (beta, theta0) = force.getEquationOfState()
    assert law == GenDPDEForce.TaitThermalExpansion
    assert beta.value_in_unit(unit.kilojoule_per_mole / unit.nanometer**3 / unit.kelvin) == pytest.approx(
        1.77e6 * 1e-27 * AVOGADRO / 1000, rel=1e-12)
    assert theta0 == 125.7 * unit.kelvin
    assert force.addTypeEquationOfState(4, GenDPDEForce.VanDerWaals, [0.5, 0.1 * unit.nanometer**3, 0.01]) == 0
    assert force.getNumTypeEquationsOfState() == 1
    type_, law, parameters = force.getTypeEquationOfState(0)
    assert (type_, law) == (4, GenDPDEForce.VanDerWaals)
    assert [p._value for p in parameters] == [0.5, 0.1, 0.01]
    assert force.dependsOnTemperature()
    for other in (copy.deepcopy(force), pickle.loads(pickle.dumps(force))):
        assert other.getTypeEquationOfState(0)[1] == GenDPDEForce.VanDerWaals
        assert other.getEquationOfState()[1][1] == 125.7 * unit.kelvin


def test_bad_laws_are_refused_by_name():
    force = GenDPDEForce(1.0)
    with pytest.raises(openmm.OpenMMException, match="takes 2 parameters .*not 1"):
        force.setEquationOfState(GenDPDEForce.TaitThermalExpansion, [1.0])
    with pytest.raises(openmm.OpenMMException, match="van der Waals excluded volume b = -1"):
        force.setEquationOfState(GenDPDEForce.VanDerWaals, [1.0, -1.0, 1.0])
    with pytest.raises(TypeError, match="theta0"):
        force.setEquationOfState(GenDPDEForce.TaitThermalExpansion, [1.0, 3 * unit.nanometer])
    assert force.getEquationOfState() == [GenDPDEForce.Tait, []]


def _lattice_system(law_force):
    system = openmm.System()
    edge, side = 3.0, 6
    system.setDefaultPeriodicBoxVectors(*(openmm.Vec3(*(edge if i == k else 0 for i in range(3))) for k in range(3)))
    positions = []
    for x in range(side):
        for y in range(side):
            for z in range(side):
                system.addParticle(200.0)
                positions.append(openmm.Vec3(x + 0.5, y + 0.5, z + 0.5) * (edge / side))
    system.addForce(law_force)
    return system, positions


def test_a_law_that_depends_on_temperature_needs_a_gendpde_integrator():
    force = GenDPDEForce(1.0)
    force.setEquationOfState(GenDPDEForce.TaitThermalExpansion, [10.0, 300.0])
    system, _ = _lattice_system(force)
    with pytest.raises(openmm.OpenMMException, match="TaitThermalExpansion.*needs a GenDPDEIntegrator"):
        openmm.Context(system, openmm.VerletIntegrator(0.001), openmm.Platform.getPlatformByName("Reference"))


def test_opencl_gives_reference_s_pressures_and_temperatures():
    """The OpenCL platform (PoCL here) in double precision against Reference, 216 particles of the thermal Tait law:
    after 20 Conservative steps from the same state, the particles' pressures and temperatures agree to 1e-9 relative
    (double precision; the two platforms sum in different orders, so not to the bit)."""
    names = [openmm.Platform.getPlatform(i).getName() for i in range(openmm.Platform.getNumPlatforms())]
    if "OpenCL" not in names:
        pytest.skip("no OpenCL platform here")
    results = []
    for platform, properties in (("Reference", {}), ("OpenCL", {"Precision": "double"})):
        force = GenDPDEForce(1.0)
        force.setEquationOfState(GenDPDEForce.TaitThermalExpansion, [10.0, 300.0])
        system, positions = _lattice_system(force)
        integrator = GenDPDEIntegrator(0.001, 0.0, 0.0, 0.1)
        integrator.setMode(GenDPDEIntegrator.Conservative)
        integrator.setParticleTemperatures([300.0 + (i % 7) for i in range(system.getNumParticles())])
        context = openmm.Context(system, integrator, openmm.Platform.getPlatformByName(platform), properties)
        context.setPositions(positions)
        context.setVelocitiesToTemperature(300, 5)
        integrator.step(20)
        results.append((force.getParticlePressures(context)._value, integrator.getParticleTemperatures()._value))
    (p_ref, t_ref), (p_ocl, t_ocl) = results
    numpy.testing.assert_allclose(p_ocl, p_ref, rtol=1e-9, atol=1e-9 * numpy.abs(p_ref).max())
    numpy.testing.assert_allclose(t_ocl, t_ref, rtol=1e-9)
    assert numpy.abs(t_ref - numpy.array([300.0 + (i % 7) for i in range(len(t_ref))])).max() > 1e-3   # they moved


def test_isothermal_pressure_is_the_law_at_the_bath_temperature():
    """In the Isothermal mode every particle is at T: pi_i = pi_Tait(n_i) + beta (T - theta0), with the Tait pressure
    that the same force gives without the thermal law (the particles' densities are the same)."""
    tait = GenDPDEForce(1.0)
    system, positions = _lattice_system(tait)
    context = openmm.Context(system, openmm.VerletIntegrator(0.001), openmm.Platform.getPlatformByName("Reference"))
    context.setPositions(positions)
    expected = tait.getParticlePressures(context).value_in_unit(unit.kilojoule_per_mole / unit.nanometer**3)
    thermal = GenDPDEForce(1.0)
    beta, theta0, bath = 2.5, 300.0, 340.0
    thermal.setEquationOfState(GenDPDEForce.TaitThermalExpansion, [beta, theta0])
    system, positions = _lattice_system(thermal)
    integrator = GenDPDEIntegrator(0.001, 1.0, 0.0, 0.1)
    integrator.setMode(GenDPDEIntegrator.Isothermal)
    integrator.setTemperature(bath)
    context = openmm.Context(system, integrator, openmm.Platform.getPlatformByName("Reference"))
    context.setPositions(positions)
    found = thermal.getParticlePressures(context).value_in_unit(unit.kilojoule_per_mole / unit.nanometer**3)
    numpy.testing.assert_allclose(found, expected + beta * (bath - theta0), rtol=1e-12)
    # The law's parameters change in the Context with updateParametersInContext.
    thermal.setEquationOfState(GenDPDEForce.TaitThermalExpansion, [2 * beta, theta0])
    thermal.updateParametersInContext(context)
    found = thermal.getParticlePressures(context).value_in_unit(unit.kilojoule_per_mole / unit.nanometer**3)
    numpy.testing.assert_allclose(found, expected + 2 * beta * (bath - theta0), rtol=1e-12)


# The table of the laws (C++ GenDPDEEquationsOfState.h, through SWIG) is what the unit wrapping, the checks and the
# serialization read: every law in it works from Python with nothing written here about it.
def _table():
    from openmmgendpde import gendpde as swig
    return swig, range(swig.numEquationsOfState())


def _in_range(swig, law, k):
    """A value the table allows for parameter k of law (as the C++ test picks them)."""
    minimum, maximum = swig.equationOfStateParameterRange(law, k)
    value = 1.25 + k
    if value < minimum or (swig.equationOfStateParameterExcludesMinimum(law, k) and value == minimum):
        value = 2 * minimum if minimum > 0 else minimum + 1
    return min(value, maximum)


def test_every_law_of_the_table_round_trips_with_the_table_s_units():
    from openmmgendpde.api import _LAW_PARAMETERS
    from openmmgendpde.internal.wrapping import parse_units as _parse_units
    swig, laws = _table()
    assert len(laws) >= 3 and sorted(_LAW_PARAMETERS) == list(laws)
    force = GenDPDEForce(1.0)
    for law in laws:
        assert getattr(GenDPDEForce, swig.equationOfStateName(law)) == law
        names = [swig.equationOfStateParameterName(law, k) for k in range(swig.numEquationOfStateParameters(law))]
        assert [name for name, _ in _LAW_PARAMETERS[law]] == names
        units = [_parse_units(swig.equationOfStateParameterUnits(law, k)) for k in range(len(names))]
        values = [_in_range(swig, law, k) for k in range(len(names))]
        quantities = [unit.Quantity(v, u) if unit.is_unit(u) else v for v, u in zip(values, units)]
        force.addTypeEquationOfState(10 + law, law, quantities)
        with pytest.raises(openmm.OpenMMException, match=f"the {swig.equationOfStateName(law)} equation of state "
                                                         f"takes {len(names)} parameters"):
            force.setEquationOfState(law, values + [1.0])
    copied = openmm.XmlSerializer.deserialize(openmm.XmlSerializer.serialize(force))
    for law in laws:
        type_, found, parameters = GenDPDEForce.cast(copied).getTypeEquationOfState(law)
        assert (type_, found) == (10 + law, law)
        values = [_in_range(swig, law, k) for k in range(len(parameters))]
        assert [p.value_in_unit(u) if unit.is_unit(u) else p
                for p, (_, u) in zip(parameters, _LAW_PARAMETERS[law])] == values


def test_the_table_s_units_are_openmm_s():
    from openmmgendpde.api import _LAW_PARAMETERS
    from openmmgendpde.internal.wrapping import PRESSURE_PER_KELVIN
    thermal = _LAW_PARAMETERS[GenDPDEForce.TaitThermalExpansion]
    assert thermal == [("beta", PRESSURE_PER_KELVIN), ("theta0", unit.kelvin)]
    (_, a), (_, b), (_, k) = _LAW_PARAMETERS[GenDPDEForce.VanDerWaals]
    assert a == unit.kilojoule_per_mole * unit.nanometer**3 and b == unit.nanometer**3
    assert k == unit.kilojoule_per_mole / unit.kelvin
    with pytest.raises(openmm.OpenMMException, match="no parameter 3"):
        _table()[0].equationOfStateParameterName(GenDPDEForce.VanDerWaals, 3)


#: Parameters of each law for a liquid of 8 particles/nm^3 (the lattice of _lattice_system).
_LIQUID_LAWS = {GenDPDEForce.Tait: [], GenDPDEForce.TaitThermalExpansion: [2.5, 300.0],
                GenDPDEForce.VanDerWaals: [0.3, 0.02, 0.01]}


@pytest.mark.parametrize("estimator", ["VA", "VB"])
@pytest.mark.parametrize("law", sorted(_LIQUID_LAWS))
def test_physics_particle_state_is_the_force_s(estimator, law):
    """openmmgendpde.physics.particleState of each particle's primitive density gives the pressures the Reference
    platform gives, bit for bit, for every law (Isothermal at 340 K for those that depend on temperature)."""
    from openmmgendpde import physics
    force = GenDPDEForce(1.0)
    force.setDensityEstimator(getattr(GenDPDEForce, estimator))
    force.setEquationOfState(law, _LIQUID_LAWS[law])
    force.setBackgroundPressure(0.05)
    system, positions = _lattice_system(force)
    jitter = numpy.random.default_rng(4).normal(0.0, 0.03, (len(positions), 3))
    positions = [openmm.Vec3(*(numpy.array(p) + d)) for p, d in zip(positions, jitter)]
    integrator = GenDPDEIntegrator(0.001, 1.0, 0.0, 0.1)
    integrator.setMode(GenDPDEIntegrator.Isothermal)
    integrator.setTemperature(340.0)
    context = openmm.Context(system, integrator, openmm.Platform.getPlatformByName("Reference"))
    context.setPositions(positions)
    n0 = force.getPrimitiveDensities(context)._value
    pressures = force.getParticlePressures(context)._value
    tait = [q._value if unit.is_quantity(q) else q for q in force.getTaitParameters()]
    for i in range(0, len(n0), 7):
        state = physics.particleState(getattr(GenDPDEForce, estimator), 1.0, 1.0, n0[i], 0.0, law, _LIQUID_LAWS[law],
                                      *tait, 0.05, True, 340.0, 0.0, 0.0, False, 0.1)
        assert state[0] == physics.PARTICLE_VALID
        assert state[2] == pressures[i]


def test_physics_covers_every_estimator_and_law():
    from openmmgendpde import physics
    n0, cutoff, scaling = 6.5, 1.0, 1.2
    assert list(physics.particleVolume(GenDPDEForce.VA, n0, 0.0, cutoff, scaling))[:2] == list(
        physics.particleVolumeVA(n0))
    vb = list(physics.particleVolume(GenDPDEForce.VB, n0, 0.0, cutoff, scaling))
    assert vb[:2] == list(physics.particleVolumeVB(n0, cutoff / scaling))
    assert list(physics.particleVolume(GenDPDEForce.VC, n0, 0.0, cutoff, scaling))[:2] == vb[:2]   # bulk: V-C is V-B
    assert physics.particleVolume(GenDPDEForce.VC, n0, 4 * n0**2, cutoff, scaling)[0] > vb[0]   # a one-sided one
    tait = (4.27, 0.12, 15.0, 7.0)
    status, e, sigma, pi0, pit = physics.localEquationOfState(GenDPDEForce.Tait, [], *tait, 0.0, 5.0)
    assert (status, sigma, pit) == (physics.PARTICLE_VALID, 0.0, 0.0)
    assert [pi0, e] == list(physics.taitEquationOfState(5.0, *tait))
    status, e, sigma, pi0, pit = physics.localEquationOfState(GenDPDEForce.TaitThermalExpansion, [2.5, 300.0], *tait,
                                                              0.0, 5.0)
    assert pit == 2.5 and pi0 + 300.0 * pit == pytest.approx(physics.taitEquationOfState(5.0, *tait)[0], rel=1e-12)
    status = physics.localEquationOfState(GenDPDEForce.VanDerWaals, [0.3, 0.5, 0.01], *tait, 0.0, 2.5)[0]
    assert status == physics.PARTICLE_OUTSIDE_DOMAIN   # b n >= 1
    with pytest.raises(openmm.OpenMMException, match="van der Waals excluded volume b = -1"):
        physics.localEquationOfState(GenDPDEForce.VanDerWaals, [0.3, -1.0, 0.01], *tait, 0.0, 2.5)


def test_a_law_is_spelt_only_in_the_core_the_table_and_the_api_enum():
    """What a new law touches (issue 41): its formula in the physics core, its entry in the table (and its value of
    GenDPDEForce::EquationOfState), and its oracle in the tests. The van der Waals law, the latest added, is named in
    no other source file of the plugin: not in the checks, messages, serialization, platforms, Python wrapping, the
    LAMMPS package or its input files (which take the laws from the table)."""
    import pathlib
    import re
    root = pathlib.Path(__file__).resolve().parents[2]
    pattern = re.compile(r"van ?der ?Waals|VAN_DER_WAALS", re.IGNORECASE)
    sources = [path for folder in ("core", "openmmapi", "platforms", "serialization", "python/openmmgendpde", "lammps")
               for path in (root / folder).rglob("*")
               if path.suffix in (".h", ".cpp", ".cc", ".in", ".py", ".i") and "tests" not in path.parts
               and path.name not in ("gendpde.py", "_version.py")]   # (what SWIG and CMake generate, where copied)
    sources.append(root / "python" / "gendpde.i")
    assert len(sources) > 50
    found = sorted(str(path.relative_to(root)) for path in sources if pattern.search(path.read_text()))
    assert found == ["core/include/gendpde/GenDPDEEquationsOfState.h", "core/include/gendpde/GenDPDEPhysicsCore.h",
                     "openmmapi/include/GenDPDEForce.h"]
