"""The thermodynamic state of a GenDPDE simulation at one instant, in OpenMM units: the one definition of what
GenDPDEReporter writes and what the liquid-argon studies (openmmgendpde.study) average."""

import dataclasses

import numpy as np
from openmm import unit

from .units import BOLTZMANN

_K = unit.kelvin
_DENSITY = unit.nanometer**-3
_PRESSURE = unit.kilojoule_per_mole / unit.nanometer**3
_ENERGY = unit.kilojoule_per_mole


@dataclasses.dataclass(frozen=True)
class ThermodynamicSample:
    """One sample, every field an ``openmm.unit`` Quantity in OpenMM units."""
    time: unit.Quantity                   # ps
    kinetic_temperature: unit.Quantity    # K: 2K/(d k_B), d = kinetic_degrees_of_freedom (on-step velocities)
    mean_temperature: unit.Quantity       # K: <theta_i>
    harmonic_temperature: unit.Quantity   # K: <1/theta_i>^-1
    density: unit.Quantity                # nm^-3: n-bar, the mean of n_i = 1/V_i
    pressure: unit.Quantity               # kJ/mol/nm^3: the virial pressure (2K + W)/(3V) of the GenDPDEForce
    conserved_energy: unit.Quantity       # kJ/mol: K + U + sum eps_i


def kinetic_degrees_of_freedom(system):
    """3N - 3 for the N particles of ``system`` that move (mass > 0): GenDPDE conserves momentum (at least 1)."""
    moving = sum(1 for i in range(system.getNumParticles()) if system.getParticleMass(i).value_in_unit(unit.amu) > 0)
    return max(1, 3 * moving - 3)


def sample_thermodynamics(state, context, integrator, force, degrees_of_freedom):
    """A ThermodynamicSample of ``context`` now. ``state`` is a State of ``context`` with energies, ``integrator``
    its GenDPDEIntegrator, ``force`` the GenDPDEForce of its System, ``degrees_of_freedom`` from
    kinetic_degrees_of_freedom(system). The volume V is that of the State's periodic box."""
    kinetic = state.getKineticEnergy().value_in_unit(_ENERGY)
    theta = integrator.getParticleTemperatures().value_in_unit(_K)
    a, b, c = state.getPeriodicBoxVectors().value_in_unit(unit.nanometer)
    volume = a[0] * b[1] * c[2]
    virial = force.getVirial(context).value_in_unit(_ENERGY)
    density = np.mean(force.getParticleDensities(context).value_in_unit(_DENSITY))
    kb = BOLTZMANN.value_in_unit(_ENERGY / _K)
    return ThermodynamicSample(
        time=state.getTime(),
        kinetic_temperature=unit.Quantity(2 * kinetic / (degrees_of_freedom * kb), _K),
        mean_temperature=unit.Quantity(np.mean(theta), _K),
        harmonic_temperature=unit.Quantity(1 / np.mean(1 / theta), _K),
        density=unit.Quantity(density, _DENSITY),
        pressure=unit.Quantity((2 * kinetic + virial) / (3 * volume), _PRESSURE),
        conserved_energy=integrator.getConservedEnergy(),
    )
