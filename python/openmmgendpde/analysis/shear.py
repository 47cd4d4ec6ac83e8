# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""The shear viscosity of a reverse non-equilibrium shear flow (models.shear.ReverseShearFlow; docs/flows.md, "Shear
flow and the flow curve"), in OpenMM units (nm, ps, amu, kJ/mol; eta in amu/(nm ps) = 1.6605e-6 Pa s; a momentum flux
in amu/(nm ps^2) = kJ/mol/nm^3, a pressure).

The exchanges move x momentum into the slab at z = 0 (width w) out of the slab at L/2; in the steady state it flows
back through both halves: J = (sum of the momenta moved)/(2 A t), A the xy area, t the time they were moved in. The
profile v_x(z) falls linearly from the slab at 0 to the one at L/2 and rises again in the second half; its slopes, of
lines through the bins at least ``margin`` from the slabs (flows.between_slabs) in each frame, give the shear rate
gamma_dot = (slope of the second half - slope of the first)/2 > 0, and eta = J/gamma_dot. The error of gamma_dot comes
from its time series' statistical inefficiency (statistics.correlated_mean), that of J from the series of the moved
momenta's; they combine as relative errors.

The same flux is the xz component of the pressure tensor in the sheared region: P_xz = +J in the first half and -J in
the second (the momentum flux of x momentum along +z, Irving-Kirkwood). ``shear_stress`` averages it from profiles'
per-bin pressure tensors. profiles.profile's tensor holds the kinetic part and the virial of the conservative forces
given to it; the pair friction and noise of a DPD or GenDPDE integrator carry momentum too, so it equals J only in the
Conservative mode (tested) and otherwise gives the part of the stress the conservative forces and the motion carry.
"""

import dataclasses
import math

import numpy as np

from .flows import between_slabs, line_slopes
from .statistics import correlated_mean


def momentum_flux(momenta, area, duration):
    """J = sum(momenta)/(2 A t) (amu/(nm ps^2) = kJ/mol/nm^3): the x momentum (amu nm/ps) moved into the slab at z = 0
    in ``duration`` (ps) flowing back through both halves of area ``area`` (nm^2)."""
    if not (area > 0 and duration > 0):
        raise ValueError(f"area = {area}, duration = {duration}: both must be > 0 (nm^2, ps)")
    return float(np.sum(momenta)) / (2 * area * duration)


def fitted_bins(centre, box_length, slabs, margin):
    """(lower, upper): the bins (masks over ``centre``, nm) fitted in each half, at least ``margin`` (nm) from the
    exchange slabs of a box of length ``box_length`` (nm) cut into ``slabs`` slabs."""
    return between_slabs(centre, box_length, box_length / slabs, margin)


def shear_rates(centre, frames, lower, upper):
    """gamma_dot (1/ps) of each frame (row) of ``frames``, binned v_x (nm/ps): (slope of the bins ``upper`` - slope of
    the bins ``lower``)/2, > 0 for the flow ReverseShearFlow drives."""
    return (line_slopes(centre, frames, upper) - line_slopes(centre, frames, lower)) / 2


def shear_stress(pressures_xz, lower, upper):
    """The xz pressure (kJ/mol/nm^3) of each frame (row of ``pressures_xz``, per bin) in the sheared region, signed so
    that it equals J in the steady state: (mean over the bins ``lower`` - mean over the bins ``upper``)/2."""
    pressures_xz = np.asarray(pressures_xz, float)
    return (pressures_xz[:, lower].mean(axis=1) - pressures_xz[:, upper].mean(axis=1)) / 2


@dataclasses.dataclass
class ShearViscosity:
    """eta = J/gamma_dot (amu/(nm ps)) +- its standard error, with the shear rate gamma_dot (1/ps) and the momentum flux
    J (kJ/mol/nm^3) it came from, each +- its standard error; the independent samples of gamma_dot's series; the
    time-averaged profile (``centre`` nm, ``profile`` v_x nm/ps, ``profile_error``) and the bins fitted (``fitted``)."""
    viscosity: float
    error: float
    shear_rate: float
    shear_rate_error: float
    momentum_flux: float
    momentum_flux_error: float
    independent_samples: float
    centre: np.ndarray
    profile: np.ndarray
    profile_error: np.ndarray
    fitted: np.ndarray


def shear_viscosity(momenta, area, duration, centre, frames, box_length, slabs, margin):
    """The viscosity of a steady reverse shear flow (the module's docstring): ``momenta`` (amu nm/ps) moved by the
    exchanges in ``duration`` (ps) through the area ``area`` (nm^2); ``frames``, v_x (nm/ps) binned at ``centre``
    (nm) along the box's z length ``box_length`` (nm), sampled over the same time, one frame per row; ``slabs`` the
    driver's slab count, ``margin`` (nm) the distance from the slabs of the bins fitted. A ValueError for fewer than 2
    exchanges or frames."""
    momenta, frames = np.asarray(momenta, float), np.asarray(frames, float)
    if len(momenta) < 2 or len(frames) < 2:
        raise ValueError(f"shear_viscosity: {len(momenta)} exchanges and {len(frames)} frames; at least 2 of each are "
                         f"needed")
    lower, upper = fitted_bins(centre, box_length, slabs, margin)
    rate = correlated_mean(shear_rates(centre, frames, lower, upper))
    flux = momentum_flux(momenta, area, duration)
    flux_error = correlated_mean(momenta).standard_error * len(momenta) / (2 * area * duration)
    viscosity = flux / rate.mean
    error = abs(viscosity) * math.hypot(flux_error / flux if flux else 0.0, rate.standard_error / rate.mean)
    profile_error = np.array([correlated_mean(column).standard_error for column in frames.T])
    return ShearViscosity(viscosity, error, rate.mean, rate.standard_error, flux, flux_error,
                          rate.independent_samples, np.asarray(centre, float), frames.mean(axis=0), profile_error,
                          lower | upper)
