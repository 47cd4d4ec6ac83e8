"""Tune f_cut of the VB estimator so that the mean density equals the imposed one (`tune-fcut`); the paper tuned it
by hand.

Self-consistent iteration: run VB at the current f_cut (openmmgendpde.study protocol) keeping production frames;
on those frames, evaluate n-bar at trial values of f_cut (GenDPDEForce.updateParametersInContext, no new Context);
solve n-bar(f_cut) = n0 on the straight line through them; set the new f_cut in the running Context and continue.
The structure barely depends on f_cut, so two or three iterations converge. The uncertainty of f_cut is that of
n-bar (block average) divided by |d n-bar / d f_cut|.
"""

import numpy as np
from openmm import unit

from .presets import ARGON_STATE, ARGON_UNITS, argon_cutoff
from .progress import Progress
from .statistics import block_average
from .study import add_protocol_arguments, protocol_from_arguments, run_argon


def mean_density_on_frames(force, context, frames, cutoff_scaling):
    """n-bar* averaged over frames, with the force's f_cut set to cutoff_scaling (restored afterwards)."""
    original = force.getCutoffScaling()
    force.setCutoffScaling(cutoff_scaling)
    force.updateParametersInContext(context)
    values = []
    for positions in frames:
        context.setPositions(positions * unit.nanometer)
        values.append(np.mean(force.getParticleDensities(context).value_in_unit(unit.nanometer**-3)))
    force.setCutoffScaling(original)
    force.updateParametersInContext(context)
    return ARGON_UNITS.from_openmm(float(np.mean(values)), "number_density")


def tune(cutoff, protocol, platform="Reference", start=None, tolerance=0.001, max_iterations=5, progress=None,
         report=print):
    """Returns (f_cut, its standard error, n-bar*, its error, iterations, f_cut of the last run): f_cut solves
    n-bar*(f_cut) = n0* on the straight line through the last run, at which n-bar* was measured."""
    target = ARGON_STATE.density
    scaling = start if start is not None else argon_cutoff(cutoff).cutoff_scaling
    running = None
    for iteration in range(1, max_iterations + 1):
        samples, argon, simulation = run_argon(cutoff, "VB", protocol, platform, scaling, frames=10, progress=progress,
                                               continue_from=running)
        running = (argon, simulation)
        context = simulation.context
        density, density_error = block_average(samples.density)
        state = context.getState(getPositions=True, getVelocities=True, getIntegratorParameters=True)
        step = 0.01
        low = mean_density_on_frames(argon.force, context, samples.frames, scaling - step)
        high = mean_density_on_frames(argon.force, context, samples.frames, scaling + step)
        context.setState(state)
        slope = (high - low) / (2 * step)
        new = max(1.0, scaling + (target - density) / slope)
        report(f"iteration {iteration}: f_cut = {scaling:.4f}: n-bar* = {density:.4f} +- {density_error:.4f}, "
               f"d n-bar*/d f_cut = {slope:.3f} -> f_cut = {new:.4f}")
        # The estimate: where the line through the last run's measurement reaches n0.
        measured = (new, density_error / abs(slope), density, density_error, iteration, scaling)
        if abs(density - target) <= max(tolerance, 2 * density_error):
            return measured
        scaling = new
        argon.force.setCutoffScaling(scaling)
        argon.force.updateParametersInContext(context)
    report(f"not converged within {max_iterations} iterations; the estimate from the last run is reported")
    return measured


def run(arguments):
    protocol = protocol_from_arguments(arguments)
    progress = Progress(arguments.max_iterations * protocol.total_steps, f"tune-fcut R*={arguments.cutoff}",
                        always=arguments.progress)
    scaling, error, density, density_error, iterations, last = tune(arguments.cutoff, protocol, arguments.platform,
                                                                    arguments.start, arguments.tolerance,
                                                                    arguments.max_iterations, progress,
                                                                    report=lambda line: print(line, flush=True))
    progress.finish()
    published = argon_cutoff(arguments.cutoff).cutoff_scaling
    print(f"R_cut* = {arguments.cutoff}: f_cut = {scaling:.4f} +- {error:.4f} for n-bar* = {ARGON_STATE.density} "
          f"(last run: f_cut = {last:.4f}, n-bar* = {density:.4f} +- {density_error:.4f}; tolerance "
          f"{arguments.tolerance}, {iterations} iteration(s)); published f_cut = {published}")
    return scaling, error


def add_arguments(parser):
    add_protocol_arguments(parser)
    parser.add_argument("--cutoff", type=float, default=1.6839, help="R_cut* (default 1.6839)")
    parser.add_argument("--start", type=float, help="initial f_cut (default: the published value)")
    parser.add_argument("--tolerance", type=float, default=0.001, help="|n-bar* - n0*| accepted (default 0.001)")
    parser.add_argument("--max-iterations", type=int, default=5, help="iterations at most (default 5)")
    parser.add_argument("--progress", action="store_true", help="show progress even when not on a terminal")
    parser.set_defaults(run=run)
