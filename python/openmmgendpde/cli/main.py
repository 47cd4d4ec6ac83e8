# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""The command line of openmmgendpde: python -m openmmgendpde <subcommand> [options]; --help for each. Each subcommand
is a module of this package with its arguments (add_arguments), its run (run, over the functions of the layers
below) and its --help text (DESCRIPTION, the method's docstring where the method lives below)."""

import argparse

from . import (
    benchmark_cpu,
    benchmark_force,
    benchmark_integrator,
    calibrate,
    compression,
    flow_curve,
    lammps_input,
    rdf,
    slab,
    speed_vs_error,
    table3,
    thermal_expansion,
    timing,
    tune_fcut,
)
from .options import parse_arguments, run_command

#: (name, module, one-line help); each module has add_arguments(parser), run(arguments) and DESCRIPTION for --help.
SUBCOMMANDS = (
    ("table3", table3, "reproduce Table III: T*, n-bar*, P* for 3 cutoffs x VA/VB beside the published values"),
    ("rdf", rdf, "radial distribution functions of the six cases, plotted like Fig. 1 (PNG and PDF)"),
    ("timing", timing, "Table IV analogue: wall time per step with VA and VB, and their ratio, per cutoff"),
    ("tune-fcut", tune_fcut, "find f_cut of VB or VC so that the mean density is n0, with its uncertainty"),
    ("calibrate", calibrate, "any fluid: parameters from its physical properties, and the model's properties "
                             "measured back"),
    ("thermal-expansion", thermal_expansion, "a fluid with thermal expansion: (dP/dT)_V and alpha measured back "
                                             "beside the fluid's"),
    ("compression", compression, "how a model liquid's particle densities, structure and pressure follow a "
                                 "compression: the response, n dP/dn and n k_B T/S(0)"),
    ("slab", slab, "a liquid slab in vacuum with VA, VB and VC, and the estimators against the exact "
                   "partition-of-unity volume"),
    ("flow-curve", flow_curve, "shear viscosity against shear rate from reverse non-equilibrium shear flows "
                               "(momentum swaps)"),
    ("speed-vs-error", speed_vs_error, "cost per simulated time against the error, for several step sizes"),
    ("lammps-input", lammps_input, "a calibrated model file as the LAMMPS plugin's input: a data file and a script"),
    ("benchmark-force", benchmark_force, "GenDPDEForce against CustomGBForce: ms per force evaluation, VB/VA"),
    ("benchmark-integrator", benchmark_integrator, "GenDPDEIntegrator: ms per step against a force evaluation"),
    ("benchmark-cpu", benchmark_cpu, "the CPU platform's threads side by side with Reference: ms, speed-ups, memory"),
)


def main(argv=None):
    parser = argparse.ArgumentParser(prog="python3 -m openmmgendpde",
                                     description="GenDPDE for OpenMM: fluid calibration, liquid-argon studies and "
                                                 "benchmarks.")
    subcommands = parser.add_subparsers(title="subcommands", required=True, metavar="SUBCOMMAND", dest="command")
    for name, module, summary in SUBCOMMANDS:
        module.add_arguments(subcommands.add_parser(name, help=summary,
                                                    description=getattr(module, "DESCRIPTION", module.__doc__),
                                                    formatter_class=argparse.RawDescriptionHelpFormatter))
    arguments = parse_arguments(parser, argv)
    # Every argument is checked by now (its type) or by the subcommand before it runs anything; what fails during the
    # run (a simulation that goes bad, an output that cannot be written, Ctrl-C) ends in one line, not a traceback.
    return run_command(arguments.command, arguments.run, arguments)


def format_warning(message, category, filename, lineno, line=None):
    """A warning of a command-line run (e.g. statistics.BlockAverageWarning) as one line on stderr."""
    return f"warning: {message}\n"
