"""Free surfaces (`slab`, docs/interfaces.md): a liquid-argon slab in vacuum run with V-A, V-B and V-C, and the
estimators' volumes measured against the exact partition-of-unity volume (openmmgendpde.analysis.interfaces).

Dynamics: an FCC slab of argon particles (default 5 x 5 x 10 cells, 1000 particles) at n* = 0.82, where the Tait
pressure vanishes, in a periodic box three times as long as the slab (vacuum on both sides); R* = 1.6839, f_cut =
1.35 (V-C: 1.3525, models.argon.VC_CUTOFF_SCALING), internal energies and velocities drawn at T0, isoenergetic GenDPDE
at dt* = 0.01. Every --every time units it reports the slab's core (the middle half of its initial thickness,
around its centre of mass): the true number density (particles over volume) and the mean estimated density n_i
there, the slab's width (twice the 90th percentile of the distance from its mid-plane) relative to the initial
thickness, and the surface tension (L_z/2)(P_zz - (P_xx + P_yy)/2) from the pressure tensor (two faces). Without
--quick, also the coexistence density: where the pressure of bulk liquids at n* = 0.7, 0.75, 0.8 vanishes.

Oracle: at the end of each run (and for a droplet of 1000 particles after 10 time units with V-B, and for bulk
liquids at several densities), each particle's volume from
V-A (1/n0), V-B, V-C and the exact partition-of-unity volume with V-B's kernel range Rt = R/f_cut, as densities 1/V,
averaged in slices by depth (shells by radius for the droplet); for the bulk, the mean and scatter of
V_estimator/V_exact.

Any fluid (--fluid NAME|FILE, calibrate's fluids and coarse-graining options) or calibrated model (--model FILE,
a model file of `calibrate --output`: exactly its parameters): fluid_slab builds the slab (melted at n0, cut,
thermostatted SLAB_THERMOSTAT_TIME, then isoenergetic at the suggested step) and the same samples are taken in the
model's reduced units, with the kinetic and internal (harmonic) temperatures; the surface tension over the second
half of each run is reported in mN/m beside the fluid's (its optional surface_tension). The droplet, the bulk
comparison and the coexistence density stay the argon model's.
"""

import argparse
import copy
import csv
import dataclasses
import os

import numpy as np
import openmm
from openmm import app, unit

from ..analysis.interfaces import partition_of_unity_volumes
from ..analysis.pressure import pressure_tensor
from ..analysis.statistics import block_average, correlated_mean
from ..analysis.thermodynamics import ThermodynamicProbe
from ..api import ESTIMATOR_NAMES, GenDPDEForce, GenDPDEIntegrator
from ..cli.options import NON_NEGATIVE, POSITIVE, SEED, add_output, add_platform, checked_model
from ..internal.files import atomic_write
from ..models.argon import ARGON_UNITS, liquid_argon
from ..models.lattice import fcc_box
from ..models.melting import melt_then_switch

NM = unit.nanometer


@dataclasses.dataclass
class Model:
    """A GenDPDE System (argon, or any fluid) at given positions in a rectangular periodic box, bound to a Context."""
    context: openmm.Context
    force: GenDPDEForce
    integrator: GenDPDEIntegrator
    box: np.ndarray          # edges (nm)
    temperature: unit.Quantity

    def positions(self):
        """nm, N x 3, wrapped into the box."""
        x = self.context.getState(getPositions=True).getPositions(asNumpy=True).value_in_unit(NM)
        return x - np.floor(x / self.box) * self.box


#: dt* of the argon slabs (argon_model).
ARGON_SLAB_TIME_STEP = 0.01


