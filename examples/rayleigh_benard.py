# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""A liquid layer heated from below in gravity, which starts to convect above a critical temperature difference
(Rayleigh-Benard); the velocity and temperature fields are drawn (docs/thermal.md).

Why a model liquid and not argon. Buoyancy needs thermal expansion, and gravity also compresses the layer:
drho/rho = g H/c_T^2 across a layer of depth H. At the onset Ra = g alpha dT H^3/(nu D_T) ~ 1e3, so
H^2 ~ 1e3 nu D_T/(c_T^2 (drho/rho) alpha dT): in the model's units (L = n0^(-1/3), tau = L/c_T) liquid argon at 5
atoms per particle has nu* = 0.40 and D_T* = 0.25, and a layer compressed by less than 20% at alpha dT = 0.2 must be
~100 particles deep and run ~1e6 steps. Coarser particles lower nu* and D_T* but stop diffusing (they stay a
lattice). So the liquid here (liquid_fluid()) keeps argon's density, compressibility, Tait law and particles (5
atoms, 20 neighbours) and changes what transport and buoyancy need: the friction is 1/30 of argon's, so that the
viscosity is the floor the particles' own motion sets (nu* ~ 0.05, measured here); the conductivity is chosen for a
target D_T* = 0.025 (the particles' motion adds to it: ~0.047 measured); alpha is 3 times argon's and c_v 30 times,
so that the temperature differences stay within +-20 K of T0 and the adiabatic difference g H alpha T0/c_p is small
(c_p/c_v = 1.24). The liquid fills 7 FCC cells between two walls of frozen particles (2 cells each), 14 cells wide
(one pair of rolls) and 3 thick (quasi-2D).

Setup: the walls' particles (mass 0) and the liquid's particles within half a cell of a wall have their
temperatures put back every 20 steps to T0 +- dT/2: H is the distance between those layers, and the energy put in
and taken out is the heat flux. Gravity (g H/c_T^2 = --compression) and a stiff repulsion at the walls' faces act on
the liquid (one CustomExternalForce). Each run starts from the conduction profile plus one roll's temperature pattern
(--perturbation) and runs Isoenergetic (K + U + sum eps conserved but for the resets) for --thermal-times times
H^2/D_T (the target D_T). Its second half is averaged.

Measured: nu from a transverse wave's decay (calibrate's method); lambda and the fraction of dT across the liquid
(the rest falls at the walls) from the first run, below the onset (conduction: the heat flux over the interior's
temperature gradient). Ra = g alpha (fraction dT - dT_ad) H^3/(nu D_T) with D_T = lambda/(rho c_p) (c_p of the
fluid's alpha) and the adiabatic difference dT_ad = g H alpha T0/c_p; the Nusselt number, the heat flux over that of
conduction at the same dT; the flow, the root mean square of the grid cells' mean velocities against that of
thermal noise alone; and the slip, how freely the flow slides along the walls.

    .venv/bin/python examples/rayleigh_benard.py --plot rb      # 5 differences, about 20 minutes
"""

import argparse
import dataclasses
import math

import numpy as np
import openmm
from openmm import unit

from openmmgendpde import GenDPDEIntegrator
from openmmgendpde.analysis.statistics import block_standard_error
from openmmgendpde.calibration.calibration import Calibration, Plan
from openmmgendpde.cli.options import (
    COUNT,
    NON_NEGATIVE,
    POSITIVE,
    add_platform,
    number,
    one_line_errors,
    parse_arguments,
    writable_stem,
)
from openmmgendpde.internal.files import atomic_write
from openmmgendpde.models.fluid import ARGON, ARGON_EXPANDING, coarse_grain

CELLS = (14, 3, 11)          # FCC cells along x, y, z: 2 of wall, 7 of liquid, 2 of wall
WALL_CELLS = 2
#: Ra_c of linear stability (Chandrasekhar 1961): both walls rigid (no slip), and both stress-free (full slip)
RAYLEIGH_CRITICAL = {"rigid": 1707.8, "stress-free": 27 * math.pi**4 / 4}
ATOMS = 5
NEIGHBORS = 20
DIFFUSIVITY = 0.025          # the target D_T, L^2/tau
#: The most cells of the fields' grid (--grid): one per layer of particles, 2 per FCC cell, across the box (x) and the
#: liquid (z).
MAX_GRID = (2 * CELLS[0], 2 * (CELLS[2] - 2 * WALL_CELLS))
#: Steps between the samples of the fields (run's sample_every).
SAMPLE_EVERY = 100
#: H in units of L = n0^(-1/3): the liquid's cells less the layer of half a cell at each wall (FCC cell 4^(1/3) L).
DEPTH = (CELLS[2] - 2 * WALL_CELLS - 1) * 4 ** (1 / 3)


def middle_layers(nz):
    """Which of the grid's nz layers (from the bottom face) are the interior, the middle 60% of the depth, over which
    the temperature gradient is fitted (at least 2 are needed)."""
    centres = (np.arange(nz) + 0.5) / nz
    return (centres > 0.2) & (centres < 0.8)


def liquid_fluid():
    """The model liquid: argon's density, compressibility and Tait law; 1/30 of its viscosity, 3 times its alpha, 30
    times its c_v, and the conductivity of D_T* = DIFFUSIVITY at 5 atoms per particle."""
    fluid = dataclasses.replace(ARGON_EXPANDING,
                                name="model liquid for convection (argon's density and compressibility)",
                                shear_viscosity=ARGON.shear_viscosity / 30,
                                thermal_expansion=3 * ARGON_EXPANDING.thermal_expansion,
                                heat_capacity=30 * ARGON.heat_capacity)
    f = fluid.in_openmm()
    units = coarse_grain(fluid, ATOMS, neighbors=NEIGHBORS).units
    length = units.to_openmm(1, "length").value_in_unit(unit.nanometer)
    tau = units.to_openmm(1, "time").value_in_unit(unit.picosecond)
    conductivity = DIFFUSIVITY * length**2 / tau * f["mass_density"] * specific_heat(f)[1]
    return dataclasses.replace(fluid, thermal_conductivity=conductivity * unit.kilojoule_per_mole
                               / (unit.picosecond * unit.nanometer * unit.kelvin))


def specific_heat(f):
    """(c_v, c_p) per amu (kJ/mol/K/amu) of a fluid's in_openmm() properties: c_p = c_v + T alpha^2/(rho kappa_T)."""
    c_v = f["heat_capacity"] / f["molar_mass"]
    return c_v, c_v + f["temperature"] * f["thermal_expansion"] ** 2 / (f["mass_density"] * f["compressibility"])


def build(parameters, gravity, seed, time_step):
    """The model with frozen walls and the CustomExternalForce (gravity and the walls' faces) on the liquid."""
    model = parameters.liquid(cells=CELLS, mode=GenDPDEIntegrator.Isothermal, time_step=time_step, seed=seed)
    cell = model.system.getDefaultPeriodicBoxVectors()[2][2].value_in_unit(unit.nanometer) / CELLS[2]
    z = model.positions[:, 2]
    bottom_face, top_face = (WALL_CELLS - 0.25) * cell, (CELLS[2] - WALL_CELLS - 0.25) * cell
    hot, cold = z < bottom_face, z > top_face
    external = openmm.CustomExternalForce("stiffness*(step(bottom-z)*(bottom-z)^2 + step(z-top)*(z-top)^2)"
                                          " + weight*z")
    external.addGlobalParameter("stiffness", 100 * parameters.bulk_modulus * parameters.density ** (-1 / 3))
    external.addGlobalParameter("bottom", bottom_face)
    external.addGlobalParameter("top", top_face)
    external.addGlobalParameter("weight", parameters.mass * gravity)
    for i in range(model.num_particles):
        if hot[i] or cold[i]:
            model.system.setParticleMass(i, 0.0)
        else:
            external.addParticle(i)
    model.system.addForce(external)
    return model, hot, cold, (bottom_face, top_face)


def run(parameters, difference, gravity, steps, platform, seed, grid, time_step, perturbation, layer,
        reset_every=20, sample_every=SAMPLE_EVERY):
    """One run at the wall difference ``difference`` (K). Over its second half: the heat flux (kJ/mol/ps per nm^2,
    the mean of what the hot wall gives and the cold one takes), the grid's mean velocity (x, z; nm/ps) and theta
    fields, the flow and its noise (nm/ps), and the interior's temperature gradient (K/nm, from the harmonic means
    of theta in layers, the middle 60% of the depth)."""
    model, hot, cold, (bottom, top) = build(parameters, gravity, seed, time_step)
    integrator = model.integrator
    t0 = parameters.temperature
    t_hot, t_cold = t0 + difference / 2, t0 - difference / 2
    context = model.melted(platform, GenDPDEIntegrator.Isoenergetic, 1000, 0, seed=seed)
    box = [model.system.getDefaultPeriodicBoxVectors()[k][k].value_in_unit(unit.nanometer) for k in range(3)]
    x, z = model.positions[:, 0], model.positions[:, 2]
    height = np.clip((z - bottom - layer) / (top - bottom - 2 * layer), 0, 1)
    integrator.setParticleTemperatures(list(t_hot + (t_cold - t_hot) * height + perturbation
                                            * np.sin(2 * np.pi * x / box[0]) * np.sin(np.pi * height)))
    capacity = parameters.heat_capacity
    liquid = ~(hot | cold)
    nx, nz = grid
    dt = integrator.getStepSize().value_in_unit(unit.picosecond)
    steps = steps // (2 * sample_every) * 2 * sample_every
    sums, counts, inverse = np.zeros((3, nx, nz)), np.zeros((nx, nz)), np.zeros((nx, nz))
    heats, kinetic = [], 0.0
    samples = 0
    for step in range(reset_every, steps + 1, reset_every):
        integrator.step(reset_every)
        theta = np.asarray(integrator.getParticleTemperatures().value_in_unit(unit.kelvin))
        z = context.getState(getPositions=True).getPositions(asNumpy=True).value_in_unit(unit.nanometer)[:, 2]
        heated, cooled = hot | (liquid & (z < bottom + layer)), cold | (liquid & (z > top - layer))
        measured = step > steps // 2
        if measured:
            heats.append(capacity * (float(np.sum(t_hot - theta[heated])) + float(np.sum(theta[cooled] - t_cold))) / 2)
        theta[heated], theta[cooled] = t_hot, t_cold
        integrator.setParticleTemperatures(list(theta))
        if measured and step % sample_every == 0:
            state = context.getState(getPositions=True, getVelocities=True, enforcePeriodicBox=True)
            r = state.getPositions(asNumpy=True).value_in_unit(unit.nanometer)[liquid]
            v = state.getVelocities(asNumpy=True).value_in_unit(unit.nanometer / unit.picosecond)[liquid]
            ix = np.clip((r[:, 0] / box[0] * nx).astype(int), 0, nx - 1)
            iz = np.clip(((r[:, 2] - bottom) / (top - bottom) * nz).astype(int), 0, nz - 1)
            for k in range(3):
                np.add.at(sums[k], (ix, iz), v[:, k])
            np.add.at(counts, (ix, iz), 1)
            np.add.at(inverse, (ix, iz), 1 / theta[liquid])
            kinetic += float(np.sum(v * v)) / (3 * len(v))
            samples += 1
    velocity = sums / np.maximum(counts, 1)
    # A cell's mean of N samples of pure thermal noise has the variance <v^2>/N per component.
    noise = math.sqrt(kinetic / samples * float(np.mean(1 / np.maximum(counts, 1))))
    flow = math.sqrt(float(np.mean(velocity[0] ** 2 + velocity[2] ** 2)) / 2)
    layers = counts.sum(axis=0) / inverse.sum(axis=0)
    centre = (np.arange(nz) + 0.5) / nz * (top - bottom)
    middle = middle_layers(nz)
    gradient = float(np.polyfit(centre[middle], layers[middle], 1)[0])
    # The heat per reset interval over the area; its error from 10 block means (successive resets anti-correlate)
    per_area = np.array(heats) / (reset_every * dt) / (box[0] * box[1])
    flux, flux_error = float(np.mean(per_area)), block_standard_error(per_area, 10)
    # How freely the liquid slides along the walls: the rms of u_x in the rows next to them over its largest row's
    # (1 for stress-free walls, where the linear mode's u_x ~ cos(pi z/H) is largest; 0.59 for rigid ones, the mode
    # W ~ (1 - 4 (z/H)^2)^2 at the centres of 7 rows)
    row_flow = np.sqrt(np.mean(velocity[0] ** 2, axis=0))
    slip = float((row_flow[0] + row_flow[-1]) / 2 / row_flow.max())
    return {"flux": flux, "flux_error": flux_error, "velocity": velocity, "flow": flow, "noise": noise,
            "theta": counts / np.maximum(inverse, 1e-30), "gradient": gradient, "slip": slip,
            "span": top - bottom, "box": box}


def viscosity(parameters, time_step, platform, replicas):
    """eta (amu/(nm ps)) and its error from calibrate's transverse-wave decay (``replicas`` replicas, 3 x 3 x 12
    cells). The run lasts 0.6 of the decay time of the mapping's eta: the measured eta is ~3.4 times it (the floor
    that the particles' motion sets), so that is two decay times of the wave."""
    plan = Plan(particles=500, time_step=time_step, melt=400, replicas=replicas, wave_steps=600, wave_decays=0.6,
                steady_cells=(3, 3, 12))
    calibration = Calibration(parameters, "VB", plan, platform, seed=11, report=lambda *a: None)
    measured = calibration.shear_viscosity()
    return measured.value, measured.error


def arguments_of_the_command_line():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--differences", type=POSITIVE, nargs="+", default=[12.0, 15.0, 18.0, 24.0, 40.0],
                        help="dT between the walls in K, > 0; the first must be below the onset (default 12 15 18 24 "
                             "40)")
    parser.add_argument("--compression", type=number(above=0, below=1), default=0.3,
                        help="g H/c_T^2, the layer's hydrostatic compression, which sets g; > 0 and < 1 (default 0.3)")
    parser.add_argument("--thermal-times", type=POSITIVE, default=0.6,
                        help="length of each run in H^2/D_T of the target D_T (default 0.6)")
    parser.add_argument("--time-step", type=POSITIVE, default=0.04, help="dt* (default 0.04)")
    parser.add_argument("--perturbation", type=NON_NEGATIVE, default=2.0,
                        help="amplitude (K) of the roll pattern added to the conduction profile (default 2)")
    parser.add_argument("--grid", type=COUNT, nargs=2, default=(14, 7), metavar=("NX", "NZ"),
                        help=f"cells of the fields (default 14 7; at most {MAX_GRID[0]} {MAX_GRID[1]}, one per layer "
                             f"of particles)")
    add_platform(parser, default="CPU")
    parser.add_argument("--viscosity-replicas", type=COUNT, default=3, help="transverse waves for nu (default 3)")
    parser.add_argument("--measured", type=POSITIVE, nargs=3, metavar=("NU", "LAMBDA", "FRACTION"),
                        help="nu (L^2/tau), lambda (kJ/(mol ps nm K)) and the liquid's fraction of dT (at most 1) "
                             "from an earlier run, instead of measuring them (then every difference is a convection "
                             "run)")
    parser.add_argument("--plot", metavar="STEM", type=writable_stem(".png"),
                        help="draw the second halves' mean fields to STEM.png (needs matplotlib)")
    arguments = parse_arguments(parser)
    check(parser, arguments)
    return arguments


