"""Radial distribution functions of liquid argon with VA and VB, plotted like Fig. 1 of Colella et al. (2025)
(`rdf`): three panels (one per cutoff), VA dashed, VB solid, the cutoff marked. VA shows spurious shoulders inside
R_cut (the clumped pairs), worst at R_cut* = 1.3365; VB gives an ordinary liquid g(r). g(r) comes from mdtraj
over the production frames, either saved by `table3 --output DIR` (--frames-from DIR) or from runs of its own
with the same protocol.
"""

import csv
import pathlib

import numpy as np

from ..analysis.rdf import R_MAX, radial_distribution
from ..cli.options import add_cutoffs, add_frames, add_output, chosen_cutoffs
from ..cli.progress import Progress
from ..cli.protocol import add_protocol_arguments, protocol_from_arguments
from ..internal.files import atomic_write
from ..internal.plotting import panels, save
from ..models.argon_runs import run_argon


def load_or_run(arguments, cutoff, estimator, protocol, progress, saved=None):
    """The frames (nm) and box edge (nm) of one case: from ``saved`` (table3.read_frames of --frames-from), or from a
    run of its own."""
    if saved is not None:
        progress.advance(protocol.total_steps)
        return saved[(cutoff, estimator)]
    samples = run_argon(cutoff, estimator, protocol, arguments.platform, frames=arguments.frames,
                        progress=progress).samples
    return samples.frames, samples.box_edge


def plot(curves, cutoffs, path_stem):
    figure, axes = panels(len(cutoffs), sharey=True)
    for axis, cutoff in zip(axes, cutoffs):
        for estimator, style in (("VA", "--"), ("VB", "-")):
            r, g = curves[(cutoff, estimator)]
            axis.plot(r, g, style, color="tab:red" if estimator == "VA" else "tab:blue", label=f"V-{estimator[1]}")
        axis.axvline(cutoff, color="0.5", linestyle=":", linewidth=1)
        axis.set_title(f"$R_{{cut}}^* = {cutoff}$")
        axis.set_xlabel("$r^*$")
        axis.set_xlim(0, R_MAX)
    axes[0].set_ylabel("$g(r)$")
    save(figure, path_stem, legend_axis=axes[0])


def run(arguments):
    cutoffs = chosen_cutoffs(arguments)
    saved = None
    if arguments.frames_from:   # read and checked before anything runs: a complete set from table3, every case
        from .table3 import read_frames
        try:
            saved = read_frames(arguments.frames_from, [(c, e) for c in cutoffs for e in ("VA", "VB")])
        except ValueError as error:
            raise SystemExit(f"error: rdf: --frames-from {error}") from None
    protocol = protocol_from_arguments(arguments, cutoffs=() if saved else cutoffs, estimators=("VA", "VB"))
    output = pathlib.Path(arguments.output)
    output.mkdir(parents=True, exist_ok=True)
    progress = Progress(2 * len(cutoffs) * protocol.total_steps, "rdf", always=arguments.progress)
    curves = {}
    for cutoff in cutoffs:
        for estimator in ("VA", "VB"):
            progress.label = f"rdf R*={cutoff} {estimator}"
            frames, box_edge = load_or_run(arguments, cutoff, estimator, protocol, progress, saved)
            curves[(cutoff, estimator)] = radial_distribution(frames, box_edge)
    progress.finish()
    stem = output / "fig1-rdf"
    plot(curves, cutoffs, stem)
    with atomic_write(output / "fig1-rdf.csv", newline="") as stream:
        writer = csv.writer(stream)
        keys = [(c, e) for c in cutoffs for e in ("VA", "VB")]
        writer.writerow(["r*"] + [f"g R*={c} {e}" for c, e in keys])
        r = curves[keys[0]][0]
        for index in range(len(r)):
            writer.writerow([f"{r[index]:.4f}"] + [f"{curves[k][1][index]:.5f}" for k in keys])
    # The signature of the pairing instability: the first peak of g(r), and g(r) near contact.
    for (cutoff, estimator), (r, g) in curves.items():
        peak = int(np.argmax(g))
        close = g[r < 0.3].mean()
        print(f"R_cut* = {cutoff} {estimator}: first peak g = {g[peak]:.2f} at r* = {r[peak]:.2f}; "
              f"mean g(r* < 0.3) = {close:.2f}")
    print(f"Written: {stem}.png, {stem}.pdf, {output / 'fig1-rdf.csv'}")
    return curves


def add_arguments(parser):
    add_protocol_arguments(parser)
    add_cutoffs(parser)
    parser.add_argument("--frames-from", help="read the frames saved by `table3 --output DIR` instead of running")
    add_frames(parser, "per run when running", default=50)
    add_output(parser, "the plots")
    parser.set_defaults(run=run)
