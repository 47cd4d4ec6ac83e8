"""Cost of a GenDPDEIntegrator step against a force evaluation (`benchmark-integrator`).

For each particle count, liquid argon at R* = 1.6839 (VB) is equilibrated briefly with the full GenDPDE dynamics;
then, from that same state, four Contexts are timed in alternating rounds (openmmgendpde.timing): a force
evaluation alone (Context.getState with energies), a full Isoenergetic step, a Conservative step, and a step of
OpenMM's VerletIntegrator with the same force. Ratios are medians of per-round ratios.
"""

import dataclasses

import openmm

from .presets import liquid_argon
from .measurement import (add_benchmark_arguments, alternating_rounds, default_rounds, median, median_ratio,
                          print_results)
from .progress import Progress
from . import GenDPDEIntegrator


@dataclasses.dataclass
class IntegratorBenchmark:
    num_particles: int
    cutoff: float
    platform: str
    milliseconds: dict                # candidate -> median ms per call (force evaluation or step)
    isoenergetic_over_force: float
    isothermal_over_force: float
    conservative_over_verlet: float
    rounds: int


def benchmark(num_particles, cutoff=1.6839, platform_name="Reference", rounds=None, progress=None):
    platform = openmm.Platform.getPlatformByName(platform_name)
    argon = liquid_argon(num_particles, cutoff, "VB", seed=1)
    simulation = argon.simulation(platform_name)
    argon.integrator.step(100)
    state = simulation.context.getState(getPositions=True, getVelocities=True, getIntegratorParameters=True)

    def context(mode=None, verlet=False):
        model = liquid_argon(num_particles, cutoff, "VB", seed=1)
        integrator = openmm.VerletIntegrator(model.integrator.getStepSize()) if verlet else model.integrator
        if mode is not None:
            integrator.setMode(mode)
        result = openmm.Context(model.system, integrator, platform)
        result.setPositions(state.getPositions())
        result.setVelocities(state.getVelocities())
        if not verlet:
            result.setState(state)
        return result, integrator

    force_context, _ = context(verlet=True)
    contexts = [context(GenDPDEIntegrator.Isoenergetic), context(GenDPDEIntegrator.Isothermal),
                context(GenDPDEIntegrator.Conservative), context(verlet=True)]   # the Contexts must stay alive
    isoenergetic, isothermal, conservative, verlet = (integrator for _, integrator in contexts)
    calls = 5
    candidates = {
        "force evaluation": lambda: [force_context.getState(getEnergy=True) for _ in range(calls)],
        "Isoenergetic step": lambda: isoenergetic.step(calls),
        "Isothermal step": lambda: isothermal.step(calls),
        "Conservative step": lambda: conservative.step(calls),
        "VerletIntegrator step": lambda: verlet.step(calls),
    }
    for candidate in candidates.values():
        candidate()
    if rounds is None:
        rounds = default_rounds(num_particles)
    seconds = alternating_rounds(candidates, rounds, progress)
    return IntegratorBenchmark(
        num_particles=num_particles, cutoff=cutoff, platform=platform_name,
        milliseconds={name: 1e3 * median(values) / calls for name, values in seconds.items()},
        isoenergetic_over_force=median_ratio(seconds, "Isoenergetic step", "force evaluation"),
        isothermal_over_force=median_ratio(seconds, "Isothermal step", "force evaluation"),
        conservative_over_verlet=median_ratio(seconds, "Conservative step", "VerletIntegrator step"),
        rounds=rounds)


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


def run(arguments):
    total = sum(arguments.rounds or default_rounds(n) for n in arguments.particles)
    progress = Progress(total, "benchmark-integrator", always=arguments.progress)
    results = []
    for n in arguments.particles:
        progress.label = f"benchmark-integrator N={n}"
        results.append(benchmark(n, arguments.cutoff, arguments.platform, arguments.rounds, progress))
    progress.finish()
    print_results(f"GenDPDEIntegrator on the {arguments.platform} platform, liquid argon R* = {arguments.cutoff}, VB; "
                  f"medians of alternating rounds from the same state:", format_table(results), results,
                  arguments.json)


def add_arguments(parser):
    add_benchmark_arguments(parser)
    parser.add_argument("--cutoff", type=float, default=1.6839, help="R_cut* (default 1.6839)")
    parser.set_defaults(run=run)
