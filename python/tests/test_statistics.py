# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""Block averages (openmmgendpde.analysis.statistics): the value, and the plateau check that warns without changing
it."""

import math
import warnings

import numpy as np
import pytest

from openmmgendpde.analysis.statistics import (
    BlockAverage,
    BlockAverageWarning,
    block_average,
    block_standard_error,
    correlated_mean,
    statistical_inefficiency,
)


def correlated_series(length, correlation_time, seed):
    """AR(1): x_t = phi x_(t-1) + noise with phi = exp(-1/correlation_time); g = (1 + phi)/(1 - phi)."""
    rng = np.random.default_rng(seed)
    phi = math.exp(-1 / correlation_time)
    noise = rng.normal(size=length)
    values = np.empty(length)
    values[0] = noise[0] / math.sqrt(1 - phi**2)
    for t in range(1, length):
        values[t] = phi * values[t - 1] + noise[t]
    return values


def test_block_average_is_the_mean_and_the_scatter_of_block_means():
    values = np.random.default_rng(1).normal(size=405)      # 5 samples beyond 10 blocks of 40 are dropped
    with warnings.catch_warnings():
        warnings.simplefilter("error", BlockAverageWarning)  # independent samples: no warning
        result = block_average(values)
    means = values[:400].reshape(10, 40).mean(axis=1)
    assert isinstance(result, BlockAverage)
    assert result.mean == values[:400].mean()
    assert result.standard_error == means.std(ddof=1) / math.sqrt(10) == block_standard_error(values, 10)
    mean, error = result
    assert (mean, error) == (result.mean, result.standard_error)
    with pytest.raises(ValueError, match="cannot make 10 blocks"):
        block_average(values[:9])


def test_statistical_inefficiency_of_known_series():
    """g = 1 for independent samples, (1 + phi)/(1 - phi) = 9.0 for AR(1) with correlation time 4.5 samples
    (phi = 0.80): the estimates from 4000 samples are within 0.1 and 20% (their scatter is ~0.05 and ~8%)."""
    assert statistical_inefficiency(np.random.default_rng(2).normal(size=4000)) == pytest.approx(1.0, abs=0.1)
    phi = math.exp(-1 / 4.5)
    assert statistical_inefficiency(correlated_series(4000, 4.5, 3)) == pytest.approx((1 + phi) / (1 - phi), rel=0.2)
    assert statistical_inefficiency(np.ones(50)) == 1.0


def test_blocks_shorter_than_the_correlation_warn_without_changing_the_result():
    """400 samples with a correlation time of 20 samples (g = 40): blocks of 40 samples are 1 g long, and the
    10-block standard error is ~30% too small. The warning names the series; the value is the one computed with
    the warning silenced."""
    values = correlated_series(400, 20, 4)
    with pytest.warns(BlockAverageWarning, match="density: the block-average error has not reached its plateau"):
        warned = block_average(values, name="density")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", BlockAverageWarning)
        silent = block_average(values, name="density")
    assert warned == silent
    assert warned.standard_error == block_standard_error(values, 10)


def test_correlated_mean_error_is_the_true_error_of_a_correlated_mean():
    """400 AR(1) series of 400 samples, correlation time 4.5 samples (g = 9.04, ~44 independent samples each): the
    true standard error of their mean is sqrt(var_x/N (1 + 2 sum_k (1 - k/N) phi^k)) = 0.2495. The root mean square
    of correlated_mean's standard errors must be within 10% of it (measured 1.4% off; the scatter of that RMS over
    400 series is ~0.5%, the estimator's known small-sample bias a few %), and |mean| < 1.96 standard errors in 90%
    to 98% of the series (94.4% expected with ~44 degrees of freedom; binomial scatter 1.1%). The plain s/sqrt(N),
    which ignores the correlation, gives a third of the true error and fails both."""
    n, tau = 400, 4.5
    phi = math.exp(-1 / tau)
    lags = np.arange(1, n)
    true_error = math.sqrt(1 / (1 - phi**2) / n * (1 + 2 * np.sum((1 - lags / n) * phi**lags)))
    errors, covered = [], 0
    for seed in range(400):
        result = correlated_mean(correlated_series(n, tau, 1000 + seed))
        assert result.inefficiency * result.independent_samples == pytest.approx(n)
        errors.append(result.standard_error)
        covered += abs(result.mean) < 1.96 * result.standard_error
    assert math.sqrt(np.mean(np.square(errors))) == pytest.approx(true_error, rel=0.10)
    assert 0.90 <= covered / 400 <= 0.98
    with pytest.raises(ValueError, match="at least 2 are needed"):
        correlated_mean([1.0])


def test_self_diffusion_of_a_random_walk():
    """Brownian particles with D = 0.05 nm^2/ps (steps of variance 2 D dt per axis, dt = 0.1 ps, 300 frames, 2000
    particles, plus a common drift that the centre-of-mass removal must take out): D recovered within 3 of its
    standard errors, and the error within a factor 2 of the expected scatter (the MSD of 2000 particles at the
    fitted lags, ~sqrt(2/(3 x 200)) relative per group: about 1.6% of D over 10 groups)."""
    from openmmgendpde.analysis.thermodynamics import self_diffusion
    rng = np.random.default_rng(11)
    d, dt, frames, particles = 0.05, 0.1, 300, 2000
    steps = rng.normal(scale=math.sqrt(2 * d * dt), size=(frames, particles, 3))
    positions = np.cumsum(steps, axis=0) + np.arange(frames)[:, None, None] * np.array([0.3, 0.0, -0.2])
    value, error = self_diffusion(np.arange(frames) * dt, positions)
    assert abs(value - d) < 3 * error
    assert 0.25 * 0.016 * d < error < 4 * 0.016 * d
    with pytest.raises(ValueError, match="at least 8"):
        self_diffusion(np.arange(5), positions[:5])