def main():
    arguments = arguments_of_the_command_line()
    fluid = liquid_fluid()
    parameters = coarse_grain(fluid, ATOMS, neighbors=NEIGHBORS)
    u = parameters.units
    length = u.to_openmm(1, "length").value_in_unit(unit.nanometer)
    tau = u.to_openmm(1, "time").value_in_unit(unit.picosecond)
    f = fluid.in_openmm()
    rho = f["mass_density"]
    alpha, t0 = f["thermal_expansion"], parameters.temperature
    c_v, c_p = specific_heat(f)
    cell = length * 4 ** (1 / 3)             # FCC cell edge at n0 = 1/L^3 (4 particles a cell)
    layer = cell / 2                         # the liquid within this of a wall takes the wall's temperature
    depth = DEPTH * length                   # (CELLS[2] - 2 WALL_CELLS) cells less a layer at each wall
    gravity = arguments.compression / (depth / length) * length / tau**2      # nm/ps^2
    steps = run_steps(arguments)
    adiabatic = gravity * depth * alpha * t0 / c_p
    print(f"{fluid.name}, {ATOMS} atoms per particle: L = {length:.4f} nm, tau = {tau:.4f} ps; "
          f"H = {depth / length:.2f} L"
          f" = {depth:.2f} nm; g = {gravity / length * tau**2:.4f} L/tau^2; dT_ad = {adiabatic:.2f} K; "
          f"gamma = c_p/c_v = {c_p / c_v:.3f}; {steps} steps of dt* = {arguments.time_step} per run", flush=True)

    if arguments.measured:
        nu, conductivity, fraction = arguments.measured
        nu *= length**2 / tau
        print(f"given nu = {nu * tau / length**2:.4f} L^2/tau", flush=True)
    else:
        eta, eta_error = viscosity(parameters, arguments.time_step, arguments.platform, arguments.viscosity_replicas)
        nu = eta / rho
        conductivity = fraction = None
        print(f"measured nu = {nu * tau / length**2:.4f} +- {eta_error / rho * tau / length**2:.4f} L^2/tau "
              f"(the mapping's {f['shear_viscosity'] / rho * tau / length**2:.4f})", flush=True)

    print("  dT (K)  Ra       Nu              flow/noise  flow (m/s)  interior dT/dz (K/nm)  wall slip")
    results = []
    for difference in arguments.differences:
        result = run(parameters, difference, gravity, steps, arguments.platform, 5, tuple(arguments.grid),
                     arguments.time_step, arguments.perturbation, layer)
        if conductivity is None:
            conductivity = result["flux"] / -result["gradient"]
            fraction = -result["gradient"] * depth / difference
        diffusivity = conductivity / (rho * c_p)
        if not results:
            onset = {walls: (adiabatic + critical * nu * diffusivity / (gravity * alpha * depth**3)) / fraction
                     for walls, critical in RAYLEIGH_CRITICAL.items()}
            print(f"  conduction: lambda = {conductivity:.4g} kJ/(mol ps nm K), D_T = "
                  f"{diffusivity * tau / length**2:.4f} L^2/tau (target {DIFFUSIVITY}); the liquid takes "
                  f"{fraction:.3f} of dT; predicted onset dT_c = {onset['rigid']:.1f} K (rigid walls), "
                  f"{onset['stress-free']:.1f} K (stress-free walls)")
        # Ra of the liquid's own temperature difference, fraction dT, less the adiabatic one
        rayleigh = gravity * alpha * (fraction * difference - adiabatic) * depth**3 / (nu * diffusivity)
        result.update(difference=difference, rayleigh=rayleigh,
                      nusselt=result["flux"] * depth / (conductivity * difference * fraction),
                      nusselt_error=result["flux_error"] * depth / (conductivity * difference * fraction))
        print(f"  {difference:6.1f}  {rayleigh:7.0f}  {result['nusselt']:5.3f} +- {result['nusselt_error']:5.3f}  "
              f"{result['flow'] / result['noise']:9.2f}"
              f"  {result['flow'] * 1000:9.3f}  {result['gradient']:10.4f}  {result['slip']:9.2f}", flush=True)
        results.append(result)
    if arguments.plot:
        plot(results, arguments.plot)


