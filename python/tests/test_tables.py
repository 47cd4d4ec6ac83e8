# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""The core's tables (core/include/gendpde: GenDPDEDensityEstimators.h, GenDPDEEquationsOfState.h) against the API
enum they number: each entry's name is the GenDPDEForce enum value of its place, and the enum has no value the
table lacks. This is what lets a new estimator or law touch only the core, its table and the enum."""

import re

from openmmgendpde import GenDPDEForce
from openmmgendpde import gendpde as swig
from openmmgendpde.api import ESTIMATOR_NAMES, ESTIMATORS


def _enum_values(pattern):
    """GenDPDEForce's enum values whose names match ``pattern``: {name: value}."""
    return {name: getattr(GenDPDEForce, name) for name in dir(GenDPDEForce) if re.fullmatch(pattern, name)}


def test_every_estimator_of_the_table_is_the_enum_value_of_its_place():
    names = [swig.densityEstimatorName(k) for k in range(swig.numDensityEstimators())]
    assert len(names) >= 3
    assert {name: getattr(GenDPDEForce, name) for name in names} == {name: k for k, name in enumerate(names)}
    # The enum's estimators (its two-letter V names) are exactly the table's.
    assert _enum_values(r"V[A-Z]") == {name: k for k, name in enumerate(names)}
    assert [e.name for e in ESTIMATORS] == names and list(ESTIMATOR_NAMES) == list(range(len(names)))


def test_every_law_of_the_table_is_the_enum_value_of_its_place():
    names = [swig.equationOfStateName(k) for k in range(swig.numEquationsOfState())]
    assert names[:3] == ["Tait", "TaitThermalExpansion", "VanDerWaals"]
    assert {name: getattr(GenDPDEForce, name) for name in names} == {name: k for k, name in enumerate(names)}


def test_the_estimator_table_describes_each_estimator():
    va, vb, vc = (ESTIMATORS[getattr(GenDPDEForce, name)] for name in ("VA", "VB", "VC"))
    assert (va.reads_cutoff_scaling, vb.reads_cutoff_scaling, vc.reads_cutoff_scaling) == (False, True, True)
    assert (va.needs_moments, vb.needs_moments, vc.needs_moments) == (False, False, True)
    # V-C's step factor, measured (docs/interfaces.md "V-C's energy error"): a drift ~100 times V-B's at one step,
    # second order in dt, so a step 10 times smaller.
    assert (va.stable_step_factor, vb.stable_step_factor, vc.stable_step_factor) == (1.0, 1.0, 0.1)
