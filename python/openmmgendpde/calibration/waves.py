# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""The transport coefficients of a Calibration measured: the decays of a transverse velocity wave (the shear
viscosity) and of an energy wave (the thermal conductivity) along the long box of the steady flows, and the steady
flows themselves (analysis.transport: Poiseuille flow, a heat flux between slabs); and the speed of sound, by the
oscillation of a standing sound wave in a longer box."""

import math

import numpy as np
from openmm import unit

from ..analysis.transport import heat_flux_conductivity, poiseuille_viscosity
from ..models.flows import poiseuille_body_force
from ..models.fluid import KB
from .results import Measured

#: The sound wave's velocity amplitude over the speed of sound (sound_speed), which is also the density wave's
#: relative amplitude: small enough to be linear (the frequency moves at second order in it; the wave's energy warms
#: argon by 0.3%), large enough to stand out of the mode's thermal noise: 2 <v_z sin(k z)> fluctuates by sqrt(2/N)
#: of the thermal velocity sqrt(k_B T/m), 0.034 of it in 1728 particles, 0.075-0.09 of this amplitude (argon, water:
#: v_th/c = 0.11, 0.13).
SOUND_MACH = 0.05
#: Samples of the sound wave's amplitude per period.
SOUND_SAMPLES = 40
#: The damping per period (2 pi a/omega) above which sound_speed's line warns: water's wave in 3 x 3 x 24 cells damped
#: by 0.74-2.51 and its replicas scattered by 8%; in 3 x 3 x 48 cells by 0.47-1.09, within 3% (docs/fluids.md).
SOUND_DAMPING = 1.5


class TransportMeasurements:
    """The transport measurements and the sound wave of a Calibration (a mix-in: it runs replicas through
    self.replicas and steps through self._step; its heat capacity is self.heat_capacity())."""

    def _wave_rate(self, amplitude_of, perturb, diffusivity):
        """The decay rate (1/ps) of a wave along z of the box of plan.steady_cells (the steady flows' box, so that
        both methods see the same wavelength, the longest that box has): the replicas' amplitudes averaged, then a
        least-squares line through log(amplitude) over the times where the mean amplitude exceeds 1/e^2 of its
        start; error from the replicas' individual rates. The run covers plan.wave_decays decay times
        1/(diffusivity k^2) (``diffusivity``, nm^2/ps, from the target: eta/(n0 m) or lambda/(n0 c)), at least
        plan.wave_steps steps: a shorter run, a third of the decay time in a long box, read the conductivity ~50%
        high (docs/transport.md). In a 500-particle cube (k R = 1.3 for water) the transverse wave read the
        viscosity ~0.7 of the 2048-particle cube's, and in that cube (k R = 0.83) it read 0.77 of the Poiseuille
        flow's in the long box once the friction was doubled: the dissipative stress is spread over R, so a wave
        much longer than R is needed for the macroscopic coefficient."""
        def one(index, model, context):
            edge = model.system.getDefaultPeriodicBoxVectors()[2][2].value_in_unit(unit.nanometer)
            k = 2 * math.pi / edge
            step = model.integrator.getStepSize().value_in_unit(unit.picosecond)
            steps = max(self.plan.wave_steps, round(self.plan.wave_decays / (diffusivity * k**2) / step))
            interval = max(1, steps // 150)
            perturb(model, context, k)
            times, amplitudes = [], []
            for n in range(steps // interval + 1):
                if n:
                    self._step(model.integrator, interval)
                state = context.getState(getPositions=True, getVelocities=True, getEnergy=True)
                times.append(state.getTime().value_in_unit(unit.picosecond))
                amplitudes.append(amplitude_of(model, context, state, k))
            times, amplitudes = np.array(times) - times[0], np.array(amplitudes)
            return times, amplitudes, _decay_rate(times, amplitudes), k

        runs = self.replicas(self.plan.steady_cells)(one)
        times, k = runs[-1][0], runs[-1][3]
        curves, rates = [run[1] for run in runs], [run[2] for run in runs]
        mean_rate = _decay_rate(times, np.mean(curves, axis=0))
        return mean_rate, float(np.std(rates, ddof=1) / math.sqrt(len(rates))), k, len(rates)

    def shear_viscosity(self):
        """eta from the decay of v_x = V0 sin(k z), V0 = the thermal velocity sqrt(k_B T0/m)."""
        p = self.parameters
        v0 = math.sqrt(KB * p.temperature / p.mass)

        def perturb(model, context, k):
            z = model_positions(context)[:, 2]
            velocities = context.getState(getVelocities=True).getVelocities(asNumpy=True).value_in_unit(
                unit.nanometer / unit.picosecond)
            velocities[:, 0] += v0 * np.sin(k * z)
            context.setVelocities(velocities)

        def amplitude(model, context, state, k):
            z = state.getPositions(asNumpy=True).value_in_unit(unit.nanometer)[:, 2]
            vx = state.getVelocities(asNumpy=True).value_in_unit(unit.nanometer / unit.picosecond)[:, 0]
            return 2 * np.mean(vx * np.sin(k * z))

        mass_density = p.density * p.mass
        rate, error, k, replicas = self._wave_rate(amplitude, perturb,
                                                   p.targets()["shear_viscosity"] / mass_density)
        return Measured(rate * mass_density / k**2, error * mass_density / k**2, replicas)

    def thermal_conductivity(self):
        """lambda from the decay of a wave theta_i -> theta_i (1 + 0.2 sin(k z_i)), read from the energy wave
        sum (eps_i + K_i). Each theta_i is scaled, not set: setting every theta_i to T0 (1 + 0.2 sin(k z)) took away
        the equilibrium spread of the eps_i, the harmonic mean of theta fell by 7% (argon) within 500 steps, and the
        conduction term, which goes as 1/theta^2, read the conductivity ~16% high (docs/transport.md)."""
        p = self.parameters
        heat_capacity = self.heat_capacity().value

        def perturb(model, context, k):
            z = model_positions(context)[:, 2]
            theta = np.asarray(model.integrator.getParticleTemperatures().value_in_unit(unit.kelvin))
            model.integrator.setParticleTemperatures(list(theta * (1 + 0.2 * np.sin(k * z))))

        def amplitude(model, context, state, k):
            z = state.getPositions(asNumpy=True).value_in_unit(unit.nanometer)[:, 2]
            v = state.getVelocities(asNumpy=True).value_in_unit(unit.nanometer / unit.picosecond)
            kinetic = 0.5 * p.mass * np.sum(v * v, axis=1)
            energies = np.asarray(model.integrator.getInternalEnergies().value_in_unit(unit.kilojoule_per_mole))
            return 2 * np.mean((energies + kinetic) * np.sin(k * z))

        rate, error, k, replicas = self._wave_rate(
            amplitude, perturb, p.targets()["thermal_conductivity"] / (p.density * heat_capacity))
        factor = p.density * heat_capacity / k**2
        return Measured(rate * factor, error * factor, replicas)


    def sound_speed(self, estimate):
        """The speed of sound (nm/ps, Measured) measured directly: a standing sound wave v_z = A sin(k z) laid on
        the equilibrium velocities of an Isoenergetic run (so the wave is adiabatic) in the long box of sound_cells
        (k = 2 pi/L_z), its amplitude J(t) = 2 <v_z sin(k z)> followed over plan.sound_periods periods of
        ``estimate`` (nm/ps: the derived speed), SOUND_SAMPLES a period, and fitted with
        exp(-a t) (B cos(omega t) + C sin(omega t)) (damped_cosine); c = sqrt(omega^2 + a^2)/k, the damping's
        correction (the roots of the linearised equations, omega^2 = c^2 k^2 - (Gamma k^2/2)^2, a = Gamma k^2/2).
        A = SOUND_MACH ``estimate``. Each of plan.replicas replicas gives a speed: their mean and its standard error.
        The wave must be long: its damping per period, 2 pi a/omega = pi Gamma k/c, falls as 1/L_z. In 3 x 3 x 48
        cells it was 0.26-0.44 (argon) and 0.47-1.09 (water), and the replicas read within 1% (argon) and 3% (water)
        of their mean; in 3 x 3 x 24 cells water's damped by up to 2.5 per period and its replicas scattered by 8%
        (docs/fluids.md). A line reports each replica's speed and damping."""
        def one(index, model, context):
            edge = model.system.getDefaultPeriodicBoxVectors()[2][2].value_in_unit(unit.nanometer)
            k = 2 * math.pi / edge
            step = model.integrator.getStepSize().value_in_unit(unit.picosecond)
            period = edge / estimate
            interval = max(1, round(period / SOUND_SAMPLES / step))
            frames = round(self.plan.sound_periods * period / (interval * step))
            z = model_positions(context)[:, 2]
            velocities = context.getState(getVelocities=True).getVelocities(asNumpy=True).value_in_unit(
                unit.nanometer / unit.picosecond)
            velocities[:, 2] += SOUND_MACH * estimate * np.sin(k * z)
            context.setVelocities(velocities)
            times, amplitudes = [], []
            for n in range(frames + 1):
                if n:
                    self._step(model.integrator, interval)
                state = context.getState(getPositions=True, getVelocities=True)
                times.append(state.getTime().value_in_unit(unit.picosecond))
                z = state.getPositions(asNumpy=True).value_in_unit(unit.nanometer)[:, 2]
                vz = state.getVelocities(asNumpy=True).value_in_unit(unit.nanometer / unit.picosecond)[:, 2]
                amplitudes.append(2 * np.mean(vz * np.sin(k * z)))
            omega, rate = damped_cosine(np.array(times) - times[0], np.array(amplitudes), estimate * k)
            return math.sqrt(omega**2 + rate**2) / k, 2 * math.pi * rate / omega

        cells = sound_cells(self.parameters, self.plan)
        runs = self.replicas(cells)(one)
        speeds = [speed for speed, _ in runs]
        dampings = [damping for _, damping in runs]
        self.report(f"  sound wave in {cells[0]} x {cells[1]} x {cells[2]} cells: c = "
                    + ", ".join(f"{1e3 * speed:.1f}" for speed in speeds) + " m/s (damping per period "
                    + ", ".join(f"{damping:.2f}" for damping in dampings) + ")"
                    + (f"; a damping above {SOUND_DAMPING:g} per period: the wave dies out before its frequency is "
                       f"read, a longer box is needed (Plan.sound_cells)" if max(dampings) > SOUND_DAMPING else ""))
        return Measured(float(np.mean(speeds)), float(np.std(speeds, ddof=1) / math.sqrt(len(speeds))), len(speeds))

    def steady_viscosity(self):
        """eta by periodic Poiseuille flow (transport.poiseuille_viscosity) in boxes of plan.steady_cells."""
        time = self.plan.steady_time
        result = poiseuille_viscosity(self.parameters, self.replicas(self.plan.steady_cells), poiseuille_body_force,
                                      developed=3.0 * time, measured=5.0 * time, report=self.report)
        return Measured(result.value, result.error, len(result.replica_values))

    def steady_conductivity(self):
        """lambda by a steady heat flux between slabs (transport.heat_flux_conductivity) in plan.steady_cells."""
        time = self.plan.steady_time
        result = heat_flux_conductivity(self.parameters, self.replicas(self.plan.steady_cells), developed=2.0 * time,
                                        measured=6.0 * time, report=self.report)
        return Measured(result.value, result.error, len(result.replica_values))


