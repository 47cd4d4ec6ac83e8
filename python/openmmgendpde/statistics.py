"""Averages of correlated time series with honest error bars."""

import math
from typing import NamedTuple

import numpy as np


class BlockAverage(NamedTuple):
    """The mean of a time series and its standard error (a NamedTuple, so ``mean, error = ...`` also works)."""
    mean: float
    standard_error: float


def block_average(values, blocks=10):
    """BlockAverage (mean, standard error) of a time series from the scatter of `blocks` contiguous block means.
    Valid when a block is much longer than the correlation time; the run lengths of the studies are chosen so
    (docs/argon.md). A trailing remainder shorter than a block is dropped."""
    values = np.asarray(values, dtype=float)
    length = len(values) // blocks
    if length < 1:
        raise ValueError(f"block_average: {len(values)} samples cannot make {blocks} blocks")
    means = values[:length * blocks].reshape(blocks, length).mean(axis=1)
    return BlockAverage(float(values[:length * blocks].mean()), float(means.std(ddof=1) / math.sqrt(blocks)))
