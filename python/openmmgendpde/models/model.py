# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""The model of the package and its one builder: ModelParameters holds every parameter of a one-type GenDPDE model
(its GenDPDEForce, with the local equation of state as a law of the table and its parameters, and its
GenDPDEIntegrator) and builds it whole (build: a System holding one GenDPDEForce, its GenDPDEIntegrator, a Topology
and positions); Model is what it builds, and makes every Context of it (context, simulation), brought to
equilibrium one way (equilibrate, with an Equilibration protocol). The published liquid argon (argon.liquid_argon)
and any fluid (fluid.GenDPDEParameters.liquid) are built here."""

import dataclasses
import numbers
import warnings

import numpy as np
import openmm
from openmm import app, unit

from ..api import LAWS, GenDPDEForce, GenDPDEIntegrator, law_value
from ..units import BOLTZMANN
from . import laws, melting
from .lattice import box_volume

#: The names of a model's particles in its Topology (atom, element, residue), for PDB files and viewers.
PARTICLE_NAMES = ("CG", None, "CG")
#: The residue name of a chain's beads in a model's Topology (ModelParameters.build's ``chains``), one bead a residue.
MONOMER_RESIDUE = "MON"
#: Boltzmann's constant in kJ/mol/K.
_KB = BOLTZMANN.value_in_unit(unit.kilojoule_per_mole / unit.kelvin)


@dataclasses.dataclass(frozen=True, kw_only=True)
class ModelParameters:
    """Every parameter of a GenDPDE model of one particle type, as plain floats in OpenMM units (nm, amu, ps, kJ/mol,
    K). The GenDPDEForce: the cutoff R, f_cut, the Tait parameters n0 (``density``), pi0, B_T, gamma_T, the local
    equation of state ``law`` (a GenDPDEForce.EquationOfState value) with ``law_parameters`` in the order of the table
    of laws (api.LAWS; () for Tait) and the background pressure p_b (None: none). The GenDPDEIntegrator: friction
    gamma, heat conduction kappa, heat capacity C_V per particle and bath temperature T0. And the particle mass.

    A law that extends Tait adds its parameters to the Tait parameters; any other ignores them in the force, and they
    are its tangent at n0: its pressure pi0 and modulus gamma_T B_T there (models.laws). replace() keeps that so, and
    with_thermal_pressure() and with_law() fit the law's parameters to it, for any law of the table."""
    mass: float                   # amu, one particle
    temperature: float            # K, T0
    density: float                # nm^-3, n0
    reference_pressure: float     # kJ/mol/nm^3, pi0
    bulk_modulus: float           # kJ/mol/nm^3, B_T
    tait_exponent: float          # gamma_T
    cutoff: float                 # nm, R
    cutoff_scaling: float         # f_cut of the estimators that read it (V-B, V-C)
    friction: float               # amu/ps, gamma
    heat_conduction: float        # kJ K/(mol ps), kappa
    heat_capacity: float          # kJ/mol/K, C_V per particle
    law: int = GenDPDEForce.Tait  # the local equation of state (GenDPDEForce.EquationOfState)
    law_parameters: tuple = ()    # its own parameters (api.LAWS[law].parameters), OpenMM units
    background_pressure: float = None   # kJ/mol/nm^3, p_b of GenDPDEForce (None: none)

    def __post_init__(self):
        object.__setattr__(self, "law", law_value(self.law))
        object.__setattr__(self, "law_parameters", tuple(float(value) for value in self.law_parameters))

    @property
    def tait(self):
        """The Tait parameters (n0, pi0, B_T, gamma_T)."""
        return self.density, self.reference_pressure, self.bulk_modulus, self.tait_exponent

    @property
    def equation_of_state(self):
        """The law's name, as the table of laws spells it (api.LAW_NAMES)."""
        return LAWS[self.law].name

    @property
    def particle_temperature(self):
        """theta_r = T0 (1 + k_B/C_V) (K): the particles' mean temperature at T0, where a law that depends on
        temperature gives its pressure (docs/theory.md section 11)."""
        return self.temperature * (1 + _KB / self.heat_capacity)

    @property
    def thermal_pressure(self):
        """dpi/dtheta of the law at n0 (kJ/mol/nm^3/K; beta of TaitThermalExpansion); None for a law without
        parameters of its own (Tait)."""
        if not self.law_parameters:
            return None
        return laws.pressure(self.law, self.law_parameters, self.tait, self.density, 0.0)[1]

    @property
    def thermal_reference_temperature(self):
        """The particle temperature (K) at which the law gives pi0 at n0 (theta0 of TaitThermalExpansion; the theta_r
        another law was fitted at); None for a law whose pressure does not depend on temperature."""
        if not self.law_parameters:
            return None
        return laws.reference_temperature(self.law, self.law_parameters, self.tait, self.density)

    def reference_state(self, thermal_pressure=None, temperature=None):
        """The laws.ReferenceState that the law is fitted to: pi0 and gamma_T B_T at n0, at the particle temperature
        ``temperature`` (default: the law's own reference temperature, else particle_temperature) with the thermal
        pressure ``thermal_pressure`` (default: the law's)."""
        if temperature is None:
            temperature = self.thermal_reference_temperature or self.particle_temperature
        if thermal_pressure is None:
            thermal_pressure = self.thermal_pressure or 0.0
        return laws.ReferenceState(self.density, temperature, self.reference_pressure,
                                   self.tait_exponent * self.bulk_modulus, thermal_pressure)

    def replace(self, **changes):
        """dataclasses.replace, keeping the law on its reference state. Where n0, pi0, B_T or gamma_T change and the
        law does not extend Tait, its parameters are fitted again (laws.fit) to give the new pi0 and gamma_T B_T at
        n0 with the thermal pressure and reference temperature it had: the calibration's handles (pi0, B_T) act so on
        every law. Where C_V changes, a law that depends on temperature is fitted again at the new particle
        temperature T0 (1 + k_B/C_V), where the particles' mean temperature now is (the thermal Tait law's theta0
        follows, as the mapping defines it), with the pi0, modulus and thermal pressure it had, so that the pressure at
        T0 stays."""
        changed = dataclasses.replace(self, **changes)
        if not self.law_parameters or {"law", "law_parameters"} & set(changes):
            return changed
        temperature = self.thermal_reference_temperature
        if "heat_capacity" in changes and self.thermal_pressure:
            temperature = changed.particle_temperature
        elif LAWS[self.law].extends_tait or not {"density", "reference_pressure", "bulk_modulus",
                                                 "tait_exponent"} & set(changes):
            return changed
        state = changed.reference_state(self.thermal_pressure, temperature)
        return dataclasses.replace(changed, law_parameters=laws.fit(self.law, changed.tait, state,
                                                                    self.law_parameters))

    def with_thermal_pressure(self, thermal_pressure):
        """The parameters with the law's dpi/dtheta at n0 = ``thermal_pressure`` (kJ/mol/nm^3/K), its pressure and
        modulus there kept (laws.fit; beta of TaitThermalExpansion, theta0 kept)."""
        if not self.law_parameters:
            raise ValueError(f"thermal_pressure = {thermal_pressure} is not allowed for the law "
                             f"{self.equation_of_state}: it has no parameters of its own")
        return dataclasses.replace(self, law_parameters=laws.fit(self.law, self.tait, self.reference_state(
            thermal_pressure), self.law_parameters))

    def with_law(self, law, law_parameters=None, thermal_pressure=None):
        """The parameters with the local equation of state ``law`` (its name or GenDPDEForce.EquationOfState value):
        with ``law_parameters`` as given, or fitted (laws.fit) to pi0 and gamma_T B_T at n0 and the particle
        temperature and to ``thermal_pressure`` (default: the law's now; needed for a law with parameters of its
        own where the current law has none)."""
        law = law_value(law)
        if law_parameters is None:
            if not LAWS[law].parameters:
                law_parameters = ()
            else:
                if thermal_pressure is None and self.thermal_pressure is None:
                    raise ValueError(f"the law {LAWS[law].name} needs a thermal pressure dpi/dtheta to be fitted to "
                                     f"(thermal_pressure, kJ/mol/nm^3/K; the mapping takes it from the fluid's "
                                     f"thermal_expansion)")
                state = self.reference_state(thermal_pressure, self.particle_temperature)
                law_parameters = laws.fit(law, self.tait, state)
        return dataclasses.replace(self, law=law, law_parameters=tuple(law_parameters))

    def _force(self, estimator):
        force = GenDPDEForce(self.cutoff)
        force.setDensityEstimator(estimator)
        force.setCutoffScaling(self.cutoff_scaling)
        force.setTaitParameters(*self.tait)
        if self.background_pressure is not None:
            force.setBackgroundPressure(self.background_pressure)
        if self.law != GenDPDEForce.Tait or self.law_parameters:
            force.setEquationOfState(self.law, list(self.law_parameters))
        return force

    def _integrator(self, step_size, seed, mode):
        integrator = GenDPDEIntegrator(step_size, self.friction, self.heat_conduction, self.heat_capacity)
        integrator.setTemperature(self.temperature)
        integrator.setRandomNumberSeed(seed)
        integrator.setMode(mode)
        return integrator

    def build(self, box, positions, estimator, step_size, seed=0, mode=GenDPDEIntegrator.Isoenergetic,
              names=PARTICLE_NAMES, model_type=None, chains=(), **fields):
        """The model (``model_type``, default Model, with ``fields``) of these parameters: a System of len(positions)
        particles in the periodic ``box`` (three rows, nm) with one GenDPDEForce of ``estimator`` (a
        GenDPDEForce.DensityEstimator value) and a GenDPDEIntegrator of step ``step_size`` (ps, or a Quantity),
        random seed ``seed`` (0: chosen when a Context is made) and ``mode``, a Topology whose particles are named
        ``names`` (atom, element, residue), and the ``positions`` (nm, N x 3). ``chains``: the lengths of the chains
        that the first particles form, in order (models.polymers); each is a chain of the Topology, one residue
        MONOMER_RESIDUE per bead and a Topology bond between consecutive beads (the System's bonded forces are the
        caller's); the other particles follow in one chain, one residue each. The force holds a reference to the
        System, which owns it, so that it stays valid as long as it is used."""
        bonded = sum(int(length) for length in chains)
        if bonded > len(positions) or any(int(length) < 1 for length in chains):
            raise ValueError(f"chains = {list(chains)} is not allowed: each length must be >= 1 and together at most "
                             f"the {len(positions)} particles")
        box = [openmm.Vec3(*(float(x) for x in row)) for row in box]
        system = openmm.System()
        system.setDefaultPeriodicBoxVectors(*box)
        for _ in range(len(positions)):
            system.addParticle(self.mass)
        force = self._force(estimator)
        system.addForce(force)
        force._system = system   # the System owns the C++ force (addForce): the force, once returned, keeps it alive
        integrator = self._integrator(step_size, seed, mode)
        atom, element, residue = names
        topology = app.Topology()
        for length in chains:
            chain = topology.addChain()
            beads = [topology.addAtom(atom, element, topology.addResidue(MONOMER_RESIDUE, chain))
                     for _ in range(int(length))]
            for first, second in zip(beads[:-1], beads[1:]):
                topology.addBond(first, second)
        chain = topology.addChain() if len(positions) > bonded else None
        for _ in range(len(positions) - bonded):
            topology.addAtom(atom, element, topology.addResidue(residue, chain))
        topology.setPeriodicBoxVectors(unit.Quantity(box, unit.nanometer))   # as PDBFile and PDBReporter expect
        return (model_type or Model)(system, force, integrator, topology, np.asarray(positions), self, **fields)


