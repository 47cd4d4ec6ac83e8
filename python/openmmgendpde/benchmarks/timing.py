# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""The analogue of Table IV of Colella et al. (2025) (`timing`): wall time per step of full GenDPDE (isoenergetic,
GenDPDEForce + GenDPDEIntegrator) with VA and with VB for each cutoff, and the VB/VA ratio, measured side by side:
both systems are prepared (thermostat at T0, internal energies drawn at T0), then their production steps run in
alternating rounds (openmmgendpde.benchmarks.measurement) and the ratio is the median of per-round ratios. The paper's
ratios (total simulation time, its own Fortran code) are 1.07, 1.22 and 1.03.
"""

import dataclasses

from ..models.argon import PUBLISHED_ESTIMATORS, PUBLISHED_TABLE4_RATIO, liquid_argon
from ..models.argon_runs import melt_then_draw
from .measurement import alternating_rounds, median, median_ratio


@dataclasses.dataclass
class TimingRow:
    cutoff: float
    milliseconds_per_step: dict   # estimator -> ms
    vb_over_va: float
    published: float


def prepared_simulation(cutoff, estimator, protocol, platform, preparation_time):
    """A Simulation of liquid argon ready for isoenergetic steps: melted with the thermostat for
    ``preparation_time`` and its internal energies drawn at T0 (openmmgendpde.models.argon_runs.melt_then_draw)."""
    argon = liquid_argon(protocol.num_particles, cutoff, estimator, time_step=protocol.time_step, seed=protocol.seed)
    simulation = argon.simulation(platform, velocity_seed=protocol.seed)
    melt_then_draw(argon, protocol.steps(preparation_time), protocol.seed)
    return simulation


def timing_rows(cutoffs, protocol, platform="Reference", rounds=15, steps=50, preparation_time=10.0, progress=None):
    """A TimingRow per cutoff: the published estimators prepared side by side (prepared_simulation), then ``rounds``
    alternating rounds of ``steps`` isoenergetic steps each; ``progress`` advances by the rounds."""
    rows = []
    for cutoff in cutoffs:
        if progress is not None:
            progress.label = f"timing R*={cutoff}"
        prepared = {estimator: prepared_simulation(cutoff, estimator, protocol, platform, preparation_time)
                    for estimator in PUBLISHED_ESTIMATORS}
        candidates = {estimator: (lambda integrator=prepared[estimator].integrator: integrator.step(steps))
                      for estimator in PUBLISHED_ESTIMATORS}
        seconds = alternating_rounds(candidates, rounds, progress)
        rows.append(TimingRow(cutoff, {e: 1e3 * median(s) / steps for e, s in seconds.items()},
                              median_ratio(seconds, "VB", "VA"), PUBLISHED_TABLE4_RATIO[cutoff]))
    return rows
