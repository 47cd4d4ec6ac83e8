# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""A shock in liquid argon whose particles expand with temperature, against the Rankine-Hugoniot jump of the model's
own equation of state (docs/thermal.md).

The liquid (fluid.ARGON_EXPANDING: 125.7 K, 85.31 MPa, alpha = 2.64e-3 1/K; 5 atoms per particle, R* = 1.6839) fills
a long periodic box. Each run gives the half z < L/2 the velocity +u_p along z and the other half -u_p: the two
halves collide at z = L/2, and two planar shocks run apart from there, leaving the liquid between them at rest,
compressed and heated (a symmetric impact: in the frame of either half, a piston at u_p). The dynamics is the full
GenDPDE one (Isoenergetic: K + U + sum eps conserved); the rarefactions from z = 0 cannot reach a shock before
t = L/(4 U_s), where each run ends.

Measured: the shock speed U_s (the distance between the two fronts, where the mean velocity is u_p/2, grows at
2 (U_s - u_p)), and, between the centre and the fronts (|z - L/2| from 0.3 to 0.8 of the front's distance, away from
the fronts and from the plane of first impact), the density n1, the kinetic temperature T1 and the mean particle
temperature <theta>, over the second half of the run.

Predicted: the Rankine-Hugoniot state (openmmgendpde.analysis.hugoniot) of the model's equation of state P(n, E), T(n,
E), fitted to equilibrium runs of the same model at seven densities from n0 to 1.4 n0 and three temperatures each
(T0 - 10, T0 + 60 and T0 + 130 K). That is the
fluid's equation of state, not the particles' law: the fluid's pressure adds the kinetic n k_B T and reaches the
particles' pressures through the estimator (docs/thermal.md).

    .venv/bin/python examples/shock.py                         # 3 piston speeds, 8640 particles, about 3 minutes
