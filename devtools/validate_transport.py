# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""Measure a fluid model's viscosity or conductivity two ways on the same parameters and box (docs/transport.md):
the wave decay of `calibrate` (Calibration.shear_viscosity / thermal_conductivity) and the steady flow of
openmmgendpde.analysis.transport (Poiseuille flow / heat flux between slabs), and print both with their ratio.

    python devtools/validate_transport.py --fluid argon --cells 8 8 8 --what viscosity --replicas 4

The model: coarse_grain(fluid, molecules per particle, neighbors=20) as mapped (f_cut not tuned), or a model file
(--model, e.g. calibrate --output's), its parameters scaled by --scale; V-B, dt* = 0.01,
in a box of n_x x n_y x n_z FCC cells; each replica is melted (Isothermal) and equilibrated (Isoenergetic) as
Calibration._equilibrated does. CPU platform, one thread unless --threads; --processes replicas at once.
"""

import argparse
import dataclasses
import time

import openmm

from openmmgendpde.analysis import transport
from openmmgendpde.calibration.calibration import Calibration, Plan
from openmmgendpde.calibration.report import mpa_s, w_mk
from openmmgendpde.models.fluid import coarse_grain
from openmmgendpde.models.fluid_files import FLUIDS, load_parameters


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--fluid", choices=sorted(FLUIDS), default="argon")
    parser.add_argument("--model", help="a model file (calibrate --output) instead of --fluid's mapping")
    parser.add_argument("--scale", nargs=2, action="append", default=[], metavar=("PARAMETER", "FACTOR"),
                        help="multiply a parameter of the model (friction, heat_conduction, heat_capacity, ...); "
                             "repeatable")
    parser.add_argument("--molecules-per-particle", type=float, help="default: argon 5, water 4")
    parser.add_argument("--cells", type=int, nargs=3, default=(8, 8, 8))
    parser.add_argument("--what", choices=("viscosity", "conductivity"), required=True)
    parser.add_argument("--methods", choices=("both", "wave", "steady"), default="both")
    parser.add_argument("--replicas", type=int, default=4)
    parser.add_argument("--wave-steps", type=int, default=1500,
                        help="steps of a decaying wave at least (calibrate: 1500; and 2 decay times)")
    parser.add_argument("--peak-fraction", type=float, default=0.2, help="Poiseuille peak velocity / v_th")
    parser.add_argument("--excess", type=float, default=0.1, help="heat flux: slabs at T0 (1 +- excess)")
    parser.add_argument("--bins", type=int, default=40)
    parser.add_argument("--developed", type=float, help="diffusion times waited (default the function's)")
    parser.add_argument("--measured", type=float, help="diffusion times averaged (default the function's)")
    parser.add_argument("--threads", default="1")
    parser.add_argument("--processes", type=int, default=1,
                        help="replicas run at once, one thread each (calibrate: as many as --threads)")
    parser.add_argument("--seed", type=int, default=1)
    arguments = parser.parse_args()
    if arguments.model:
        parameters = load_parameters(arguments.model)
        molecules = parameters.molecules_per_particle
    else:
        molecules = arguments.molecules_per_particle or {"argon": 5, "water": 4}[arguments.fluid]
        parameters = coarse_grain(FLUIDS[arguments.fluid], molecules, neighbors=20)
    for name, factor in arguments.scale:
        parameters = dataclasses.replace(parameters, **{name: getattr(parameters, name) * float(factor)})
    openmm.Platform.getPlatformByName("CPU").setPropertyDefaultValue("Threads", arguments.threads)
    plan = dataclasses.replace(Plan(), replicas=arguments.replicas, wave_steps=arguments.wave_steps,
                               steady_cells=tuple(arguments.cells))
    calibration = Calibration(parameters, "VB", plan, "CPU", seed=arguments.seed, workers=arguments.processes)
    replicas = calibration.replicas(plan.steady_cells)
    viscosity = arguments.what == "viscosity"
    convert = mpa_s if viscosity else w_mk
    target = convert(parameters.targets()["shear_viscosity" if viscosity else "thermal_conductivity"])
    lengths = {key: getattr(arguments, key) for key in ("developed", "measured") if getattr(arguments, key)}
    rows = []
    if arguments.methods in ("both", "wave"):
        start = time.time()
        result = calibration.shear_viscosity() if viscosity else calibration.thermal_conductivity()
        rows.append(("wave decay", result.value, result.error, time.time() - start))
    if arguments.methods in ("both", "steady"):
        start = time.time()
        if viscosity:
            result = transport.poiseuille_viscosity(calibration.parameters, replicas, bins=arguments.bins,
                                                    peak_fraction=arguments.peak_fraction, **lengths)
        else:
            result = transport.heat_flux_conductivity(calibration.parameters, replicas, bins=arguments.bins,
                                                      excess=arguments.excess, **lengths)
        rows.append(("Poiseuille flow" if viscosity else "heat flux", result.value, result.error, time.time() - start))
    unit_name = "mPa s" if viscosity else "W/(m K)"
    scaled = "".join(f", {name} x {factor}" for name, factor in arguments.scale)
    print(f"{arguments.model or arguments.fluid}{scaled}, {molecules:g} per particle, cells {tuple(arguments.cells)}, "
          f"{arguments.replicas} replicas: {arguments.what} ({unit_name})")
    print("| method | value | target | value/target | run time (s) |\n|---|---|---|---|---|")
    for name, value, error, seconds in rows:
        print(f"| {name} | {convert(value):.4g} +- {convert(error):.2g} | {target:.4g} | "
              f"{convert(value) / target:.3f} | {seconds:.0f} |")
    if len(rows) == 2:
        (_, a, ea, _), (_, b, eb, _) = rows
        print(f"steady/wave = {b / a:.3f} +- {b / a * ((ea / a)**2 + (eb / b)**2)**0.5:.3f}")


if __name__ == "__main__":
    main()