def argon_model(positions, box, estimator, cutoff=1.6839, platform="Reference", seed=1):
    """The liquid-argon model (models.argon.liquid_argon's parameters at R* = ``cutoff``) for ``positions`` (nm) in a
    rectangular box of edges ``box`` (nm): a Context with velocities and internal energies drawn at T0, Isoenergetic."""
    argon = liquid_argon(500, cutoff, estimator, time_step=ARGON_SLAB_TIME_STEP, seed=seed)
    system = openmm.System()
    system.setDefaultPeriodicBoxVectors(*(openmm.Vec3(*row) for row in np.diag(box)))
    for _ in range(len(positions)):
        system.addParticle(argon.system.getParticleMass(0))
    force = copy.copy(argon.force)
    system.addForce(force)
    integrator = copy.copy(argon.integrator)
    context = openmm.Context(system, integrator, openmm.Platform.getPlatformByName(platform))
    context.setPositions(positions * NM)
    context.setVelocitiesToTemperature(argon.temperature, seed)
    integrator.setInternalEnergiesToTemperature(argon.temperature, seed)
    return Model(context, force, integrator, np.asarray(box, float), argon.temperature)


#: Reduced time units (the model's own, GenDPDEParameters.units) that fluid_slab thermostats a new slab before its
#: isoenergetic run: chosen by measurement (docs/interfaces.md, "A slab of any fluid").
SLAB_THERMOSTAT_TIME = 10.0


@dataclasses.dataclass
class FluidSlab:
    """What fluid_slab built: the Model (Isoenergetic, bound to its Context), the System and Topology (the fluid's
    model, the box lengthened along z), the slab's initial thickness (nm), the vacuum's width (nm) and the step
    (reduced)."""
    model: Model
    system: openmm.System
    topology: app.Topology
    thickness: float
    vacuum: float
    time_step: float


def fluid_slab(parameters, cells, estimator="VC", vacuum=None, time_step=None, melt_time=20.0,
               thermostat_time=SLAB_THERMOSTAT_TIME, platform="CPU", properties=None, seed=1):
    """A liquid slab in vacuum of any fluid (a GenDPDEParameters: coarse_grain, fluid_files.load_parameters), ready
    for isoenergetic GenDPDE; a FluidSlab.

    ``cells`` = (n_x, n_y, n_z) cubic FCC cells at the fluid's density n0 (parameters.liquid) are melted for
    ``melt_time`` with the DPD thermostat at T0 (Isothermal mode, periodic in all three directions), then cut: the
    box is lengthened along z by ``vacuum`` (nm or a length Quantity; default twice the liquid's thickness, the box
    three times the slab as in `slab`) and the liquid is centred in it, so that every particle lies in the slab
    region [vacuum/2, vacuum/2 + thickness) and an empty layer ``vacuum`` wide separates its two faces across the
    periodic boundary. The slab is then thermostatted (Isothermal) for ``thermostat_time`` before the integrator
    is switched to the Isoenergetic mode with the internal energies drawn at T0: the new free surfaces relax while
    the bath takes the energy their particles release (with V-C a cut slab started isoenergetic at once heats by
    ~10-20 K; docs/interfaces.md). Times are in the model's reduced time (parameters.units); ``time_step`` is
    dt* for every stage (default: stability.suggest_time_step(parameters, estimator), measured: V-C's is a tenth
    of V-B's, for its energy error at free surfaces). ``vacuum`` must be at least twice the cutoff. ``platform`` a
    name, ``properties`` its property dict (e.g. {'Threads': '1'}); ``seed`` for the lattice's velocities, the
    thermostat and the internal energies. Bad arguments raise ValueError. The slab runs without the parameters'
    background pressure (a bulk model's, fluid.background_pressure_for): its energy p_b (V_box - sum_i V_i) counts the
    vacuum as a defect and would push the free surfaces apart."""
    parameters = dataclasses.replace(parameters, background_pressure=None)
    if time_step is None:
        from ..calibration.stability import suggest_time_step
        time_step = suggest_time_step(parameters, estimator, platform=platform)[0]
    model = parameters.liquid(cells=cells, estimator=estimator, mode=GenDPDEIntegrator.Isothermal,
                              time_step=time_step, seed=seed)
    edges = np.array([row[k].value_in_unit(NM) for k, row in enumerate(model.system.getDefaultPeriodicBoxVectors())])
    thickness = float(edges[2])
    vacuum = 2 * thickness if vacuum is None else (vacuum.value_in_unit(NM) if unit.is_quantity(vacuum)
                                                   else float(vacuum))
    if not vacuum >= 2 * parameters.cutoff:
        raise ValueError(f"vacuum = {vacuum:.4g} nm is not allowed; it must be at least twice the cutoff "
                         f"({2 * parameters.cutoff:.4g} nm), so that the slab's faces do not interact across it")
    def steps(duration):
        return int(round(duration / time_step))

    integrator = model.integrator
    context = openmm.Context(model.system, integrator, openmm.Platform.getPlatformByName(platform),
                             properties or {})
    context.setPositions(model.positions * NM)
    context.setVelocitiesToTemperature(parameters.temperature * unit.kelvin, seed)
    integrator.step(steps(melt_time))
    melted = Model(context, model.force, integrator, edges, parameters.temperature * unit.kelvin).positions()
    edges = edges + np.array([0.0, 0.0, vacuum])
    box = [openmm.Vec3(*row) for row in np.diag(edges)]
    model.system.setDefaultPeriodicBoxVectors(*box)
    model.topology.setPeriodicBoxVectors(box * NM)
    context.setPeriodicBoxVectors(*box)
    context.setPositions((melted + np.array([0.0, 0.0, vacuum / 2])) * NM)
    melt_then_switch(integrator, steps(thermostat_time), parameters.temperature * unit.kelvin, seed)
    slab = Model(context, model.force, integrator, edges, parameters.temperature * unit.kelvin)
    return FluidSlab(slab, model.system, model.topology, thickness, vacuum, time_step)


