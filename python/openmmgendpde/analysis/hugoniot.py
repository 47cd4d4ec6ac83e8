# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""The Rankine-Hugoniot jump of a fluid whose equation of state is known from equilibrium samples.

A planar shock that brings fluid at rest in the state (n0, E0, P0) to the state (n1, E1, P1) moving at the piston
speed u_p conserves mass, momentum and energy across its front. Per particle of mass m, with v = 1/n the volume per
particle and U_s the shock speed in the frame of the fluid ahead of it:

    mass      n0 U_s = n1 (U_s - u_p)              so  U_s = u_p v0/(v0 - v1)
    momentum  P1 - P0 = m n0 U_s u_p               so  (P1 - P0)(v0 - v1) = m u_p^2
    energy    E1 - E0 = (P1 + P0)(v0 - v1)/2       (E: internal energy per particle, the flow's kinetic energy apart)

The fluid's equation of state closes them. Here it is a fit to samples (n, E, P, T) of equilibrium runs of the model
itself (`EquationOfStateFit`), not the particles' law: the fluid's pressure adds the kinetic n k_B T to what the
particles' pressures give through the estimator, and its temperature is the kinetic one. Units are the caller's,
consistent ones (OpenMM's: nm^-3, kJ/mol per particle, kJ/mol/nm^3, K, amu, nm/ps: amu nm^2/ps^2 = kJ/mol).
"""

import dataclasses

import numpy as np


def _basis(x, y):
    """The fit's terms in x = n/n_ref - 1 and y = (E - E_ref)/E_scale: cubic in x, quadratic in y, with the cross
    terms x y and x^2 y (an equation of state linear in E with coefficients smooth in n is reproduced exactly)."""
    x, y = np.asarray(x, dtype=float), np.asarray(y, dtype=float)
    return np.stack([np.ones_like(x), x, x * x, x**3, y, x * y, x * x * y, y * y], axis=-1)


@dataclasses.dataclass(frozen=True)
class EquationOfStateFit:
    """Least-squares fits of P(n, E) and T(n, E) to equilibrium samples (see `fit`)."""
    density_reference: float
    energy_reference: float
    energy_scale: float
    pressure_coefficients: np.ndarray
    temperature_coefficients: np.ndarray
    density_range: tuple            # the samples' (min, max) density: the fit is not used outside it
    pressure_residual: float        # root mean square of the fit's misses at the samples
    temperature_residual: float

    @classmethod
    def fit(cls, density, energy, pressure, temperature):
        """Fit samples given as equal-length sequences; at least 8 of them, spread over several densities and
        energies (ValueError otherwise)."""
        n, e, p, t = (np.asarray(values, dtype=float) for values in (density, energy, pressure, temperature))
        if not (len(n) == len(e) == len(p) == len(t)) or len(n) < 8:
            raise ValueError(f"need at least 8 samples of equal length; got {len(n)}, {len(e)}, {len(p)}, {len(t)}")
        n_ref, e_ref = float(np.mean(n)), float(np.mean(e))
        e_scale = float(np.ptp(e)) or 1.0
        matrix = _basis(n / n_ref - 1, (e - e_ref) / e_scale)
        if np.linalg.matrix_rank(matrix) < matrix.shape[1]:
            raise ValueError("the samples do not determine the fit: give several energies at each of several densities")
        p_coefficients = np.linalg.lstsq(matrix, p, rcond=None)[0]
        t_coefficients = np.linalg.lstsq(matrix, t, rcond=None)[0]
        return cls(n_ref, e_ref, e_scale, p_coefficients, t_coefficients, (float(n.min()), float(n.max())),
                   float(np.sqrt(np.mean((matrix @ p_coefficients - p) ** 2))),
                   float(np.sqrt(np.mean((matrix @ t_coefficients - t) ** 2))))

    def _terms(self, density, energy):
        return _basis(density / self.density_reference - 1, (energy - self.energy_reference) / self.energy_scale)

    def pressure(self, density, energy):
        return self._terms(density, energy) @ self.pressure_coefficients

    def temperature(self, density, energy):
        return self._terms(density, energy) @ self.temperature_coefficients


@dataclasses.dataclass(frozen=True)
class ShockState:
    """The state behind a shock driven at ``piston_speed`` (the Hugoniot point)."""
    piston_speed: float
    density: float
    energy: float
    pressure: float
    temperature: float
    shock_speed: float      # U_s, in the frame of the fluid ahead of the shock


def shocked_state(equation_of_state, density, energy, pressure, mass, piston_speed, tolerance=1e-12):
    """The ShockState that a piston moving at ``piston_speed`` (> 0) drives into the fluid at rest in the state
    (``density``, ``energy``, ``pressure``) of particles of ``mass``. ``equation_of_state`` has pressure(n, E) and
    temperature(n, E) and, optionally, density_range = (min, max) within which the shocked density must lie
    (ValueError if the Hugoniot leaves it). Solved by bisection on n1: for each n1 the energy equation fixes E1,
    and the momentum equation is the residual."""
    if not piston_speed > 0:
        raise ValueError(f"piston_speed = {piston_speed} is not allowed; it must be > 0")
    n0, e0, p0 = density, energy, pressure
    v0 = 1 / n0

    def energy_at(n1):
        """E1 on the energy equation at n1: the root of g(E) = E - E0 - (P(n1, E) + P0)(v0 - v1)/2 by secant steps
        (one step when P is linear in E)."""
        dv = v0 - 1 / n1

        def g(e):
            return e - e0 - (float(equation_of_state.pressure(n1, e)) + p0) * dv / 2

        a, b = e0, e0 + (float(equation_of_state.pressure(n1, e0)) + p0) * dv / 2
        ga, gb = g(a), g(b)
        for _ in range(100):
            if gb == 0 or abs(b - a) <= tolerance * max(1.0, abs(b)):
                return b
            a, b = b, b - gb * (b - a) / (gb - ga)
            ga, gb = gb, g(b)
        raise ValueError(f"the energy equation has no solution found at n1 = {n1}")

    def residual(n1):
        return (float(equation_of_state.pressure(n1, energy_at(n1))) - p0) * (v0 - 1 / n1) - mass * piston_speed**2

    low = n0 * (1 + 1e-12)
    high = getattr(equation_of_state, "density_range", (None, 10 * n0))[1]
    if residual(high) < 0:
        raise ValueError(f"piston_speed = {piston_speed} compresses the fluid beyond n = {high}, the densities the "
                         f"equation of state is known at")
    while high - low > tolerance * n0:
        middle = (low + high) / 2
        low, high = (middle, high) if residual(middle) < 0 else (low, middle)
    n1 = (low + high) / 2
    e1 = energy_at(n1)
    return ShockState(piston_speed=piston_speed, density=n1, energy=e1,
                      pressure=float(equation_of_state.pressure(n1, e1)),
                      temperature=float(equation_of_state.temperature(n1, e1)),
                      shock_speed=piston_speed * v0 / (v0 - 1 / n1))