def model_positions(context):
    return context.getState(getPositions=True).getPositions(asNumpy=True).value_in_unit(unit.nanometer)


def _decay_rate(times, amplitudes):
    """Least-squares slope of -log(amplitude) over the leading times where the amplitude exceeds e^-2 of its start
    (later the thermal noise dominates)."""
    start = amplitudes[0]
    keep = np.nonzero(amplitudes / start < math.exp(-2))[0]
    end = keep[0] if len(keep) else len(amplitudes)
    end = max(end, 3)
    slope = np.polyfit(times[:end], np.log(np.abs(amplitudes[:end] / start)), 1)[0]
    return -slope


def sound_cells(parameters, plan):
    """The FCC cells of the sound wave's box: plan.sound_cells, widened across (x, y) where that is less than twice
    the cutoff (ModelParameters.liquid refuses such a box) and lengthened alike, so that L_z/L_x stays."""
    nx, ny, nz = plan.sound_cells
    cell = (4 / parameters.density) ** (1 / 3)
    across = max(nx, ny, math.floor(2 * parameters.cutoff / cell) + 1)
    return across, across, round(nz * across / max(nx, ny))


def damped_cosine(times, values, omega):
    """(omega, a) of the least-squares fit of values = exp(-a t) (B cos(omega t) + C sin(omega t)) at ``times``,
    searched from ``omega`` (the expected angular frequency) over [omega/2, 2 omega] and a in [0, omega/2): B and C
    solved exactly for each (omega, a) (linear least squares), the pair on a grid, refined by grids around the best."""
    times, values = np.asarray(times, dtype=float), np.asarray(values, dtype=float)

    def residuals(omegas, rates):
        w, r = np.meshgrid(omegas, rates, indexing="ij")
        decay = np.exp(-r[..., None] * times)
        basis = np.stack([decay * np.cos(w[..., None] * times), decay * np.sin(w[..., None] * times)], axis=-1)
        gram = np.einsum("...ti,...tj->...ij", basis, basis)
        projection = np.einsum("...ti,t->...i", basis, values)
        coefficients = np.linalg.solve(gram, projection[..., None])[..., 0]
        return np.sum(values**2) - np.einsum("...i,...i->...", coefficients, projection)

    low, high, rate_high = 0.5 * omega, 2.0 * omega, 0.5 * omega
    omegas, rates = np.linspace(low, high, 301), np.linspace(0.0, rate_high, 101)
    for _ in range(6):
        sums = residuals(omegas, rates)
        i, j = np.unravel_index(np.argmin(sums), sums.shape)
        best_omega, best_rate = omegas[i], rates[j]
        step_omega, step_rate = omegas[1] - omegas[0], rates[1] - rates[0]
        omegas = np.linspace(best_omega - 2 * step_omega, best_omega + 2 * step_omega, 41)
        rates = np.linspace(max(0.0, best_rate - 2 * step_rate), best_rate + 2 * step_rate, 41)
    return float(best_omega), float(best_rate)
