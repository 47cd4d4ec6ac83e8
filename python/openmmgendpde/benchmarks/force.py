# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""Speed of GenDPDEForce against the same potential written with OpenMM's CustomGBForce (`benchmark-force`).

For each particle count and published argon cutoff: a liquid configuration is prepared (FCC lattice at n0* = 1,
then velocity Verlet with the VB force), and four Contexts on the same platform evaluate that same configuration:
GenDPDEForce VA and VB, CustomGBForce VA and VB. Force evaluations are timed in alternating rounds
(openmmgendpde.benchmarks.measurement); the ratios VB/VA and CustomGB/GenDPDE are medians of per-round ratios. The cost
of a velocity-Verlet step with GenDPDEForce (which includes the amortised neighbor-list rebuilds) is measured the same
way.
"""

import dataclasses

import openmm
from openmm import unit

from ..models.argon import ARGON_STATE, ARGON_UNITS, PUBLISHED_ESTIMATORS, liquid_argon
from ..models.customgb import custom_gb_equivalent
from .measurement import alternating_rounds, context_threads, default_rounds, median, median_ratio

#: Time step of the preparation and of the timed Verlet steps (reduced units).
TIME_STEP = 0.01


@dataclasses.dataclass
class ForceBenchmark:
    num_particles: int
    cutoff: float
    platform: str
    threads: int                 # the CPU platform's Threads, 1 elsewhere
    evaluation_ms: dict          # candidate -> median ms per force evaluation
    vb_over_va: float            # GenDPDE VB / VA, per evaluation
    custom_gb_speedup: dict      # estimator -> median CustomGB/GenDPDE per evaluation
    verlet_step_ms: dict         # estimator -> median ms per Verlet step (GenDPDE)
    verlet_vb_over_va: float
    rounds: int


def _context(model, positions, platform):
    """A Context of ``model`` (its System as it is now) with a VerletIntegrator, at ``positions``, at rest."""
    integrator = openmm.VerletIntegrator(ARGON_UNITS.to_openmm(TIME_STEP, "time"))
    return model.context(platform, integrator=integrator, positions=positions, velocities=False)


def prepare_liquid(num_particles, cutoff, platform, steps=200):
    """Positions (nm) of a liquid-like configuration: the FCC lattice melted by `steps` Verlet steps with VB."""
    argon = liquid_argon(num_particles, cutoff, "VB")
    context = _context(argon, argon.positions, platform)
    context.setVelocitiesToTemperature(ARGON_UNITS.to_openmm(ARGON_STATE.temperature, "temperature"), 1)
    context.getIntegrator().step(steps)
    return context.getState(getPositions=True).getPositions(asNumpy=True).value_in_unit(unit.nanometer)


def benchmark(num_particles, cutoff, platform_name="Reference", rounds=None, progress=None):
    platform = openmm.Platform.getPlatformByName(platform_name)
    positions = prepare_liquid(num_particles, cutoff, platform)
    contexts = {}
    for estimator in PUBLISHED_ESTIMATORS:
        argon = liquid_argon(num_particles, cutoff, estimator)
        custom = custom_gb_equivalent(argon.force, num_particles)
        contexts[f"GenDPDE {estimator}"] = _context(argon, positions, platform)
        argon.system.removeForce(0)
        argon.system.addForce(custom)
        contexts[f"CustomGB {estimator}"] = _context(argon, positions, platform)
    for context in contexts.values():
        context.getState(getEnergy=True)   # warm up: neighbor lists, caches
    if rounds is None:
        rounds = default_rounds(num_particles)
    evaluate = {name: (lambda c=context: c.getState(getEnergy=True)) for name, context in contexts.items()}
    seconds = alternating_rounds(evaluate, rounds, progress)
    steps_per_call = 10
    step = {estimator: (lambda c=contexts[f"GenDPDE {estimator}"]: c.getIntegrator().step(steps_per_call))
            for estimator in PUBLISHED_ESTIMATORS}
    for estimator in PUBLISHED_ESTIMATORS:
        contexts[f"GenDPDE {estimator}"].setVelocitiesToTemperature(
            ARGON_UNITS.to_openmm(ARGON_STATE.temperature, "temperature"), 2)
    step_seconds = alternating_rounds(step, rounds, progress)
    return ForceBenchmark(
        num_particles=num_particles, cutoff=cutoff, platform=platform_name,
        threads=context_threads(contexts["GenDPDE VB"]),
        evaluation_ms={name: 1e3 * median(values) for name, values in seconds.items()},
        vb_over_va=median_ratio(seconds, "GenDPDE VB", "GenDPDE VA"),
        custom_gb_speedup={estimator: median_ratio(seconds, f"CustomGB {estimator}", f"GenDPDE {estimator}")
                           for estimator in PUBLISHED_ESTIMATORS},
        verlet_step_ms={estimator: 1e3 * median(values) / steps_per_call for estimator, values in step_seconds.items()},
        verlet_vb_over_va=median_ratio(step_seconds, "VB", "VA"),
        rounds=rounds)


def format_table(results):
    lines = [
        "| N | R_cut* | GenDPDE VA (ms) | GenDPDE VB (ms) | VB/VA | CustomGB VA (ms) | CustomGB VB (ms) "
        "| speed-up VA | speed-up VB | Verlet step VA / VB (ms) | VB/VA per step |",
        "|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    for r in results:
        e = r.evaluation_ms
        lines.append(
            f"| {r.num_particles} | {r.cutoff} | {e['GenDPDE VA']:.2f} | {e['GenDPDE VB']:.2f} | {r.vb_over_va:.3f} "
            f"| {e['CustomGB VA']:.1f} | {e['CustomGB VB']:.1f} | {r.custom_gb_speedup['VA']:.1f}x "
            f"| {r.custom_gb_speedup['VB']:.1f}x | {r.verlet_step_ms['VA']:.2f} / {r.verlet_step_ms['VB']:.2f} "
            f"| {r.verlet_vb_over_va:.3f} |")
    return "\n".join(lines)
