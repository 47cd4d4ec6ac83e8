# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""V-C's conserved-energy error at a free surface (docs/interfaces.md, "V-C's energy error and its time step"): second
order in the step, and far above V-B's at the same step, which is why stability.suggest_time_step gives V-C a step
ten times smaller. The slab of the `slab` study (1000 argon particles at n* = 0.82 from the lattice, R* = 1.6839,
isoenergetic, CPU), as devtools/vc_energy_drift.py measures it for the docs."""

import pytest
from openmm import unit

from openmmgendpde.studies.slab import argon_model, slab_positions
from openmmgendpde.units import ARGON_UNITS


def energy_error(estimator, step_size, duration=10.0, seed=5):
    """The change of K + U + sum eps over ``duration`` time units, per N k_B T0."""
    positions, box = slab_positions()[:2]
    model, _context = argon_model(positions, box, estimator, platform="CPU", seed=seed)
    model.integrator.setStepSize(ARGON_UNITS.to_openmm(step_size, "time"))
    kt = (unit.MOLAR_GAS_CONSTANT_R * model.temperature).value_in_unit(unit.kilojoule_per_mole)
    start = model.integrator.getConservedEnergy().value_in_unit(unit.kilojoule_per_mole)
    model.integrator.step(int(round(duration / step_size)))
    end = model.integrator.getConservedEnergy().value_in_unit(unit.kilojoule_per_mole)
    return (end - start) / (len(positions) * kt)


@pytest.mark.validation
def test_vc_energy_error_at_a_surface_is_second_order_and_far_above_vb():
    """Measured (seeds 5 and 6, 10 time units): V-C's error per N k_B T0 at dt* = 0.01, 0.005, 0.0025 is -8.4e-5,
    -3.1e-5, -6.7e-6 and -1.2e-4, -3.1e-5, -6.7e-6; V-B's at 0.01 -4.0e-7. At the largest step the surfaces' first
    relaxation blurs the order (ratio 2.7 and 3.8); from 0.005 to 0.0025 the ratio is 4.7 and 4.6 (second order: 4).
    Required (seed 5): that ratio between 3 and 8 (first order gives 2, third 8); V-C's error at 0.005 between 1e-5 and
    1e-4 in magnitude; V-B's at 0.005 at least 20 times smaller than V-C's (documented: ~100 times at 40 units)."""
    vc_coarse, vc_fine = energy_error("VC", 0.005), energy_error("VC", 0.0025)
    vb_coarse = energy_error("VB", 0.005)
    assert 1e-5 < abs(vc_coarse) < 1e-4, vc_coarse
    assert 3.0 < vc_coarse / vc_fine < 8.0, (vc_coarse, vc_fine)
    assert abs(vb_coarse) * 20 < abs(vc_coarse), (vb_coarse, vc_coarse)
