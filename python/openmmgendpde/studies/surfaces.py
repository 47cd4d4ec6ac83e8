# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""Free surfaces measured (`slab`, docs/interfaces.md): each estimator's particle volumes against the exact
partition-of-unity volume (analysis.interfaces) in slices of a slab, shells of a droplet and bulk liquids; the bulk
pressure and the coexistence density; the surface tension against a fluid's; and the figure of a slab run. The slabs
and droplets themselves are studies.slab's."""

import numpy as np
from openmm import unit

from ..analysis.interfaces import partition_of_unity_volumes
from ..analysis.pressure import pressure_tensor
from ..analysis.statistics import correlated_mean
from ..api import GenDPDEForce, GenDPDEIntegrator
from ..models.argon import ARGON_UNITS
from ..models.lattice import fcc_box
from .slab import NM, argon_model, depth, droplet_positions


def estimator_volumes(model, context):
    """(V-A volumes 1/n0, V-B volumes, V-C volumes, exact partition-of-unity volumes with kernel range Rt = R/f_cut),
    nm^3, at the current positions of ``context``, a Context of ``model`` (the force's estimator is left as it
    was)."""
    force = model.force
    n0 = force.getPrimitiveDensities(context).value_in_unit(NM**-3)
    estimator = force.getDensityEstimator()
    volumes = []
    for trial in (GenDPDEForce.VB, GenDPDEForce.VC):
        force.setDensityEstimator(trial)
        force.updateParametersInContext(context)
        volumes.append(force.getParticleVolumes(context).value_in_unit(NM**3))
    force.setDensityEstimator(estimator)
    force.updateParametersInContext(context)
    reduced_range = force.getCutoffDistance().value_in_unit(NM) / force.getCutoffScaling()
    exact = partition_of_unity_volumes(model.wrapped_positions(context), reduced_range, box=model.box_edges)
    return 1 / n0, volumes[0], volumes[1], exact


def depth_profile(model, context, thickness, bin_width=0.25, units=ARGON_UNITS):
    """Rows (depth from, depth to in units of the initial half thickness, particles, true density, then the mean
    density 1/V of the exact volume, V-B, V-A and V-C; densities reduced in ``units``) of slices by depth."""
    length = units.unit("length").value_in_unit(NM)
    va, vb, vc, exact = estimator_volumes(model, context)
    box = model.box_edges
    d = depth(model.wrapped_positions(context), box) / (thickness / 2)
    area = box[0] * box[1]
    rows = []
    for low in np.arange(0, d.max() + bin_width, bin_width):
        members = (d >= low) & (d < low + bin_width)
        if members.sum() < 10:
            continue
        true = members.sum() / (2 * area * bin_width * thickness / 2) * length**3
        rows.append((low, low + bin_width, int(members.sum()), true,
                     *(float(np.mean(1 / v[members])) * length**3 for v in (exact, vb, va, vc))))
    return rows


def radial_profile(model, context, radius, bin_width=0.2):
    """Rows (distance from, to in units of the initial radius, particles, true density, then the mean density 1/V
    of the exact volume, V-B, V-A and V-C; densities reduced) of spherical shells around the droplet's centre of
    mass (the droplet must not straddle the box: its box is large)."""
    length = ARGON_UNITS.unit("length").value_in_unit(NM)
    va, vb, vc, exact = estimator_volumes(model, context)
    x = model.wrapped_positions(context)
    d = np.linalg.norm(x - x.mean(axis=0), axis=1) / radius
    rows = []
    for low in np.arange(0, d.max() + bin_width, bin_width):
        members = (d >= low) & (d < low + bin_width)
        if members.sum() < 10:
            continue
        shell = 4 * np.pi / 3 * ((low + bin_width) ** 3 - low**3) * radius**3
        rows.append((low, low + bin_width, int(members.sum()), members.sum() / shell * length**3,
                     *(float(np.mean(1 / v[members])) * length**3 for v in (exact, vb, va, vc))))
    return rows


def run_droplet(estimator="VB", duration=10.0, num_particles=1000, platform="CPU", seed=5):
    """A droplet of ``num_particles`` at n* = 0.82 run for ``duration`` time units; (model, its Context, initial
    radius nm)."""
    positions, box, radius = droplet_positions(num_particles)
    model, context = argon_model(positions, box, estimator, platform=platform, seed=seed)
    tau = ARGON_UNITS.unit("time").value_in_unit(unit.picosecond)
    model.integrator.step(int(round(duration * tau / model.integrator.getStepSize().value_in_unit(unit.picosecond))))
    return model, context, radius