"""

import argparse
import math

import numpy as np
from openmm import unit

from openmmgendpde import GenDPDEIntegrator
from openmmgendpde.analysis.hugoniot import EquationOfStateFit, shocked_state
from openmmgendpde.analysis.statistics import correlated_mean
from openmmgendpde.analysis.thermodynamics import ThermodynamicProbe
from openmmgendpde.calibration.expansion import MIN_SAMPLES, SAMPLE_EVERY, mapped, run_at
from openmmgendpde.calibration.expansion import MPA_PER_OPENMM_PRESSURE as MPA
from openmmgendpde.cli.options import (
    COUNT,
    NON_NEGATIVE_COUNT,
    POSITIVE,
    add_platform,
    fcc_particles,
    integer,
    number,
    one_line_errors,
    parse_arguments,
)
from openmmgendpde.units import BOLTZMANN

KB = BOLTZMANN.value_in_unit(unit.kilojoule_per_mole / unit.kelvin)
PRESSURE = unit.kilojoule_per_mole / unit.nanometer**3
M_PER_S = (1.0 * unit.nanometer / unit.picosecond).value_in_unit(unit.meter / unit.second)


def equation_of_state(parameters, arguments):
    """EquationOfStateFit of the model from equilibrium runs on a grid of densities and temperatures."""
    rows = []
    print("The model's equation of state (equilibrium runs, "
          f"{arguments.table_particles} particles, {arguments.table_steps} steps each):")
    print("  n/n0    T (K)     E (kJ/mol)   P (MPa)")
    for k, ratio in enumerate(np.linspace(1.0, arguments.table_compression, 7)):
        for j, offset in enumerate((-10.0, 60.0, 130.0)):
            run = run_at(parameters, arguments.table_particles, parameters.temperature + offset, arguments.table_melt,
                         arguments.table_steps, SAMPLE_EVERY, arguments.platform, seed=10 * k + j + 1,
                         density=ratio * parameters.density)
            rows.append((run.density, run.energy, run.pressure.mean, run.temperature.mean))
            print(f"  {ratio:.3f}  {run.temperature.mean:8.2f}  {run.energy:10.4f}  {run.pressure.mean * MPA:9.2f}",
                  flush=True)
    fit = EquationOfStateFit.fit(*zip(*rows))
    print(f"  fit: rms misses {fit.pressure_residual * MPA:.2f} MPa, {fit.temperature_residual:.2f} K")
    return fit


def front_half_distance(z, vz, centre, speed, bin_width):
    """Half the distance between the two fronts, where the mean velocity crosses -+u_p/2 on either side of the
    centre (binned profile, linear interpolation between bins)."""
    edges = np.arange(0.0, 2 * centre + bin_width / 2, bin_width)
    counts, _ = np.histogram(z, edges)
    sums, _ = np.histogram(z, edges, weights=vz)
    profile = sums / np.maximum(counts, 1)
    middle = (edges[:-1] + edges[1:]) / 2
    distances = []
    for side in (-1, 1):     # left of the centre the fluid comes at +u_p; right of it at -u_p
        order = np.argsort(side * (middle - centre))
        order = order[side * (middle[order] - centre) > 0]
        values = -side * profile[order]
        beyond = np.nonzero(values > speed / 2)[0]
        if len(beyond) == 0 or beyond[0] == 0:
            return math.nan
        i = beyond[0]
        d0, d1 = abs(middle[order[i - 1]] - centre), abs(middle[order[i]] - centre)
        v0, v1 = values[i - 1], values[i]
        distances.append(d0 + (speed / 2 - v0) * (d1 - d0) / (v1 - v0))
    return sum(distances) / 2


def shock_run(context, integrator, checkpoint, speed, steps, chunk, box, mass):
    """Measured shock speed and shocked state of one impact at +-``speed`` (nm/ps) from ``checkpoint``."""
    context.loadCheckpoint(checkpoint)
    lx, ly, lz = box
    centre = lz / 2
    state = context.getState(getPositions=True, getVelocities=True, enforcePeriodicBox=True)
    z = state.getPositions(asNumpy=True).value_in_unit(unit.nanometer)[:, 2]
    velocities = state.getVelocities(asNumpy=True).value_in_unit(unit.nanometer / unit.picosecond)
    velocities[:, 2] += np.where(z < centre, speed, -speed)
    context.setVelocities(velocities)
    dt = integrator.getStepSize().value_in_unit(unit.picosecond)
    times, fronts, densities, temperatures, thetas = [], [], [], [], []
    for done in range(chunk, steps + 1, chunk):
        integrator.step(chunk)
        state = context.getState(getPositions=True, getVelocities=True, enforcePeriodicBox=True)
        r = state.getPositions(asNumpy=True).value_in_unit(unit.nanometer)
        v = state.getVelocities(asNumpy=True).value_in_unit(unit.nanometer / unit.picosecond)
        w = front_half_distance(r[:, 2], v[:, 2], centre, speed, 0.5)
        times.append(done * dt)
        fronts.append(w)
        if done > steps // 2:
            inside = (np.abs(r[:, 2] - centre) > 0.3 * w) & (np.abs(r[:, 2] - centre) < 0.8 * w)
            count = int(np.count_nonzero(inside))
            densities.append(count / (lx * ly * 2 * 0.5 * w))
            u = v[inside] - v[inside].mean(axis=0)
            temperatures.append(mass * float(np.sum(u * u)) / ((3 * count - 3) * KB))
            theta = np.asarray(integrator.getParticleTemperatures().value_in_unit(unit.kelvin))
            thetas.append(float(np.mean(theta[inside])))
    times, fronts = np.array(times), np.array(fronts)
    late = times > times[-1] / 3
    slope = np.polyfit(times[late], fronts[late], 1)[0]
    return {"shock_speed": slope + speed, "density": correlated_mean(densities),
            "temperature": correlated_mean(temperatures), "theta": float(np.mean(thetas))}


#: Steps between the shock run's samples (shock_run's chunk), and the fewest samples a run needs: the front's speed is
#: fitted over the last two thirds, the shocked state averaged over the second half.
CHUNK, MIN_CHUNKS = 25, 8


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--speeds", type=POSITIVE, nargs="+", default=[100.0, 200.0, 300.0],
                        help="piston speeds u_p in m/s, > 0 (default 100 200 300)")
    parser.add_argument("--width", type=COUNT, default=6, help="FCC cells across the box (default 6)")
    parser.add_argument("--length", type=COUNT, default=60, help="FCC cells along the box (default 60)")
    parser.add_argument("--table-particles", type=fcc_particles, default=864,
                        help="particles of each equilibrium run, 4 m^3 (default 864)")
    parser.add_argument("--table-melt", type=NON_NEGATIVE_COUNT, default=1000,
                        help="Isothermal steps before each equilibrium run (default 1000)")
    parser.add_argument("--table-steps", type=integer(SAMPLE_EVERY * MIN_SAMPLES, why=f" ({MIN_SAMPLES} samples, one "
                                                                                       f"every {SAMPLE_EVERY} steps)"),
                        default=3000, help="sampled steps of each equilibrium run (default 3000)")
    parser.add_argument("--table-compression", type=number(above=1), default=1.4,
                        help="the largest n/n0 of the runs, > 1 (default 1.4)")
    add_platform(parser, default="CPU", allowed=("Reference", "CPU"))
    arguments = parse_arguments(parser)

    parameters = mapped()
    # Every argument checked before anything runs: each box holds the cutoff (the table's at its largest density).
    for option, build in (("--width and --length", lambda: parameters.liquid(
                              cells=(arguments.width, arguments.width, arguments.length))),
                          ("--table-particles and --table-compression", lambda: parameters.liquid(
                              arguments.table_particles, density=arguments.table_compression * parameters.density))):
        try:
            build()
        except ValueError as error:
            parser.error(f"{option}: {error}".replace("use more cells", "give more cells or particles"))
    fit = equation_of_state(parameters, arguments)

    model = parameters.liquid(cells=(arguments.width, arguments.width, arguments.length),
                              mode=GenDPDEIntegrator.Isothermal, seed=7)
    integrator = model.integrator
    context = model.melted(arguments.platform, GenDPDEIntegrator.Isoenergetic, 1000, 500, seed=7)
    probe = ThermodynamicProbe(model.system)
    samples = []
    for _ in range(20):
        integrator.step(20)
        samples.append(probe.sample(context.getState(getEnergy=True, getVelocities=True), context, integrator))
    n0 = model.num_particles / model.volume
    e0 = float(np.mean([s.conserved_energy.value_in_unit(unit.kilojoule_per_mole) for s in samples])) \
        / model.num_particles
    t0 = float(np.mean([s.kinetic_temperature.value_in_unit(unit.kelvin) for s in samples]))
    p_measured = float(np.mean([s.pressure.value_in_unit(PRESSURE) for s in samples]))
    p0 = float(fit.pressure(n0, e0))
    checkpoint = context.createCheckpoint()
    box = [model.system.getDefaultPeriodicBoxVectors()[k][k].value_in_unit(unit.nanometer) for k in range(3)]
    dt = integrator.getStepSize().value_in_unit(unit.picosecond)
    # Each speed's predicted state and run length, before any impact is run: within the table's densities, and long
    # enough to measure.
    runs = []
    for speed_si in arguments.speeds:
        try:
            predicted = shocked_state(fit, n0, e0, p0, parameters.mass, speed_si / M_PER_S)
        except ValueError as error:
            raise SystemExit(f"error: shock.py: --speeds {speed_si:g}: {error} (the table's: raise "
                             f"--table-compression, or give lower speeds)") from None
        steps = int(box[2] / (4 * predicted.shock_speed) / dt)
        if steps < MIN_CHUNKS * CHUNK:
            raise SystemExit(f"error: shock.py: --speeds {speed_si:g}: the shock would cross the box in {steps} steps, "
                             f"fewer than the {MIN_CHUNKS * CHUNK} a measurement needs; give a longer box (--length) "
                             f"or lower speeds")
        runs.append((speed_si, predicted, steps))
    print(f"Ahead of the shock: {model.num_particles} particles, n0 = {n0:.4f} nm^-3, T0 = {t0:.2f} K, "
          f"E0 = {e0:.4f} kJ/mol, P0 = {p0 * MPA:.2f} MPa from the fit ({p_measured * MPA:.2f} measured), "
          f"box {box[0]:.2f} x {box[1]:.2f} x {box[2]:.2f} nm")
    print("   u_p     U_s (m/s)              n1/n0                     T1 (K)           <theta> (K)")
    print(" (m/s)  measured Hugoniot      measured  Hugoniot       measured Hugoniot      measured")
    for speed_si, predicted, steps in runs:
        speed = speed_si / M_PER_S
        measured = shock_run(context, integrator, checkpoint, speed, steps, CHUNK, box, parameters.mass)
        print(f" {speed_si:5.0f}  {measured['shock_speed'] * M_PER_S:8.1f} {predicted.shock_speed * M_PER_S:8.1f}  "
              f"{measured['density'].mean / n0:.4f} +- {measured['density'].standard_error / n0:.4f}    "
              f"{predicted.density / n0:.4f}  "
              f"{measured['temperature'].mean:7.2f} +- {measured['temperature'].standard_error:4.2f} "
              f"{predicted.temperature:8.2f}       {measured['theta']:7.2f}", flush=True)


if __name__ == "__main__":
    one_line_errors("shock.py")
    main()
