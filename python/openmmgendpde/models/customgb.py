# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""The GenDPDE conservative potential written with OpenMM's stock ``CustomGBForce``.

An independent implementation (Lepton expressions, OpenMM's own neighbor search and chain rule) used by the tests
as an oracle and by the benchmark as the baseline. It needs every particle to have a neighbor (k > 0), because the
closed form of the VB volume is written literally.
"""

import math

import openmm
from openmm import unit

from ..api import GenDPDEForce
from ..internal.wrapping import NUMBER_DENSITY, PRESSURE


def custom_gb_equivalent(force, num_particles):
    """A ``CustomGBForce`` with the same energy and forces as ``force`` (a ``GenDPDEForce``) for
    ``num_particles`` particles."""
    cutoff = force.getCutoffDistance().value_in_unit(unit.nanometer)
    n0 = force.getReferenceDensity().value_in_unit(NUMBER_DENSITY)
    pi0 = force.getReferencePressure().value_in_unit(PRESSURE)
    bulk = force.getBulkModulus().value_in_unit(PRESSURE)
    gamma = force.getTaitExponent()
    rt = cutoff / force.getCutoffScaling()
    gb = openmm.CustomGBForce()
    gb.setCutoffDistance(cutoff)
    gb.setNonbondedMethod(openmm.CustomGBForce.CutoffPeriodic if force.usesPeriodicBoundaryConditions()
                          else openmm.CustomGBForce.CutoffNonPeriodic)
    gb.addComputedValue("n0", f"{15 / (2 * math.pi * cutoff**3)!r}*(1-r/{cutoff!r})^2",
                        openmm.CustomGBForce.ParticlePairNoExclusions)
    if force.getDensityEstimator() == GenDPDEForce.VA:
        gb.addComputedValue("V", "1/n0", openmm.CustomGBForce.SingleParticle)
    else:
        gb.addComputedValue(
            "V", f"{4 * math.pi / 3 * rt**3!r} - {4 * math.pi * rt**3!r}*sqrt(k)*((1-k)*atan(1/sqrt(k))"
                 f" + sqrt(k)*(1-log((k+1)/k))); k={2 * math.pi / 15 * rt**3!r}*n0",
            openmm.CustomGBForce.SingleParticle)
    gb.addEnergyTerm(f"{bulk - pi0!r}*V + {bulk / ((gamma - 1) * n0)!r}*(1/(V*{n0!r}))^{gamma - 1!r}",
                     openmm.CustomGBForce.SingleParticle)
    for _ in range(num_particles):
        gb.addParticle([])
    return gb