@dataclasses.dataclass(frozen=True)
class Equilibration:
    """How a model leaves its lattice: ``thermostat_steps`` steps with the DPD thermostat (Isothermal) at
    ``temperature`` (K; None: the model's T0), velocities and internal energies drawn with ``seed``, then ``mode``
    and ``settle_steps`` steps in it (the exchange between the motion and the internal energies settles).

    With ``temperature_window`` > 0 (the Isoenergetic mode only) the liquid is then brought to that temperature
    (melting.bring_to_temperature: windows of ``temperature_window`` steps sampled every ``sample_interval``, the
    thermal energies scaled until the harmonic mean of theta_i and the kinetic temperature are within ``tolerance``
    standard errors of it, at most ``max_corrections`` times): without it an Isoenergetic liquid settles where the
    energy it had at the switch puts it, off T0 by a draw whose standard deviation is 1.4 K for 500 particles of argon
    and 2.1 K for water (docs/fluids.md, "A liquid ready to run").
    READY_LIQUID is such a protocol. Bad values raise ValueError naming the field when it is made."""
    thermostat_steps: int
    settle_steps: int = 0
    mode: int = GenDPDEIntegrator.Isoenergetic
    temperature: float = None
    seed: int = 0
    temperature_window: int = 0
    sample_interval: int = 20
    tolerance: float = 2.0
    max_corrections: int = 4

    def __post_init__(self):
        for name in ("thermostat_steps", "settle_steps", "temperature_window"):
            value = getattr(self, name)
            if isinstance(value, bool) or not isinstance(value, numbers.Integral) or value < 0:
                raise ValueError(f"Equilibration: {name} = {value!r} is not allowed; it must be an integer >= 0")
        if self.temperature_window:
            if self.mode != GenDPDEIntegrator.Isoenergetic:
                raise ValueError(f"Equilibration: temperature_window = {self.temperature_window} is not allowed with "
                                 f"mode = {self.mode}; only an Isoenergetic liquid (mode "
                                 f"{GenDPDEIntegrator.Isoenergetic}) is brought to the temperature (the Isothermal "
                                 f"thermostat keeps its bath's); use temperature_window = 0")
            melting.check_window(self.temperature_window, self.sample_interval, self.tolerance,
                                 self.max_corrections)


