# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""Cost against accuracy of the time step (`speed-vs-error`): for several step sizes, from one equilibrated state
(openmmgendpde.models.argon_runs protocol at the smallest step), the same simulated time of isoenergetic GenDPDE with VA
and with VB, reporting the wall time per unit of simulated time against four errors:

- the drift of the conserved energy K + U + sum eps (slope of a straight-line fit, per particle and time unit);
- |T_kin/T_harm - 1|: the violation of the equilibrium identity T_kin = <1/theta>^-1, exact in the limit dt -> 0;
- |n-bar* - n-bar*(smallest step)| and |P* - P*(smallest step)|, beside the statistical error of the difference.

Writes a table and a log-log plot (PNG and PDF) of cost against each error.
"""

import csv
import dataclasses

import numpy as np
import openmm

from ..analysis.statistics import BlockAverage, block_average
from ..internal.files import atomic_write
from ..internal.plotting import panels, save
from ..models.argon import PUBLISHED_ESTIMATORS, liquid_argon
from ..models.argon_runs import FULL, run_argon


@dataclasses.dataclass
class Point:
    estimator: str
    time_step: float
    seconds_per_time_unit: float
    drift: float                  # reduced energy per particle per time unit
    temperature_error: float      # |T_kin/T_harm - 1|
    temperature_error_bar: float  # its standard error (block average)
    density: BlockAverage         # n-bar*: mean, standard error
    pressure: BlockAverage        # P*
    density_error: float = 0.0    # |n-bar - reference|
    pressure_error: float = 0.0
    density_error_bar: float = 0.0    # standard error of that difference
    pressure_error_bar: float = 0.0


def measure(cutoff, estimator, steps, protocol, platform, progress):
    # One equilibrated state at the smallest step, then each step size from it.
    reference = dataclasses.replace(protocol, time_step=min(steps), production_time=protocol.sample_interval)
    simulation = run_argon(cutoff, estimator, reference, platform, progress=progress).simulation
    state = simulation.context.getState(getPositions=True, getVelocities=True, getIntegratorParameters=True)
    points = []
    for time_step in steps:
        run = dataclasses.replace(protocol, time_step=time_step, thermostat_time=0.0, equilibration_time=0.0)
        argon = liquid_argon(protocol.num_particles, cutoff, estimator, time_step=time_step, seed=protocol.seed)
        new = openmm.app.Simulation(argon.topology, argon.system, argon.integrator,
                                    openmm.Platform.getPlatformByName(platform))
        new.context.setState(state)
        samples = run_argon(cutoff, estimator, run, platform, progress=progress, continue_from=(argon, new)).samples
        slope = np.polyfit(samples.time, samples.conserved_energy, 1)[0]
        case = f"{estimator} dt* = {time_step:g}"
        ratios = np.array(samples.kinetic_temperature) / np.array(samples.harmonic_temperature)
        ratio, ratio_error = block_average(ratios, name=f"{case} T_kin/T_harm")
        points.append(Point(estimator, time_step, samples.wall_time / (samples.steps * time_step),
                            abs(slope) / protocol.num_particles, abs(ratio - 1), ratio_error,
                            block_average(samples.density, name=f"{case} n-bar*"),
                            block_average(samples.pressure, name=f"{case} P*")))
    smallest = min(points, key=lambda p: p.time_step)
    for p in points:
        p.density_error = abs(p.density.mean - smallest.density.mean)
        p.pressure_error = abs(p.pressure.mean - smallest.pressure.mean)
        if p is not smallest:
            p.density_error_bar = float(np.hypot(p.density.standard_error, smallest.density.standard_error))
            p.pressure_error_bar = float(np.hypot(p.pressure.standard_error, smallest.pressure.standard_error))
    return points


def plot(points, path_stem):
    """Cost against each error, log-log; horizontal bars are the statistical standard errors: where a bar reaches
    below the point, the step-size bias is not resolved."""
    errors = (("drift", None, "energy drift per particle per time unit"),
              ("temperature_error", "temperature_error_bar", "|T_kin/T_harm - 1|"),
              ("density_error", "density_error_bar", "|n-bar* - n-bar*(smallest dt)|"),
              ("pressure_error", "pressure_error_bar", "|P* - P*(smallest dt)|"))
    figure, axes = panels(len(errors))
    for axis, (field, bar, label) in zip(axes, errors):
        for estimator, style in zip(PUBLISHED_ESTIMATORS, ("o--", "s-")):
            chosen = [p for p in points if p.estimator == estimator and getattr(p, field) > 0]
            if not chosen:
                continue
            x = np.array([getattr(p, field) for p in chosen])
            y = [p.seconds_per_time_unit for p in chosen]
            if bar is None:
                axis.loglog(x, y, style, label=f"V-{estimator[1]}")
            else:
                spread = np.array([getattr(p, bar) for p in chosen])
                axis.errorbar(x, y, xerr=[np.minimum(spread, 0.9 * x), spread], fmt=style, capsize=2,
                              label=f"V-{estimator[1]}")
                axis.set_xscale("log")
                axis.set_yscale("log")
            for p in chosen:
                axis.annotate(f"{p.time_step:g}", (getattr(p, field), p.seconds_per_time_unit), fontsize=7)
        axis.set_xlabel(label)
    axes[0].set_ylabel("wall time per time unit (s)")
    save(figure, path_stem, legend_axis=axes[0])


#: The runs of the study: the protocol's phases (models.argon_runs.FULL) with 50 time units of production per step size.
DEFAULTS = dataclasses.replace(FULL, production_time=50.0)


def study(cutoff, steps, protocol=DEFAULTS, platform="Reference", progress=None):
    """The Points of both published estimators at R_cut* = ``cutoff`` for the step sizes ``steps`` (measure);
    ``progress`` advances by the steps and is labelled by the estimator."""
    points = []
    for estimator in PUBLISHED_ESTIMATORS:
        if progress is not None:
            progress.label = f"speed-vs-error {estimator}"
        points += measure(cutoff, estimator, steps, protocol, platform, progress)
    return points


def total_steps(protocol, steps):
    """The steps study() takes (the progress bar's total)."""
    preparation = (protocol.steps(protocol.thermostat_time + protocol.equilibration_time) * protocol.time_step
                   / min(steps))
    return int(len(PUBLISHED_ESTIMATORS) * (preparation + sum(protocol.production_time / s for s in steps)))


def table(points):
    """The Points as a Markdown table."""
    lines = ["| estimator | dt* | wall s per time unit | energy drift /particle/time | |T_kin/T_harm - 1| "
             "| n-bar* | |dn-bar*| | P* | |dP*| |", "|---|---|---|---|---|---|---|---|---|"]
    lines += [f"| {p.estimator} | {p.time_step:g} | {p.seconds_per_time_unit:.3f} | {p.drift:.2e} "
              f"| {p.temperature_error:.4f} +- {p.temperature_error_bar:.4f} | {p.density.mean:.4f} +- "
              f"{p.density.standard_error:.4f} | {p.density_error:.4f} | {p.pressure.mean:.4f} +- "
              f"{p.pressure.standard_error:.4f} | {p.pressure_error:.4f} |" for p in points]
    return "\n".join(lines)


def write_csv(points, path):
    with atomic_write(path, newline="") as stream:
        writer = csv.writer(stream)
        writer.writerow(["estimator", "dt*", "wall s per time unit", "drift", "|Tkin/Tharm-1|", "its error",
                         "n-bar*", "n-bar* error", "|dn|", "P*", "P* error", "|dP|"])
        for p in points:
            writer.writerow([p.estimator, p.time_step, p.seconds_per_time_unit, p.drift, p.temperature_error,
                             p.temperature_error_bar, p.density.mean, p.density.standard_error, p.density_error,
                             p.pressure.mean, p.pressure.standard_error, p.pressure_error])
