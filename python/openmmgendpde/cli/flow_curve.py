# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""`flow-curve`: its arguments and output; the study is openmmgendpde.studies.shear (whose docstring is the command's
--help)."""

import argparse
import json

import numpy as np

from ..analysis.shear import fitted_bins
from ..api import GenDPDEIntegrator
from ..calibration.report import mpa_s
from ..internal.files import atomic_write
from ..studies import shear as study
from .fluids import FLUID_OPTIONS, add_fluid_arguments, model_or_fluid
from .options import (
    NON_NEGATIVE,
    POSITIVE,
    SEED,
    add_json,
    add_platform,
    checked_model,
    command_line_error,
    integer,
    number,
)

DESCRIPTION = study.__doc__
MODES = {"isoenergetic": GenDPDEIntegrator.Isoenergetic, "isothermal": GenDPDEIntegrator.Isothermal}
#: --quick: a functional check in seconds (512 particles, one interval, short runs).
QUICK = {"cells": (4, 4, 8), "intervals": [25], "developed": 0.5, "measured": 1.0}


def run(arguments):
    parameters = model_or_fluid(arguments, "flow-curve", "argon")
    options = dict(cells=tuple(arguments.cells), developed=arguments.developed, measured=arguments.measured)
    intervals = arguments.intervals
    if arguments.quick:
        options.update({key: value for key, value in QUICK.items() if key != "intervals"})
        intervals = QUICK["intervals"]
    length = checked_model("flow-curve", lambda: parameters.liquid(cells=options["cells"]),
                           "use more --cells").box_edges[2]
    slab = length / arguments.slabs
    margin = parameters.cutoff / 2 if arguments.margin is None else arguments.margin
    try:
        fitted_bins((np.arange(arguments.slabs) + 0.5) * slab, length, arguments.slabs, margin)
    except ValueError as error:
        raise command_line_error("flow-curve", f"{error} (--cells, --slabs, --margin)") from None
    target = parameters.targets()["shear_viscosity"]
    print(f"{parameters.fluid.name}: {parameters.molecules_per_particle:g} molecules per particle, cells "
          f"{options['cells']}, {arguments.mode}, {arguments.slabs} slabs ({slab:.3g} nm), lines fitted {margin:.3g} "
          f"nm from them; the fluid's viscosity {mpa_s(target):.4g} mPa s", flush=True)
    runs = study.flow_curve(parameters, intervals, mode=MODES[arguments.mode], slabs=arguments.slabs,
                            margin=margin, platform=arguments.platform, seed=arguments.seed, report=print, **options)
    print("| interval (steps) | shear rate (1/ps) | peak / v_th | J (kJ/mol/nm^3) | eta (amu/(nm ps)) | eta (mPa s) "
          "| eta / fluid's | theta_harm (K) |")
    print("|---|---|---|---|---|---|---|---|")
    for r in runs:
        result = r.result
        print(f"| {r.interval} | {result.shear_rate:.4g} +- {result.shear_rate_error:.2g} | {r.peak_fraction:.2f} | "
              f"{result.momentum_flux:.4g} +- {result.momentum_flux_error:.2g} | {result.viscosity:.4g} +- "
              f"{result.error:.2g} | {mpa_s(result.viscosity):.4g} +- {mpa_s(result.error):.2g} | "
              f"{result.viscosity / target:.3f} | {temperatures(r)} |")
    if arguments.json:
        with atomic_write(arguments.json) as stream:
            json.dump({"fluid": parameters.fluid.name, "cells": list(options["cells"]), "mode": arguments.mode,
                       "target_viscosity": target, "runs": [study.record(r) for r in runs]}, stream, indent=1,
                      default=float)
    return runs


def temperatures(run):
    """The table's theta_harm column: the lowest and highest bin, or 'frozen' in the Isothermal mode (the particles'
    temperatures do not evolve there)."""
    if run.mode == GenDPDEIntegrator.Isothermal:
        return "frozen"
    return f"{run.temperature_profile.min():.1f} - {run.temperature_profile.max():.1f}"


def even_slabs(text):
    """An argparse type: an even integer from 4 to 1000 (the exchange slabs are slab 0 and slab slabs/2)."""
    value = integer(4, 1000)(text)
    if value % 2:
        raise argparse.ArgumentTypeError(f"{value} is not allowed; it must be an even integer from 4 to 1000 (the "
                                         f"exchange slabs are slab 0 and slab slabs/2)")
    return value


def add_arguments(parser):
    parser.add_argument("--model", help="a model file (calibrate --output), which holds its fluid and every "
                        "parameter (--fluid and its coarse-graining are refused with it); else the mapping of --fluid")
    add_fluid_arguments(parser, default="argon")
    parser.set_defaults(**dict.fromkeys(FLUID_OPTIONS))   # (not given: None; --model refuses them)
    parser.add_argument("--cells", type=integer(1, 100), nargs=3, default=[8, 8, 8], metavar=("NX", "NY", "NZ"),
                        help="FCC cells of the box (default 8 8 8: 2048 particles); the flow is along x, its "
                             "gradient along z")
    parser.add_argument("--intervals", type=integer(1), nargs="+", default=[100, 50, 25, 12],
                        help="steps between momentum swaps, one run each (default 100 50 25 12: faster flows to the "
                             "right)")
    parser.add_argument("--slabs", type=even_slabs, default=20,
                        help="slabs along z (= bins of the profile), even (default 20)")
    parser.add_argument("--margin", type=NON_NEGATIVE, help="nm between the exchange slabs and the bins fitted "
                                                            "(default R/2)")
    parser.add_argument("--developed", type=POSITIVE, default=2.0,
                        help="momentum diffusion times waited before averaging (default 2)")
    parser.add_argument("--measured", type=number(above=0), default=10.0,
                        help="momentum diffusion times averaged (default 10)")
    parser.add_argument("--mode", choices=sorted(MODES), default="isoenergetic",
                        help="the integrator's mode (default isoenergetic: a temperature profile forms; isothermal: "
                             "the DPD thermostat takes the viscous heat, without the Ito term of the friction)")
    parser.add_argument("--quick", action="store_true", help="4 x 4 x 8 cells, one interval (25), short runs: a "
                                                             "functional check in seconds")
    parser.add_argument("--seed", type=SEED, default=1, help="random seed of the first run (default 1)")
    add_platform(parser, default="CPU")
    add_json(parser)
    parser.set_defaults(run=run)
