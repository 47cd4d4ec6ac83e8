# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""Cost of a GenDPDEIntegrator step against a force evaluation and against OpenMM's own integrators
(`benchmark-integrator`).

For each particle count, liquid argon at R* = 1.6839 (VB) is melted from its lattice and equilibrated at T0 with
the DPD thermostat (Isothermal mode, 20 time units, as the studies' protocol does); then, from that same state,
these candidates are timed in alternating rounds (openmmgendpde.benchmarks.measurement): a force evaluation alone
(Context.getState with energies), a step of each GenDPDEIntegrator mode, a step of OpenMM's VerletIntegrator with
the same force, and a step of OpenMM's DPDIntegrator with the same thermostat. The DPD comparison is made twice: on
the argon System (with its GenDPDEForce) and on the same particles with no force at all (plain DPD: each integrator
builds its own pair list), started in the equilibrium of a force-free DPD fluid: uniformly random positions and
the thermostatted velocities (from the liquid's positions, or the lattice, the ideal gas takes ~20 ps to forget
its structure, and its kinetic temperature drifts meanwhile). Ratios are medians of per-round ratios.

Same thermostat: DPDIntegrator damps a pair's relative velocity at the rate 2 f omega_R^2 (f in 1/ps), GenDPDE's
Isothermal mode at gamma omega_R^2 (1/m_i + 1/m_j); with equal masses m the two are the same dynamics for
f = gamma/m, with the same cutoff, temperature and step. After the timing, each thermostat's kinetic temperature
2K/((3N - 3) k_B) is sampled (its own definition of K, as a reporter would see it) and printed side by side.
"""

import dataclasses

import numpy as np
import openmm
from openmm import unit

from ..analysis.statistics import block_average
from ..api import GenDPDEIntegrator
from ..models.argon import DEFAULT_CUTOFF, liquid_argon
from ..units import BOLTZMANN
from .measurement import alternating_rounds, context_threads, default_rounds, median, median_ratio

#: The candidates whose kinetic temperature is sampled after the timing, and how: samples, steps between samples.
THERMOSTATS = ("Isothermal step", "DPDIntegrator step", "Isothermal step, no force", "DPDIntegrator step, no force")
TEMPERATURE_SAMPLES, STEPS_PER_SAMPLE, TEMPERATURE_BLOCKS = 100, 5, 10
#: Steps of the DPD thermostat that melt the lattice and equilibrate the liquid (20 time units at dt* = 0.01).
EQUILIBRATION_STEPS = 2000


@dataclasses.dataclass
class IntegratorBenchmark:
    num_particles: int
    cutoff: float
    platform: str
    threads: int                      # the CPU platform's Threads, 1 elsewhere
    milliseconds: dict                # candidate -> median ms per call (force evaluation or step)
    isoenergetic_over_force: float
    isothermal_over_force: float
    conservative_over_verlet: float
    isothermal_over_dpd: float                   # with the GenDPDEForce
    isothermal_over_dpd_without_force: float     # plain DPD
    bath_temperature: float                      # K
    kinetic_temperatures: dict                   # thermostatted candidate -> BlockAverage (K)
    rounds: int


def dpd_integrator(model):
    """OpenMM's DPDIntegrator with the thermostat of ``model``'s GenDPDEIntegrator in Isothermal mode: same bath
    temperature, cutoff and step, friction f = gamma/m (all particles of ``model`` have the same mass m)."""
    integrator = model.integrator
    mass = model.system.getParticleMass(0).value_in_unit(unit.amu)
    friction = integrator.getFriction().value_in_unit(unit.amu / unit.picosecond) / mass
    return openmm.DPDIntegrator(integrator.getTemperature(), friction / unit.picosecond,
                                model.force.getCutoffDistance(), integrator.getStepSize())


def without_forces(system):
    """A copy of ``system`` with its particles and box but no force, still periodic: a CustomExternalForce that
    acts on no particle marks it so (both integrators then apply periodic boundaries) at no cost."""
    bare = openmm.System()
    bare.setDefaultPeriodicBoxVectors(*system.getDefaultPeriodicBoxVectors())
    for i in range(system.getNumParticles()):
        bare.addParticle(system.getParticleMass(i))
    bare.addForce(openmm.CustomExternalForce("0*periodicdistance(x, y, z, 0, 0, 0)"))
    return bare


def kinetic_temperature(context, integrator, samples, steps_per_sample, name="kinetic temperature"):
    """BlockAverage (mean, standard error; K) of 2K/((3N - 3) k_B) over ``samples`` samples ``steps_per_sample``
    steps apart."""
    dof = 3 * context.getSystem().getNumParticles() - 3
    kb = BOLTZMANN.value_in_unit(unit.kilojoule_per_mole / unit.kelvin)
    values = []
    for _ in range(samples):
        integrator.step(steps_per_sample)
        kinetic = context.getState(getEnergy=True).getKineticEnergy().value_in_unit(unit.kilojoule_per_mole)
        values.append(2 * kinetic / (dof * kb))
    return block_average(values, blocks=TEMPERATURE_BLOCKS, name=name)


@dataclasses.dataclass
class StartingState:
    """The equilibrated liquid that every candidate starts from."""
    state: openmm.State           # positions, velocities and internal energies after the thermostat
    velocities: np.ndarray        # nm/ps, the state's without centre-of-mass motion
    gas_positions: np.ndarray     # nm, uniformly random in the box: the start of the force-free candidates
    bath_temperature: float       # K


def equilibrated_start(num_particles, cutoff, platform_name):
    """Liquid argon (VB) melted from its lattice and equilibrated with the DPD thermostat at T0 for
    EQUILIBRATION_STEPS steps."""
    argon = liquid_argon(num_particles, cutoff, "VB", seed=1, mode=GenDPDEIntegrator.Isothermal)
    simulation = argon.simulation(platform_name)
    argon.integrator.step(EQUILIBRATION_STEPS)
    state = simulation.context.getState(getPositions=True, getVelocities=True, getIntegratorParameters=True)
    masses = np.array([argon.system.getParticleMass(i).value_in_unit(unit.amu) for i in range(num_particles)])
    velocities = state.getVelocities(asNumpy=True).value_in_unit(unit.nanometer / unit.picosecond)
    velocities -= masses @ velocities / masses.sum()   # no centre-of-mass motion: 3N - 3 degrees of freedom
    edge = state.getPeriodicBoxVectors()[0][0].value_in_unit(unit.nanometer)
    gas_positions = np.random.default_rng(1).uniform(0, edge, (num_particles, 3))
    return StartingState(state, velocities, gas_positions, argon.temperature.value_in_unit(unit.kelvin))


@dataclasses.dataclass
class Candidate:
    """A Context and its integrator (the Context must stay alive while the integrator steps)."""
    context: openmm.Context
    integrator: openmm.Integrator


def candidate(start, num_particles, cutoff, platform, mode=None, kind="GenDPDE", bare=False):
    """A fresh liquid-argon model in a Context at ``start``: with a GenDPDEIntegrator in ``mode`` (and the
    internal energies of ``start``), or kind "Verlet" (VerletIntegrator) or "DPD" (dpd_integrator); ``bare``:
    without forces (without_forces), at the gas positions."""
    model = liquid_argon(num_particles, cutoff, "VB", seed=1)
    if bare:
        model = dataclasses.replace(model, system=without_forces(model.system))
    if kind == "Verlet":
        integrator = openmm.VerletIntegrator(model.integrator.getStepSize())
    elif kind == "DPD":
        integrator = dpd_integrator(model)
        integrator.setRandomNumberSeed(1)
    else:
        integrator = model.integrator
        integrator.setMode(mode)
        if bare:
            integrator.setCutoffDistance(model.force.getCutoffDistance())
    positions = start.gas_positions if bare else start.state.getPositions()
    context = model.context(platform, integrator=integrator, positions=positions, velocities=False)
    if kind == "GenDPDE":
        context.setState(start.state)   # with the internal energies
        context.setPositions(positions)
    context.setVelocities(start.velocities)
    return Candidate(context, integrator)


def benchmark(num_particles, cutoff=DEFAULT_CUTOFF, platform_name="Reference", rounds=None, progress=None):
    platform = openmm.Platform.getPlatformByName(platform_name)
    start = equilibrated_start(num_particles, cutoff, platform_name)

    def make(mode=None, kind="GenDPDE", bare=False):
        return candidate(start, num_particles, cutoff, platform, mode, kind, bare)

    force_context = make(kind="Verlet").context
    contexts = {
        "Isoenergetic step": make(GenDPDEIntegrator.Isoenergetic),
        "Isothermal step": make(GenDPDEIntegrator.Isothermal),
        "Conservative step": make(GenDPDEIntegrator.Conservative),
        "VerletIntegrator step": make(kind="Verlet"),
        "DPDIntegrator step": make(kind="DPD"),
        "Isothermal step, no force": make(GenDPDEIntegrator.Isothermal, bare=True),
        "DPDIntegrator step, no force": make(kind="DPD", bare=True),
    }
    calls = 5
    candidates = {"force evaluation": lambda: [force_context.getState(getEnergy=True) for _ in range(calls)]}
    for name, timed in contexts.items():
        candidates[name] = (lambda integrator: lambda: integrator.step(calls))(timed.integrator)
    for call in candidates.values():
        call()
    if rounds is None:
        rounds = default_rounds(num_particles)
    seconds = alternating_rounds(candidates, rounds, progress)
    temperatures = {name: kinetic_temperature(contexts[name].context, contexts[name].integrator,
                                              TEMPERATURE_SAMPLES, STEPS_PER_SAMPLE,
                                              f"N = {num_particles} {name}: kinetic temperature")
                    for name in THERMOSTATS}
    return IntegratorBenchmark(
        num_particles=num_particles, cutoff=cutoff, platform=platform_name, threads=context_threads(force_context),
        milliseconds={name: 1e3 * median(values) / calls for name, values in seconds.items()},
        isoenergetic_over_force=median_ratio(seconds, "Isoenergetic step", "force evaluation"),
        isothermal_over_force=median_ratio(seconds, "Isothermal step", "force evaluation"),
        conservative_over_verlet=median_ratio(seconds, "Conservative step", "VerletIntegrator step"),
        isothermal_over_dpd=median_ratio(seconds, "Isothermal step", "DPDIntegrator step"),
        isothermal_over_dpd_without_force=median_ratio(seconds, "Isothermal step, no force",
                                                       "DPDIntegrator step, no force"),
        bath_temperature=start.bath_temperature, kinetic_temperatures=temperatures, rounds=rounds)


def format_table(results):
    lines = ["| N | force evaluation (ms) | Isoenergetic step (ms) | Isothermal step (ms) | Conservative step (ms) "
             "| VerletIntegrator step (ms) | Isoenergetic / force | Isothermal / force | Conservative / Verlet |",
             "|---|---|---|---|---|---|---|---|---|"]
    for r in results:
        m = r.milliseconds
        lines.append(f"| {r.num_particles} | {m['force evaluation']:.2f} | {m['Isoenergetic step']:.2f} "
                     f"| {m['Isothermal step']:.2f} | {m['Conservative step']:.2f} | {m['VerletIntegrator step']:.2f} "
                     f"| {r.isoenergetic_over_force:.2f} | {r.isothermal_over_force:.2f} "
                     f"| {r.conservative_over_verlet:.3f} |")
    return "\n".join(lines)


def format_dpd_table(results):
    lines = ["| N | System | GenDPDE Isothermal (ms/step) | DPDIntegrator (ms/step) | GenDPDE / DPDIntegrator "
             "| T bath (K) | T kinetic GenDPDE (K) | T kinetic DPDIntegrator (K) |",
             "|---|---|---|---|---|---|---|---|"]
    for r in results:
        m, t = r.milliseconds, r.kinetic_temperatures
        for label, suffix, ratio in (("with GenDPDEForce", "", r.isothermal_over_dpd),
                                     ("no force", ", no force", r.isothermal_over_dpd_without_force)):
            gendpde, dpd = t["Isothermal step" + suffix], t["DPDIntegrator step" + suffix]
            lines.append(f"| {r.num_particles} | {label} | {m['Isothermal step' + suffix]:.2f} "
                         f"| {m['DPDIntegrator step' + suffix]:.2f} | {ratio:.3f} | {r.bath_temperature:.1f} "
                         f"| {gendpde.mean:.1f} +- {gendpde.standard_error:.1f} | {dpd.mean:.1f} +- "
                         f"{dpd.standard_error:.1f} |")
    return "\n".join(lines)
