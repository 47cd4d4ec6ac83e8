# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""GenDPDEForce equals the same potential written with OpenMM's stock CustomGBForce (an independent implementation:
Lepton expressions, OpenMM's neighbor search and automatic chain rule), on the Reference platform (double)."""

import numpy as np
import openmm
import pytest
from helpers import DENSITY, energy_and_forces, lattice_liquid, make_context, rms

from openmmgendpde import GenDPDEForce
from openmmgendpde.models.customgb import custom_gb_equivalent


@pytest.mark.parametrize("estimator", [GenDPDEForce.VA, GenDPDEForce.VB])
@pytest.mark.parametrize("periodic", [True, False])
@pytest.mark.parametrize("density_factor", [1.0, 5.0])
def test_energy_and_forces_match_custom_gb(estimator, periodic, density_factor):
    cells = 7 if density_factor > 1 else 5
    system, force, positions = lattice_liquid(cells, density=density_factor * DENSITY, jitter=0.2,
                                              estimator=estimator, periodic=periodic)
    reference = openmm.Platform.getPlatformByName("Reference")
    energy, forces = energy_and_forces(make_context(system, positions, reference))
    custom_gb = custom_gb_equivalent(force, system.getNumParticles())
    system.removeForce(0)   # deletes the GenDPDEForce: `force` must not be used after this
    system.addForce(custom_gb)
    energy_gb, forces_gb = energy_and_forces(make_context(system, positions, reference))
    # Both are double-precision sums of the same terms (the closed form of VB is accurate to ~1e-14 at these k).
    assert energy == pytest.approx(energy_gb, rel=1e-11)
    assert np.max(np.abs(forces - forces_gb)) <= 1e-9 * rms(forces_gb)