def check(parser, arguments):
    """Every argument checked against the others before anything runs (a usage error, status 2): the grid against
    the layers of particles and the interior's fit, the temperatures above zero, runs long enough to sample, the
    measured fraction of dT at most 1, matplotlib for --plot."""
    nx, nz = arguments.grid
    if nx > MAX_GRID[0] or nz > MAX_GRID[1] or middle_layers(nz).sum() < 2:
        parser.error(f"--grid {nx} {nz} is not allowed; it must be at most {MAX_GRID[0]} {MAX_GRID[1]} (one cell per "
                     f"layer of particles), with at least 2 layers in the middle 60% of the depth, where the "
                     f"temperature gradient is fitted (NZ = 2 or from 4 on)")
    t0 = liquid_fluid().in_openmm()["temperature"]
    coldest = max(arguments.differences) / 2 + arguments.perturbation
    if not coldest < t0:
        parser.error(f"--differences {max(arguments.differences):g} and --perturbation {arguments.perturbation:g} "
                     f"are not allowed together: the cold wall and the roll pattern would reach {t0 - coldest:g} K; "
                     f"dT/2 + the perturbation must stay below T0 = {t0:g} K")
    steps = run_steps(arguments)
    if steps < 2 * SAMPLE_EVERY:
        parser.error(f"--thermal-times {arguments.thermal_times:g} is not allowed with --time-step "
                     f"{arguments.time_step:g}: runs of {steps} steps; at least {2 * SAMPLE_EVERY} are needed (the "
                     f"second half sampled every {SAMPLE_EVERY})")
    if arguments.measured and arguments.measured[2] > 1:
        parser.error(f"--measured FRACTION {arguments.measured[2]:g} is not allowed; the liquid's fraction of dT is "
                     f"at most 1")
    if arguments.plot:
        try:
            import matplotlib  # noqa: F401
        except ImportError:
            parser.error("--plot needs matplotlib (pip install matplotlib)")