def slab_positions(cells=(5, 5, 10), density=0.82, vacuum=3.0):
    """(positions nm, box edges nm, thickness nm): an FCC slab at ``density`` (reduced) of ``cells`` cubic cells,
    normal to z, centred in a box ``vacuum`` times as long as the slab along z."""
    length = ARGON_UNITS.unit("length").value_in_unit(NM)
    positions, box = fcc_box(density / length**3, cells)
    edges = np.diag(np.asarray(box, float)).copy()
    thickness = edges[2]
    edges[2] *= vacuum
    positions[:, 2] += 0.5 * (edges[2] - thickness)
    return positions, edges, thickness


def depth(positions, box, axis=2):
    """Each particle's distance (nm) from the slab's mid-plane: the plane through the circular mean of the
    coordinates along ``axis`` (periodic)."""
    width = box[axis]
    angle = 2 * np.pi * positions[:, axis] / width
    centre = (np.arctan2(np.sin(angle).mean(), np.cos(angle).mean()) % (2 * np.pi)) * width / (2 * np.pi)
    return np.abs((positions[:, axis] - centre + width / 2) % width - width / 2)


@dataclasses.dataclass
class SlabSample:
    time: float            # reduced
    core_density: float    # true number density of the core (reduced)
    core_estimate: float   # mean n_i of the core's particles (reduced)
    width: float           # twice the 90th percentile of the depth, over the initial thickness
    tension: float         # (L_z/2) (P_zz - (P_xx + P_yy)/2): the surface tension of each of the two faces (reduced)
    kinetic_temperature: float = float("nan")   # K: 2 K/((3N - 3) k_B), centre-of-mass frame
    harmonic_temperature: float = float("nan")  # K: <1/theta_i>^-1, the internal temperature (T0 at equilibrium)


