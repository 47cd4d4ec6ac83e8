# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""The Rankine-Hugoniot solver (openmmgendpde.analysis.hugoniot) against the ideal gas's shock, known in closed form,
and the fit of an equation of state against functions it must reproduce exactly."""

import math

import numpy as np
import pytest

from openmmgendpde.analysis.hugoniot import EquationOfStateFit, shocked_state

GAMMA = 5 / 3       # monatomic ideal gas: P = (GAMMA - 1) n E, T = (GAMMA - 1) E/k_B
KB = 0.0083144626   # kJ/mol/K
MASS = 40.0         # amu


class IdealGas:
    density_range = (1.0, 79.9)   # below 4 n0 = 80 (n0 = 20), the limit of the strongest shock

    @staticmethod
    def pressure(n, e):
        return (GAMMA - 1) * n * e

    @staticmethod
    def temperature(n, e):
        return (GAMMA - 1) * e / KB


def ideal_gas_shock(n0, e0, piston_speed):
    """The ideal gas's Hugoniot in closed form (e.g. Zel'dovich and Raizer, ch. I): the shock speed
    U_s = (GAMMA + 1) u_p/4 + sqrt(((GAMMA + 1) u_p/4)^2 + c0^2) with c0^2 = GAMMA P0/(m n0); n1 = n0 U_s/(U_s - u_p);
    P1 = P0 + m n0 U_s u_p."""
    p0 = (GAMMA - 1) * n0 * e0
    c0 = math.sqrt(GAMMA * p0 / (MASS * n0))
    a = (GAMMA + 1) * piston_speed / 4
    us = a + math.sqrt(a * a + c0 * c0)
    n1 = n0 * us / (us - piston_speed)
    p1 = p0 + MASS * n0 * us * piston_speed
    return us, n1, p1, p1 / ((GAMMA - 1) * n1)


@pytest.mark.parametrize("piston_speed", [0.01, 0.3, 1.0, 3.0])
def test_shocked_state_is_the_ideal_gas_hugoniot(piston_speed):
    """From a weak shock (u_p << c0 = 0.29 nm/ps: U_s -> c0) to a strong one (n1/n0 -> (GAMMA + 1)/(GAMMA - 1) = 4):
    U_s, n1, P1, E1 and T1 as the closed form gives them, to 1e-9 (the bisection's tolerance is 1e-12 of n0)."""
    n0, e0 = 20.0, 1.5 * KB * 120.0
    shock = shocked_state(IdealGas, n0, e0, IdealGas.pressure(n0, e0), MASS, piston_speed)
    us, n1, p1, e1 = ideal_gas_shock(n0, e0, piston_speed)
    assert shock.shock_speed == pytest.approx(us, rel=1e-9)
    assert shock.density == pytest.approx(n1, rel=1e-9)
    assert shock.pressure == pytest.approx(p1, rel=1e-9)
    assert shock.energy == pytest.approx(e1, rel=1e-9)
    assert shock.temperature == pytest.approx(e1 * (GAMMA - 1) / KB, rel=1e-9)
    if piston_speed == 3.0:
        assert 3.9 < shock.density / n0 < 4.0


def test_fit_reproduces_an_equation_of_state_of_its_form():
    """P = a(n) + b(n) E + c E^2 with a cubic, b quadratic, and T linear in E: the fit has these terms, so it
    reproduces them at points between the samples to rounding (1e-9 relative), and its misses at the samples are 0."""
    rng = np.random.default_rng(3)
    n = np.repeat(np.linspace(4.0, 5.5, 6), 3) * (1 + 0.01 * rng.standard_normal(18))
    e = 50 + 10 * rng.random(18)

    def pressure(n, e):
        return 50 + 300 * (n - 4) + 40 * (n - 4) ** 3 + (8 + 2 * (n - 4) ** 2) * e + 0.01 * e * e

    def temperature(n, e):
        return 3 * e - 20 * (n - 4)

    fit = EquationOfStateFit.fit(n, e, pressure(n, e), temperature(n, e))
    for point in ((4.3, 52.0), (5.1, 58.0)):
        assert fit.pressure(*point) == pytest.approx(pressure(*point), rel=1e-9)
        assert fit.temperature(*point) == pytest.approx(temperature(*point), rel=1e-9)
    assert fit.pressure_residual < 1e-9 * 500 and fit.temperature_residual < 1e-9 * 150
    assert fit.density_range == (pytest.approx(n.min()), pytest.approx(n.max()))


def test_refusals():
    """A piston at rest, a shock beyond the known densities, and samples that cannot determine the fit."""
    n0, e0 = 20.0, 1.5 * KB * 120.0
    with pytest.raises(ValueError, match="piston_speed = 0"):
        shocked_state(IdealGas, n0, e0, IdealGas.pressure(n0, e0), MASS, 0.0)

    class Narrow(IdealGas):
        density_range = (20.0, 22.0)

    with pytest.raises(ValueError, match="beyond n = 22"):
        shocked_state(Narrow, n0, e0, IdealGas.pressure(n0, e0), MASS, 1.0)
    with pytest.raises(ValueError, match="several energies"):
        EquationOfStateFit.fit([4.0] * 9, np.linspace(1, 2, 9), np.ones(9), np.ones(9))
