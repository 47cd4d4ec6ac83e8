# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""Radial distribution functions of liquid argon with VA and VB, plotted like Fig. 1 of Colella et al. (2025)
(`rdf`): three panels (one per cutoff), VA dashed, VB solid, the cutoff marked. VA shows spurious shoulders inside
R_cut (the clumped pairs), worst at R_cut* = 1.3365; VB gives an ordinary liquid g(r). g(r) comes from mdtraj
over the production frames, either saved by `table3 --output DIR` (--frames-from DIR) or from runs of its own
with the same protocol.
"""

import csv

import numpy as np

from ..analysis.rdf import R_MAX, radial_distribution
from ..internal.files import atomic_write
from ..internal.plotting import panels, save
from ..models.argon import PUBLISHED_ESTIMATORS
from ..models.argon_runs import run_argon


def plot(curves, cutoffs, path_stem):
    figure, axes = panels(len(cutoffs), sharey=True)
    for axis, cutoff in zip(axes, cutoffs):
        for estimator, style, color in zip(PUBLISHED_ESTIMATORS, ("--", "-"), ("tab:red", "tab:blue")):
            r, g = curves[(cutoff, estimator)]
            axis.plot(r, g, style, color=color, label=f"V-{estimator[1]}")
        axis.axvline(cutoff, color="0.5", linestyle=":", linewidth=1)
        axis.set_title(f"$R_{{cut}}^* = {cutoff}$")
        axis.set_xlabel("$r^*$")
        axis.set_xlim(0, R_MAX)
    axes[0].set_ylabel("$g(r)$")
    save(figure, path_stem, legend_axis=axes[0])


def curves(cutoffs, protocol, platform="Reference", frames=50, saved=None, progress=None):
    """{(cutoff, estimator): (r*, g(r))} of the published estimators at ``cutoffs``: over the frames of ``saved``
    (table3.read_frames of a table3 run), or of runs of the protocol of their own (models.argon_runs.run_argon on
    ``platform``, keeping ``frames``); ``progress`` advances by the steps of each case."""
    found = {}
    for cutoff in cutoffs:
        for estimator in PUBLISHED_ESTIMATORS:
            if progress is not None:
                progress.label = f"rdf R*={cutoff} {estimator}"
            if saved is not None:
                if progress is not None:
                    progress.advance(protocol.total_steps)
                positions, box_edge = saved[(cutoff, estimator)]
            else:
                samples = run_argon(cutoff, estimator, protocol, platform, frames=frames, progress=progress).samples
                positions, box_edge = samples.frames, samples.box_edge
            found[(cutoff, estimator)] = radial_distribution(positions, box_edge)
    return found


def write_csv(curves, cutoffs, path):
    """The curves as a CSV table: r* and g(r) of each case."""
    with atomic_write(path, newline="") as stream:
        writer = csv.writer(stream)
        keys = [(c, e) for c in cutoffs for e in PUBLISHED_ESTIMATORS]
        writer.writerow(["r*"] + [f"g R*={c} {e}" for c, e in keys])
        r = curves[keys[0]][0]
        for index in range(len(r)):
            writer.writerow([f"{r[index]:.4f}"] + [f"{curves[k][1][index]:.5f}" for k in keys])


def signature(curves):
    """The pairing instability in one line per case: the first peak of g(r), and g(r) near contact."""
    lines = []
    for (cutoff, estimator), (r, g) in curves.items():
        peak = int(np.argmax(g))
        lines.append(f"R_cut* = {cutoff} {estimator}: first peak g = {g[peak]:.2f} at r* = {r[peak]:.2f}; "
                     f"mean g(r* < 0.3) = {g[r < 0.3].mean():.2f}")
    return lines