def sample_slab(model, thickness, time, units=ARGON_UNITS):
    """A SlabSample of ``model`` now (time reduced); reduced quantities in ``units`` (argon's by default)."""
    length = units.unit("length").value_in_unit(NM)
    x = model.positions()
    d = depth(x, model.box)
    core = d < thickness / 4
    area = model.box[0] * model.box[1]
    estimates = model.force.getParticleDensities(model.context).value_in_unit(NM**-3)
    p = pressure_tensor(model.force, model.context)
    tension = 0.5 * model.box[2] * (p[2, 2] - 0.5 * (p[0, 0] + p[1, 1]))                   # kJ/mol/nm^2
    tension_unit = units.unit("surface_tension").value_in_unit(unit.kilojoule_per_mole / NM**2)
    state = model.context.getState(getEnergy=True, getVelocities=True)
    thermal = ThermodynamicProbe(model.context.getSystem()).sample(state, model.context, model.integrator)
    return SlabSample(time, core.sum() / (area * thickness / 2) * length**3,
                      float(estimates[core].mean()) * length**3, 2 * np.percentile(d, 90) / thickness,
                      float(tension) / tension_unit, thermal.kinetic_temperature.value_in_unit(unit.kelvin),
                      thermal.harmonic_temperature.value_in_unit(unit.kelvin))


def sample_run(model, thickness, duration, every, units=ARGON_UNITS, report=None):
    """Run ``model`` for ``duration`` reduced time units of ``units``; a list of SlabSample every ``every`` time
    units (the first at t = 0). ``report(sample)`` is called after each."""
    tau = units.unit("time").value_in_unit(unit.picosecond)
    dt = model.integrator.getStepSize().value_in_unit(unit.picosecond) / tau
    steps = int(round(every / dt))
    if steps < 1:
        raise ValueError(f"every = {every:g} time units is less than one step (dt* = {dt:g}); it must be at least that")
    samples = [sample_slab(model, thickness, 0.0, units)]
    while samples[-1].time < duration - 0.5 * steps * dt:   # (a whole number of steps: the last sample nearest)
        model.integrator.step(steps)
        samples.append(sample_slab(model, thickness, samples[-1].time + steps * dt, units))
        if report is not None:
            report(samples[-1])
    return samples


def run_slab(estimator, duration=100.0, every=10.0, cells=(5, 5, 10), platform="CPU", seed=5, report=None):
    """Run the argon slab with ``estimator`` for ``duration`` reduced time units; a list of SlabSample every
    ``every`` time units (the first at t = 0), the Model at the end and the initial thickness (nm)."""
    positions, box, thickness = slab_positions(cells)
    model = argon_model(positions, box, estimator, platform=platform, seed=seed)
    return sample_run(model, thickness, duration, every, report=report), model, thickness


def run_fluid_slab(parameters, estimator, duration, every, cells, platform="CPU", seed=5, report=None, **build):
    """The slab of any fluid (fluid_slab, with ``build`` its options) run isoenergetically for ``duration`` time
    units of the model (parameters.units); (SlabSamples every ``every``, FluidSlab)."""
    slab = fluid_slab(parameters, cells, estimator, platform=platform, seed=seed, **build)
    return sample_run(slab.model, slab.thickness, duration, every, parameters.units, report), slab


def estimator_volumes(model):
    """(V-A volumes 1/n0, V-B volumes, V-C volumes, exact partition-of-unity volumes with kernel range Rt = R/f_cut),
    nm^3, at the model's current positions (the force's estimator is left as it was)."""
    force, context = model.force, model.context
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
    exact = partition_of_unity_volumes(model.positions(), reduced_range, box=model.box)
    return 1 / n0, volumes[0], volumes[1], exact


def depth_profile(model, thickness, bin_width=0.25, units=ARGON_UNITS):
    """Rows (depth from, depth to in units of the initial half thickness, particles, true density, then the mean
    density 1/V of the exact volume, V-B, V-A and V-C; densities reduced in ``units``) of slices by depth."""
    length = units.unit("length").value_in_unit(NM)
    va, vb, vc, exact = estimator_volumes(model)
    d = depth(model.positions(), model.box) / (thickness / 2)
    area = model.box[0] * model.box[1]
    rows = []
    for low in np.arange(0, d.max() + bin_width, bin_width):
        members = (d >= low) & (d < low + bin_width)
        if members.sum() < 10:
            continue
        true = members.sum() / (2 * area * bin_width * thickness / 2) * length**3
        rows.append((low, low + bin_width, int(members.sum()), true,
                     *(float(np.mean(1 / v[members])) * length**3 for v in (exact, vb, va, vc))))
    return rows


