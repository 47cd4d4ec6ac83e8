"""Tune f_cut of the VB (or VC) estimator so that the mean density equals the imposed one (`tune-fcut`); the paper tuned
it by hand.

Self-consistent iteration: run VB at the current f_cut (openmmgendpde.models.argon_runs protocol) keeping production
frames; on those frames, evaluate n-bar at trial values of f_cut (GenDPDEForce.updateParametersInContext, no new
Context); solve n-bar(f_cut) = n0 on the straight line through them; set the new f_cut in the running Context and
continue. The structure barely depends on f_cut, so two or three iterations converge. The uncertainty of f_cut is that
of n-bar (block average) divided by |d n-bar / d f_cut|.

With --fluid NAME|FILE (calibrate's fluids and coarse-graining options: --molecules-per-particle, --neighbors or
--cutoff in nm) the model of any fluid is tuned instead, by calibrate's own iteration (Calibration.
tune_cutoff_scaling: --max-iterations runs of calibrate's plan, --quick its QUICK plan) to n-bar = n0.
"""

import dataclasses

from ..analysis.density import mean_density_on_frames
from ..analysis.statistics import block_average
from ..cli.options import COUNT, POSITIVE, add_cutoff, checked_model, chosen_cutoff
from ..cli.progress import Progress
from ..cli.protocol import add_protocol_arguments, protocol_from_arguments
from ..models.argon import ARGON_STATE, argon_cutoff, default_cutoff_scaling, liquid_argon
from ..models.argon_runs import run_argon


@dataclasses.dataclass(frozen=True)
class CutoffScalingEstimate:
    """What ``tune`` found: the f_cut that solves n-bar*(f_cut) = n0* on the straight line through the last run,
    and what that run measured."""
    cutoff_scaling: float        # the estimate of f_cut
    standard_error: float        # of cutoff_scaling: that of n-bar* divided by |d n-bar*/d f_cut|
    density: float               # n-bar* measured in the last run
    density_error: float         # its standard error (block average)
    iterations: int              # runs made
    last_cutoff_scaling: float   # f_cut of the last run, at which n-bar* was measured


def tune(cutoff, protocol, platform="Reference", start=None, tolerance=0.001, max_iterations=5, progress=None,
         report=print, estimator="VB"):
    """A CutoffScalingEstimate: f_cut of ``estimator`` ('VB' or 'VC') solving n-bar*(f_cut) = n0* on the straight
    line through the last run, with its standard error and that run's n-bar*."""
    target = ARGON_STATE.density
    cutoff_scaling = start if start is not None else default_cutoff_scaling(cutoff, estimator)
    running = None
    for iteration in range(1, max_iterations + 1):
        run = run_argon(cutoff, estimator, protocol, platform, cutoff_scaling, frames=10, progress=progress,
                        continue_from=running)
        samples, argon, simulation = run.samples, run.argon, run.simulation
        running = (argon, simulation)
        context = simulation.context
        density, density_error = block_average(samples.density, name=f"n-bar* at f_cut = {cutoff_scaling:.4f}")
        state = context.getState(getPositions=True, getVelocities=True, getIntegratorParameters=True)
        delta = 0.01
        low = mean_density_on_frames(argon.force, context, samples.frames, cutoff_scaling - delta)
        high = mean_density_on_frames(argon.force, context, samples.frames, cutoff_scaling + delta)
        context.setState(state)
        slope = (high - low) / (2 * delta)
        next_cutoff_scaling = max(1.0, cutoff_scaling + (target - density) / slope)
        report(f"iteration {iteration}: f_cut = {cutoff_scaling:.4f}: n-bar* = {density:.4f} +- {density_error:.4f}, "
               f"d n-bar*/d f_cut = {slope:.3f} -> f_cut = {next_cutoff_scaling:.4f}")
        # The estimate: where the line through the last run's measurement reaches n0.
        measured = CutoffScalingEstimate(next_cutoff_scaling, density_error / abs(slope), density, density_error,
                                         iteration, cutoff_scaling)
        if abs(density - target) <= max(tolerance, 2 * density_error):
            return measured
        cutoff_scaling = next_cutoff_scaling
        argon.force.setCutoffScaling(cutoff_scaling)
        argon.force.updateParametersInContext(context)
    report(f"not converged within {max_iterations} iterations; the estimate from the last run is reported")
    return measured


