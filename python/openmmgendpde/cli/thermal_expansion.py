# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""`thermal-expansion`: its arguments and output; the measurement is openmmgendpde.calibration.expansion's (whose
docstring is the command's --help)."""

import sys

from openmm import unit

from ..calibration import expansion
from ..models.fluid_files import fluid_named
from .fluids import add_fluid_arguments
from .options import (
    NON_NEGATIVE_COUNT,
    POSITIVE,
    SEED,
    add_platform,
    checked_model,
    command_line_error,
    fcc_particles,
    integer,
)

DESCRIPTION = expansion.__doc__
#: The names --fluid took before every command took the same ones, and those names (until 0.3, with a warning).
OLD_FLUID_NAMES = {"liquid": "argon-expanding", "supercritical": "supercritical-argon"}


def fluid_of(arguments):
    """(Fluid, its mapped GenDPDEParameters) of --fluid (a built-in name or a fluid or model file, as every command
    takes it) and the coarse-graining options; a fluid without a thermal expansion, or a bad name, ends in a one-line
    error."""
    name = arguments.fluid
    if name in OLD_FLUID_NAMES:
        print(f"warning: thermal-expansion: --fluid {name} is now --fluid {OLD_FLUID_NAMES[name]} (the old name is "
              f"removed in version 0.3)", file=sys.stderr)
        name = OLD_FLUID_NAMES[name]
    try:
        fluid = fluid_named(name)
        return fluid, expansion.mapped(fluid, arguments.molecules_per_particle, neighbors=arguments.neighbors,
                                       cutoff=None if arguments.cutoff is None else arguments.cutoff * unit.nanometer)
    except ValueError as error:
        raise command_line_error("thermal-expansion", error) from None


def report(result, results):
    """The lines of one measurement (the mapped beta first, then each correction)."""
    label = "mapped" if not results else f"after correction {len(results)}"
    print(f" beta = {result.thermal_pressure:.5f} kJ/mol/nm^3/K ({label})")
    for t, te, p, e in zip(result.temperatures, result.temperature_errors, result.pressures, result.pressure_errors):
        print(f"  T = {t:.2f} +- {te:.2f} K: P = {p:.3f} +- {e:.3f} MPa")
    print(f"  (dP/dT)_V = {result.slope:.4f} +- {result.slope_error:.4f} MPa/K (fluid: {result.target_slope:.4f})")
    print(f"  alpha = kappa_T (dP/dT)_V = {result.alpha:.4e} +- {result.alpha_error:.1e} 1/K "
          f"(fluid: {result.target_alpha:.4e}; ratio {result.alpha / result.target_alpha:.3f})", flush=True)
    results.append(result)


def run(arguments):
    fluid, parameters = fluid_of(arguments)
    # Checked before anything runs: the box against the cutoff, and the two temperatures T0 -+ dT above zero.
    checked_model("thermal-expansion", lambda: parameters.liquid(arguments.particles, seed=arguments.seed),
                  "use more --particles")
    if arguments.delta is not None and not arguments.delta < parameters.temperature:
        raise SystemExit(f"error: thermal-expansion: --delta {arguments.delta:g} is not allowed; it must be < T0 = "
                         f"{parameters.temperature:g} K of {fluid.name} (the run at T0 - dT needs a temperature > 0)")
    print(f"{fluid.name}, {arguments.particles} particles, {parameters.neighbors:.2f} neighbours within the cutoff "
          f"{parameters.cutoff:.4f} nm, {arguments.platform}")
    reported = []
    return expansion.measured_and_corrected(
        parameters, arguments.iterations, lambda result: report(result, reported), num_particles=arguments.particles,
        delta=arguments.delta, melt_steps=arguments.melt, steps=arguments.steps, sample_every=expansion.SAMPLE_EVERY,
        platform=arguments.platform, seed=arguments.seed)


def add_arguments(parser):
    add_fluid_arguments(parser, default="argon-expanding", coarse_graining_defaults=(
        f"default of thermal-expansion: {expansion.MOLECULES_PER_PARTICLE} molecules per particle, argon-expanding "
        f"at the paper's R* = 1.6839, another fluid at 20 neighbours within the cutoff, as that R* gives"))
    parser.add_argument("--particles", type=fcc_particles, default=4000, help="4 m^3 particles (default 4000)")
    parser.add_argument("--delta", type=POSITIVE, help="dT (K) of the runs at T0 -+ dT, > 0 and < T0 (default: 8%% "
                                                       "of T0)")
    parser.add_argument("--melt", type=NON_NEGATIVE_COUNT, default=1000,
                        help="Isothermal steps before each run (default 1000)")
    every, samples = expansion.SAMPLE_EVERY, expansion.MIN_SAMPLES
    parser.add_argument("--steps", type=integer(every * samples, why=f" ({samples} samples, one every {every} steps)"),
                        default=4000, help=f"sampled Isoenergetic steps per run (default 4000; at least "
                                           f"{every * samples})")
    parser.add_argument("--seed", type=SEED, default=1, help="random seed (default 1)")
    parser.add_argument("--iterations", type=NON_NEGATIVE_COUNT, default=1,
                        help="corrections of beta from the measured slope, each measured again (default 1)")
    add_platform(parser, default="CPU")
    parser.set_defaults(run=run)