def bulk_pressure(estimator, density, steps=2000, platform="CPU", seed=9):
    """The pressure P* (reduced, virial with on-step velocities) of a bulk liquid of 500 particles at reduced
    ``density``: FCC melted by ``steps`` Isothermal steps at T0, then ``steps`` isoenergetic steps sampled every 100."""
    length = ARGON_UNITS.unit("length").value_in_unit(NM)
    positions, box = fcc_box(density / length**3, (5, 5, 5))
    model, context = argon_model(positions, np.diag(np.asarray(box, float)), estimator, platform=platform, seed=seed)
    model.integrator.setMode(GenDPDEIntegrator.Isothermal)
    model.integrator.step(steps)
    model.integrator.setMode(GenDPDEIntegrator.Isoenergetic)
    pressure_unit = ARGON_UNITS.unit("pressure").value_in_unit(unit.kilojoule_per_mole / NM**3)
    values = []
    for _ in range(steps // 100):
        model.integrator.step(100)
        values.append(np.trace(pressure_tensor(model.force, context)) / 3 / pressure_unit)
    return float(np.mean(values))


def coexistence_density(estimator, densities=(0.7, 0.75, 0.8), platform="CPU"):
    """The density (reduced) at which the bulk pressure vanishes, by linear interpolation through bulk_pressure at
    ``densities``: the density a liquid keeps against vacuum. Also the pressures."""
    pressures = [bulk_pressure(estimator, density, platform=platform) for density in densities]
    slope, intercept = np.polyfit(densities, pressures, 1)
    return -intercept / slope, pressures


def bulk_comparison(densities=(0.7, 0.82, 1.0, 1.2), cells=(5, 5, 5), steps=2000, platform="CPU", seed=7):
    """For bulk liquids at each reduced density (FCC melted by ``steps`` Isothermal V-B steps): rows (density,
    mean and standard deviation over particles of V_VB/V_exact, the same for V_VA/V_exact, correlation of V_VB with
    V_exact, mean and standard deviation of V_VC/V_exact). The exact volumes average to 1/n exactly (the partition of
    unity fills the box)."""
    length = ARGON_UNITS.unit("length").value_in_unit(NM)
    rows = []
    for density in densities:
        positions, box = fcc_box(density / length**3, cells)
        model, context = argon_model(positions, np.diag(np.asarray(box, float)), "VB", platform=platform, seed=seed)
        model.integrator.setMode(GenDPDEIntegrator.Isothermal)
        model.integrator.step(steps)
        va, vb, vc, exact = estimator_volumes(model, context)
        rows.append((density, float(np.mean(vb / exact)), float(np.std(vb / exact)), float(np.mean(va / exact)),
                     float(np.std(va / exact)), float(np.corrcoef(vb, exact)[0, 1]), float(np.mean(vc / exact)),
                     float(np.std(vc / exact))))
    return rows


def plot(runs, profiles, path_stem):
    """Left: the core's true density (solid) and mean n_i (dashed) against time for each estimator; right: the
    density by depth at the end of the V-B run: true, exact partition of unity, V-B, V-A."""
    from ..internal.plotting import panels, save
    figure, (left, right) = panels(2)
    for (estimator, samples), colour in zip(runs.items(), ("C0", "C1", "C2")):
        t = [s.time for s in samples]
        left.plot(t, [s.core_density for s in samples], color=colour, label=f"{estimator}: true density")
        left.plot(t, [s.core_estimate for s in samples], color=colour, linestyle="--", label=f"{estimator}: mean n_i")
    left.set_xlabel("t*")
    left.set_ylabel("core density n*")
    left.legend(frameon=False, fontsize=8)
    if "VB" in profiles:
        rows = np.array(profiles["VB"])
        centre = 0.5 * (rows[:, 0] + rows[:, 1])
        for column, label in zip((3, 4, 5, 6, 7), ("true", "exact partition of unity", "V-B", "V-A", "V-C")):
            right.plot(centre, rows[:, column], marker="o", markersize=3, label=label)
        right.set_xlabel("depth / initial half thickness")
        right.set_ylabel("density n* (V-B run, end)")
    save(figure, path_stem, right if "VB" in profiles else None)


def _mn_m(value):
    """kJ/mol/nm^2 -> mN/m."""
    return (value * unit.kilojoule_per_mole / NM**2 / unit.AVOGADRO_CONSTANT_NA).value_in_unit(
        unit.newton / unit.meter) * 1e3


def surface_tension_table(tensions, parameters):
    """The surface tension over the second half of each run against the fluid's, a line and a Markdown table:
    ``tensions`` estimator -> the samples' tensions (reduced, parameters.units); the mean +- its standard error
    (statistics.correlated_mean) and the independent samples N/g, in mN/m, beside the target (the fluid's
    surface_tension; '-' where it has none) and slab/target."""
    target = parameters.targets()["surface_tension"]
    target = None if target is None else _mn_m(target)
    scale = _mn_m(parameters.units.unit("surface_tension").value_in_unit(unit.kilojoule_per_mole / NM**2))
    lines = ["Surface tension over the second half of each run (standard errors and independent samples N/g from "
             "statistics.correlated_mean); target: the liquid-vapour surface tension of " + parameters.fluid.name
             + (" (not given: the fluid's optional surface_tension)" if target is None else ""),
             "| estimator | target (mN/m) | slab (mN/m) | slab/target | independent samples |",
             "|---|---|---|---|---|"]
    for estimator, values in tensions.items():
        values = scale * np.asarray(values, float)
        if len(values) >= 2:
            result = correlated_mean(values)
            mean, measured = result.mean, f"{result.mean:.4g} +- {result.standard_error:.2g}"
            samples = f"{result.independent_samples:.1f} of {len(values)}"
        else:
            mean = float(values[0])
            measured, samples = f"{mean:.4g} (one sample: no error)", "1"
        lines.append(f"| {estimator} | {'-' if target is None else f'{target:.4g}'} | {measured} | "
                     f"{'-' if target is None else f'{mean / target:.3f}'} | {samples} |")
    return "\n".join(lines)