def run_fluid(arguments):
    """tune-fcut --fluid: calibrate's tuning (Calibration.tune_cutoff_scaling: --max-iterations runs of its plan,
    --quick its QUICK plan, --particles and --time-step overriding it) for the coarse-grained fluid."""
    from ..cli.fluids import parameters_from_arguments
    from .calibration import QUICK, Calibration, Plan
    parameters = parameters_from_arguments(arguments, "tune-fcut")
    plan = QUICK if arguments.quick else Plan()
    overrides = {"particles": arguments.particles, "time_step": arguments.time_step}
    plan = dataclasses.replace(plan, **{key: value for key, value in overrides.items() if value is not None})
    parameters = parameters.for_estimator(arguments.estimator)
    if arguments.start is not None:
        parameters = parameters.with_cutoff_scaling(arguments.start)
    checked_model("tune-fcut", lambda: parameters.liquid(plan.particles, arguments.estimator, time_step=plan.time_step,
                                                         seed=1 if arguments.seed is None else arguments.seed),
                  "use more --particles, or fewer --neighbors (a smaller --cutoff)")
    print(f"{parameters.fluid.name}: {arguments.molecules_per_particle:g} molecules per particle, "
          f"{parameters.neighbors:.1f} neighbours within R = {parameters.cutoff:.4f} nm, {arguments.estimator}, "
          f"{plan.particles} particles, n0 = {parameters.density:.4f} nm^-3", flush=True)
    calibration = Calibration(parameters, arguments.estimator, plan, arguments.platform,
                              seed=1 if arguments.seed is None else arguments.seed,
                              report=lambda line: print(line, flush=True))
    scaling = calibration.tune_cutoff_scaling(arguments.max_iterations)
    print(f"f_cut of {arguments.estimator} = {scaling:.4f} for n-bar = n0 ({arguments.max_iterations} iteration(s); "
          f"the first estimate was {parameters.cutoff_scaling:.4f})")
    return scaling


def run(arguments):
    if arguments.fluid is not None:
        return run_fluid(arguments)
    arguments.cutoff = chosen_cutoff(arguments)
    protocol = protocol_from_arguments(arguments, cutoffs=[arguments.cutoff], estimators=[arguments.estimator])
    if arguments.start is not None:   # (f_cut within what GenDPDEForce allows)
        checked_model("tune-fcut", lambda: liquid_argon(protocol.num_particles, arguments.cutoff, arguments.estimator,
                                                        arguments.start, protocol.time_step))
    progress = Progress(arguments.max_iterations * protocol.total_steps, f"tune-fcut R*={arguments.cutoff}",
                        always=arguments.progress)
    estimate = tune(arguments.cutoff, protocol, arguments.platform, arguments.start, arguments.tolerance,
                    arguments.max_iterations, progress, report=lambda line: print(line, flush=True),
                    estimator=arguments.estimator)
    progress.finish()
    published = argon_cutoff(arguments.cutoff).cutoff_scaling
    print(f"R_cut* = {arguments.cutoff}: f_cut = {estimate.cutoff_scaling:.4f} +- {estimate.standard_error:.4f} for "
          f"n-bar* = {ARGON_STATE.density} (last run: f_cut = {estimate.last_cutoff_scaling:.4f}, n-bar* = "
          f"{estimate.density:.4f} +- {estimate.density_error:.4f}; tolerance {arguments.tolerance}, "
          f"{estimate.iterations} iteration(s)); published f_cut{'' if arguments.estimator == 'VB' else ' of VB'} = "
          f"{published}")
    return estimate


def add_arguments(parser):
    add_protocol_arguments(parser)
    add_cutoff(parser, fluid=True)
    from ..cli.fluids import add_fluid_arguments
    add_fluid_arguments(parser, default=None, cutoff=False)
    parser.add_argument("--estimator", choices=("VB", "VC"), default="VB", help="the estimator to tune (default VB)")
    parser.add_argument("--start", type=POSITIVE, help="initial f_cut (default: the published value)")
    parser.add_argument("--tolerance", type=POSITIVE, default=0.001,
                        help="|n-bar* - n0*| accepted (default 0.001; the argon model only: with --fluid, "
                             "--max-iterations runs are made)")
    parser.add_argument("--max-iterations", type=COUNT, default=5,
                        help="iterations at most (default 5; with --fluid, the iterations made)")
    parser.set_defaults(run=run)
