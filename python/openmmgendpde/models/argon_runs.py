# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""Liquid-argon runs as in Colella et al. (J. Chem. Theory Comput. 2025): the protocol shared by the studies of
the command line (table3, rdf, timing, tune-fcut, speed-vs-error).

A run starts from the FCC lattice at n0* = 1 with Maxwell-Boltzmann velocities at T0 (openmmgendpde.models.argon) and
goes through three phases:

1. ``thermostat_time`` with the DPD thermostat at T0 (Isothermal mode): the lattice melts and, with VA, the
   particles clump into pairs; the free energy they release goes to the bath. (Starting isoenergetic from the
   lattice instead heats the VA system to T* ~ 0.016 at R* = 1.3365, because n_i on the lattice is far from its
   liquid value.)
2. The internal energies are drawn from their equilibrium Gamma law at T0
   (GenDPDEIntegrator.setInternalEnergiesToTemperature; theta_i = T0 for all would leave them k_B T0 per particle
   short of equilibrium, i.e. ~7% too cold), then ``equilibration_time`` of full isoenergetic GenDPDE.
3. ``production_time`` of isoenergetic GenDPDE, sampled every ``sample_interval``.

All times are in reduced units (the time unit is 0.8962 ps).
"""

import dataclasses
import time

import numpy as np
from openmm import app, unit

from ..analysis.thermodynamics import ThermodynamicProbe
from .argon import ARGON_UNITS, LiquidArgon, liquid_argon
from .melting import melt_then_switch


@dataclasses.dataclass(frozen=True)
class Protocol:
    """Sizes and lengths of a liquid-argon run (reduced units)."""
    num_particles: int = 4000
    time_step: float = 0.005
    thermostat_time: float = 20.0
    equilibration_time: float = 20.0
    production_time: float = 200.0
    sample_interval: float = 0.5
    seed: int = 1

    def steps(self, duration):
        return int(round(duration / self.time_step))

    @property
    def total_steps(self):
        return self.steps(self.thermostat_time) + self.steps(self.equilibration_time) + self.steps(self.production_time)


#: The published-comparison runs (docs/argon.md explains the choice).
FULL = Protocol()


#: A short version for CI and the main job: same phases, 500 particles, dt* = 0.01.
QUICK = Protocol(num_particles=500, time_step=0.01, thermostat_time=10.0, equilibration_time=10.0,
                 production_time=30.0, sample_interval=0.5)


@dataclasses.dataclass
class Samples:
    """Production samples in reduced units (openmmgendpde.analysis.thermodynamics defines each quantity)."""
    time: list = dataclasses.field(default_factory=list)
    kinetic_temperature: list = dataclasses.field(default_factory=list)   # 2K/((3N - 3) k_B), on-step velocities
    harmonic_temperature: list = dataclasses.field(default_factory=list)  # <1/theta_i>^-1
    mean_temperature: list = dataclasses.field(default_factory=list)      # <theta_i>
    density: list = dataclasses.field(default_factory=list)               # n-bar: mean of n_i = 1/V_i
    pressure: list = dataclasses.field(default_factory=list)              # (2K + W)/(3 V_box)
    conserved_energy: list = dataclasses.field(default_factory=list)      # K + U + sum eps
    frames: list = dataclasses.field(default_factory=list)                # positions (nm) for the RDF
    box_edge: float = 0.0                                                 # nm
    wall_time: float = 0.0                                                # s, production only
    steps: int = 0                                                        # production steps

    def append(self, sample, units=ARGON_UNITS):
        """Add a ThermodynamicSample (OpenMM units), converted to ``units``."""
        self.time.append(units.from_openmm(sample.time, "time"))
        self.kinetic_temperature.append(units.from_openmm(sample.kinetic_temperature, "temperature"))
        self.harmonic_temperature.append(units.from_openmm(sample.harmonic_temperature, "temperature"))
        self.mean_temperature.append(units.from_openmm(sample.mean_temperature, "temperature"))
        self.density.append(units.from_openmm(sample.density, "number_density"))
        self.pressure.append(units.from_openmm(sample.pressure, "pressure"))
        self.conserved_energy.append(units.from_openmm(sample.conserved_energy, "energy"))


@dataclasses.dataclass
class ArgonRun:
    """A finished run: its production samples, the model and the Simulation (which can be continued)."""
    samples: Samples
    argon: LiquidArgon
    simulation: app.Simulation


def melt_then_draw(argon, thermostat_steps, seed, step=None):
    """Phases 1 and the start of 2 of the protocol: ``thermostat_steps`` steps with the DPD thermostat at T0
    (Isothermal mode), then isoenergetic mode with the internal energies drawn from their equilibrium Gamma law at
    T0 (``setInternalEnergiesToTemperature(T0, seed)``). ``step(n)`` advances n steps: the integrator's own by
    default; pass e.g. ``Simulation.step`` (reporters, step count) or a stepper that reports progress."""
    melt_then_switch(argon.integrator, thermostat_steps, argon.temperature, seed, step=step)


def stepper(integrator, progress=None, chunk=200):
    """A function step(n) that advances ``integrator`` n steps in chunks of at most ``chunk`` steps, advancing
    ``progress`` (if given) after each chunk."""
    def step(steps):
        done = 0
        while done < steps:
            size = min(steps - done, chunk)
            integrator.step(size)
            done += size
            if progress is not None:
                progress.advance(size)
    return step


def run_argon(cutoff, estimator, protocol=FULL, platform="Reference", cutoff_scaling=None, frames=0, progress=None,
              continue_from=None):
    """Run the protocol for one cutoff R* and estimator ('VA' or 'VB'); return an ArgonRun.
    ``frames`` positions are kept, evenly spread over the production phase. ``progress`` (a Progress) advances by
    the number of steps done. ``continue_from`` = (LiquidArgon, Simulation) of an earlier run continues that run
    (equilibration and production only) instead of starting from the lattice."""
    if continue_from is None:
        argon = liquid_argon(protocol.num_particles, cutoff, estimator, cutoff_scaling, protocol.time_step,
                             seed=protocol.seed)
        simulation = argon.simulation(platform, velocity_seed=protocol.seed)
    else:
        argon, simulation = continue_from
    advance = stepper(argon.integrator, progress)
    if continue_from is None:
        melt_then_draw(argon, protocol.steps(protocol.thermostat_time), protocol.seed, advance)
    elif progress is not None:
        progress.advance(protocol.steps(protocol.thermostat_time))
    advance(protocol.steps(protocol.equilibration_time))
    return ArgonRun(production(argon, simulation, protocol, frames, advance), argon, simulation)


def production(argon, simulation, protocol, frames, advance):
    """Phase 3: ``protocol.production_time`` sampled every ``protocol.sample_interval``, keeping ``frames``
    positions evenly spread over it; ``advance(n)`` steps. Returns the Samples."""
    context = simulation.context
    samples = Samples(box_edge=argon.system.getDefaultPeriodicBoxVectors()[0][0].value_in_unit(unit.nanometer))
    probe = ThermodynamicProbe(argon.system)
    every = protocol.steps(protocol.sample_interval)
    count = protocol.steps(protocol.production_time) // every
    keep = set(np.linspace(0, count - 1, frames).round().astype(int)) if frames else set()
    start = time.perf_counter()
    for index in range(count):
        advance(every)
        state = context.getState(getEnergy=True, getVelocities=True, getPositions=index in keep)
        samples.append(probe.sample(state, context, argon.integrator))
        if index in keep:
            samples.frames.append(state.getPositions(asNumpy=True).value_in_unit(unit.nanometer))
    samples.wall_time = time.perf_counter() - start
    samples.steps = count * every
    return samples
