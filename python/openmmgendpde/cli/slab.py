# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""`slab`: its arguments, checked before anything runs, and its output; the slabs are openmmgendpde.studies.slab's
(whose docstring is the command's --help), the measurements against the exact volumes studies.surfaces'."""

import argparse
import os

import numpy as np
from openmm import unit

from ..analysis.statistics import block_average
from ..api import ESTIMATOR_NAMES
from ..models.argon import ARGON_UNITS
from ..models.fluid import COARSE_GRAINING
from ..models.fluid_files import load_parameters
from ..studies import slab as study
from ..studies import surfaces
from .fluids import add_fluid_arguments, parameters_from_arguments
from .options import NON_NEGATIVE, POSITIVE, SEED, add_output, add_platform, checked_model

DESCRIPTION = study.__doc__
#: The options of the slab of a fluid file or built-in fluid (--fluid) or of a model file (--model), and
#: fluid_slab's argument each sets.
FLUID_OPTIONS = {"time_step": "time_step", "thermostat_time": "thermostat_time", "melt_time": "melt_time"}
#: The coarse-graining options of --fluid (fluids.add_fluid_arguments), which a --model file's parameters replace:
#: None where not given (fluid_parameters puts fluid.COARSE_GRAINING's defaults back).
COARSE_GRAINING_OPTIONS = ("molecules_per_particle", "neighbors", "cutoff")


def _option(name):
    return f"--{name.replace('_', '-')}"


def fluid_parameters(arguments, cells):
    """The GenDPDEParameters of --fluid (coarse-grained) or --model (a model file's, exactly), None for the published
    argon model, checked against the slab's ``cells`` before anything runs; a bad argument exits with a one-line
    error (status 1)."""
    coarse_graining = [name for name in COARSE_GRAINING_OPTIONS if getattr(arguments, name) is not None]
    if arguments.model is not None:
        if arguments.fluid is not None:
            raise SystemExit("error: slab: --fluid and --model exclude each other; give one")
        if coarse_graining:
            raise SystemExit(f"error: slab: {_option(coarse_graining[0])} applies to --fluid only; a --model file "
                             f"holds every parameter of its model")
        parameters = load_model(arguments.model)
        source = f"--model {arguments.model}"
    elif arguments.fluid is None:
        given = [name for name in FLUID_OPTIONS if getattr(arguments, name) is not None] + coarse_graining
        if given:
            raise SystemExit(f"error: slab: {_option(given[0])} applies to the slab of a --fluid or --model only")
        return None
    else:
        defaults = {name: value for name, value in COARSE_GRAINING.items() if getattr(arguments, name) is None}
        parameters = parameters_from_arguments(argparse.Namespace(**{**vars(arguments), **defaults}), "slab")
        source = f"--fluid {arguments.fluid}"
    checked_model(f"slab: {source}", lambda: parameters.liquid(
        cells=cells, **({} if arguments.time_step is None else {"time_step": arguments.time_step}),
        seed=arguments.seed), "use fewer --neighbors (a smaller --cutoff)" if arguments.model is None else
        "the slab's box is fixed; use a model with a shorter cutoff")
    return parameters


def load_model(path):
    """fluid_files.load_parameters of the model file ``path`` (--model); exits with a one-line error naming the
    file if it is missing or not a model file."""
    if not os.path.isfile(path):
        raise SystemExit(f"error: slab: --model {path}: no such file")
    if os.path.splitext(path)[1].lower() not in (".toml", ".json"):
        raise SystemExit(f"error: slab: --model {path} is not allowed; a model file ends in .toml or .json")
    try:
        return load_parameters(path)
    except ValueError as error:
        raise SystemExit(f"error: slab: --model {' '.join(str(error).split())}")


def checked_arguments(arguments):
    """(duration, every, cells, the parameters of --fluid or --model or None) of the arguments, every one checked
    before anything runs; a one-line error (SystemExit) otherwise."""
    duration, every = (10.0, 5.0) if arguments.quick else (arguments.duration, arguments.every)
    if every > duration:
        raise SystemExit(f"error: slab: --every {every:g} is not allowed; it must be at most --duration {duration:g} "
                         f"(a sample every --every time units of the run)")
    cells = (5, 5, 6) if arguments.quick else (5, 5, 10)
    parameters = fluid_parameters(arguments, cells)
    for estimator in arguments.estimators if parameters is not None else ():
        try:   # (a model file's f_cut serves the estimator it was tuned for, and V-A, which has none)
            parameters.checked_estimator(estimator)
        except ValueError as error:
            raise SystemExit(f"error: slab: --estimators {estimator}: {error}") from None
    time_step = study.ARGON_SLAB_TIME_STEP if parameters is None else arguments.time_step   # (None: measured later)
    if time_step is not None and round(every / time_step) < 1:
        raise SystemExit(f"error: slab: --every {every:g} is not allowed; it must be at least one step, dt* = "
                         f"{time_step:g}")
    return duration, every, cells, parameters


def run_one(arguments, parameters, estimator, duration, every, cells):
    """The slab of one estimator, its heading printed: (samples, model, its Context, initial thickness)."""
    if parameters is None:
        print(f"{estimator}: slab of {4 * np.prod(cells)} particles, {duration:g} time units")
        return study.run_slab(estimator, duration, every, cells, arguments.platform)
    build = {key: getattr(arguments, name) for name, key in FLUID_OPTIONS.items()
             if getattr(arguments, name) is not None}
    try:
        samples, slab = study.run_fluid_slab(parameters, estimator, duration, every, cells, arguments.platform,
                                             arguments.seed, **build)
    except ValueError as error:   # (--every less than the step measured for the model)
        raise SystemExit(f"error: slab: {error}") from None
    model_file = "" if arguments.model is None else f"the model in {arguments.model}; "
    tau = parameters.units.unit("time").value_in_unit(unit.picosecond)
    print(f"{estimator}: slab of {4 * np.prod(cells)} particles of {parameters.fluid.name} "
          f"({model_file}T0 = {parameters.temperature:g} K), dt* = {slab.time_step:.4g}, melted and "
          f"thermostatted {build.get('thermostat_time', study.SLAB_THERMOSTAT_TIME):g} time units after the cut, "
          f"then {duration:g} time units isoenergetic (time unit {tau:.4g} ps; reduced units of the model: "
          f"length n0^(-1/3))")
    return samples, slab.model, slab.context, slab.thickness


def print_run(estimator, samples, duration, parameters):
    """The samples of one slab and the means over the second half of its run; the surface tensions of that half."""
    temperatures = parameters is not None
    print("   t*   core true n*   core mean n_i*   width/initial   surface tension*"
          + ("   T_kin (K)   T_harm (K)" if temperatures else ""))
    for s in samples:
        print(f"{s.time:6.1f}   {s.core_density:12.3f}   {s.core_estimate:14.3f}   {s.width:13.2f}   "
              f"{s.tension:16.4f}" + (f"   {s.kinetic_temperature:9.1f}   {s.harmonic_temperature:10.1f}"
                                      if temperatures else ""))
    late = [s for s in samples if s.time > duration / 2]
    tensions = [s.tension for s in late]
    if len(late) >= 10:   # enough samples for 5 blocks of 2
        tension = block_average(tensions, 5, name=f"{estimator} surface tension")
        mean = tension.mean
        error = f"+- {tension.standard_error:.4f} (block average, 5 blocks; sd {np.std(tensions):.4f})"
    else:
        mean = float(np.mean(tensions))
        error = f"(sd {np.std(tensions):.4f}; too few samples for an error)"
    print(f"{estimator}: over the second half ({len(late)} samples), core true n* "
          f"{np.mean([s.core_density for s in late]):.3f}, surface tension* {mean:.4f} {error}"
          + (f"; T_kin {np.mean([s.kinetic_temperature for s in late]):.1f} K, T_harm "
             f"{np.mean([s.harmonic_temperature for s in late]):.1f} K (T0 {parameters.temperature:g} K)"
             if temperatures else ""))
    return tensions


def print_profile(estimator, samples, model, context, thickness, units):
    profile = surfaces.depth_profile(model, context, thickness, units=units)
    print(f"{estimator} at t* = {samples[-1].time:g}: density by depth (units of the initial half "
          f"thickness; particles): true, exact partition of unity, V-B, V-A, V-C")
    for row in profile:
        print("  {:4.1f}-{:4.1f} ({:4d}): {:6.3f} {:8.3f} {:8.3f} {:8.3f} {:8.3f}".format(*row))
    return profile


def print_argon_oracles(arguments):
    """The argon model's droplet and bulk liquids against the exact volumes (without --no-oracle), and its coexistence
    density (without --quick)."""
    if not arguments.no_oracle:
        count = 400 if arguments.quick else 1000
        model, context, radius = surfaces.run_droplet("VB", 10.0, count, arguments.platform)
        print(f"VB droplet of {count} particles at t* = 10: density by distance from its centre (units of the initial "
              f"radius; particles): true, exact partition of unity, V-B, V-A, V-C")
        for row in surfaces.radial_profile(model, context, radius):
            print("  {:4.1f}-{:4.1f} ({:4d}): {:6.3f} {:8.3f} {:8.3f} {:8.3f} {:8.3f}".format(*row))
        print("bulk liquids (V-B runs): n*, V_VB/V_exact mean and sd, V_VA/V_exact mean and sd, corr(V_VB, V_exact), "
              "V_VC/V_exact mean and sd")
        for row in surfaces.bulk_comparison(cells=(4, 4, 4) if arguments.quick else (5, 5, 5),
                                            steps=200 if arguments.quick else 2000, platform=arguments.platform):
            print("  {:5.2f}: {:6.3f} {:6.3f}   {:6.3f} {:6.3f}   {:5.2f}   {:6.3f} {:6.3f}".format(*row))
    if not arguments.quick:
        for estimator in [e for e in arguments.estimators if e != "VA"]:   # (V-A's bulk liquids pair)
            density, pressures = surfaces.coexistence_density(estimator, platform=arguments.platform)
            print(f"{estimator}: bulk P* {', '.join(f'{p:.4f}' for p in pressures)} at n* = 0.7, 0.75, 0.8: "
                  f"P* = 0 at n* = {density:.3f} (the coexistence density with vacuum)")


def run(arguments):
    duration, every, cells, parameters = checked_arguments(arguments)
    units = ARGON_UNITS if parameters is None else parameters.units
    os.makedirs(arguments.output, exist_ok=True)
    runs, profiles, tensions = {}, {}, {}
    for estimator in arguments.estimators:
        samples, model, context, thickness = run_one(arguments, parameters, estimator, duration, every, cells)
        runs[estimator] = samples
        tensions[estimator] = print_run(estimator, samples, duration, parameters)
        if not arguments.no_oracle:
            profiles[estimator] = print_profile(estimator, samples, model, context, thickness, units)
    study.write_csv(runs, os.path.join(arguments.output, "slab.csv"), temperatures=parameters is not None)
    if parameters is not None:
        print(surfaces.surface_tension_table(tensions, parameters))
        print("(the droplet, the bulk comparison and the coexistence density are the argon model's: run slab "
              "without --fluid or --model)")
    else:
        print_argon_oracles(arguments)
    surfaces.plot(runs, profiles, os.path.join(arguments.output, "slab"))
    print(f"wrote {arguments.output}/slab.csv, slab.png, slab.pdf")


def add_arguments(parser):
    add_platform(parser, default="CPU")
    add_output(parser, "slab.csv and the plots")
    parser.add_argument("--duration", type=POSITIVE, default=100.0, help="time units per run (default 100)")
    parser.add_argument("--every", type=POSITIVE, default=10.0, help="time units between samples (default 10)")
    parser.add_argument("--quick", action="store_true", help="a 600-particle slab for 10 time units (seconds)")
    parser.add_argument("--estimators", nargs="+", choices=list(ESTIMATOR_NAMES.values()),
                        default=list(ESTIMATOR_NAMES.values()), help="the slabs to run (default: every estimator)")
    parser.add_argument("--no-oracle", action="store_true", help="skip the exact volumes (the slow part)")
    add_fluid_arguments(parser, default=None)
    parser.set_defaults(**dict.fromkeys(COARSE_GRAINING_OPTIONS))   # (not given: None; --model refuses them)
    parser.add_argument("--model", help="a model file written by `calibrate --output` (.toml or .json): the slab of "
                        "exactly its parameters (a calibrated model) instead of --fluid and its coarse-graining")
    parser.add_argument("--time-step", type=POSITIVE, help="with --fluid or --model: dt* in the model's reduced time "
                        "(default stability.suggest_time_step's, measured: V-C's is a tenth of V-B's)")
    parser.add_argument("--thermostat-time", type=NON_NEGATIVE, help=f"with --fluid or --model: time units the slab is "
                        f"thermostatted after the cut, before the isoenergetic run (default "
                        f"{study.SLAB_THERMOSTAT_TIME:g}; 0: none)")
    parser.add_argument("--melt-time", type=NON_NEGATIVE, help="with --fluid or --model: time units the bulk liquid "
                        "melts before the cut (default 20)")
    parser.add_argument("--seed", type=SEED, default=5, help="with --fluid or --model: random seed (default 5)")
    parser.set_defaults(run=run)
