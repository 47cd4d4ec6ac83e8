# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""The --fluid options that every command building a model from a fluid shares: a built-in name or a fluid file, and
the coarse-graining."""

import argparse

from openmm import unit

from ..models.fluid import (
    COARSE_GRAINING,
    MIN_DEFAULT_INTERNAL_HEAT_CAPACITY,
    MOLECULES_PER_PARTICLE,
    coarse_grain,
    default_molecules_per_particle,
)
from ..models.fluid_files import FLUIDS, fluid_named, load_parameters
from .options import POSITIVE, command_line_error


def add_fluid_arguments(parser, default="water", cutoff=True, coarse_graining_defaults=None):
    """--fluid (a built-in name or a fluid file; ``default``, or None: the subcommand's own model), and the
    coarse-graining of coarse_grain: --molecules-per-particle and --neighbors, or --cutoff (nm; ``cutoff`` False
    where the subcommand defines its own --cutoff and reads it as nm with --fluid). ``coarse_graining_defaults``:
    where a subcommand has defaults of its own, a text that says them (then both options default to None)."""
    default_text = f"default {default}" if default else "default: the published liquid-argon model"
    parser.add_argument("--fluid", default=default,
                        help=f"a built-in fluid ({', '.join(sorted(FLUIDS))}; {default_text}) or a fluid file "
                             f"(.toml or .json: each property 'value unit', docs/fluids.md)")
    molecules = (f"default {MOLECULES_PER_PARTICLE}, or more where the fluid's molecules hold little heat: enough for "
                 f"a particle's internal heat capacity to stay >= {MIN_DEFAULT_INTERNAL_HEAT_CAPACITY:g} k_B once c_v "
                 f"is matched; argon 5, supercritical argon 7")
    neighbors = f"default {COARSE_GRAINING['neighbors']:g}"
    if coarse_graining_defaults is not None:
        molecules = neighbors = coarse_graining_defaults
    parser.add_argument("--molecules-per-particle", type=POSITIVE, help=f"coarse-graining level ({molecules})",
                        default=None if coarse_graining_defaults else COARSE_GRAINING["molecules_per_particle"])
    parser.add_argument("--neighbors", type=POSITIVE, help=f"particles within the cutoff at n0 ({neighbors}), unless "
                                                           f"--cutoff is given",
                        default=None if coarse_graining_defaults else COARSE_GRAINING["neighbors"])
    if cutoff:
        parser.add_argument("--cutoff", type=POSITIVE, help="the cutoff R in nm (instead of --neighbors)")


def parameters_from_arguments(arguments, command):
    """coarse_grain of --fluid (fluid_named) with --molecules-per-particle (default_molecules_per_particle where not
    given: ``arguments`` is set to it) and --neighbors or --cutoff (nm); a bad argument exits (SystemExit, status 1)
    with a one-line error naming ``command`` and the option."""
    neighbors = arguments.neighbors if arguments.cutoff is None else None
    cutoff = None if arguments.cutoff is None else arguments.cutoff * unit.nanometer
    try:
        fluid = fluid_named(arguments.fluid)
        if arguments.molecules_per_particle is None:
            arguments.molecules_per_particle = default_molecules_per_particle(fluid)
        return coarse_grain(fluid, arguments.molecules_per_particle, neighbors=neighbors, cutoff=cutoff)
    except ValueError as error:
        raise command_line_error(command, error) from None


#: The options of the mapping of --fluid (add_fluid_arguments): a subcommand that also takes --model sets their
#: defaults to None (not given), so that model_or_fluid can refuse them with --model and put its defaults back.
FLUID_OPTIONS = ("fluid", "molecules_per_particle", "neighbors", "cutoff")


def model_or_fluid(arguments, command, default_fluid):
    """The parameters of --model (a model file, models.fluid_files.load_parameters) or of the mapping of --fluid
    (``default_fluid`` and the coarse-graining defaults where not given; parameters_from_arguments). --fluid and its
    coarse-graining with --model are refused: the model file holds its fluid and every parameter. A bad argument
    exits (SystemExit, status 1) with a one-line error naming ``command``."""
    given = [name for name in FLUID_OPTIONS if getattr(arguments, name) is not None]
    if arguments.model is not None:
        if given:
            raise SystemExit(f"error: {command}: --{given[0].replace('_', '-')} {getattr(arguments, given[0])} is "
                             f"not allowed with --model {arguments.model}: a model file holds its fluid and every "
                             f"parameter; give one of --model and --fluid")
        try:
            return load_parameters(arguments.model)
        except (OSError, ValueError) as error:
            raise command_line_error(command, error) from None
    defaults = {name: value for name, value in {"fluid": default_fluid, **COARSE_GRAINING}.items()
                if getattr(arguments, name) is None}
    return parameters_from_arguments(argparse.Namespace(**{**vars(arguments), **defaults}), command)
