# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""The transport coefficients of a Calibration measured: the decays of a transverse velocity wave (the shear
viscosity) and of an energy wave (the thermal conductivity) along the long box of the steady flows, and the steady
flows themselves (analysis.transport: Poiseuille flow, a heat flux between slabs)."""

import math

import numpy as np
from openmm import unit

from ..analysis.transport import heat_flux_conductivity, poiseuille_viscosity
from ..models.fluid import KB
from .results import Measured


class TransportMeasurements:
    """The transport measurements of a Calibration (a mix-in: it runs replicas through self.replicas and steps through
    self._step; its heat capacity is self.heat_capacity())."""

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


    def steady_viscosity(self):
        """eta by periodic Poiseuille flow (transport.poiseuille_viscosity) in boxes of plan.steady_cells."""
        time = self.plan.steady_time
        result = poiseuille_viscosity(self.parameters, self.replicas(self.plan.steady_cells), developed=3.0 * time,
                                      measured=5.0 * time, report=self.report)
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