def run_steps(arguments):
    """The steps of each run: --thermal-times H^2/D_T (the target D_T) at --time-step."""
    return round(arguments.thermal_times * DEPTH**2 / DIFFUSIVITY / arguments.time_step)


def plot(results, stem):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    figure, axes = plt.subplots(len(results), 1, figsize=(8, 2.6 * len(results)), squeeze=False)
    # One arrow scale for every panel: the largest run's rms flow is 1/12 of the width
    scale = 12 * max(result["flow"] for result in results)
    for axis, result in zip(axes[:, 0], results):
        # The grid spans the liquid from face to face (``span``), its layers at the walls' temperatures included
        velocity, theta, box, span = result["velocity"], result["theta"], result["box"], result["span"]
        nx, nz = theta.shape
        x = (np.arange(nx) + 0.5) / nx * box[0]
        z = (np.arange(nz) + 0.5) / nz * span
        image = axis.pcolormesh(np.linspace(0, box[0], nx + 1), np.linspace(0, span, nz + 1),
                                theta.T, cmap="coolwarm", shading="flat")
        axis.quiver(*np.meshgrid(x, z, indexing="ij"), velocity[0], velocity[2], scale=scale)
        axis.set_aspect("equal")
        axis.set_title(f"dT = {result['difference']:g} K, Ra = {result['rayleigh']:.0f}, "
                       f"Nu = {result['nusselt']:.2f}, flow/noise = {result['flow'] / result['noise']:.1f}")
        axis.set_xlabel("x (nm)")
        axis.set_ylabel("z (nm)")
        figure.colorbar(image, ax=axis, label="theta (K), harmonic mean")
    figure.tight_layout()
    with atomic_write(f"{stem}.png", "wb") as stream:
        figure.savefig(stream, format="png", dpi=120)
    print(f"wrote {stem}.png")


if __name__ == "__main__":
    one_line_errors("rayleigh_benard.py")
    main()
