# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""Accuracy of the volume estimators (docs/theory.md sections 2-3) against 40-digit quadrature.

Target: relative error <= 1e-12 for V and dV/dn0 at every k in [0, 1e12], including the numerical traps: k = 0,
tiny k (dV/dn0 ~ k^-1/2), the switches between the branches (closed forms below k = 1/16, piecewise polynomials
from 1/16 to 16, quadrature from k = 16 on, where the closed form would cancel catastrophically), and large k.
"""

import math

import mpmath as mp
import numpy as np
import pytest

from openmmgendpde.physics import particleVolumeVA, particleVolumeVB, volumeIntegralsVB

mp.mp.dps = 40


def reference_integrals(k):
    """I(k) = int_0^1 y^2 (1-y)^2/(y^2+k) dy and J(k) = int_0^1 y^2 (1-y)^2/(y^2+k)^2 dy at 40 digits. The
    integrands peak near y = sqrt(k); breakpoints at sqrt(k) * 16^m let tanh-sinh quadrature resolve the peak
    for any k down to 1e-300."""
    k = mp.mpf(k)
    points = [mp.mpf(0)]
    point = mp.sqrt(k)
    while point < 1:
        points.append(point)
        point *= 16
    points.append(mp.mpf(1))
    integral_i = mp.quad(lambda y: y**2 * (1 - y)**2 / (y**2 + k), points)
    integral_j = mp.quad(lambda y: y**2 * (1 - y)**2 / (y**2 + k)**2, points)
    return integral_i, integral_j


K_GRID = ([1e-300, 1e-200, 1e-100, 1e-50, 1e-30, 1e-20] + list(np.logspace(-16, 12, 113))
          + [math.nextafter(0.1, 0), 0.1, math.nextafter(0.1, 1)]
          + [k for switch in (1 / 16, 16.0)   # the branch switches, and the doubles on either side
             for k in (math.nextafter(switch, 0), switch, math.nextafter(switch, math.inf))])


def relative_error(found, expected):
    return float(abs(mp.mpf(found) - expected) / abs(expected))


def test_integrals_at_zero_are_the_exact_limits():
    integral_i, integral_j = volumeIntegralsVB(0.0)
    assert integral_i == 1.0 / 3.0
    assert integral_j == math.inf


@pytest.mark.validation
@pytest.mark.parametrize("k", K_GRID)
def test_integrals_match_quadrature(k):
    integral_i, integral_j = volumeIntegralsVB(k)
    expected_i, expected_j = reference_integrals(k)
    assert relative_error(integral_i, expected_i) <= 1e-12
    assert relative_error(integral_j, expected_j) <= 1e-12


@pytest.mark.parametrize("reduced_range", [0.37, 1.0, 2.5])
@pytest.mark.parametrize("k", [0.0, 1e-9, 0.03, 0.35, 1.8, 40.0, 1e7])
def test_particle_volume_scales_the_integrals(reduced_range, k):
    """V = 4 pi Rt^3 I(k) and dV/dn0 = -(8 pi^2/15) Rt^6 J(k), with k = (2 pi/15) Rt^3 n0 (checked at 40 digits
    for the k that the double inputs really represent)."""
    n0 = k / (2 * math.pi / 15 * reduced_range**3)
    volume, derivative = particleVolumeVB(n0, reduced_range)
    rt = mp.mpf(reduced_range)
    exact_k = 2 * mp.pi / 15 * rt**3 * mp.mpf(n0)
    if k == 0.0:
        assert volume == pytest.approx(4 * math.pi / 3 * reduced_range**3, rel=1e-15)
        assert derivative == -math.inf
        return
    integral_i, integral_j = reference_integrals(exact_k)
    assert relative_error(volume, 4 * mp.pi * rt**3 * integral_i) <= 1e-12
    assert relative_error(derivative, -8 * mp.pi**2 / 15 * rt**6 * integral_j) <= 1e-12


def test_vb_tends_to_va_at_high_density():
    """V-B -> 1/n0 as k -> infinity (docs/theory.md section 3): V n0 - 1 = O(1/k)."""
    for n0 in [1e3, 1e6, 1e9]:
        volume_b, derivative_b = particleVolumeVB(n0, 1.0)
        volume_a, derivative_a = particleVolumeVA(n0)
        k = 2 * math.pi / 15 * n0
        assert abs(volume_b / volume_a - 1) < 10 / k
        assert abs(derivative_b / derivative_a - 1) < 10 / k


def test_va_is_the_inverse_primitive_density():
    volume, derivative = particleVolumeVA(4.0)
    assert volume == 0.25 and derivative == -0.0625
