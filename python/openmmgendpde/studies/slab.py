# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
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

import csv
import dataclasses

import numpy as np
import openmm
from openmm import unit

from ..analysis.pressure import pressure_tensor
from ..analysis.thermodynamics import ThermodynamicProbe
from ..api import GenDPDEIntegrator, estimator_value
from ..internal.files import atomic_write
from ..models.argon import ARGON_NAMES, ARGON_UNITS, LiquidArgon, argon_cutoff, argon_parameters
from ..models.lattice import fcc_box
from ..models.melting import melt_then_switch

NM = unit.nanometer


#: dt* of the argon slabs (argon_model).
ARGON_SLAB_TIME_STEP = 0.01


def argon_model(positions, box, estimator, cutoff=1.6839, platform="Reference", seed=1):
    """The liquid-argon model (models.argon's parameters at R* = ``cutoff``, step ARGON_SLAB_TIME_STEP) for
    ``positions`` (nm) in a rectangular box of edges ``box`` (nm), and its Context (``platform``) with velocities and
    internal energies drawn at T0, Isoenergetic: (LiquidArgon, Context)."""
    model = argon_parameters(cutoff, estimator).build(
        np.diag(np.asarray(box, float)), np.asarray(positions, float), estimator_value(estimator),
        ARGON_UNITS.to_openmm(ARGON_SLAB_TIME_STEP, "time"), seed, names=ARGON_NAMES, model_type=LiquidArgon,
        cutoff=argon_cutoff(cutoff))
    context = model.context(platform, seed=seed)
    model.integrator.setInternalEnergiesToTemperature(model.temperature, seed)
    return model, context


#: Reduced time units (the model's own, GenDPDEParameters.units) that fluid_slab thermostats a new slab before its
#: isoenergetic run: chosen by measurement (docs/interfaces.md, "A slab of any fluid").
SLAB_THERMOSTAT_TIME = 10.0


@dataclasses.dataclass
class FluidSlab:
    """What fluid_slab built: the fluid's model (model.Model: its System and Topology with the box lengthened along z,
    Isoenergetic) and its Context, the slab's initial thickness (nm), the vacuum's width (nm) and the step
    (reduced)."""
    model: object
    context: object
    thickness: float
    vacuum: float
    time_step: float

    @property
    def system(self):
        return self.model.system

    @property
    def topology(self):
        return self.model.topology


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
    parameters = parameters.replace(background_pressure=None)
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
    context = model.context(platform, parameters.temperature, seed, properties or {})
    integrator.step(steps(melt_time))
    melted = model.wrapped_positions(context)
    edges = edges + np.array([0.0, 0.0, vacuum])
    box = [openmm.Vec3(*row) for row in np.diag(edges)]
    model.system.setDefaultPeriodicBoxVectors(*box)
    model.topology.setPeriodicBoxVectors(box * NM)
    context.setPeriodicBoxVectors(*box)
    context.setPositions((melted + np.array([0.0, 0.0, vacuum / 2])) * NM)
    melt_then_switch(integrator, steps(thermostat_time), parameters.temperature * unit.kelvin, seed)
    return FluidSlab(model, context, thickness, vacuum, time_step)


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


def sample_slab(model, context, thickness, time, units=ARGON_UNITS):
    """A SlabSample of ``model`` (a model.Model) in ``context`` now (time reduced); reduced quantities in ``units``
    (argon's by default)."""
    length = units.unit("length").value_in_unit(NM)
    box = model.box_edges
    x = model.wrapped_positions(context)
    d = depth(x, box)
    core = d < thickness / 4
    area = box[0] * box[1]
    estimates = model.force.getParticleDensities(context).value_in_unit(NM**-3)
    p = pressure_tensor(model.force, context)
    tension = 0.5 * box[2] * (p[2, 2] - 0.5 * (p[0, 0] + p[1, 1]))                   # kJ/mol/nm^2
    tension_unit = units.unit("surface_tension").value_in_unit(unit.kilojoule_per_mole / NM**2)
    state = context.getState(getEnergy=True, getVelocities=True)
    thermal = ThermodynamicProbe(model.system).sample(state, context, model.integrator)
    return SlabSample(time, core.sum() / (area * thickness / 2) * length**3,
                      float(estimates[core].mean()) * length**3, 2 * np.percentile(d, 90) / thickness,
                      float(tension) / tension_unit, thermal.kinetic_temperature.value_in_unit(unit.kelvin),
                      thermal.harmonic_temperature.value_in_unit(unit.kelvin))


def sample_run(model, context, thickness, duration, every, units=ARGON_UNITS, report=None):
    """Run ``model`` in ``context`` for ``duration`` reduced time units of ``units``; a list of SlabSample every
    ``every`` time units (the first at t = 0). ``report(sample)`` is called after each."""
    tau = units.unit("time").value_in_unit(unit.picosecond)
    dt = model.integrator.getStepSize().value_in_unit(unit.picosecond) / tau
    steps = int(round(every / dt))
    if steps < 1:
        raise ValueError(f"every = {every:g} time units is less than one step (dt* = {dt:g}); it must be at least that")
    samples = [sample_slab(model, context, thickness, 0.0, units)]
    while samples[-1].time < duration - 0.5 * steps * dt:   # (a whole number of steps: the last sample nearest)
        model.integrator.step(steps)
        samples.append(sample_slab(model, context, thickness, samples[-1].time + steps * dt, units))
        if report is not None:
            report(samples[-1])
    return samples


def run_slab(estimator, duration=100.0, every=10.0, cells=(5, 5, 10), platform="CPU", seed=5, report=None):
    """Run the argon slab with ``estimator`` for ``duration`` reduced time units: a list of SlabSample every
    ``every`` time units (the first at t = 0), the model and its Context at the end, and the initial thickness
    (nm)."""
    positions, box, thickness = slab_positions(cells)
    model, context = argon_model(positions, box, estimator, platform=platform, seed=seed)
    return sample_run(model, context, thickness, duration, every, report=report), model, context, thickness


def run_fluid_slab(parameters, estimator, duration, every, cells, platform="CPU", seed=5, report=None, **build):
    """The slab of any fluid (fluid_slab, with ``build`` its options) run isoenergetically for ``duration`` time
    units of the model (parameters.units); (SlabSamples every ``every``, FluidSlab)."""
    slab = fluid_slab(parameters, cells, estimator, platform=platform, seed=seed, **build)
    return sample_run(slab.model, slab.context, slab.thickness, duration, every, parameters.units, report), slab


def write_csv(runs, path, temperatures=False):
    """The samples of ``runs`` {estimator: [SlabSample]} as a CSV table (with the temperatures of a fluid's slab)."""
    with atomic_write(path, newline="") as out:
        writer = csv.writer(out)
        writer.writerow(["estimator", "time", "core_true_density", "core_mean_estimate", "width", "surface_tension"]
                        + (["kinetic_temperature_K", "harmonic_temperature_K"] if temperatures else []))
        for estimator, samples in runs.items():
            for s in samples:
                writer.writerow([estimator, s.time, s.core_density, s.core_estimate, s.width, s.tension]
                                + ([s.kinetic_temperature, s.harmonic_temperature] if temperatures else []))
