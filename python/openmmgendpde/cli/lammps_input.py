# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""A calibrated model file (calibrate --output; fluid_files.load_parameters) as input for the project's LAMMPS plugin
(pair style gendpde and fix gendpde), so that the fluid runs in LAMMPS as it does in OpenMM (docs/lammps.md).

The model is built as every study builds it (GenDPDEParameters.liquid: an FCC lattice of --particles at n0 in a
cubic box, its GenDPDEForce and GenDPDEIntegrator), the velocities drawn as Model.context draws them (Maxwell-
Boltzmann at T0 with --seed), and two files are written into --output: gendpde.data (atom_style atomic: box,
masses, positions and velocities; atom i + 1 is OpenMM's particle i) and in.gendpde (the pair style, the fix, the
neighbour skin and the ghost cutoff the fix's sweep needs; variables at the top), with models.lammps_files, the
project's one LAMMPS writer. Every number is converted from OpenMM's units (nm, kJ/mol, ps, amu, K) to LAMMPS's
--units: metal (Å, eV, ps, g/mol, K; the default) with 1 kJ/mol = 1000/(e N_A) eV (CODATA 2018), real (Å, kcal/mol,
fs, g/mol, K) with 1 kcal/mol = 4.184 kJ/mol, or lj holding OpenMM's own numbers with k_B = 1 (temperatures as
k_B T). Pressures are energy/volume (eV/Å^3 in metal), not LAMMPS's pressure units. LAMMPS's own k_B is 1.13e-6
(metal) or 1.23e-6 (real) relatively larger than OpenMM's (openmmgendpde.models.lammps_files lists the units and
what differs). Then:

    cd OUTPUT && lmp -var plugin /path/to/gendpdeplugin.so -in in.gendpde

--skin (in the units' length): by default 0.1 R (rounded up to 4 significant digits), the skin of the plugin's
OpenMM platforms, which scales with the model's cutoff R; LAMMPS's own metal default, 2 Å, does not. The box must be
at least 4 R wide (the fix's sweep cells): a box too small is refused, saying so.
"""

import os

import openmm

from ..models.fluid_files import load_parameters
from ..models.lammps_files import DATA_FILE, MAX_SEED, MODES, SCRIPT_FILE, model_input, write_lammps_input
from ..models.lammps_units import UNITS
from .options import (
    COUNT,
    NON_NEGATIVE_COUNT,
    POSITIVE,
    command_line_error,
    fcc_particles,
    integer,
    writable_directory,
)

COMMAND = "lammps-input"
#: The particles by default: those models are calibrated with (calibrate's default, calibration.Plan.particles;
#: test_lammps_input checks they agree), since
#: GenDPDEParameters.liquid() has no default of its own.
DEFAULT_PARTICLES = 2048
#: --seed: the fix takes 0 to 2^31 - 1, and 0 would make OpenMM pick a seed of its own when a Context is created.
SEED = integer(1, MAX_SEED, " (the fix gendpde's random seed and the velocities' OpenMM seed; 0 would let OpenMM pick "
                            "one, and LAMMPS could not draw the same random numbers)")


def plugin_path(text):
    """An argparse type for --plugin: a path written into the input script, made absolute; refused if LAMMPS would
    split or substitute it (white space, quotes, '#', '$', '&')."""
    import argparse
    if not text or any(c.isspace() or c in "\"'#$&" for c in text):
        raise argparse.ArgumentTypeError(f"{text!r} is not allowed; the path must have no white space, quotes, '#', "
                                         f"'$' or '&' (LAMMPS would split or substitute it)")
    return os.path.abspath(text)


def run(arguments):
    if not os.path.isfile(arguments.model):
        raise SystemExit(f"error: {COMMAND}: {arguments.model}: no such file")
    try:
        parameters = load_parameters(arguments.model)
        texts = model_input(parameters, arguments.particles, arguments.mode, arguments.seed, arguments.step_size,
                            arguments.steps, arguments.thermo, arguments.skin, arguments.plugin,
                            f"{parameters.fluid.name}, from {os.path.basename(arguments.model)}", arguments.units)
    except (ValueError, openmm.OpenMMException) as error:
        raise command_line_error(COMMAND, error, "use more --particles") from None
    data, script = write_lammps_input(arguments.output, texts)
    length = UNITS[texts.units]["length"][0]
    print(f"{parameters.fluid.name}: {arguments.particles} particles, {arguments.mode}, seed {arguments.seed}, units "
          f"{texts.units}, R = {texts.cutoff:.6g} {length}, skin {texts.skin:g} {length}, comm_modify cutoff "
          f"{texts.ghost:g} {length}.")
    print(f"Wrote {data} and {script}; run them with:")
    plugin = "" if arguments.plugin else " -var plugin /path/to/gendpdeplugin.so"
    print(f"  cd {arguments.output} && lmp{plugin} -in {SCRIPT_FILE}")
    return data, script


def add_arguments(parser):
    parser.add_argument("model", metavar="MODEL", help="a model file (.toml or .json) written by calibrate --output")
    parser.add_argument("--particles", type=fcc_particles, default=DEFAULT_PARTICLES,
                        help=f"particle count, 4 m^3 (default {DEFAULT_PARTICLES}, that of calibrate)")
    parser.add_argument("--output", type=writable_directory, default=".", metavar="DIRECTORY",
                        help=f"directory for {DATA_FILE} and {SCRIPT_FILE} (made if absent; default: the current one)")
    parser.add_argument("--steps", type=NON_NEGATIVE_COUNT, default=1000, help="steps of the run (default 1000)")
    parser.add_argument("--step-size", type=POSITIVE, help="the step in ps (default the model's: dt* = 0.01 of its "
                                                           "reduced time)")
    parser.add_argument("--mode", choices=list(MODES), default="isoenergetic",
                        help="the fix's mode (default isoenergetic)")
    parser.add_argument("--seed", type=SEED, default=1, help="random seed of the fix and of the velocities (default 1)")
    parser.add_argument("--plugin", type=plugin_path, metavar="PATH",
                        help="gendpdeplugin.so, written as the default of the script's variable plugin (default: "
                             "none; give it to lmp with -var plugin PATH)")
    parser.add_argument("--units", choices=list(UNITS), default="metal",
                        help="LAMMPS's units: metal (default), real, or lj holding OpenMM's numbers with k_B = 1")
    parser.add_argument("--skin", type=POSITIVE, help="the neighbour skin in the units' length (default 0.1 R, as "
                                                      "the OpenMM platforms, rounded up to 4 significant digits)")
    parser.add_argument("--thermo", type=COUNT, default=100, help="thermo output every this many steps (default 100)")
    parser.set_defaults(run=run)
