# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""`tune-fcut`: its arguments and output; the iterations are openmmgendpde.calibration.fcut's (whose docstring is the
command's --help)."""

import dataclasses

from ..api import estimators_reading_cutoff_scaling
from ..calibration import fcut
from ..calibration.calibration import QUICK, Plan
from ..models.argon import ARGON_STATE, argon_cutoff, liquid_argon
from .fluids import add_fluid_arguments, parameters_from_arguments
from .options import COUNT, POSITIVE, add_cutoff, checked_model, chosen_cutoff
from .progress import Progress
from .protocol import add_protocol_arguments, protocol_from_arguments

DESCRIPTION = fcut.__doc__


def run_fluid(arguments):
    """tune-fcut --fluid: calibrate's tuning (fcut.tune_fluid: --max-iterations runs of its plan, --quick its QUICK
    plan, --particles and --time-step overriding it) for the coarse-grained fluid."""
    parameters = parameters_from_arguments(arguments, "tune-fcut")
    plan = QUICK if arguments.quick else Plan()
    overrides = {"particles": arguments.particles, "time_step": arguments.time_step}
    plan = dataclasses.replace(plan, **{key: value for key, value in overrides.items() if value is not None})
    parameters = parameters.for_estimator(arguments.estimator)
    if arguments.start is not None:
        parameters = parameters.with_cutoff_scaling(arguments.start)
    seed = 1 if arguments.seed is None else arguments.seed
    checked_model("tune-fcut", lambda: parameters.liquid(plan.particles, arguments.estimator, time_step=plan.time_step,
                                                         seed=seed),
                  "use more --particles, or fewer --neighbors (a smaller --cutoff)")
    print(f"{parameters.fluid.name}: {arguments.molecules_per_particle:g} molecules per particle, "
          f"{parameters.neighbors:.1f} neighbours within R = {parameters.cutoff:.4f} nm, {arguments.estimator}, "
          f"{plan.particles} particles, n0 = {parameters.density:.4f} nm^-3", flush=True)
    scaling = fcut.tune_fluid(parameters, arguments.estimator, plan, arguments.platform, seed,
                              arguments.max_iterations, report=lambda line: print(line, flush=True))
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
    estimate = fcut.tune(arguments.cutoff, protocol, arguments.platform, arguments.start, arguments.tolerance,
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
    add_fluid_arguments(parser, default=None, cutoff=False)
    parser.add_argument("--estimator", choices=estimators_reading_cutoff_scaling(), default="VB",
                        help="the estimator to tune (default VB)")
    parser.add_argument("--start", type=POSITIVE, help="initial f_cut (default: the published value)")
    parser.add_argument("--tolerance", type=POSITIVE, default=0.001,
                        help="|n-bar* - n0*| accepted (default 0.001; the argon model only: with --fluid, "
                             "--max-iterations runs are made)")
    parser.add_argument("--max-iterations", type=COUNT, default=5,
                        help="iterations at most (default 5; with --fluid, the iterations made)")
    parser.set_defaults(run=run)
