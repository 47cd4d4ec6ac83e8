# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""`compression`: its arguments and output; the study is openmmgendpde.studies.compression (whose docstring is the
command's --help)."""

import argparse
import json

from ..api import ESTIMATOR_NAMES
from ..calibration.calibration import Plan
from ..calibration.expansion import MPA_PER_OPENMM_PRESSURE
from ..internal.files import atomic_write
from ..models.fluid import KB
from ..studies import compression as study
from .fluids import FLUID_OPTIONS, add_fluid_arguments, model_or_fluid
from .options import add_json, add_platform, fcc_particles, integer, number

DESCRIPTION = study.__doc__
def model_of(arguments):
    """The parameters of --model (a model file) or of the mapping of --fluid (default water), with --cutoff-scaling,
    --reference-pressure and --background-pressure instead of theirs where given. --fluid and its coarse-graining
    with --model are refused: the model file holds its fluid and every parameter."""
    parameters = model_or_fluid(arguments, "compression", "water")
    changes = {}
    if arguments.cutoff_scaling is not None:
        changes["cutoff_scaling"] = arguments.cutoff_scaling
    if arguments.reference_pressure is not None:
        changes["reference_pressure"] = arguments.reference_pressure
    if arguments.background_pressure is not None:
        changes["background_pressure"] = arguments.background_pressure or None
    return parameters.replace(**changes)


def run(arguments):
    parameters = model_of(arguments)
    if arguments.quick:
        plan = study.quick_plan()
    else:
        plan = Plan(particles=arguments.particles, frames=arguments.frames, interval=arguments.interval)
    mpa = MPA_PER_OPENMM_PRESSURE
    print(f"{parameters.fluid.name}: {arguments.estimator}, {plan.particles} particles, {parameters.neighbors:.3g} "
          f"neighbours within R = {parameters.cutoff:.4g} nm, f_cut = {parameters.cutoff_scaling:.4g}, pi0 = "
          f"{parameters.reference_pressure * mpa:.4g} MPa, B_T = {parameters.bulk_modulus * mpa:.4g} MPa "
          f"(gamma_T B_T = {parameters.tait_exponent * parameters.bulk_modulus * mpa:.4g} MPa), p_b = "
          f"{(parameters.background_pressure or 0) * mpa:.4g} MPa, B_T/(n0 k_B T0) = "
          f"{parameters.bulk_modulus / (parameters.density * KB * parameters.temperature):.3g}", flush=True)
    print("| c | n-bar/n | sd(n_i)/n-bar | n0-bar/n | g(r < 0.15 R) | Q6 | q6 | D (1e-9 m^2/s) | P (MPa) |")
    print("|---|---|---|---|---|---|---|---|---|")
    result = study.compress(parameters, arguments.compressions, arguments.estimator, plan, arguments.platform,
                            arguments.seed, report=print_point)
    if result.response is not None:
        target = parameters.targets()["bulk_modulus"]
        modulus = result.bulk_modulus
        print(f"particle-density response (n/n-bar) dn-bar/dn = {result.response.value:.3f} +- "
              f"{result.response.error:.3f}; primitive d ln n0-bar/d ln n = {result.primitive_response:.3f}")
        print(f"n dP/dn = {modulus.value * mpa:.1f} +- {modulus.error * mpa:.1f} MPa (the fluid's {target * mpa:.1f}: "
              f"{modulus.value / target:.3f})")
    structural, central = result.structure_modulus, result.central
    if structural is not None:
        print(f"n k_B T/S(k -> 0) at c = {central.compression:+.3f}: {structural.value * mpa:.1f} +- "
              f"{structural.error * mpa:.1f} MPa (S(k) at k = "
              + ", ".join(f"{k:.3g}" for k, _, _ in central.structure) + " nm^-1: "
              + ", ".join(f"{s:.4f}" for _, s, _ in central.structure) + ")")
    if arguments.json:
        with atomic_write(arguments.json) as stream:
            json.dump(study.record(parameters, arguments.estimator, plan, result), stream, indent=1, default=float)


def print_point(p):
    mpa = MPA_PER_OPENMM_PRESSURE
    print(f"| {p.compression:+.3f} | {p.mean_density.value / p.density:.4f} +- {p.mean_density.error / p.density:.4f} "
          f"| {p.spread:.4f} | {p.primitive:.4f} | {p.close_pairs:.3f} | {p.global_q6:.3f} | {p.local_q6:.3f} | "
          f"{p.diffusion.value * 1e3:.3g} +- {p.diffusion.error * 1e3:.2g} | {p.pressure.value * mpa:.2f} +- "
          f"{p.pressure.error * mpa:.2f} |", flush=True)


def compressions(text):
    """An argparse type: study.compressions_of."""
    try:
        return study.compressions_of(text)
    except ValueError as error:
        raise argparse.ArgumentTypeError(str(error)) from None


def add_arguments(parser):
    parser.add_argument("--model", help="a model file (calibrate --output), which holds its fluid and every "
                        "parameter (--fluid and its coarse-graining are refused with it); else the mapping of --fluid")
    add_fluid_arguments(parser)
    parser.set_defaults(**dict.fromkeys(FLUID_OPTIONS))   # (not given: None; --model refuses them, model_of fills them)
    parser.add_argument("--estimator", choices=list(ESTIMATOR_NAMES.values()), default="VB",
                        help="density estimator (default VB)")
    parser.add_argument("--compressions", type=compressions, default=[-0.05, 0.0, 0.05],
                        help="relative compressions c, comma-separated: boxes at n0 (1 + c) (default -0.05,0,0.05; "
                             "write --compressions=-0.02,0,0.02)")
    parser.add_argument("--particles", type=fcc_particles, default=2048, help="4 m^3 particles (default 2048)")
    parser.add_argument("--quick", action="store_true",
                        help="500 particles, 40 frames 25 steps apart (a functional check: 6 s measured on 2 "
                             "shared cores)")
    parser.add_argument("--frames", type=integer(2), default=150, help="frames per box (default 150)")
    parser.add_argument("--interval", type=integer(1), default=50, help="steps between frames (default 50)")
    parser.add_argument("--cutoff-scaling", type=number(at_least=1.0), help="f_cut instead of the model's")
    parser.add_argument("--reference-pressure", type=number(), help="pi0 (kJ/mol/nm^3) instead of the model's")
    parser.add_argument("--background-pressure", type=number(at_least=0.0),
                        help="p_b (kJ/mol/nm^3) instead of the model's; 0: none")
    parser.add_argument("--seed", type=integer(1), default=1, help="random seed (default 1)")
    add_platform(parser, default="CPU")
    add_json(parser)
    parser.set_defaults(run=run)
