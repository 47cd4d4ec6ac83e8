# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""The thermodynamic state of a simulation at one instant, in OpenMM units: the one definition of what
GenDPDEReporter writes and what the liquid-argon studies (openmmgendpde.models.argon_runs) average.

What can be measured depends on the simulation, and what cannot is reported as NaN rather than as a wrong number:

- kinetic temperature: 2 K_int/(d k_B) with the kinetic energy in the frame of the centre of mass,
  K_int = K - |P|^2/(2M), and d = 3N - 3 for the N moving particles (the momentum-conserving dynamics of GenDPDE
  and DPD keeps P; OpenMM's setVelocitiesToTemperature does not always make it zero);
- particle temperatures theta_i and the conserved energy K + U + sum eps_i: only with a GenDPDEIntegrator; the
  energy is conserved (so its drift is meaningful) in the Isoenergetic and Conservative modes, not in Isothermal;
- mean density: only if the System has a GenDPDEForce (the first one's n_i);
- virial pressure P = (2 K_int + W)/(3V): only with periodic boundaries. W is the sum of the exact virials of the
  GenDPDEForces and, for the force groups that hold other forces, -dU/dlambda under a uniform scaling of positions
  and box by lambda (central difference, lambda = 1 +- 1e-5; two energy evaluations per such group; the Context's
  positions and box are restored exactly afterwards). External fields (external_fields: CustomExternalForce, and
  the custom forces whose energy reads a particle's absolute coordinates) are left out: a field acts on the
  particles from outside the fluid and carries no momentum across a surface inside it, so it has no place in the
  pressure of a periodic fluid (its "virial" sum_i r_i . F_i depends on where the origin is and grows as a fluid
  flows along a body force; the group-wise difference also crossed the Poiseuille force's sign flip: one particle
  there moved the pressure of 108 argon particles by -98,688 bar, test_flows.py). A group that holds an external
  field beside another force that is not a GenDPDEForce cannot be split by the group-wise difference, and is
  refused (an OpenMMException naming both forces): put the field in a force group of its own. K_int removes only
  the centre of mass's motion, at the positions' time (with a GenDPDEIntegrator the stored velocities are half a
  step behind, and a body force's total, unlike the pair forces', need not be zero: its half kick is added), so a
  flow's kinetic energy is in P (rho <v^2>/3 more; analysis.profiles removes each slice's mean velocity).
"""

import dataclasses
import math
import re

import numpy as np
import openmm
from openmm import unit

from ..api import GenDPDEForce, GenDPDEIntegrator
from ..units import BOLTZMANN
from .statistics import correlated_mean

_K = unit.kelvin
_DENSITY = unit.nanometer**-3
_PRESSURE = unit.kilojoule_per_mole / unit.nanometer**3
_ENERGY = unit.kilojoule_per_mole
_NAN = float("nan")
#: Relative change of the box edge for the numerical virial of forces other than GenDPDEForce.
VIRIAL_SCALING_STEP = 1e-5


@dataclasses.dataclass(frozen=True)
class ThermodynamicSample:
    """One sample, every field an ``openmm.unit`` Quantity in OpenMM units (NaN where it cannot be measured)."""
    time: unit.Quantity                   # ps
    kinetic_temperature: unit.Quantity    # K: 2 K_int/(d k_B) (on-step velocities, centre-of-mass frame)
    mean_temperature: unit.Quantity       # K: <theta_i>
    harmonic_temperature: unit.Quantity   # K: <1/theta_i>^-1
    density: unit.Quantity                # nm^-3: n-bar, the mean of n_i = 1/V_i
    pressure: unit.Quantity               # kJ/mol/nm^3: the virial pressure (2 K_int + W)/(3V)
    conserved_energy: unit.Quantity       # kJ/mol: K + U + sum eps_i
    energy_is_conserved: bool             # whether the dynamics conserves conserved_energy (drift meaningful)


class ThermodynamicProbe:
    """Measures ThermodynamicSamples of the simulations of one System. It decides once, from the System, what can
    be measured and how (see the module's docstring)."""

    def __init__(self, system):
        masses = particle_masses(system)
        self.masses = masses
        self.degrees_of_freedom = max(1, 3 * int(np.count_nonzero(masses > 0)) - 3)
        self.periodic = system.usesPeriodicBoundaryConditions()
        forces = [system.getForce(i) for i in range(system.getNumForces())]
        self.gendpde_forces = [GenDPDEForce.cast(f) for f in forces if GenDPDEForce.isinstance(f)]
        #: The indices of the forces the virial leaves out (external_fields).
        self.external_fields = external_fields(system)
        self.force_groups = [f.getForceGroup() for f in forces]
        # Forces that may carry energy (CMMotionRemover carries none) and act between particles, by group.
        others = [i for i, f in enumerate(forces) if not GenDPDEForce.isinstance(f)
                  and not isinstance(f, openmm.CMMotionRemover) and i not in self.external_fields]
        other_groups = {forces[i].getForceGroup() for i in others}
        if self.periodic:
            for field in self.external_fields:
                group = forces[field].getForceGroup()
                mixed = [i for i in others if forces[i].getForceGroup() == group]
                if mixed:
                    raise openmm.OpenMMException(
                        f"virial pressure: force {field} ({_describe(forces[field])}, an external field) shares force "
                        f"group {group} with force {mixed[0]} ({_describe(forces[mixed[0]])}): the pressure leaves "
                        f"external fields out, and the numerical virial of a group cannot split it; put the external "
                        f"field in a force group of its own (setForceGroup, e.g. "
                        f"openmmgendpde.models.flows.BODY_FORCE_GROUP = 31)")
        self.exact_virial_forces = [f for f in self.gendpde_forces if f.getForceGroup() not in other_groups]
        self.numerical_virial_groups = sorted(other_groups)

    def internal_kinetic_energy(self, state, context=None, integrator=None):
        """K_int = K - |P|^2/(2M) (kJ/mol, a float): the kinetic energy of ``state`` (a State with energies and
        velocities) in the frame of the centre of mass. With the ``context`` and its ``integrator`` (a
        GenDPDEIntegrator) and external fields in the System, P includes the fields' half kick (_external_impulse)."""
        kinetic = state.getKineticEnergy().value_in_unit(_ENERGY)
        velocities = state.getVelocities(asNumpy=True).value_in_unit(unit.nanometer / unit.picosecond)
        momentum = self.masses @ velocities
        gendpde = _as_gendpde_integrator(integrator) if integrator is not None else None
        if gendpde is not None and self.external_fields:
            momentum = momentum + self._external_impulse(context, gendpde)
        return kinetic - float(momentum @ momentum) / (2 * self.masses.sum())

    def kinetic_temperature(self, state, context=None, integrator=None):
        """2 K_int/(d k_B) (K, a float) of ``state`` (a State with energies and velocities), d = 3N - 3
        (internal_kinetic_energy)."""
        kb = BOLTZMANN.value_in_unit(_ENERGY / _K)
        return 2 * self.internal_kinetic_energy(state, context, integrator) / (self.degrees_of_freedom * kb)

    def sample(self, state, context, integrator):
        """A ThermodynamicSample of ``context`` now. ``state`` is a State of ``context`` with energies and
        velocities; ``integrator`` the Context's integrator (any type)."""
        internal_kinetic = self.internal_kinetic_energy(state, context, integrator)
        kb = BOLTZMANN.value_in_unit(_ENERGY / _K)
        gendpde = _as_gendpde_integrator(integrator)
        mean, harmonic = particle_temperature_means(integrator)
        conserved = conserved_energy(integrator)
        is_conserved = gendpde is not None and gendpde.getMode() != GenDPDEIntegrator.Isothermal
        density = (np.mean(self.gendpde_forces[0].getParticleDensities(context).value_in_unit(_DENSITY))
                   if self.gendpde_forces else _NAN)
        return ThermodynamicSample(
            time=state.getTime(),
            kinetic_temperature=unit.Quantity(2 * internal_kinetic / (self.degrees_of_freedom * kb), _K),
            mean_temperature=unit.Quantity(mean, _K),
            harmonic_temperature=unit.Quantity(harmonic, _K),
            density=unit.Quantity(density, _DENSITY),
            pressure=unit.Quantity(self._pressure(state, context, internal_kinetic), _PRESSURE),
            conserved_energy=unit.Quantity(conserved, _ENERGY),
            energy_is_conserved=is_conserved,
        )

    def _external_impulse(self, context, integrator):
        """(dt/2) sum_i F_i of the external fields that ``integrator`` (a GenDPDEIntegrator) integrates: the
        momentum that takes the stored velocities, half a step behind, to the positions' time, at which the kinetic
        energy is (docs/integrator.md). The pair forces sum to zero; a body force's total need not."""
        groups = {self.force_groups[i] for i in self.external_fields} & integration_groups(integrator)
        if not groups:
            return np.zeros(3)
        forces = context.getState(getForces=True, groups=groups).getForces(asNumpy=True)
        step = integrator.getStepSize().value_in_unit(unit.picosecond)
        return 0.5 * step * forces.value_in_unit(_ENERGY / unit.nanometer).sum(axis=0)

    def _pressure(self, state, context, internal_kinetic):
        if not self.periodic:
            return _NAN
        a, b, c = state.getPeriodicBoxVectors().value_in_unit(unit.nanometer)
        volume = a[0] * b[1] * c[2]
        virial = sum(f.getVirial(context).value_in_unit(_ENERGY) for f in self.exact_virial_forces)
        if self.numerical_virial_groups:
            virial += numerical_virial(context, set(self.numerical_virial_groups))
        return (2 * internal_kinetic + virial) / (3 * volume)


#: A particle's (or a group's centroid's) absolute coordinate in the energy of a CustomCompoundBondForce or
#: CustomCentroidBondForce: x1, y2, z3 ... (a CustomExternalForce is an external field whatever its expression).
_COORDINATE = re.compile(r"(?<![A-Za-z0-9_.])[xyz][0-9]+(?![A-Za-z0-9_])")


def is_external_field(force):
    """Whether the energy of ``force`` (an openmm.Force) depends on the particles' absolute positions, so that it is
    an external field rather than an interaction between particles: every CustomExternalForce; a
    CustomCompoundBondForce or CustomCentroidBondForce whose energy expression reads a coordinate x1, y1, z1, ...;
    a CustomCVForce with such a force among its collective variables (then the whole CustomCVForce). OpenMM's other
    forces depend on differences of positions only."""
    if isinstance(force, openmm.CustomExternalForce):
        return True
    if isinstance(force, (openmm.CustomCompoundBondForce, openmm.CustomCentroidBondForce)):
        return bool(_COORDINATE.search(force.getEnergyFunction()))
    if isinstance(force, openmm.CustomCVForce):
        return any(is_external_field(force.getCollectiveVariable(i))
                   for i in range(force.getNumCollectiveVariables()))
    return False


def external_fields(system):
    """The indices of the forces of ``system`` that are external fields (is_external_field)."""
    return [i for i in range(system.getNumForces()) if is_external_field(system.getForce(i))]


def external_field_groups(system):
    """The force groups of ``system`` that hold an external field (is_external_field)."""
    return {system.getForce(i).getForceGroup() for i in external_fields(system)}


def _describe(force):
    name = force.getName()
    kind = type(force).__name__
    return kind if name == kind or not name else f"{kind} '{name}'"


def particle_masses(system):
    """The masses of ``system``'s particles (amu, a numpy array; 0 for a massless, fixed particle)."""
    return np.array([system.getParticleMass(i).value_in_unit(unit.amu) for i in range(system.getNumParticles())])


def strain_derivatives(context, groups, strains, step=VIRIAL_SCALING_STEP):
    """-dU/d epsilon (kJ/mol) of the energy U of force ``groups`` (a set of force group numbers) under each strain D of
    ``strains`` (3 x 3 arrays): positions and periodic box deformed by I + epsilon D, by central differences at
    epsilon = +-``step`` (two energy evaluations per strain, error O(step^2)); a list, one per strain. The Context's
    positions and box are restored exactly afterwards (a GenDPDEIntegrator treats that as a move:
    docs/integrator.md). The one numerical strain derivative of the package: numerical_virial and
    pressure.numerical_virial_tensor."""
    state = context.getState(getPositions=True)
    positions = state.getPositions(asNumpy=True).value_in_unit(unit.nanometer)
    box = state.getPeriodicBoxVectors(asNumpy=True).value_in_unit(unit.nanometer)
    derivatives = []
    try:
        for strain in strains:
            energies = []
            for epsilon in (step, -step):
                deformation = (np.eye(3) + epsilon * np.asarray(strain, dtype=float)).T
                context.setPeriodicBoxVectors(*(box @ deformation))
                context.setPositions(positions @ deformation)
                energies.append(context.getState(getEnergy=True, groups=groups).getPotentialEnergy()
                                .value_in_unit(_ENERGY))
            derivatives.append(-(energies[0] - energies[1]) / (2 * step))
    finally:
        context.setPeriodicBoxVectors(*box)
        context.setPositions(positions)
    return derivatives


def numerical_virial(context, groups):
    """W = -dU/dlambda (kJ/mol) of the energy of force ``groups`` under a uniform scaling of the positions and the
    periodic box by lambda, by a central difference at lambda = 1 +- VIRIAL_SCALING_STEP (strain_derivatives with the
    strain I; error O(step^2)). The Context's positions and box are restored exactly."""
    return strain_derivatives(context, groups, [np.eye(3)])[0]


def integration_groups(integrator):
    """The force groups (a set) whose forces ``integrator`` integrates (Integrator.getIntegrationForceGroups, a bit
    mask, -1 for every group; or a set)."""
    groups = integrator.getIntegrationForceGroups()
    if isinstance(groups, (set, frozenset)):
        return set(groups)
    return {group for group in range(32) if groups >> group & 1}


def particle_temperature_means(integrator):
    """(mean, harmonic mean) of the particle temperatures theta_i (K, floats) of a GenDPDEIntegrator bound to a
    Context; (nan, nan) for any other integrator. The harmonic mean <1/theta_i>^-1 is the thermodynamic temperature
    (docs/theory.md section 8)."""
    gendpde = _as_gendpde_integrator(integrator)
    if gendpde is None:
        return _NAN, _NAN
    theta = gendpde.getParticleTemperatures().value_in_unit(_K)
    return float(np.mean(theta)), harmonic_temperature(theta)


def conserved_energy(integrator):
    """K + U + sum eps_i (kJ/mol, a float: GenDPDEIntegrator.getConservedEnergy, U of the integration force groups)
    of a GenDPDEIntegrator bound to a Context; nan for any other integrator. With a body force its group's energy is
    in U (models.flows says what that energy means)."""
    gendpde = _as_gendpde_integrator(integrator)
    return _NAN if gendpde is None else float(gendpde.getConservedEnergy().value_in_unit(_ENERGY))


def harmonic_temperature(temperatures):
    """<1/theta_i>^-1 (K, a float) of the particle temperatures ``temperatures`` (K: an array, or a Quantity such
    as GenDPDEIntegrator.getParticleTemperatures()): the thermodynamic temperature of the particles, which equals the
    kinetic one in equilibrium (the arithmetic mean is biased high by 1 + k_B/C_V; docs/theory.md section 8)."""
    if unit.is_quantity(temperatures):
        temperatures = temperatures.value_in_unit(_K)
    return float(1 / np.mean(1 / np.asarray(temperatures, dtype=float)))


def ensemble_temperature(context, integrator):
    """The temperature (K, a float) of the ensemble that the liquid in ``context`` samples now, the one a Monte Carlo
    barostat's acceptance should use: with a GenDPDEIntegrator in its Isothermal mode (or any other integrator that
    has getTemperature(), a thermostat) the bath's; in its Isoenergetic mode the liquid's own, the harmonic mean of
    theta_i (its motion and internal energies are one closed system, whose temperature it is: the kinetic
    temperature equals it in equilibrium, and it is the precise one of the two); in its Conservative mode, where the
    internal energies exchange nothing, the kinetic temperature of the motion (centre-of-mass frame, 3N - 3).
    ValueError for an integrator of neither kind."""
    gendpde = _as_gendpde_integrator(integrator)
    if gendpde is not None:
        mode = gendpde.getMode()
        if mode == GenDPDEIntegrator.Isoenergetic:
            return harmonic_temperature(gendpde.getParticleTemperatures())
        if mode == GenDPDEIntegrator.Conservative:
            state = context.getState(getEnergy=True, getVelocities=True)
            return ThermodynamicProbe(context.getSystem()).kinetic_temperature(state, context, gendpde)
        return gendpde.getTemperature().value_in_unit(_K)
    if callable(getattr(integrator, "getTemperature", None)):
        return integrator.getTemperature().value_in_unit(_K)
    raise ValueError(f"integrator = a {type(integrator).__name__} is not allowed; the temperature of its ensemble is "
                     f"known for a GenDPDEIntegrator or an integrator with a thermostat (getTemperature)")


def _as_gendpde_integrator(integrator):
    if isinstance(integrator, GenDPDEIntegrator):
        return integrator
    if GenDPDEIntegrator.isinstance(integrator):
        return GenDPDEIntegrator.cast(integrator)
    return None


def is_nan(quantity):
    return math.isnan(quantity.value_in_unit(quantity.unit))


def self_diffusion(times, positions, groups=10, lags=10):
    """The self-diffusion coefficient D (nm^2/ps) and its standard error from unwrapped positions (frames x N x 3,
    nm; a State's positions are unwrapped unless enforcePeriodicBox) at ``times`` (ps, evenly spaced): the slope of
    the mean square displacement, 6 D, fitted over ``lags`` lags from a quarter to half of the run (the diffusive
    regime, every time origin used), the system's centre of mass removed (equal masses). The error is the scatter
    of D over ``groups`` groups of particles (each particle's displacement is nearly independent of the others')."""
    times = np.asarray(times, dtype=float)
    x = np.asarray(positions, dtype=float)
    x = x - x.mean(axis=1, keepdims=True)
    frames = len(times)
    if frames < 8:
        raise ValueError(f"self_diffusion: {frames} frames; at least 8 are needed")
    steps = np.unique(np.linspace(frames // 4, frames // 2, lags).astype(int))
    members = np.array_split(np.arange(x.shape[1]), groups)
    msd = np.array([[np.mean(np.sum((x[lag:, m] - x[:-lag, m]) ** 2, axis=2)) for m in members] for lag in steps])
    lag_times = times[steps] - times[0]
    slopes = np.polyfit(lag_times, msd, 1)[0]
    values = slopes / 6
    return float(values.mean()), float(values.std(ddof=1) / np.sqrt(groups))


def configurational_heat_capacity(potential_energies, temperature, bath_heat_capacity):
    """The configurational heat capacity C_U = d<U>/dT at fixed volume (kJ/mol/K, whole system) of an Isoenergetic
    GenDPDE run from the fluctuation of its potential energy U: (C_U, its standard error, the independent samples
    N/g the error rests on).

    ``potential_energies``: a time series of U (kJ/mol) in equilibrium; ``temperature`` (K): its harmonic-mean
    temperature; ``bath_heat_capacity`` (kJ/mol/K): the heat capacity of what U exchanges energy with at fixed total
    energy, the kinetic energy and the internal energies: (3N - 3) k_B/2 + N (C_V + k_B) (each eps_i/(k_B T) follows
    a Gamma law of shape C_V/k_B + 1, docs/theory.md section 8). In the Isoenergetic mode the configurations are
    distributed as Omega_U(U) (E - U)^(D - 1) with D k_B that heat capacity, so U fluctuates as a system in contact
    with a finite bath: <dU^2> = k_B T^2 C_U C_B/(C_U + C_B) (Lebowitz, Percus and Verlet 1967), which this inverts:
    C_U = X C_B/(C_B - X), X = <dU^2>/(k_B T^2). For a bath much larger than C_U this is the canonical
    <dU^2>/(k_B T^2). The variance's error is that of the mean of the squared deviations (correlated_mean)."""
    energies = np.asarray(potential_energies, dtype=float)
    kb = BOLTZMANN.value_in_unit(_ENERGY / _K)
    squares = correlated_mean((energies - energies.mean()) ** 2)
    scale = 1 / (kb * temperature**2)
    x, x_error = squares.mean * scale, squares.standard_error * scale
    if not 0 <= x < bath_heat_capacity:
        raise ValueError(f"configurational_heat_capacity: <dU^2>/(k_B T^2) = {x:.4g} kJ/mol/K is not below the bath's "
                         f"heat capacity {bath_heat_capacity:.4g} kJ/mol/K: not an equilibrium Isoenergetic run")
    value = x * bath_heat_capacity / (bath_heat_capacity - x)
    error = x_error * bath_heat_capacity**2 / (bath_heat_capacity - x) ** 2
    return value, error, squares.independent_samples


def bath_heat_capacity(num_particles, internal_heat_capacity):
    """(3N - 3) k_B/2 + N (C_V + k_B) (kJ/mol/K): the heat capacity of the kinetic and internal energies of N
    particles of heat capacity C_V (``internal_heat_capacity``, kJ/mol/K) each, in the Isoenergetic mode."""
    kb = BOLTZMANN.value_in_unit(_ENERGY / _K)
    return (3 * num_particles - 3) * kb / 2 + num_particles * (internal_heat_capacity + kb)


def heat_capacity_per_particle(internal_heat_capacity, configurational=0.0):
    """The isochoric heat capacity per particle (kJ/mol/K) of a GenDPDE fluid whose conservative energy does not
    depend on the temperatures (Tait): C_V + k_B (each eps_i/(k_B T) follows a Gamma law of shape C_V/k_B + 1,
    docs/theory.md section 8) + 3 k_B/2 (the motion) + c_U (``configurational``, per particle: the configurations
    follow T; configurational_heat_capacity measures it, 0.4 k_B for argon, 0.06 k_B for water as calibrate maps
    them). ``internal_heat_capacity``: C_V (kJ/mol/K)."""
    kb = BOLTZMANN.value_in_unit(_ENERGY / _K)
    return internal_heat_capacity + 2.5 * kb + configurational


def adiabatic_bulk_modulus(density, temperature, bulk_modulus, thermal_pressure, heat_capacity):
    """K_S = n (dP/dn)_s of a fluid at number density n (``density``, nm^-3) and T (K) from its isothermal
    K_T = n (dP/dn)_T (``bulk_modulus``, kJ/mol/nm^3), its thermal pressure coefficient (dP/dT)_n
    (``thermal_pressure``, kJ/mol/nm^3/K) and its isochoric heat capacity per particle c_v (``heat_capacity``,
    kJ/mol/K): K_S = K_T + T (dP/dT)_n^2/(n c_v). (At fixed entropy per particle, ds = c_v dT/T + (dP/dT)_n d(1/n)
    by a Maxwell relation, so (dT/dn)_s = T (dP/dT)_n/(n^2 c_v), and (dP/dn)_s = (dP/dn)_T + (dP/dT)_n (dT/dn)_s.)
    The speed of sound is sqrt(K_S/rho)."""
    return bulk_modulus + temperature * thermal_pressure**2 / (density * heat_capacity)
