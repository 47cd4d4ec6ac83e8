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
from ..analysis.profiles import profile
from ..analysis.shear import shear_viscosity
from ..api import GenDPDEIntegrator
from ..models.fluid import KB
from ..models.model import Equilibration
from ..models.shear import ReverseShearFlow

#: The equilibration of each run: steps with the DPD thermostat, then in the run's mode (as calibrate's transport runs).
MELT_STEPS, SETTLE_STEPS = 1000, 500


@dataclasses.dataclass
class ShearRun:
    """One exchange interval's run: the ShearViscosity (``result``), the interval (steps), the flow's peak speed (the
    fitted lines at the slabs' centres, nm/ps) over the thermal velocity sqrt(k_B T0/m), the time-averaged harmonic
    mean of theta_i per bin (K, ``temperature_profile``), the measured time (ps) and the target viscosity."""
    interval: int
    result: object
    peak_fraction: float
    temperature_profile: np.ndarray
    measured_time: float
    target_viscosity: float


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


def shear_run(parameters, interval, cells=(8, 8, 8), estimator=None, time_step=0.01,
              mode=GenDPDEIntegrator.Isoenergetic, slabs=20, developed=2.0, measured=10.0, samples_per_time=10,
              margin=None, platform="CPU", properties=None, seed=1, report=print):
    """A ShearRun of the model of ``parameters`` (GenDPDEParameters) with one swap every ``interval`` steps (the
    module's docstring): ``cells`` FCC cells, ``estimator`` (default the one f_cut was tuned for), step ``time_step``
    in reduced time, ``mode``, ``slabs`` slabs (= bins of the profile), lines fitted at least ``margin`` (nm; default
    R/2) from the exchange slabs, ``platform`` (a name) with ``properties``, random ``seed``."""
    margin = parameters.cutoff / 2 if margin is None else margin
    model = parameters.liquid(cells=cells, estimator=estimator, mode=GenDPDEIntegrator.Isothermal,
                              time_step=time_step, seed=seed)
    context = model.equilibrate(platform, Equilibration(MELT_STEPS, SETTLE_STEPS, mode, seed=seed), properties)
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
    flow = ReverseShearFlow(interval, slabs)
    every = max(1, round(tau / samples_per_time / step))
    flow.step(context, round(developed * tau / step))
    flow.reset()
    start = state_time = context.getState().getTime().value_in_unit(unit.picosecond)
    masses = np.full(n, parameters.mass)
    frames, temperatures = [], []
    for _ in range(max(2, round(measured * samples_per_time))):
        flow.step(context, every)
        state = context.getState(getPositions=True, getVelocities=True)
        state_time = state.getTime().value_in_unit(unit.picosecond)
        theta = model.integrator.getParticleTemperatures().value_in_unit(unit.kelvin)
        binned = profile(state.getPositions(asNumpy=True).value_in_unit(unit.nanometer),
                         state.getVelocities(asNumpy=True).value_in_unit(unit.nanometer / unit.picosecond), masses,
                         state.getPeriodicBoxVectors(asNumpy=True).value_in_unit(unit.nanometer), bins=slabs,
                         temperatures=theta)
        frames.append(binned["velocity"][:, 0])
        temperatures.append(binned["theta_harmonic"])
    result = shear_viscosity(flow.momenta, flow.area, state_time - start, binned["centre"], frames, length, slabs,
                             margin)
    thermal = math.sqrt(KB * parameters.temperature / parameters.mass)
    peak = result.shear_rate * (length / 2 - length / slabs) / 2
    run = ShearRun(interval, result, peak / thermal, np.mean(temperatures, axis=0), state_time - start, target)
    report(f"  interval {interval} steps: eta = {result.viscosity:.4g} +- {result.error:.2g} amu/(nm ps), "
           f"gamma_dot = {result.shear_rate:.4g} +- {result.shear_rate_error:.2g} 1/ps, J = "
           f"{result.momentum_flux:.4g} +- {result.momentum_flux_error:.2g} kJ/mol/nm^3, peak {peak / thermal:.2f} "
           f"v_th, {result.independent_samples:.0f} independent frames; theta_harm {run.temperature_profile.min():.1f}"
           f" to {run.temperature_profile.max():.1f} K over {state_time - start:.0f} ps")
    return run


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
