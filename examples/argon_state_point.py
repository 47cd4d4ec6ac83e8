"""Evaluate liquid argon at n0* = 1 (FCC lattice, Maxwell-Boltzmann temperature T0*) with the VA and VB density
estimators at the three published cutoffs, and print mean n_i, mean pi_i and the virial pressure in reduced units.

    PYTHONPATH=build/python /usr/bin/python3 examples/argon_state_point.py [--particles 4000] [--platform CPU]
"""

import argparse

import numpy as np
import openmm

from openmmgendpde.presets import ARGON_CUTOFFS, ARGON_STATE, ARGON_UNITS, liquid_argon


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--particles", type=int, default=4000, help="4 m^3 particles (default 4000)")
    parser.add_argument("--platform", default="Reference", help="OpenMM platform (default Reference)")
    args = parser.parse_args()
    units, state = ARGON_UNITS, ARGON_STATE
    print(f"Liquid argon, {args.particles} particles on an FCC lattice at n0* = {state.density}, "
          f"T* = {state.temperature} (reduced units; pressure unit {units.unit('pressure')})")
    print(f"{'R_cut*':>8} {'estimator':>9} {'mean n_i*':>10} {'mean pi_i*':>11} {'P* (virial)':>12}")
    for cutoff in ARGON_CUTOFFS:
        for estimator in ("VA", "VB"):
            argon = liquid_argon(args.particles, cutoff.cutoff, estimator)
            context = openmm.Context(argon.system, openmm.VerletIntegrator(0.001),
                                     openmm.Platform.getPlatformByName(args.platform))
            context.setPositions(argon.positions)
            densities = argon.force.getParticleDensities(context)
            pressures = argon.force.getParticlePressures(context)
            virial = argon.force.getVirial(context)
            # P = (2K + W)/(3V) with the equipartition kinetic energy 2K = 3 N k_B T0.
            volume = units.from_openmm(argon.box_volume, "volume")
            pressure = (3 * argon.num_particles * state.temperature + units.from_openmm(virial, "energy")) / (3 * volume)
            print(f"{cutoff.cutoff:8.4f} {estimator:>9} {units.from_openmm(np.mean(densities), 'number_density'):10.4f} "
                  f"{units.from_openmm(np.mean(pressures), 'pressure'):11.4f} {pressure:12.4f}")


if __name__ == "__main__":
    main()
