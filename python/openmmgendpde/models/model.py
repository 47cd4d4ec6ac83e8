"""The model of the package: a System holding one GenDPDEForce, its GenDPDEIntegrator, a Topology and lattice
positions, built for the published liquid argon (argon.LiquidArgon) or any fluid (fluid.FluidModel), and brought to
equilibrium one way (equilibrate, with an Equilibration protocol)."""

import dataclasses

import numpy as np
import openmm
from openmm import app, unit

from ..api import GenDPDEForce, GenDPDEIntegrator
from .lattice import box_volume
from .melting import melt_then_switch


@dataclasses.dataclass(frozen=True)
class Equilibration:
    """How a model leaves its lattice: ``thermostat_steps`` steps with the DPD thermostat (Isothermal) at
    ``temperature`` (K; None: the model's T0), velocities and internal energies drawn with ``seed``, then ``mode``
    and ``settle_steps`` steps in it (the exchange between the motion and the internal energies settles)."""
    thermostat_steps: int
    settle_steps: int = 0
    mode: int = GenDPDEIntegrator.Isoenergetic
    temperature: float = None
    seed: int = 0


@dataclasses.dataclass
class Model:
    """A ready model in OpenMM units (nm, amu, ps, kJ/mol, K): its System (one GenDPDEForce), GenDPDEIntegrator (bath
    temperature T0), Topology and lattice positions (nm, N x 3)."""
    system: openmm.System
    force: GenDPDEForce
    integrator: GenDPDEIntegrator
    topology: app.Topology
    positions: np.ndarray

    @property
    def num_particles(self):
        return self.system.getNumParticles()

    @property
    def volume(self):
        """The box's volume (nm^3)."""
        return box_volume(self.system)

    @property
    def bath_temperature(self):
        """T0 (K, a float), at which the model was built: the integrator's bath temperature here; the argon and fluid
        models give their own T0 (equilibrate() may move the bath)."""
        return self.integrator.getTemperature().value_in_unit(unit.kelvin)

    def context(self, platform="Reference", temperature=None, seed=1):
        """An openmm.Context of the model (``platform``: an openmm.Platform or its name) at the lattice positions,
        velocities drawn at ``temperature`` (K; default T0) with ``seed``."""
        if isinstance(platform, str):
            platform = openmm.Platform.getPlatformByName(platform)
        context = openmm.Context(self.system, self.integrator, platform)
        self._place(context, self.bath_temperature if temperature is None else temperature, seed)
        return context

    def simulation(self, platform="Reference", velocity_seed=1):
        """An openmm.app.Simulation of the model at the lattice positions, with Maxwell-Boltzmann velocities at T0
        (``platform``: its name)."""
        simulation = app.Simulation(self.topology, self.system, self.integrator,
                                    openmm.Platform.getPlatformByName(platform))
        self._place(simulation.context, self.bath_temperature, velocity_seed)
        return simulation

    def _place(self, context, temperature, seed):
        """The lattice positions, and Maxwell-Boltzmann velocities at ``temperature`` (K) drawn with ``seed``."""
        context.setPositions(self.positions)
        context.setVelocitiesToTemperature(temperature * unit.kelvin, seed)

    def equilibrate(self, platform, protocol):
        """A Context of the model brought off its lattice by ``protocol`` (an Equilibration): the integrator's bath at
        its temperature, velocities drawn at it, its thermostat steps, then its mode with the internal energies drawn
        at that temperature (melting.melt_then_switch) and its settle steps."""
        temperature = self.bath_temperature if protocol.temperature is None else protocol.temperature
        integrator = self.integrator
        integrator.setMode(GenDPDEIntegrator.Isothermal)
        integrator.setTemperature(temperature)
        context = self.context(platform, temperature, protocol.seed)
        melt_then_switch(integrator, protocol.thermostat_steps, temperature, protocol.seed, protocol.mode)
        integrator.step(protocol.settle_steps)
        return context

    def melted(self, platform, mode, melt_steps, settle_steps, temperature=None, seed=0):
        """equilibrate(platform, Equilibration(melt_steps, settle_steps, mode, temperature, seed))."""
        return self.equilibrate(platform, Equilibration(melt_steps, settle_steps, mode, temperature, seed))
