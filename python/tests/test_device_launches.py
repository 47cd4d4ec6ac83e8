# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""The kernel launches of an Isoenergetic step on a GPU platform, counted by the plugin's profile (GENDPDE_PROFILE,
printed to standard error when the Context is deleted): a step of a run with a GenDPDEForce that shares the sweep's
build takes 8, whether or not the order is built at it (docs/performance.md, issue 52's goal: 12 or fewer). The force
launches 3 (`buildSharedList`, which returns at once between builds, and its two passes), the integrator 5 (the step's
start; the sweep's check and, at a build, its cells, in one launch; `orderBlocks`, which returns at once between
builds; the 8 colours in one launch; the step's end). With GENDPDE_SWEEP_LAUNCH_PER_STAGE=1 the check, the four steps
of the cells and the colours take a launch each: 19. The count per step is the difference between two runs of
different lengths, so that what a Context launches once (the first evaluation, the first build's clearing) cancels."""

import gc
import re

import pytest
from conftest import GPU_PLATFORMS

from openmmgendpde import GenDPDEIntegrator
from openmmgendpde.models.argon import liquid_argon

COUNTS = re.compile(
    r"GenDPDE (GenDPDEForce|GenDPDEIntegrator), counts: (\d+) calls \(steps or evaluations\), "
    r"([0-9.]+) launches"
)


def launches(platform, steps, capfd):
    """The plugin's launches, force and integrator together, in a Context's life of `steps` Isoenergetic steps."""
    model = liquid_argon(500, 1.6839, "VB", seed=1, mode=GenDPDEIntegrator.Isoenergetic)
    context = model.context(platform, properties={"Precision": "mixed"}, seed=1)
    capfd.readouterr()
    model.integrator.step(steps)
    del context, model
    gc.collect()
    found = COUNTS.findall(capfd.readouterr().err)
    assert sorted(owner for owner, _, _ in found) == ["GenDPDEForce", "GenDPDEIntegrator"]
    return sum(round(int(calls) * float(per_call)) for _, calls, per_call in found)


@pytest.mark.gpu
@pytest.mark.parametrize("per_stage, expected", [(False, 8), (True, 19)])
@pytest.mark.parametrize("name", GPU_PLATFORMS)
def test_an_isoenergetic_step_takes_eight_launches(name, per_stage, expected, capfd, monkeypatch):
    monkeypatch.setenv("GENDPDE_PROFILE", "1")
    if per_stage:
        monkeypatch.setenv("GENDPDE_SWEEP_LAUNCH_PER_STAGE", "1")
    assert (launches(name, 30, capfd) - launches(name, 10, capfd)) == 20 * expected