def droplet_positions(num_particles=1000, density=0.82, vacuum=3.0):
    """(positions nm, box edges nm, radius nm): the ``num_particles`` sites of an FCC lattice at ``density``
    (reduced) nearest a lattice centre, centred in a cubic box ``vacuum`` times the droplet's diameter."""
    length = ARGON_UNITS.unit("length").value_in_unit(NM)
    cells = int(np.ceil((num_particles / 4) ** (1 / 3) * 1.6))
    positions, box = fcc_box(density / length**3, (cells, cells, cells))
    centre = np.diag(np.asarray(box, float)) / 2
    distance = np.linalg.norm(positions - centre, axis=1)
    chosen = np.argsort(distance)[:num_particles]
    radius = (3 * num_particles / (4 * np.pi * density)) ** (1 / 3) * length
    edge = 2 * radius * vacuum
    return positions[chosen] - centre + edge / 2, np.full(3, edge), radius


def radial_profile(model, radius, bin_width=0.2):
    """Rows (distance from, to in units of the initial radius, particles, true density, then the mean density 1/V
    of the exact volume, V-B, V-A and V-C; densities reduced) of spherical shells around the droplet's centre of
    mass (the droplet must not straddle the box: its box is large)."""
    length = ARGON_UNITS.unit("length").value_in_unit(NM)
    va, vb, vc, exact = estimator_volumes(model)
    x = model.positions()
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
    """A droplet of ``num_particles`` at n* = 0.82 run for ``duration`` time units; (Model, initial radius nm)."""
    positions, box, radius = droplet_positions(num_particles)
    model = argon_model(positions, box, estimator, platform=platform, seed=seed)
    tau = ARGON_UNITS.unit("time").value_in_unit(unit.picosecond)
    model.integrator.step(int(round(duration * tau / model.integrator.getStepSize().value_in_unit(unit.picosecond))))
    return model, radius


