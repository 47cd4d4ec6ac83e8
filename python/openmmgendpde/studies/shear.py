# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""flow-curve: the shear viscosity of a fluid model against the shear rate, from reverse non-equilibrium shear flows
(Mueller-Plathe 1999; models.shear.ReverseShearFlow, analysis.shear; docs/flows.md, "Shear flow and the flow curve").

For each exchange interval (steps between two momentum swaps: a shorter interval drives a faster flow), a fresh
liquid of the model in a box of FCC cells is melted with the DPD thermostat (1000 steps) and run 500 steps in the
mode of the run with its internal energies drawn at T0 (as calibrate's transport runs are, docs/transport.md). The
expected zig-zag profile is laid on its velocities (shear rate from the target viscosity and the mean momentum of a
swap, which the extremes of a slab's Maxwell-Boltzmann velocities give); the flow develops for ``developed`` and is
averaged over ``measured`` momentum diffusion times tau = rho (L/2)^2/(eta pi^2) of the target eta, with
``samples_per_time`` profiles per tau. Each run gives eta = J/gamma_dot with its standard error, the shear rate, the
flux, the flow's peak speed against the thermal velocity, and the temperature profile (harmonic mean of theta_i per
bin) that the viscous heating and the exchanges (which cool the slabs) leave in the Isoenergetic mode.

    python -m openmmgendpde flow-curve --fluid argon --molecules-per-particle 5 --cells 8 8 8 --intervals 100 50 25 12
"""

import dataclasses
import math

import numpy as np
from openmm import unit

from ..analysis.flows import momentum_diffusion_time, slab_profile
from ..analysis.pressure import numerical_virial_tensor, virial_tensor
from ..analysis.profiles import profile
from ..analysis.shear import shear_viscosity
from ..analysis.statistics import correlated_mean
from ..api import GenDPDEIntegrator
from ..models.fluid import KB
from ..models.model import Equilibration
from ..models.polymers import polymer_solution
from ..models.shear import ReverseShearFlow

#: The equilibration of each run: steps with the DPD thermostat, then in the run's mode (as calibrate's transport runs).
MELT_STEPS, SETTLE_STEPS = 1000, 500


@dataclasses.dataclass
class ShearRun:
    """One exchange interval's run: the ShearViscosity (``result``), the interval (steps), the flow's peak speed (the
    fitted lines at the slabs' centres, nm/ps) over the thermal velocity sqrt(k_B T0/m), the time-averaged harmonic
    mean of theta_i per bin (K, ``temperature_profile``; frozen in the Isothermal mode), the measured time (ps), the
    target viscosity and the integrator's mode."""
    interval: int
    result: object
    peak_fraction: float
    temperature_profile: np.ndarray
    measured_time: float
    target_viscosity: float
    mode: int = GenDPDEIntegrator.Isoenergetic


def maximum_of_normals(count):
    """The expected largest of ``count`` independent standard normal variates (by quadrature of
    count x phi(x) Phi(x)^(count - 1))."""
    x = np.linspace(-10, 10, 20001)
    density = np.exp(-x**2 / 2) / math.sqrt(2 * math.pi)
    cumulative = 0.5 * (1 + np.vectorize(math.erf)(x / math.sqrt(2)))
    return float(np.trapezoid(x * count * density * cumulative ** (count - 1), x))


def expected_shear_rate(mass, temperature, viscosity, area, length, particles_per_slab, exchange_time):
    """gamma_dot (1/ps) of the steady flow that one swap every ``exchange_time`` (ps) drives, estimated: a swap moves
    2 m (c v_th - u), c the expected largest of a slab's particles' normal variates, u = gamma_dot L/4 the slabs' flow
    speed, and J = 2 m (c v_th - u)/(2 A t) = eta gamma_dot. Only the run's starting profile uses it."""
    thermal = math.sqrt(KB * temperature / mass)
    c = maximum_of_normals(max(1, round(particles_per_slab)))
    return 2 * mass * c * thermal / (2 * area * exchange_time * viscosity + mass * length / 2)


def _equilibrated(parameters, cells, estimator, time_step, mode, platform, properties, seed, build=None):
    """(model, context): the model's liquid in ``cells`` (or the model ``build()`` makes, with its Isothermal
    integrator), then equilibrated (MELT_STEPS with the DPD thermostat, SETTLE_STEPS in ``mode``)."""
    model = build() if build is not None else parameters.liquid(
        cells=cells, estimator=estimator, mode=GenDPDEIntegrator.Isothermal, time_step=time_step, seed=seed)
    return model, model.equilibrate(platform, Equilibration(MELT_STEPS, SETTLE_STEPS, mode, seed=seed), properties)


def _started_flow(parameters, model, context, interval, slabs):
    """(ReverseShearFlow, tau in ps, step in ps): the driver of the model's Context, with the expected zig-zag profile
    (expected_shear_rate at the target viscosity) laid on its velocities, the total momentum kept."""
    edges = model.box_edges
    length, area, n = edges[2], edges[0] * edges[1], model.num_particles
    target = parameters.targets()["shear_viscosity"]
    step = model.integrator.getStepSize().value_in_unit(unit.picosecond)
    tau = momentum_diffusion_time(parameters.mass * n / model.volume, target, length)
    rate = expected_shear_rate(parameters.mass, parameters.temperature, target, area, length, n / slabs,
                               interval * step)
    state = context.getState(getPositions=True, getVelocities=True)
    positions = state.getPositions(asNumpy=True).value_in_unit(unit.nanometer)
    velocities = state.getVelocities(asNumpy=True).value_in_unit(unit.nanometer / unit.picosecond)
    added = rate * (length / 2 - length / slabs) / 2 * slab_profile(positions[:, 2], length, length / slabs)
    velocities[:, 0] += added - added.mean()
    context.setVelocities(velocities)
    return ReverseShearFlow(interval, slabs), tau, step


def _binned(model, context, slabs, virials=False, on_step=False):
    """profiles.profile of the Context now along z in ``slabs`` bins, with theta_i, and with the GenDPDEForce's
    per-particle virials (``virials``) and the on-step velocities v + (dt/2) F/m (``on_step``)."""
    state = context.getState(getPositions=True, getVelocities=True, getForces=on_step)
    velocities = state.getVelocities(asNumpy=True).value_in_unit(unit.nanometer / unit.picosecond)
    masses = np.full(model.num_particles, model.parameters.mass)
    if on_step:
        step = model.integrator.getStepSize().value_in_unit(unit.picosecond)
        forces = state.getForces(asNumpy=True).value_in_unit(unit.kilojoule_per_mole / unit.nanometer)
        velocities = velocities + 0.5 * step * forces / masses[:, None]
    theta = model.integrator.getParticleTemperatures().value_in_unit(unit.kelvin)
    binned = profile(state.getPositions(asNumpy=True).value_in_unit(unit.nanometer), velocities, masses,
                     state.getPeriodicBoxVectors(asNumpy=True).value_in_unit(unit.nanometer), bins=slabs,
                     temperatures=theta,
                     virials=virial_tensor(model.force, context, per_particle=True) if virials else None)
    binned["time"] = state.getTime().value_in_unit(unit.picosecond)
    return binned


def shear_run(parameters, interval, cells=(8, 8, 8), estimator=None, time_step=0.01,
              mode=GenDPDEIntegrator.Isoenergetic, slabs=20, developed=2.0, measured=10.0, samples_per_time=10,
              margin=None, platform="CPU", properties=None, seed=1, report=print):
    """A ShearRun of the model of ``parameters`` (GenDPDEParameters) with one swap every ``interval`` steps (the
    module's docstring): ``cells`` FCC cells, ``estimator`` (default the one f_cut was tuned for), step ``time_step``
    in reduced time, ``mode``, ``slabs`` slabs (= bins of the profile), lines fitted at least ``margin`` (nm; default
    R/2) from the exchange slabs, ``platform`` (a name) with ``properties``, random ``seed``."""
    margin = parameters.cutoff / 2 if margin is None else margin
    model, context = _equilibrated(parameters, cells, estimator, time_step, mode, platform, properties, seed)
    length = model.box_edges[2]
    flow, tau, step = _started_flow(parameters, model, context, interval, slabs)
    every = max(1, round(tau / samples_per_time / step))
    flow.step(context, round(developed * tau / step))
    flow.reset()
    start = context.getState().getTime().value_in_unit(unit.picosecond)
    frames, temperatures = [], []
    for _ in range(max(2, round(measured * samples_per_time))):
        flow.step(context, every)
        binned = _binned(model, context, slabs)
        frames.append(binned["velocity"][:, 0])
        temperatures.append(binned["theta_harmonic"])
    duration = binned["time"] - start
    result = shear_viscosity(flow.momenta, flow.area, duration, binned["centre"], frames, length, slabs, margin)
    thermal = math.sqrt(KB * parameters.temperature / parameters.mass)
    peak = result.shear_rate * (length / 2 - length / slabs) / 2
    run = ShearRun(interval, result, peak / thermal, np.mean(temperatures, axis=0), duration,
                   parameters.targets()["shear_viscosity"], mode)
    report(f"  interval {interval} steps: eta = {result.viscosity:.4g} +- {result.error:.2g} amu/(nm ps), "
           f"gamma_dot = {result.shear_rate:.4g} +- {result.shear_rate_error:.2g} 1/ps, J = "
           f"{result.momentum_flux:.4g} +- {result.momentum_flux_error:.2g} kJ/mol/nm^3, peak {peak / thermal:.2f} "
           f"v_th, {result.independent_samples:.0f} independent frames over {duration:.0f} ps"
           + ("" if mode == GenDPDEIntegrator.Isothermal else
              f"; theta_harm {run.temperature_profile.min():.1f} to {run.temperature_profile.max():.1f} K"))
    return run


# --- A polymer solution: the normal stress differences ---------------------------------------------------------------

#: The force group of the chains' bonds (their virial tensor is numerical: pressure.numerical_virial_tensor).
BOND_GROUP = 1


@dataclasses.dataclass(frozen=True)
class Chains:
    """Linear chains of ``length`` particles holding ``fraction`` of the particles, as models.polymers.polymer_solution
    makes them (self-avoiding walks on the liquid's lattice; harmonic bonds of its defaults: rest length the lattice's
    nearest-neighbour distance, stiffness 100 k_B T0/b0^2)."""
    length: int = 10
    fraction: float = 0.3

    def count(self, num_particles):
        """The number of chains among ``num_particles``: round(fraction N/length)."""
        return round(self.fraction * num_particles / self.length)


@dataclasses.dataclass
class NormalStresses:
    """The normal stress differences of a run (kJ/mol/nm^3, each a statistics.CorrelatedMean of its time series), in
    the stress convention sigma = -P with the flow along x, its gradient along z and the vorticity along y:
    N1 = sigma_xx - sigma_zz = P_zz - P_xx (``first``) and N2 = sigma_zz - sigma_yy = P_yy - P_zz (``second``); the
    mean pressure tensor (``pressure``); the ShearViscosity (``viscosity``, None at rest) and the interval (None: no
    swaps)."""
    interval: object
    first: object
    second: object
    pressure: np.ndarray
    viscosity: object


def polymer_normal_stresses(parameters, interval, chains=Chains(), cells=(6, 6, 8), estimator=None, time_step=0.01,
                            mode=GenDPDEIntegrator.Isoenergetic, slabs=20, developed=5.0, measured=12.5,
                            samples_per_time=10, margin=None, platform="CPU", properties=None, seed=1, report=print):
    """NormalStresses of the model's liquid with ``chains`` (Chains, made by models.polymers.polymer_solution; their
    bonds in BOND_GROUP) sheared by a swap every ``interval`` steps (None: at rest, the control, where both
    differences must vanish), run as shear_run runs (the lengths in momentum
    diffusion times of the solvent's target viscosity). Each frame's pressure tensor: the mean over the bins of
    profiles.profile's (the kinetic part with the on-step velocities about each bin's mean flow, and the
    GenDPDEForce's per-particle virial tensors) plus the bonds' numerical_virial_tensor over the volume. Both
    differences are even in the shear rate, so the whole box serves despite the zig-zag (the slabs' bins included)."""
    margin = parameters.cutoff / 2 if margin is None else margin

    def build():
        model = polymer_solution(parameters, chains.length, chains.count(4 * math.prod(cells)), cells, estimator,
                                 GenDPDEIntegrator.Isothermal, time_step, seed, placement_seed=seed)
        model.bonds.setForceGroup(BOND_GROUP)
        return model
    model, context = _equilibrated(parameters, cells, estimator, time_step, mode, platform, properties, seed, build)
    if interval is None:
        step = model.integrator.getStepSize().value_in_unit(unit.picosecond)
        tau = momentum_diffusion_time(parameters.mass * model.num_particles / model.volume,
                                      parameters.targets()["shear_viscosity"], model.box_edges[2])
        advance, flow = model.integrator.step, None
    else:
        flow, tau, step = _started_flow(parameters, model, context, interval, slabs)
        advance = lambda steps: flow.step(context, steps)   # noqa: E731
    every = max(1, round(tau / samples_per_time / step))
    advance(round(developed * tau / step))
    if flow is not None:
        flow.reset()
    start = context.getState().getTime().value_in_unit(unit.picosecond)
    pressures, frames = [], []
    for _ in range(max(2, round(measured * samples_per_time))):
        advance(every)
        binned = _binned(model, context, slabs, virials=True, on_step=True)
        pressures.append(binned["pressure"].mean(axis=0)
                         + numerical_virial_tensor(context, {BOND_GROUP}) / model.volume)
        frames.append(binned["velocity"][:, 0])
    pressures = np.array(pressures)
    first = correlated_mean(pressures[:, 2, 2] - pressures[:, 0, 0])
    second = correlated_mean(pressures[:, 1, 1] - pressures[:, 2, 2])
    viscosity = None
    if flow is not None:
        viscosity = shear_viscosity(flow.momenta, flow.area, binned["time"] - start, binned["centre"], frames,
                                    model.box_edges[2], slabs, margin)
    result = NormalStresses(interval, first, second, pressures.mean(axis=0), viscosity)
    sheared = (f"eta = {viscosity.viscosity:.4g} +- {viscosity.error:.2g} amu/(nm ps), gamma_dot = "
               f"{viscosity.shear_rate:.4g} 1/ps" if viscosity else "at rest")
    report(f"  interval {interval}: {sheared}; N1 = {first.mean:.3g} +- {first.standard_error:.2g}, N2 = "
           f"{second.mean:.3g} +- {second.standard_error:.2g} kJ/mol/nm^3 ({first.independent_samples:.0f} and "
           f"{second.independent_samples:.0f} independent frames)")
    return result


def record(run):
    """A ShearRun as a dict of plain numbers and lists (for JSON), OpenMM units."""
    result = run.result
    return {"interval": run.interval, "viscosity": result.viscosity, "error": result.error,
            "shear_rate": result.shear_rate, "shear_rate_error": result.shear_rate_error,
            "momentum_flux": result.momentum_flux, "momentum_flux_error": result.momentum_flux_error,
            "independent_samples": result.independent_samples, "peak_fraction": run.peak_fraction,
            "measured_time": run.measured_time, "centre": list(result.centre), "profile": list(result.profile),
            "profile_error": list(result.profile_error), "fitted": [bool(b) for b in result.fitted],
            "temperature_profile": list(run.temperature_profile)}


def flow_curve(parameters, intervals, report=print, **options):
    """[shear_run(parameters, interval, **options) for each of ``intervals``], each with its own seed (the given one
    plus its index)."""
    seed = options.pop("seed", 1)
    return [shear_run(parameters, interval, seed=seed + index, report=report, **options)
            for index, interval in enumerate(intervals)]
