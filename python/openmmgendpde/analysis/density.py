# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""The mean particle density n-bar of a GenDPDEForce over frames, at a given f_cut: the measurement that the f_cut
tuners (calibration.fcut, calibration.calibrate) step on."""

import numpy as np
from openmm import unit

from ..units import ARGON_UNITS


def mean_density_on_frames(force, context, frames, cutoff_scaling, units=ARGON_UNITS):
    """n-bar averaged over frames (positions in nm), with the force's f_cut set to cutoff_scaling (restored
    afterwards): in the reduced ``units`` (argon's by default), or in nm^-3 if ``units`` is None."""
    original = force.getCutoffScaling()
    force.setCutoffScaling(cutoff_scaling)
    force.updateParametersInContext(context)
    values = []
    for positions in frames:
        context.setPositions(positions * unit.nanometer)
        values.append(np.mean(force.getParticleDensities(context).value_in_unit(unit.nanometer**-3)))
    force.setCutoffScaling(original)
    force.updateParametersInContext(context)
    mean = float(np.mean(values))
    return mean if units is None else units.from_openmm(mean, "number_density")
