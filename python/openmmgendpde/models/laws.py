# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""A model's local equation of state fitted to a reference state, for any law of the table (api.LAWS): the laws are
evaluated by the physics core (physics.localEquationOfState), so no law is spelt here and a law added to the table
can be mapped onto a fluid and calibrated with no change to Python.

A reference state is the particle density n0, the particles' temperature theta_r there (the mean particle temperature
at the bath temperature T0, T0 (1 + k_B/C_V): docs/theory.md section 11) and what the law must give at (n0, theta_r):
the pressure pi, its modulus n dpi/dn and its thermal pressure dpi/dtheta. A law that extends Tait takes the Tait
parameters for pi and n dpi/dn (pi0 and gamma_T B_T), and its own parameters are fitted so that they add nothing to
either there and give the thermal pressure; any other law ignores the Tait parameters, and its own parameters are
fitted to all three (the Tait parameters are then the law's tangent at n0). The fit is a least-squares solve
(scipy.optimize.least_squares) in each parameter's natural scale (its unit made of n0^(-1/3), theta_r and the modulus),
from the current parameters or from a grid of starts, accepted only where it reproduces the state (RESIDUAL).
"""

import dataclasses
import itertools
import math

import numpy as np
import openmm
from openmm import unit

from .. import physics
from ..api import LAWS

#: The largest residual of a fit that is accepted (each of pi, n dpi/dn and theta_r dpi/dtheta relative to the
#: modulus): the modulus is a central difference with relative step MODULUS_STEP, good to ~1e-10.
RESIDUAL = 1e-8
MODULUS_STEP = 1e-5
_PRESSURE = unit.kilojoule_per_mole / unit.nanometer**3
#: A residual for parameters the law refuses or where n0 is outside its domain.
_OUTSIDE = 1e3


@dataclasses.dataclass(frozen=True)
class ReferenceState:
    """What a law must give at the density ``density`` (n0, nm^-3) and particle temperature ``temperature``
    (theta_r, K): ``pressure`` pi (kJ/mol/nm^3, without the background pressure), ``modulus`` n dpi/dn (kJ/mol/nm^3)
    and ``thermal_pressure`` dpi/dtheta (kJ/mol/nm^3/K)."""
    density: float
    temperature: float
    pressure: float
    modulus: float
    thermal_pressure: float


def pressure(law, parameters, tait, density, temperature):
    """(pi, dpi/dtheta) of ``law`` with its ``parameters`` and the Tait parameters ``tait`` = (n0, pi0, B_T, gamma_T)
    at ``density`` (nm^-3) and ``temperature`` (K), without a background pressure; ValueError where the law has no
    valid state there (a density outside its domain, an overflow)."""
    status, _, _, at_zero, thermal = physics.localEquationOfState(int(law), list(parameters), *tait, 0.0, density)
    if status != physics.PARTICLE_VALID:
        raise ValueError(f"the law {LAWS[int(law)].name} with parameters {list(parameters)} has no valid state at "
                         f"n = {density:.6g} nm^-3")
    return at_zero + temperature * thermal, thermal


def state_of(law, parameters, tait, density, temperature):
    """The ReferenceState that ``law`` with ``parameters`` gives at (``density``, ``temperature``) (pressure)."""
    pi, thermal = pressure(law, parameters, tait, density, temperature)
    high = pressure(law, parameters, tait, density * (1 + MODULUS_STEP), temperature)[0]
    low = pressure(law, parameters, tait, density * (1 - MODULUS_STEP), temperature)[0]
    return ReferenceState(density, temperature, pi, (high - low) / (2 * MODULUS_STEP), thermal)


def reference_temperature(law, parameters, tait, density):
    """The particle temperature at which ``law`` gives the Tait pressure pi0 at n0 (theta0 of a thermal Tait law, the
    theta_r a law was fitted at), or None for a law whose pressure does not depend on temperature."""
    at_zero, thermal = pressure(law, parameters, tait, density, 0.0)
    return None if thermal == 0 else (tait[1] - at_zero) / thermal


def _scale(unit_, state):
    """The natural size of a parameter in ``unit_`` (an openmm.unit Unit in OpenMM units): its unit made of the length
    n0^(-1/3), the temperature theta_r and the energy modulus x length^3 (1 for a unit of other dimensions)."""
    powers = {dimension.name: power for dimension, power in unit_.iter_base_dimensions()}
    energy = powers.get("mass", 0)
    if powers.get("time", 0) != -2 * energy:
        return 1.0
    length = state.density ** (-1 / 3)
    return ((abs(state.modulus) * length**3) ** energy * length ** (powers.get("length", 0) - 2 * energy)
            * state.temperature ** powers.get("temperature", 0))


class _Problem:
    """The residuals of one fit in the variables u: parameter k = scale_k exp(u_k) where its range is >= 0, else
    scale_k u_k."""

    def __init__(self, law, tait, state):
        self.law, self.tait, self.state = law, tait, state
        description = LAWS[int(law)]
        self.scales = np.array([_scale(unit_, state) for _, unit_ in description.parameters])
        self.positive = np.array([minimum >= 0 for minimum, _ in description.ranges])

    def matched(self):
        """The parameters where each is the state's quantity of its unit, if it has one (a pressure, a thermal
        pressure, a temperature, a density), else its natural size."""
        s = self.state
        quantities = ((_PRESSURE, s.pressure), (_PRESSURE / unit.kelvin, s.thermal_pressure),
                      (unit.kelvin, s.temperature), (unit.nanometer**-3, s.density))
        values = [next((value for kind, value in quantities if unit_ == kind or (
            unit_.is_compatible(kind) and unit_.conversion_factor_to(kind) == 1)), scale)
            for (_, unit_), scale in zip(LAWS[int(self.law)].parameters, self.scales)]
        return tuple(float(value) for value in values)

    def parameters(self, u):
        return tuple(float(v) for v in np.where(self.positive, self.scales * np.exp(np.minimum(u, 700)),
                                                self.scales * u))

    def variables(self, parameters):
        values = np.asarray(parameters, dtype=float) / self.scales
        return np.where(self.positive, np.log(np.maximum(values, 1e-300)), values)

    def residuals(self, u):
        return self.residuals_of(self.parameters(u))

    def residuals_of(self, parameters):
        s = self.state
        try:
            got = state_of(self.law, parameters, self.tait, s.density, s.temperature)
        except (ValueError, openmm.OpenMMException):
            return np.full(3, _OUTSIDE)
        return np.array([got.pressure - s.pressure, got.modulus - s.modulus,
                         s.temperature * (got.thermal_pressure - s.thermal_pressure)]) / abs(s.modulus)


def _least_squares(problem, u):
    """Minimise |residuals(u)|^2 from ``u`` (scipy's least_squares, trust-region reflective); (u, residuals) at the
    end, or ``u`` and its residuals where the start has no valid state."""
    from scipy.optimize import least_squares  # scipy: an extra of the package (pip install .[studies])
    r = problem.residuals(u)
    if np.max(np.abs(r)) >= _OUTSIDE:
        return u, r
    solution = least_squares(problem.residuals, u, xtol=1e-15, ftol=1e-15, gtol=1e-15, max_nfev=200 * (len(u) + 1))
    return solution.x, solution.fun


#: The starts of a fit without current parameters, per variable: factors e^u of the natural size (positive
#: parameters) or multiples of it (signed ones).
_GRID = {True: (0.0, -1.0, 1.0, -2.0, 2.0, -3.0, 3.0), False: (1.0, -1.0, 0.3, -0.3, 3.0, -3.0)}
_MAX_STARTS = 400


def fit(law, tait, state, start=None):
    """The parameters of ``law`` (a GenDPDEForce.EquationOfState value) with which it gives ``state`` (a
    ReferenceState) beside the Tait parameters ``tait`` = (n0, pi0, B_T, gamma_T); the fit starts from ``start``
    (current parameters) if given, else from a grid. ValueError, naming the law and the state, if no parameters
    reproduce it within RESIDUAL."""
    description = LAWS[int(law)]
    problem = _Problem(law, tait, state)
    given = ([] if start is None else [tuple(float(value) for value in start)]) + [problem.matched()]
    for parameters in given:   # (a start that reproduces the state already is kept, to the bit)
        if np.max(np.abs(problem.residuals_of(parameters))) < RESIDUAL:
            return parameters
    grid = itertools.product(*(_GRID[bool(positive)] for positive in problem.positive))
    starts = itertools.chain((problem.variables(parameters) for parameters in given),
                             (np.array(u) for u in itertools.islice(grid, _MAX_STARTS)))
    best = None
    for u in starts:
        u, r = _least_squares(problem, np.asarray(u, dtype=float))
        if best is None or np.max(np.abs(r)) < np.max(np.abs(best[1])):
            best = (u, r)
        if np.max(np.abs(r)) < RESIDUAL:
            return problem.parameters(u)
    worst = math.inf if best is None else float(np.max(np.abs(best[1])))
    raise ValueError(f"no parameters of the law {description.name} ({', '.join(description.parameter_names)}) give "
                     f"pi = {state.pressure:.6g} kJ/mol/nm^3, n dpi/dn = {state.modulus:.6g} kJ/mol/nm^3 and "
                     f"dpi/dtheta = {state.thermal_pressure:.6g} kJ/mol/nm^3/K at n0 = {state.density:.6g} nm^-3 and "
                     f"theta = {state.temperature:.6g} K (the closest missed by {worst:.2g} of the modulus)")
