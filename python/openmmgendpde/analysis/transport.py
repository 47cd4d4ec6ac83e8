# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""Transport coefficients from steady non-equilibrium flows (docs/transport.md): a second, independent method for
each of `calibrate`'s wave-decay measurements, in OpenMM units (nm, ps, amu, kJ/mol, K).

- Shear viscosity eta (amu/(nm ps)) from periodic Poiseuille flow: a body force +F x-hat (kJ/mol/nm) on the particles
  with wrapped z in [0, L/2) and -F x-hat on those in [L/2, L) (zero in total on average). The steady flow is
  v_x(z) = (n0 F/(2 eta)) h(z), h(z) = z (L/2 - z) in the first half and antisymmetric in the second; the binned,
  time-averaged profile is fitted to A h + c, and eta = n0 F/(2 A).
- Thermal conductivity lambda (kJ/(mol ps nm K)) from a steady heat flux: every few steps the internal temperatures
  of a hot slab (wrapped z in [0, w)) are reset to T0 (1 + e) and those of a cold slab ([L/2, L/2 + w)) to
  T0 (1 - e); Q, the energy put into the hot slab (and taken from the cold one) per reset interval t, flows through
  both halves, J = Q/(2 A t) (A the box's xy area), and lambda = J/|dT/dz| with dT/dz the slope of the temperature
  profile (the harmonic mean of theta_i per bin) between the slabs, away from them.

Both run in the Isoenergetic mode (the model being calibrated), one run per replica, through a runner
``replicas(one) -> [one(index, model, context) for each replica]`` that equilibrates a model for each call:
``each_replica(equilibrated, count)`` runs them one after another on ``equilibrated() -> (FluidModel, Context)``,
and `calibrate.Calibration.replicas` side by side in processes of one thread. Run lengths are given in the relaxation
time of the slowest mode of the half box (estimated from the target coefficient). Each result has ``value`` and
``error`` (standard error) as `calibrate.Measured` has, and the details of the run.
"""

import dataclasses
import math

import numpy as np
from openmm import unit

from ..units import BOLTZMANN
from .flows import (  # noqa: F401  (bin_shape ... momentum_diffusion_time: part of this module's API)
    between_slabs,
    bin_shape,
    fit_amplitude,
    half_sign,
    line_slopes,
    momentum_diffusion_time,
    poiseuille_shape,
    slab_profile,
    thermal_diffusion_time,
    viscosity_from_amplitude,
)
from .profiles import profile
from .statistics import block_standard_error, statistical_inefficiency
from .thermodynamics import external_field_groups, heat_capacity_per_particle

KB = BOLTZMANN.value_in_unit(unit.kilojoule_per_mole / unit.kelvin)


@dataclasses.dataclass
class TransportResult:
    """A transport coefficient (``value`` +- ``error``, a standard error) and how it was measured: the replicas'
    values and errors, the binned profile (``centre`` nm, ``profile`` and its ``profile_error``), and a dict of the
    run's other numbers (``details``: forcing, times, temperature rise ...)."""
    value: float
    error: float
    replica_values: list
    replica_errors: list
    centre: np.ndarray
    profile: np.ndarray
    profile_error: np.ndarray
    details: dict


def each_replica(equilibrated, count):
    """The runner of ``count`` replicas one after another in this process: run(one) calls
    one(index, *equilibrated()) for index 0 .. count - 1 and returns the results."""
    return lambda one: [one(index, *equilibrated()) for index in range(count)]


# --- Poiseuille flow ------------------------------------------------------------------------------------------------

def poiseuille_viscosity(parameters, replicas, body_force, peak_fraction=0.2, developed=3.0, measured=5.0,
                         bins=20, samples_per_time=10, report=print):
    """The shear viscosity (amu/(nm ps)) from periodic Poiseuille flow along z, a run on each of the equilibrated
    models (Isoenergetic) that ``replicas`` gives (each_replica). ``body_force``: the builder of the force,
    models.flows.poiseuille_body_force or one called as it, ``body_force(F, L, N)`` (the models layer sits above this
    one, so the caller hands it in); its force group is left out of the energies.

    F is chosen so that the peak velocity, n0 F L^2/(32 eta) with the target eta, is ``peak_fraction`` of the thermal
    velocity sqrt(k_B T0/m); every run starts from that profile laid on the equilibrium velocities, waits
    ``developed`` and then averages over ``measured`` momentum diffusion times tau = rho (L/2)^2/(eta pi^2) (target
    eta; the details give the waiting time in tau of the measured eta), sampling ``samples_per_time`` profiles per
    tau. Each run's amplitude A comes from the time series of per-frame fits (their mean is the fit of the averaged
    profile), its error from the series' statistical inefficiency; the result is the replicas' mean, its error the
    larger of the propagated one and the replicas' scatter over sqrt(replicas).

    Viscous heating: the flow dissipates n0 F <|v|> per volume, so T rises by
    Delta T/T0 = (16/(3 pi^2)) f^2 X k_B/c over X diffusion times at f = peak_fraction (c = C_V + 3 k_B/2 per
    particle): 0.9% for argon (c = 14 k_B) at f = 0.25 and X = 9, less for water. The details give the measured
    rise of the harmonic mean of theta_i and of the kinetic temperature (about the bins' flow) over a run, from a
    line through their time series; keep both below ~2% of T0 (smaller f, shorter runs, more replicas)."""
    targets = parameters.targets()

    def one(replica, model, context):
        n = model.num_particles
        length = model.system.getDefaultPeriodicBoxVectors()[2][2].value_in_unit(unit.nanometer)
        density = n / model.volume
        mass_density = density * parameters.mass
        thermal = math.sqrt(KB * parameters.temperature / parameters.mass)
        force = 32 * targets["shear_viscosity"] * peak_fraction * thermal / (density * length**2)
        tau = momentum_diffusion_time(mass_density, targets["shear_viscosity"], length)
        step = model.integrator.getStepSize().value_in_unit(unit.picosecond)
        interval = max(1, round(tau / samples_per_time / step))
        external = body_force(force, length, n)
        model.system.addForce(external)
        context.reinitialize(preserveState=True)
        state = context.getState(getPositions=True, getVelocities=True)
        positions = state.getPositions(asNumpy=True).value_in_unit(unit.nanometer)
        velocities = state.getVelocities(asNumpy=True).value_in_unit(unit.nanometer / unit.picosecond)
        amplitude_guess = density * force / (2 * targets["shear_viscosity"])
        velocities[:, 0] += amplitude_guess * poiseuille_shape(positions[:, 2], length)
        context.setVelocities(velocities)
        shape = bin_shape(bins, length)
        warm = round(developed * tau / step / interval)
        frames = warm + round(measured * tau / step / interval)
        times, flows, kinetic, harmonic = [], [], [], []
        for frame in range(frames + 1):
            if frame:
                model.integrator.step(interval)
            sample = _sample(model, context, bins)
            times.append(sample["time"])
            flows.append(sample["velocity"][:, 0])
            kinetic.append(sample["kinetic_temperature"])
            harmonic.append(sample["harmonic_temperature"])
        times, flows = np.array(times), np.array(flows)
        eta, error, amplitude, drifts = _viscosity_from_frames(flows[warm + 1:], shape, density, force)
        run_time = times[-1] - times[0]
        rise = {name: np.polyfit(times, series, 1)[0] * run_time / parameters.temperature
                for name, series in (("harmonic", harmonic), ("kinetic", kinetic))}
        waited = (times[warm] - times[0]) / momentum_diffusion_time(mass_density, eta, length)
        report(f"  Poiseuille replica {replica + 1}: eta = {eta:.4g} +- {error:.2g} amu/(nm ps) "
               f"(F = {force:.4g} kJ/mol/nm, peak {amplitude * length**2 / 16:.3g} nm/ps = "
               f"{amplitude * length**2 / 16 / thermal:.2f} v_th, drift {np.mean(drifts):+.2g} nm/ps); waited "
               f"{waited:.1f} tau of this eta; heating over {run_time:.0f} ps: theta_harm "
               f"{100 * rise['harmonic']:+.2f}%, T_kin {100 * rise['kinetic']:+.2f}% of T0")
        extra = {"force": force, "box_length": length, "density": density, "thermal_velocity": thermal,
                 "peak_velocity": amplitude * length**2 / 16, "sample_interval_steps": interval,
                 "run_time": run_time, "waited_tau": waited, "drift": float(np.mean(drifts))}
        return eta, error, flows[warm + 1:], dict(extra, temperature_rise=rise)

    runs = replicas(one)
    values, errors, profiles, details = zip(*runs)
    rises = [detail["temperature_rise"] for detail in details]
    return _combine(values, errors, profiles, details[-1]["box_length"], bins,
                    dict(details[-1], temperature_rise=rises, peak_fraction=peak_fraction))


def _viscosity_from_frames(flows, shape, density, force, check=None):
    """(eta, its error, the amplitude A, the drifts c per frame) from binned profiles ``flows`` (frames x bins, nm/ps)
    of a steady Poiseuille flow with the bins' ``shape`` (bin_shape): A from the time series of per-frame fits (their
    mean is the fit of the averaged profile), its error from the series' statistical inefficiency. ``check(A, its
    error)``, if given, is called before eta is computed (to refuse a profile without the flow)."""
    amplitudes, drifts = fit_amplitude(flows, shape)
    amplitude, amplitude_error = _mean_and_error(amplitudes)
    if check is not None:
        check(amplitude, amplitude_error)
    eta = viscosity_from_amplitude(amplitude, density, force)
    return eta, eta * amplitude_error / amplitude, amplitude, drifts


def viscosity_from_profiles(profiles, force, density=None, start=0.0, direction=0, box_length=None):
    """The shear viscosity (amu/(nm ps)) of a steady periodic Poiseuille flow from the output of a ProfileReporter
    (analysis.profiles) along the axis across the flow: ``profiles`` is its CSV file (a path) or that file read by
    ``numpy.genfromtxt(path, delimiter=",", names=True, comments="#")``. ``force``: the body force's F (kJ/mol/nm,
    models.flows.poiseuille_body_force); ``density``: n (nm^-3), by default the mean of the file's density column
    (N/V); ``start``: the frames before this time (ps) are left out (the flow develops over a few
    momentum_diffusion_time); ``direction``: the flow's component (0, 1, 2: the columns vx, vy, vz); ``box_length``
    (nm): the box along the axis, by default 2 bins times the first bin's centre.

    The fit and its error are those of poiseuille_viscosity: each frame's profile fitted to A s_b + c with s_b the
    bins' mean of poiseuille_shape (bin_shape: the number of bins must be even), eta = n F/(2 A), the error of A from
    the statistical inefficiency of the per-frame series. Returns a TransportResult (one replica) whose details give
    the force, density, box length, frames used, peak velocity A L^2/16 and mean drift. Raises ValueError for a
    file without the columns, fewer than 2 frames after ``start``, or a profile with no flow along ``direction``."""
    data = profiles if isinstance(profiles, np.ndarray) else np.genfromtxt(profiles, delimiter=",", names=True,
                                                                           comments="#")
    column = "v" + "xyz"[direction] if direction in (0, 1, 2) else None
    needed = ["step", "time", "bin", "centre", "density", column]
    names = data.dtype.names or ()
    if column is None or any(name not in names for name in needed):
        raise ValueError(f"viscosity_from_profiles: direction = {direction!r} and the columns {list(names)}: it needs "
                         f"direction 0, 1 or 2 and a ProfileReporter's columns {needed}")
    data = np.atleast_1d(data)
    bins = int(data["bin"].max()) + 1
    frames = len(data) // bins
    if frames * bins != len(data) or np.any(data["bin"] != np.tile(np.arange(bins), frames)):
        raise ValueError(f"viscosity_from_profiles: {len(data)} rows are not whole frames of bins 0 .. {bins - 1}")
    times = data["time"].reshape(frames, bins)[:, 0]
    kept = times >= start
    if kept.sum() < 2:
        raise ValueError(f"viscosity_from_profiles: start = {start} ps leaves {int(kept.sum())} of {frames} frames "
                         f"(times {times[0]:.6g} .. {times[-1]:.6g} ps); at least 2 are needed")
    flows = data[column].reshape(frames, bins)[kept]
    length = 2 * bins * float(data["centre"][0]) if box_length is None else float(box_length)
    n = float(np.mean(data["density"][:bins * frames])) if density is None else float(density)
    shape = bin_shape(bins, length)

    def check(amplitude, amplitude_error):
        if not amplitude * force > 2 * amplitude_error * abs(force):
            raise ValueError(f"viscosity_from_profiles: the profile's amplitude along {column} is {amplitude:.3g} +- "
                             f"{amplitude_error:.2g} 1/(nm ps) for F = {force} kJ/mol/nm: no Poiseuille flow along "
                             f"that direction (the amplitude must have the sign of F and be more than 2 standard "
                             f"errors)")

    eta, error, amplitude, drifts = _viscosity_from_frames(flows, shape, n, force, check)
    details = {"force": float(force), "density": n, "box_length": length, "frames": int(kept.sum()),
               "peak_velocity": amplitude * length**2 / 16, "drift": float(np.mean(drifts))}
    return _combine([eta], [error], [flows], length, bins, details)


def _sample(model, context, bins):
    """The binned profile along z of the current state (profiles.profile) with the harmonic mean of theta_i per bin
    ('theta_harmonic') and overall ('harmonic_temperature'), the kinetic temperature about the bins' mean velocities
    ('kinetic_temperature', all bins together; per bin 'kinetic_profile') and the time (ps)."""
    state = context.getState(getPositions=True, getVelocities=True)
    theta = np.asarray(model.integrator.getParticleTemperatures().value_in_unit(unit.kelvin))
    box = [list(v.value_in_unit(unit.nanometer)) for v in state.getPeriodicBoxVectors()]
    masses = np.full(model.num_particles, model.parameters.mass)
    # One particle type for all: profile's per-type theta is the harmonic mean of theta_i per bin.
    result = profile(state.getPositions(asNumpy=True).value_in_unit(unit.nanometer),
                     state.getVelocities(asNumpy=True).value_in_unit(unit.nanometer / unit.picosecond),
                     masses, box, bins=bins, temperatures=theta, types=np.zeros(model.num_particles, int))
    degrees = np.maximum(result["count"] - 1, 0)
    result["theta_harmonic"] = result["type_theta"][:, 0]
    result["harmonic_temperature"] = 1 / np.mean(1 / theta)
    result["kinetic_profile"] = result["kinetic_temperature"]
    result["kinetic_temperature"] = float(np.nansum(result["kinetic_profile"] * degrees) / degrees.sum())
    result["time"] = state.getTime().value_in_unit(unit.picosecond)
    return result


def _mean_and_error(series):
    """The mean of a correlated time series and its standard error, sqrt(g var/n) with g the statistical
    inefficiency."""
    series = np.asarray(series, float)
    g = statistical_inefficiency(series)
    return float(series.mean()), float(series.std(ddof=1) * math.sqrt(g / len(series)))


def _combine(values, errors, frames, length, bins, details):
    """A TransportResult from the replicas: the mean, and the larger of the propagated error and the replicas'
    scatter over sqrt(replicas) (when there are at least 2)."""
    values, errors = np.array(values), np.array(errors)
    propagated = float(np.sqrt(np.sum(errors**2)) / len(values))
    scatter = float(values.std(ddof=1) / math.sqrt(len(values))) if len(values) > 1 else 0.0
    all_frames = np.concatenate(frames)
    centre = (np.arange(bins) + 0.5) * length / bins
    profile_error = np.array([_mean_and_error(column)[1] for column in all_frames.T])
    details = dict(details, propagated_error=propagated, scatter_error=scatter)
    return TransportResult(float(values.mean()), max(propagated, scatter), list(values), list(errors), centre,
                           all_frames.mean(axis=0), profile_error, details)


# --- Heat flux between thermostatted slabs --------------------------------------------------------------------------

def heat_flux_conductivity(parameters, replicas, excess=0.1, slab_bins=2, bins=20, reset_steps=10,
                           developed=2.0, measured=6.0, samples_per_time=20, margin=None, uniform=False,
                           report=print):
    """The thermal conductivity (kJ/(mol ps nm K)) from a steady heat flux along z between a hot and a cold slab, a
    run on each of the equilibrated models (Isoenergetic) that ``replicas`` gives (each_replica).

    The box is cut into ``bins`` bins along z; the hot slab is the first ``slab_bins`` of them (width w), the cold
    slab as many from L/2. Every ``reset_steps`` steps theta_i of the particles in the hot slab is set to
    T0 (1 + ``excess``) and in the cold slab to T0 (1 - ``excess``) (GenDPDEIntegrator.setParticleTemperatures; the
    others keep theirs): by default each slab's theta_i are scaled so that their harmonic mean, the thermodynamic
    temperature, is the slab's; with ``uniform`` every theta_i is set to it, which also takes away the equilibrium
    spread of the eps_i, k_B T per particle (docs/integrator.md), so that the slab relaxes to a harmonic mean lower by
    C_V/(C_V + k_B) (0.926 for argon) and the whole box cools (docs/transport.md). The change of sum eps_i
    (getInternalEnergies) in each slab is the energy it took, Q_hot > 0 and Q_cold < 0. Every run starts with theta_i
    scaled by 1 + excess s(z) (slab_profile: the expected steady profile, each particle keeping its place in the
    equilibrium distribution), waits ``developed`` and averages over ``measured`` thermal diffusion times tau = n0 c
    (L/2)^2/(lambda pi^2) (target lambda, c = C_V + 5 k_B/2, thermodynamics.heat_capacity_per_particle without the
    configurational part).

    Q = (Q_hot - Q_cold)/2 per reset interval t flows through both halves: J = Q/(2 A t), A the xy area. dT/dz: the
    slopes of lines through the harmonic means of theta_i of the bins in [w + margin, L/2 - margin] and
    [L/2 + w + margin, L - margin] (margin: the cutoff R unless given, nm), averaged with the sign of each half;
    lambda = J/|dT/dz|, the errors of J (from 10 block means) and dT/dz (from the statistical inefficiency of its time
    series) combined as relative errors; over replicas as poiseuille_viscosity. The details also give the slope of the
    kinetic temperature profile, the mean temperature, and the energy accounting: E = K + U + sum eps_i changes only
    through the resets, E(end) - E(start) against the sum of the injected energies ('energy_change', 'injected'; the
    hot slab's alone 'injected_hot'), all in kJ/mol."""
    run = _HeatFlux(parameters, excess, slab_bins, bins, reset_steps, developed, measured, samples_per_time,
                    parameters.cutoff if margin is None else margin, uniform, report)
    values, errors, profiles, details = zip(*replicas(run.one))
    return _combine(values, errors, profiles, details[-1]["box_length"], bins, details[-1])


@dataclasses.dataclass
class _HeatFlux:
    """The settings of heat_flux_conductivity (its docstring), and its run on one replica (one)."""
    parameters: object
    excess: float
    slab_bins: int
    bins: int
    reset_steps: int
    developed: float
    measured: float
    samples_per_time: float
    margin: float
    uniform: bool
    report: object

    def geometry(self, model):
        """(box length, xy area, slab width, bin centres, and the bins fitted: all of them, the first half's, the
        second half's) of ``model``'s box."""
        vectors = model.system.getDefaultPeriodicBoxVectors()
        length = vectors[2][2].value_in_unit(unit.nanometer)
        area = vectors[0][0].value_in_unit(unit.nanometer) * vectors[1][1].value_in_unit(unit.nanometer)
        width = length * self.slab_bins / self.bins
        centre = (np.arange(self.bins) + 0.5) * length / self.bins
        first, second = between_slabs(centre, length, width, self.margin)
        return length, area, width, centre, first | second, first, second

    def reset(self, model, context, length, width):
        """The slabs' theta_i reset to T0 (1 -+ excess); the change of each eps_i and the hot and cold slabs."""
        t0 = self.parameters.temperature
        wrapped = np.mod(_positions(context)[:, 2], length)
        hot = wrapped < width
        cold = (wrapped >= length / 2) & (wrapped < length / 2 + width)
        theta = np.asarray(model.integrator.getParticleTemperatures().value_in_unit(unit.kelvin))
        before = _internal_energies(model)
        for members, target in ((hot, t0 * (1 + self.excess)), (cold, t0 * (1 - self.excess))):
            theta[members] = target if self.uniform else theta[members] * target * np.mean(1 / theta[members])
        model.integrator.setParticleTemperatures(list(theta))
        return _internal_energies(model) - before, hot, cold

    def one(self, replica, model, context):
        """The run on one replica: (lambda, its error, the harmonic-mean profiles sampled, the details)."""
        length, area, width, centre, region, first, second = self.geometry(model)
        density = model.num_particles / model.volume
        heat_capacity = heat_capacity_per_particle(self.parameters.heat_capacity)
        tau = thermal_diffusion_time(density, heat_capacity, self.parameters.targets()["thermal_conductivity"], length)
        step = model.integrator.getStepSize().value_in_unit(unit.picosecond)
        interval = step * self.reset_steps
        every = max(1, round(tau / self.samples_per_time / interval))
        resets, warm = round((self.developed + self.measured) * tau / interval), round(self.developed * tau / interval)
        z = _positions(context)[:, 2]
        theta = np.asarray(model.integrator.getParticleTemperatures().value_in_unit(unit.kelvin))
        model.integrator.setParticleTemperatures(list(theta * (1 + self.excess * slab_profile(z, length, width))))
        energy_start = _total_energy(model, context)
        injected, hot_total, fluxes, frames, kinetic_frames, means = 0.0, 0.0, [], [], [], []
        for reset in range(resets):
            model.integrator.step(self.reset_steps)
            change, hot, cold = self.reset(model, context, length, width)
            q_hot, q_cold = change[hot].sum(), change[cold].sum()
            injected += change.sum()
            hot_total += q_hot
            if reset >= warm:
                fluxes.append((q_hot - q_cold) / 2 / (2 * area * step * self.reset_steps))
                if (reset - warm) % every == 0:
                    sample = _sample(model, context, self.bins)
                    frames.append(sample["theta_harmonic"])
                    kinetic_frames.append(sample["kinetic_profile"])
                    means.append(sample["harmonic_temperature"])
        energy_change = _total_energy(model, context) - energy_start
        gradients = (line_slopes(centre, frames, second) - line_slopes(centre, frames, first)) / 2
        gradient, gradient_error = _mean_and_error(gradients)
        # The injections at successive resets are anti-correlated (each one removes the slab's fluctuation that the
        # last one left), so that their mean converges faster than a series with g >= 1 would: its error from the
        # scatter of 10 block means (each one the injected energy of its block over its length).
        flux, flux_error = float(np.mean(fluxes)), block_standard_error(np.array(fluxes), 10)
        conductivity = flux / gradient
        error = conductivity * math.hypot(flux_error / flux, gradient_error / gradient)
        kinetic_gradient = float(np.mean(line_slopes(centre, kinetic_frames, second)
                                         - line_slopes(centre, kinetic_frames, first)) / 2)
        waited = warm * step * self.reset_steps / thermal_diffusion_time(density, heat_capacity, conductivity, length)
        self.report(f"  heat-flux replica {replica + 1}: lambda = {conductivity:.4g} +- {error:.2g} kJ/(mol ps nm K) "
                    f"(J = {flux:.4g} +- {flux_error:.2g} kJ/(mol ps nm^2), dT/dz = {gradient:.4g} +- "
                    f"{gradient_error:.2g} K/nm from theta, {kinetic_gradient:.4g} K/nm from T_kin); waited "
                    f"{waited:.1f} tau of this lambda; mean theta_harm {np.mean(means):.2f} K; energy: E(end) - "
                    f"E(start) = {energy_change:.5g} kJ/mol, injected {injected:.5g} kJ/mol")
        return conductivity, error, np.array(frames), {
            "box_length": length, "area": area, "slab_width": width, "margin": self.margin, "excess": self.excess,
            "fit_bins": int(region.sum()), "flux": flux, "flux_error": flux_error, "gradient": gradient,
            "gradient_error": gradient_error, "kinetic_gradient": kinetic_gradient,
            "mean_temperature": float(np.mean(means)), "energy_change": energy_change, "injected": injected,
            "injected_hot": hot_total, "run_time": resets * self.reset_steps * step, "waited_tau": waited,
            "kinetic_profile": np.mean(kinetic_frames, axis=0)}


def _positions(context):
    return context.getState(getPositions=True).getPositions(asNumpy=True).value_in_unit(unit.nanometer)


def _internal_energies(model):
    return np.asarray(model.integrator.getInternalEnergies().value_in_unit(unit.kilojoule_per_mole))


def _total_energy(model, context):
    """K + U + sum eps_i (kJ/mol), the energy that the Isoenergetic mode conserves (without external fields: the
    groups of external_field_groups)."""
    groups = set(range(32)) - external_field_groups(model.system)
    state = context.getState(getEnergy=True, groups=groups)
    return ((state.getKineticEnergy() + state.getPotentialEnergy()).value_in_unit(unit.kilojoule_per_mole)
            + float(_internal_energies(model).sum()))
