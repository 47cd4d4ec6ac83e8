"""The virial and pressure tensors (openmmgendpde.pressure) against the C++ scalar virial and the energy's response
to deformations of the box."""

import numpy as np
import openmm
import pytest
from openmm import unit

from conftest import PLATFORMS
from helpers import lattice_liquid, make_context
from openmmgendpde import GenDPDEForce
from openmmgendpde.pressure import pressure_tensor, virial_tensor


@pytest.mark.parametrize("estimator", [GenDPDEForce.VA, GenDPDEForce.VB])
@pytest.mark.parametrize("name", PLATFORMS)
def test_trace_is_the_scalar_virial(name, estimator):
    """trace W = GenDPDEForce.getVirial (the platform's own sum over pairs): 1e-10 relative (the same sums in
    another order); the tensor is symmetric (central pair forces) to rounding."""
    system, force, positions = lattice_liquid(6, estimator=estimator, seed=12, jitter=0.2)
    context = make_context(system, positions, openmm.Platform.getPlatformByName(name))
    w = virial_tensor(force, context)
    assert np.trace(w) == pytest.approx(force.getVirial(context).value_in_unit(unit.kilojoule_per_mole), rel=1e-10)
    assert np.abs(w - w.T).max() <= 1e-12 * np.abs(w).max()


def energy_after(context, system, positions, box, deform):
    """U (kJ/mol) with positions and box vectors (rows) mapped by the matrix ``deform`` (r -> deform r)."""
    new_box = [openmm.Vec3(*(deform @ np.array(v))) for v in box]
    context.setPeriodicBoxVectors(*new_box)
    context.setPositions(positions @ deform.T)
    return context.getState(getEnergy=True).getPotentialEnergy().value_in_unit(unit.kilojoule_per_mole)


@pytest.mark.parametrize("estimator", [GenDPDEForce.VA, GenDPDEForce.VB])
def test_components_are_the_energys_response_to_strain(estimator):
    """W_ab = -dU/d epsilon for the strain r_a -> r_a + epsilon r_b of positions and box: stretching along x gives
    W_xx, shearing x by z gives W_xz (the sheared box is triclinic, which GenDPDEForce supports). Central
    differences with epsilon = 1e-6: truncation ~1e-12 relative, rounding eps |U|/1e-6 ~ 1e-9 of |W|: 1e-6 relative
    to the largest component."""
    system, force, positions = lattice_liquid(6, estimator=estimator, seed=13, jitter=0.2)
    context = make_context(system, positions, openmm.Platform.getPlatformByName("Reference"))
    w = virial_tensor(force, context)
    box = [np.array(v.value_in_unit(unit.nanometer)) for v in system.getDefaultPeriodicBoxVectors()]
    epsilon = 1e-6
    for a, b in ((0, 0), (1, 1), (2, 2), (0, 2), (0, 1), (1, 2)):
        strain = np.zeros((3, 3))
        strain[a, b] = epsilon
        plus = energy_after(context, system, positions, box, np.eye(3) + strain)
        minus = energy_after(context, system, positions, box, np.eye(3) - strain)
        derivative = (plus - minus) / (2 * epsilon)
        assert -derivative == pytest.approx(w[a, b], abs=1e-6 * np.abs(w).max()), (a, b)


def test_pressure_tensor_trace_is_the_virial_pressure():
    """trace P / 3 = (2 K_int + W)/(3V), the scalar virial pressure of the reporters (openmmgendpde.thermodynamics,
    from the integrator's kinetic energy and GenDPDEForce.getVirial): the same sums, 1e-10 relative."""
    from openmmgendpde.thermodynamics import ThermodynamicProbe
    from helpers import argon_integrator, TEMPERATURE
    system, force, positions = lattice_liquid(6, seed=14)
    integrator = argon_integrator(0.01 * unit.picosecond)
    integrator.setTemperature(TEMPERATURE * unit.kelvin)
    context = make_context(system, positions, openmm.Platform.getPlatformByName("Reference"), integrator)
    context.setVelocitiesToTemperature(TEMPERATURE * unit.kelvin, 3)
    integrator.setInternalEnergiesToTemperature(TEMPERATURE * unit.kelvin, 4)
    integrator.step(20)
    state = context.getState(getEnergy=True, getVelocities=True, getForces=True)
    p = pressure_tensor(force, context, state)
    scalar = ThermodynamicProbe(system).sample(state, context, integrator).pressure
    assert np.trace(p) / 3 == pytest.approx(scalar.value_in_unit(unit.kilojoule_per_mole / unit.nanometer**3),
                                            rel=1e-10)
