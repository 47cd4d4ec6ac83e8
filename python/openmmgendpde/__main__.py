"""Command line of openmmgendpde: python3 -m openmmgendpde <subcommand> [options]; --help for each."""

import argparse

from . import benchmark_force, benchmark_integrator


def main(argv=None):
    parser = argparse.ArgumentParser(prog="python3 -m openmmgendpde",
                                     description="GenDPDE for OpenMM: liquid-argon studies and benchmarks.")
    subcommands = parser.add_subparsers(title="subcommands", required=True, metavar="SUBCOMMAND")
    benchmark_force.add_arguments(subcommands.add_parser(
        "benchmark-force", help="GenDPDEForce against CustomGBForce: ms per force evaluation, VB/VA",
        description=benchmark_force.__doc__))
    benchmark_integrator.add_arguments(subcommands.add_parser(
        "benchmark-integrator", help="GenDPDEIntegrator: ms per step against a force evaluation and VerletIntegrator",
        description=benchmark_integrator.__doc__))
    arguments = parser.parse_args(argv)
    arguments.run(arguments)


if __name__ == "__main__":
    main()