def bulk_pressure(estimator, density, steps=2000, platform="CPU", seed=9):
    """The pressure P* (reduced, virial with on-step velocities) of a bulk liquid of 500 particles at reduced
    ``density``: FCC melted by ``steps`` Isothermal steps at T0, then ``steps`` isoenergetic steps sampled every 100."""
    length = ARGON_UNITS.unit("length").value_in_unit(NM)
    positions, box = fcc_box(density / length**3, (5, 5, 5))
    model = argon_model(positions, np.diag(np.asarray(box, float)), estimator, platform=platform, seed=seed)
    model.integrator.setMode(GenDPDEIntegrator.Isothermal)
    model.integrator.step(steps)
    model.integrator.setMode(GenDPDEIntegrator.Isoenergetic)
    pressure_unit = ARGON_UNITS.unit("pressure").value_in_unit(unit.kilojoule_per_mole / NM**3)
    values = []
    for _ in range(steps // 100):
        model.integrator.step(100)
        values.append(np.trace(pressure_tensor(model.force, model.context)) / 3 / pressure_unit)
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
        model = argon_model(positions, np.diag(np.asarray(box, float)), "VB", platform=platform, seed=seed)
        model.integrator.setMode(GenDPDEIntegrator.Isothermal)
        model.integrator.step(steps)
        va, vb, vc, exact = estimator_volumes(model)
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


#: The options of the slab of a fluid file or built-in fluid (--fluid) or of a model file (--model), and
#: fluid_slab's argument each sets.
FLUID_OPTIONS = {"time_step": "time_step", "thermostat_time": "thermostat_time", "melt_time": "melt_time"}
#: The coarse-graining options of --fluid (calibrate.add_fluid_arguments), which a --model file's parameters replace:
#: None where not given (fluid_parameters puts calibrate.COARSE_GRAINING's defaults back).
COARSE_GRAINING_OPTIONS = ("molecules_per_particle", "neighbors", "cutoff")


def _option(name):
    return f"--{name.replace('_', '-')}"


def fluid_parameters(arguments, cells):
    """The GenDPDEParameters of --fluid (coarse-grained) or --model (a model file's, exactly), None for the published
    argon model, checked against the slab's ``cells`` before anything runs; a bad argument exits with a one-line
    error (status 1)."""
    coarse_graining = [name for name in COARSE_GRAINING_OPTIONS if getattr(arguments, name) is not None]
    if arguments.model is not None:
        if arguments.fluid is not None:
            raise SystemExit("error: slab: --fluid and --model exclude each other; give one")
        if coarse_graining:
            raise SystemExit(f"error: slab: {_option(coarse_graining[0])} applies to --fluid only; a --model file "
                             f"holds every parameter of its model")
        parameters = load_model(arguments.model)
        source = f"--model {arguments.model}"
    elif arguments.fluid is None:
        given = [name for name in FLUID_OPTIONS if getattr(arguments, name) is not None] + coarse_graining
        if given:
            raise SystemExit(f"error: slab: {_option(given[0])} applies to the slab of a --fluid or --model only")
        return None
    else:
        from ..cli.fluids import parameters_from_arguments
        from ..models.fluid import COARSE_GRAINING
        defaults = {name: value for name, value in COARSE_GRAINING.items() if getattr(arguments, name) is None}
        parameters = parameters_from_arguments(argparse.Namespace(**{**vars(arguments), **defaults}), "slab")
        source = f"--fluid {arguments.fluid}"
    checked_model(f"slab: {source}", lambda: parameters.liquid(
        cells=cells, **({} if arguments.time_step is None else {"time_step": arguments.time_step}),
        seed=arguments.seed), "use fewer --neighbors (a smaller --cutoff)" if arguments.model is None else
        "the slab's box is fixed; use a model with a shorter cutoff")
    return parameters


def load_model(path):
    """fluid_files.load_parameters of the model file ``path`` (--model); exits with a one-line error naming the
    file if it is missing or not a model file."""
    if not os.path.isfile(path):
        raise SystemExit(f"error: slab: --model {path}: no such file")
    if os.path.splitext(path)[1].lower() not in (".toml", ".json"):
        raise SystemExit(f"error: slab: --model {path} is not allowed; a model file ends in .toml or .json")
    from ..models.fluid_files import load_parameters
    try:
        return load_parameters(path)
    except ValueError as error:
        raise SystemExit(f"error: slab: --model {' '.join(str(error).split())}")


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


def run(arguments):
    duration, every = (10.0, 5.0) if arguments.quick else (arguments.duration, arguments.every)
    if every > duration:
        raise SystemExit(f"error: slab: --every {every:g} is not allowed; it must be at most --duration {duration:g} "
                         f"(a sample every --every time units of the run)")
    cells = (5, 5, 6) if arguments.quick else (5, 5, 10)
    parameters = fluid_parameters(arguments, cells)
    for estimator in arguments.estimators if parameters is not None else ():
        try:   # (a model file's f_cut serves the estimator it was tuned for, and V-A, which has none)
            parameters.checked_estimator(estimator)
        except ValueError as error:
            raise SystemExit(f"error: slab: --estimators {estimator}: {error}") from None
    time_step = ARGON_SLAB_TIME_STEP if parameters is None else arguments.time_step   # (None: measured in the run)
    if time_step is not None and round(every / time_step) < 1:
        raise SystemExit(f"error: slab: --every {every:g} is not allowed; it must be at least one step, dt* = "
                         f"{time_step:g}")
    units = ARGON_UNITS if parameters is None else parameters.units
    os.makedirs(arguments.output, exist_ok=True)
    runs, profiles, tensions = {}, {}, {}
    for estimator in arguments.estimators:
        if parameters is None:
            print(f"{estimator}: slab of {4 * np.prod(cells)} particles, {duration:g} time units")
            samples, model, thickness = run_slab(estimator, duration, every, cells, arguments.platform)
        else:
            build = {key: getattr(arguments, name) for name, key in FLUID_OPTIONS.items()
                     if getattr(arguments, name) is not None}
            try:
                samples, slab = run_fluid_slab(parameters, estimator, duration, every, cells, arguments.platform,
                                               arguments.seed, **build)
            except ValueError as error:   # (--every less than the step measured for the model)
                raise SystemExit(f"error: slab: {error}") from None
            model, thickness = slab.model, slab.thickness
            model_file = "" if arguments.model is None else f"the model in {arguments.model}; "
            tau = units.unit("time").value_in_unit(unit.picosecond)
            print(f"{estimator}: slab of {4 * np.prod(cells)} particles of {parameters.fluid.name} "
                  f"({model_file}T0 = {parameters.temperature:g} K), dt* = {slab.time_step:.4g}, melted and "
                  f"thermostatted {build.get('thermostat_time', SLAB_THERMOSTAT_TIME):g} time units after the cut, "
                  f"then {duration:g} time units isoenergetic (time unit {tau:.4g} ps; reduced units of the model: "
                  f"length n0^(-1/3))")
        runs[estimator] = samples
        temperatures = parameters is not None
        print("   t*   core true n*   core mean n_i*   width/initial   surface tension*"
              + ("   T_kin (K)   T_harm (K)" if temperatures else ""))
        for s in samples:
            print(f"{s.time:6.1f}   {s.core_density:12.3f}   {s.core_estimate:14.3f}   {s.width:13.2f}   "
                  f"{s.tension:16.4f}" + (f"   {s.kinetic_temperature:9.1f}   {s.harmonic_temperature:10.1f}"
                                          if temperatures else ""))
        late = [s for s in samples if s.time > duration / 2]
        tensions[estimator] = [s.tension for s in late]
        if len(late) >= 10:   # enough samples for 5 blocks of 2
            tension = block_average(tensions[estimator], 5, name=f"{estimator} surface tension")
            mean = tension.mean
            error = (f"+- {tension.standard_error:.4f} (block average, 5 blocks; sd "
                     f"{np.std(tensions[estimator]):.4f})")
        else:
            mean = float(np.mean(tensions[estimator]))
            error = f"(sd {np.std(tensions[estimator]):.4f}; too few samples for an error)"
        print(f"{estimator}: over the second half ({len(late)} samples), core true n* "
              f"{np.mean([s.core_density for s in late]):.3f}, surface tension* {mean:.4f} {error}"
              + (f"; T_kin {np.mean([s.kinetic_temperature for s in late]):.1f} K, T_harm "
                 f"{np.mean([s.harmonic_temperature for s in late]):.1f} K (T0 {parameters.temperature:g} K)"
                 if temperatures else ""))
        if not arguments.no_oracle:
            profiles[estimator] = depth_profile(model, thickness, units=units)
            print(f"{estimator} at t* = {samples[-1].time:g}: density by depth (units of the initial half "
                  f"thickness; particles): true, exact partition of unity, V-B, V-A, V-C")
            for row in profiles[estimator]:
                print("  {:4.1f}-{:4.1f} ({:4d}): {:6.3f} {:8.3f} {:8.3f} {:8.3f} {:8.3f}".format(*row))
    with atomic_write(os.path.join(arguments.output, "slab.csv"), newline="") as out:
        writer = csv.writer(out)
        temperatures = parameters is not None
        writer.writerow(["estimator", "time", "core_true_density", "core_mean_estimate", "width", "surface_tension"]
                        + (["kinetic_temperature_K", "harmonic_temperature_K"] if temperatures else []))
        for estimator, samples in runs.items():
            for s in samples:
                writer.writerow([estimator, s.time, s.core_density, s.core_estimate, s.width, s.tension]
                                + ([s.kinetic_temperature, s.harmonic_temperature] if temperatures else []))
    if parameters is not None:
        print(surface_tension_table(tensions, parameters))
        print("(the droplet, the bulk comparison and the coexistence density are the argon model's: run slab "
              "without --fluid or --model)")
        plot(runs, profiles, os.path.join(arguments.output, "slab"))
        print(f"wrote {arguments.output}/slab.csv, slab.png, slab.pdf")
        return
    if not arguments.no_oracle:
        count = 400 if arguments.quick else 1000
        model, radius = run_droplet("VB", 10.0, count, arguments.platform)
        print(f"VB droplet of {count} particles at t* = 10: density by distance from its centre (units of the initial "
              f"radius; particles): true, exact partition of unity, V-B, V-A, V-C")
        for row in radial_profile(model, radius):
            print("  {:4.1f}-{:4.1f} ({:4d}): {:6.3f} {:8.3f} {:8.3f} {:8.3f} {:8.3f}".format(*row))
        print("bulk liquids (V-B runs): n*, V_VB/V_exact mean and sd, V_VA/V_exact mean and sd, corr(V_VB, V_exact), "
              "V_VC/V_exact mean and sd")
        for row in bulk_comparison(cells=(4, 4, 4) if arguments.quick else (5, 5, 5),
                                   steps=200 if arguments.quick else 2000, platform=arguments.platform):
            print("  {:5.2f}: {:6.3f} {:6.3f}   {:6.3f} {:6.3f}   {:5.2f}   {:6.3f} {:6.3f}".format(*row))
    if not arguments.quick:
        for estimator in [e for e in arguments.estimators if e != "VA"]:   # (V-A's bulk liquids pair)
            density, pressures = coexistence_density(estimator, platform=arguments.platform)
            print(f"{estimator}: bulk P* {', '.join(f'{p:.4f}' for p in pressures)} at n* = 0.7, 0.75, 0.8: "
                  f"P* = 0 at n* = {density:.3f} (the coexistence density with vacuum)")
    plot(runs, profiles, os.path.join(arguments.output, "slab"))
    print(f"wrote {arguments.output}/slab.csv, slab.png, slab.pdf")


def add_arguments(parser):
    add_platform(parser, default="CPU")
    add_output(parser, "slab.csv and the plots")
    parser.add_argument("--duration", type=POSITIVE, default=100.0, help="time units per run (default 100)")
    parser.add_argument("--every", type=POSITIVE, default=10.0, help="time units between samples (default 10)")
    parser.add_argument("--quick", action="store_true", help="a 600-particle slab for 10 time units (seconds)")
    parser.add_argument("--estimators", nargs="+", choices=list(ESTIMATOR_NAMES.values()),
                        default=list(ESTIMATOR_NAMES.values()), help="the slabs to run (default: every estimator)")
    parser.add_argument("--no-oracle", action="store_true", help="skip the exact volumes (the slow part)")
    from ..cli.fluids import add_fluid_arguments
    add_fluid_arguments(parser, default=None)
    parser.set_defaults(**dict.fromkeys(COARSE_GRAINING_OPTIONS))   # (not given: None; --model refuses them)
    parser.add_argument("--model", help="a model file written by `calibrate --output` (.toml or .json): the slab of "
                        "exactly its parameters (a calibrated model) instead of --fluid and its coarse-graining")
    parser.add_argument("--time-step", type=POSITIVE, help="with --fluid or --model: dt* in the model's reduced time "
                        "(default stability.suggest_time_step's, measured: V-C's is a tenth of V-B's)")
    parser.add_argument("--thermostat-time", type=NON_NEGATIVE, help=f"with --fluid or --model: time units the slab is "
                        f"thermostatted after the cut, before the isoenergetic run (default {SLAB_THERMOSTAT_TIME:g}; "
                        f"0: none)")
    parser.add_argument("--melt-time", type=NON_NEGATIVE, help="with --fluid or --model: time units the bulk liquid "
                        "melts before the cut (default 20)")
    parser.add_argument("--seed", type=SEED, default=5, help="with --fluid or --model: random seed (default 5)")
    parser.set_defaults(run=run)