#: A liquid ready to run at T0 (Model.simulation(..., equilibration=READY_LIQUID), Model.equilibrate): 3000 steps
#: with the DPD thermostat (30 time units at the models' default step dt* = 0.01: water's particle densities need
#: ~25 to reach their plateau, docs/fluids.md), the thermal energies put at their mean at T0, 500 Isoenergetic
#: steps, then windows of 2000 steps until the harmonic mean of theta_i and the kinetic temperature are within 2
#: standard errors of T0 (for 500 particles of argon ~0.1 K and ~0.4 K).
READY_LIQUID = Equilibration(3000, 500, temperature_window=2000)


@dataclasses.dataclass
class Model:
    """A ready model in OpenMM units (nm, amu, ps, kJ/mol, K): its System (one GenDPDEForce), GenDPDEIntegrator (bath
    temperature T0), Topology, positions (nm, N x 3) and the ModelParameters it was built from. Every Context of a
    model is made by context() or simulation()."""
    system: openmm.System
    force: GenDPDEForce
    integrator: GenDPDEIntegrator
    topology: app.Topology
    positions: np.ndarray
    parameters: ModelParameters = None
    #: The melting.LiquidTemperatures of the last equilibration that brought the liquid to its temperature
    #: (equilibrate or simulation with an Equilibration whose temperature_window > 0); None before.
    equilibration_report: melting.LiquidTemperatures = dataclasses.field(default=None, repr=False, compare=False,
                                                                         kw_only=True)

    @property
    def num_particles(self):
        return self.system.getNumParticles()

    @property
    def volume(self):
        """The box's volume (nm^3)."""
        return box_volume(self.system)

    @property
    def box_edges(self):
        """The edges of the System's default (rectangular) periodic box, nm (a numpy array of 3)."""
        vectors = self.system.getDefaultPeriodicBoxVectors()
        return np.array([vectors[k][k].value_in_unit(unit.nanometer) for k in range(3)])

    @property
    def bath_temperature(self):
        """T0 (K, a float), at which the model was built (equilibrate() may move the integrator's bath)."""
        if self.parameters is not None:
            return self.parameters.temperature
        return self.integrator.getTemperature().value_in_unit(unit.kelvin)

    def add_barostat(self, pressure, frequency=25, seed=0):
        """Add an openmm.MonteCarloBarostat at ``pressure`` (a Quantity, or bar) and the model's T0, trying a volume
        move every ``frequency`` steps with random seed ``seed`` (0: chosen when a Context is made), to the System,
        and return it; before a Context of the model is made. Its
        temperature is T0, that of the Isothermal mode's bath; in the Isoenergetic mode the liquid is at its own
        temperature, which BarostatTemperatureReporter (or its setTemperature, for a Context) keeps the
        barostat at (docs/fluids.md, "A barostat at the liquid's temperature"). Bad arguments raise ValueError
        naming the argument, its value and what is allowed, before the System changes."""
        value = pressure.value_in_unit(unit.bar) if unit.is_quantity(pressure) and \
            pressure.unit.is_compatible(unit.bar) else pressure
        if isinstance(value, bool) or not isinstance(value, numbers.Real) or not np.isfinite(value):
            raise ValueError(f"add_barostat: pressure = {pressure!r} is not allowed; it must be a finite pressure (a "
                             f"Quantity, or bar)")
        if isinstance(frequency, bool) or not isinstance(frequency, numbers.Integral) or frequency < 1:
            raise ValueError(f"add_barostat: frequency = {frequency!r} is not allowed; it must be an integer >= 1 "
                             f"(steps between volume moves)")
        if isinstance(seed, bool) or not isinstance(seed, numbers.Integral) or not 0 <= seed < 2**31:
            raise ValueError(f"add_barostat: seed = {seed!r} is not allowed; it must be an integer in [0, 2^31)")
        barostat = openmm.MonteCarloBarostat(float(value) * unit.bar, self.bath_temperature * unit.kelvin,
                                             int(frequency))
        barostat.setRandomNumberSeed(int(seed))
        self.system.addForce(barostat)
        barostat._system = self.system   # the System owns the C++ barostat (addForce), as for the model's force
        return barostat

    def context(self, platform="Reference", temperature=None, seed=1, properties=None, positions=None,
                integrator=None, velocities=True):
        """An openmm.Context of the model (``platform``: an openmm.Platform or its name, with ``properties``) and its
        integrator (or ``integrator``), at its positions (or ``positions``, nm), with velocities drawn at
        ``temperature`` (K; default T0) with ``seed`` unless ``velocities`` is False."""
        if isinstance(platform, str):
            platform = openmm.Platform.getPlatformByName(platform)
        integrator = self.integrator if integrator is None else integrator
        context = (openmm.Context(self.system, integrator, platform) if properties is None
                   else openmm.Context(self.system, integrator, platform, properties))
        context.setPositions(self.positions if positions is None else positions)
        if velocities:
            context.setVelocitiesToTemperature((self.bath_temperature if temperature is None else temperature)
                                               * unit.kelvin, seed)
        return context

    def simulation(self, platform="Reference", velocity_seed=1, properties=None, equilibration=None):
        """An openmm.app.Simulation of the model (``platform``: its name, with ``properties``). Without
        ``equilibration``: at its lattice positions, with Maxwell-Boltzmann velocities at T0 drawn with
        ``velocity_seed``. With an Equilibration (e.g. READY_LIQUID): velocities drawn at its temperature, then
        brought off the lattice by it as equilibrate() does (its Context's step count and time then count those
        steps), so that the Simulation holds a liquid ready to run; the temperatures reached are in
        equilibration_report."""
        temperature = self._equilibration_temperature(equilibration)
        simulation = app.Simulation(self.topology, self.system, self.integrator,
                                    openmm.Platform.getPlatformByName(platform), properties)
        simulation.context.setPositions(self.positions)
        simulation.context.setVelocitiesToTemperature(temperature * unit.kelvin, velocity_seed)
        if equilibration is not None:
            self._leave_lattice(simulation.context, equilibration, temperature)
        return simulation

    def wrapped_positions(self, context):
        """The positions of ``context`` (a Context of the model) in nm, N x 3, wrapped into the box (box_edges)."""
        x = context.getState(getPositions=True).getPositions(asNumpy=True).value_in_unit(unit.nanometer)
        box = self.box_edges
        return x - np.floor(x / box) * box

    def equilibrate(self, platform, protocol, properties=None):
        """A Context of the model brought off its lattice by ``protocol`` (an Equilibration): the integrator's bath at
        its temperature, velocities drawn at it, its thermostat steps, then its mode with the internal energies drawn
        at that temperature (melting.melt_then_switch) and its settle steps; with its temperature_window, the thermal
        energies put at their mean at that temperature after the draw and the liquid then brought to it
        (melting.melt_to_temperature; the temperatures reached are in equilibration_report, and a RuntimeWarning says
        so if they are not within its tolerance)."""
        temperature = self._equilibration_temperature(protocol)
        context = self.context(platform, temperature, protocol.seed, properties)
        self._leave_lattice(context, protocol, temperature)
        return context

    def _equilibration_temperature(self, protocol):
        """The temperature (K) of ``protocol`` (an Equilibration, or None: T0); with a protocol the integrator is put
        in the Isothermal mode with its bath there. ValueError if ``protocol`` is not an Equilibration."""
        if protocol is None:
            return self.bath_temperature
        if not isinstance(protocol, Equilibration):
            raise ValueError(f"equilibration = {protocol!r} is not allowed; it must be an Equilibration (e.g. "
                             f"READY_LIQUID) or None")
        temperature = self.bath_temperature if protocol.temperature is None else protocol.temperature
        self.integrator.setMode(GenDPDEIntegrator.Isothermal)
        self.integrator.setTemperature(temperature)
        return temperature

    def _leave_lattice(self, context, protocol, temperature):
        """The steps of ``protocol`` (an Equilibration) on ``context`` (a Context of the model) at ``temperature``."""
        integrator = self.integrator
        if not protocol.temperature_window:
            melting.melt_then_switch(integrator, protocol.thermostat_steps, temperature, protocol.seed, protocol.mode)
            integrator.step(protocol.settle_steps)
        else:
            report = melting.melt_to_temperature(context, integrator, protocol.thermostat_steps, temperature,
                                                 protocol.seed, protocol.settle_steps, protocol.temperature_window,
                                                 protocol.sample_interval, protocol.tolerance,
                                                 protocol.max_corrections)
            self.equilibration_report = report
            if not report.converged:
                warnings.warn(f"the liquid did not reach its temperature within {protocol.max_corrections} "
                              f"corrections: {report}; run longer windows (temperature_window) or more corrections",
                              RuntimeWarning, stacklevel=3)

    def melted(self, platform, mode, melt_steps, settle_steps, temperature=None, seed=0):
        """equilibrate(platform, Equilibration(melt_steps, settle_steps, mode, temperature, seed))."""
        return self.equilibrate(platform, Equilibration(melt_steps, settle_steps, mode, temperature, seed))


def set_temperature_field(integrator, positions, temperature):
    """Set every particle's internal temperature theta_i = temperature(r_i) (K; r_i in nm, a row of ``positions``,
    e.g. State.getPositions(asNumpy=True) or a plain N x 3 array): a temperature field, such as two regions at two
    temperatures for a heat-conduction study. The integrator must be bound to its Context."""
    if unit.is_quantity(positions):
        positions = positions.value_in_unit(unit.nanometer)
    values = []
    for r in np.asarray(positions, dtype=float):
        t = temperature(r)
        t = t.value_in_unit(unit.kelvin) if unit.is_quantity(t) else float(t)
        values.append(t)
    integrator.setParticleTemperatures(values)
