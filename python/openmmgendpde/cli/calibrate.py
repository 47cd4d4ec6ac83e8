# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""`calibrate`: its arguments, checked before anything runs, and its output; the protocol is
openmmgendpde.calibration.calibrate.calibrate (whose docstring, the method, is the command's --help)."""

import dataclasses
import json
import os
import sys

import openmm

from ..api import ESTIMATOR_NAMES
from ..calibration import calibrate as protocol
from ..calibration.calibration import QUICK, Plan
from ..calibration.report import changes_table, melts_line, parameter_table, plot, results_table
from ..calibration.results import CRITERIA, QUICK_CRITERIA, missed_properties
from ..internal.files import atomic_write
from ..models.fluid_files import save_parameters
from .fluids import add_fluid_arguments, parameters_from_arguments
from .options import (
    POSITIVE,
    SEED,
    add_json,
    add_platform,
    add_progress,
    checked_model,
    failure_message,
    fcc_particles,
    platform_description,
    writable_file,
    writable_stem,
)
from .progress import Progress

DESCRIPTION = protocol.__doc__


def replica_processes(platform):
    """How many replicas run at once (Calibration.workers): on the CPU platform as many as it has threads (its
    default Threads, --threads), each process on one; elsewhere one (a GPU runs one Context at a time)."""
    if platform != "CPU":
        return 1
    return int(openmm.Platform.getPlatformByName("CPU").getPropertyDefaultValue("Threads"))


def checked_arguments(arguments):
    """(the mapped parameters for --estimator, the Plan) of the arguments, every one checked before anything runs (a
    model built once checks the particles against the cutoff, and every parameter against what GenDPDEForce and
    GenDPDEIntegrator allow); a one-line error (SystemExit) otherwise."""
    parameters = parameters_from_arguments(arguments, "calibrate")
    plan = QUICK if arguments.quick else Plan()
    if arguments.particles is not None:
        plan = dataclasses.replace(plan, particles=arguments.particles)
    if arguments.time_step is not None:
        plan = dataclasses.replace(plan, time_step=arguments.time_step)
    if arguments.output and os.path.splitext(arguments.output)[1].lower() not in (".toml", ".json"):
        raise SystemExit(f"error: calibrate: --output {arguments.output} is not allowed; it must end in .toml or .json")
    if arguments.plot:
        try:
            import matplotlib  # noqa: F401 (the optional studies dependency, needed for --plot at the end)
        except ImportError:
            raise SystemExit("error: calibrate: --plot needs matplotlib (pip install matplotlib)") from None
    parameters = parameters.for_estimator(arguments.estimator)
    checked_model("calibrate", lambda: parameters.liquid(plan.particles, arguments.estimator, time_step=plan.time_step,
                                                         seed=arguments.seed),
                  "use more --particles, or fewer --neighbors (a smaller --cutoff)")
    return parameters, plan


def run(arguments):
    """calibrate (the protocol's docstring); a stage that fails (protocol.StageFailure: e.g. an internal energy that
    a step would take below zero) ends in a one-line error naming it."""
    parameters, plan = checked_arguments(arguments)
    workers = min(replica_processes(arguments.platform), plan.replicas)
    print(f"{parameters.fluid.name}: {arguments.molecules_per_particle:g} molecules per particle, "
          f"{parameters.neighbors:.1f} neighbours within R, {arguments.estimator}, {plan.particles} particles, "
          f"{platform_description(arguments)}"
          + (f" (the replicas of a transport measurement {workers} at once, one thread each)" if workers > 1 else ""))
    print("Parameters (OpenMM units; reduced: mass of a particle, L = n0^(-1/3), energy L^3/kappa_T, k_B = 1):")
    print(parameter_table(parameters))
    progress = Progress(protocol.estimated_steps(plan, arguments.estimator), "calibrate", always=arguments.progress)
    try:
        result = protocol.calibrate(parameters, arguments.estimator, plan, arguments.platform, arguments.seed,
                                    QUICK_CRITERIA if arguments.quick else CRITERIA, workers, progress,
                                    report=lambda line: print(line, flush=True))
    except protocol.StageFailure as failure:
        raise SystemExit(f"error: calibrate: {failure} (dt* = {plan.time_step:g}: --time-step; heat capacity: "
                         f"--molecules-per-particle)") from None
    finally:
        progress.finish()
    print_report(result, arguments.quick)
    unwritten = write_outputs(result, arguments)
    if result.missed:
        properties = missed_properties(result.missed)
        print(f"error: calibrate: the calibration failed, {len(properties)} judged "
              f"{'property' if len(properties) == 1 else 'properties'} missed ({'; '.join(properties)}; CRITERIA, "
              f"docs/fluids.md):\n  " + "\n  ".join(map(str, result.missed)), file=sys.stderr)
    if unwritten:
        outputs = sum(bool(given) for given in (arguments.output, arguments.json, arguments.plot))
        raise SystemExit(f"error: calibrate: {'; '.join(unwritten)}"
                         + ("; the other outputs were written" if len(unwritten) < outputs else ""))
    if result.missed:
        raise SystemExit(1)
    judged = {row for row, _, _ in result.rows}
    print(f"Every judged result within its tolerance ({', '.join(prop.label for prop in CRITERIA if prop in judged)}"
          f"{'; --quick: transport within a factor 2' if arguments.quick else ''}).")
    return result.results


def print_report(result, quick):
    print(melts_line(result))
    print(changes_table(result.mapped, result.parameters))
    print("Targets and what the model gives (standard errors; independent samples: N/g of a time series, or "
          "the replicas):")
    print(results_table(result))
    print("Notes: the bulk modulus that B_T can reach is set by how the particle densities n_i follow the true "
          "density (the response above; docs/fluids.md); the transport coefficients are iterated on the wave decays "
          "and measured again by the steady flows in the same box (docs/transport.md)"
          + ("; the conductivity of a fluid that expands on the heat flux (docs/thermal.md)." if result.expanding
             else "."))
    print(f"{result.runs} runs in {result.wall_time:.0f} s.")


def write_outputs(result, arguments):
    """--output, --json and --plot, each written atomically (files.atomic_write) and each on its own: one that cannot
    be written (a full disk) does not keep the others from being written; the lines saying why, of those not
    written."""
    unwritten = []

    def write(option, path, done, function, *arguments_):
        try:
            function(*arguments_)
            print(done)
        except OSError as error:
            unwritten.append(f"{option} {path} could not be written ({failure_message(error)})")

    if arguments.output:
        fluid, estimator = result.mapped.fluid, result.estimator
        verdict = ("MISSED: " + "; ".join(map(str, result.missed)) if result.missed
                   else "every judged result within its tolerance")
        write("--output", arguments.output,
              f"The calibrated model is in {arguments.output} (fluid_files.load_parameters reads it).",
              save_parameters, result.parameters, arguments.output,
              f"{fluid.name}: calibrated by python -m openmmgendpde calibrate ({arguments.molecules_per_particle:g} "
              f"molecules per particle, {estimator}, {result.plan.particles} particles, seed {arguments.seed}); "
              f"{verdict}.\nBuild it again: openmmgendpde.models.fluid_files.load_parameters(path).liquid("
              f"num_particles, '{estimator}')")
    if arguments.json:
        write("--json", arguments.json, f"The parameters and results are in {arguments.json}.", _write_json,
              result.record, arguments.json)
    if arguments.plot:
        write("--plot", arguments.plot, f"Figure: {arguments.plot}.png and .pdf", plot, result.record, arguments.plot)
    return unwritten


def _write_json(record, path):
    with atomic_write(path) as stream:
        json.dump(record, stream, indent=1)


def add_arguments(parser):
    add_fluid_arguments(parser)
    parser.add_argument("--estimator", choices=list(ESTIMATOR_NAMES.values()), default="VB",
                        help="the density estimator (default VB; VC is VB with free surfaces)")
    parser.add_argument("--particles", type=fcc_particles, help="4 m^3 particles (default 2048; --quick 500)")
    parser.add_argument("--quick", action="store_true", help="500 particles and short runs (a functional check: "
                        "1.2-1.6 min measured on 2 shared cores, more on a busier machine); the speed of sound is "
                        "derived only, not measured by a sound wave as without --quick")
    parser.add_argument("--time-step", type=POSITIVE, help="dt* in the model's reduced time (default 0.01; smaller "
                        "where an internal energy would become negative: "
                        "openmmgendpde.calibration.stability.suggest_time_step gives one for a model)")
    parser.add_argument("--seed", type=SEED, default=1, help="random seed (default 1)")
    add_json(parser, "the parameters and results")
    add_progress(parser)
    parser.add_argument("--plot", metavar="STEM", type=writable_stem(),
                        help="also draw the results and the iterations to STEM.png and STEM.pdf (needs matplotlib)")
    parser.add_argument("--output", type=writable_file, help="write the calibrated model to this file (.toml or "
                        ".json), which openmmgendpde.models.fluid_files.load_parameters reads back")
    add_platform(parser)
    parser.set_defaults(run=run)
