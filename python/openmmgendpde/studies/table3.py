# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""Table III of Colella et al. (J. Chem. Theory Comput. 2025) reproduced (`table3`): for the three published cutoffs
and both estimators (--estimators; VC against the published VB values), the production averages of T* (kinetic,
and harmonic mean of theta_i), n-bar* and P* with
block-average error bars (10 blocks; a warning on stderr where they have not reached their plateau, see
openmmgendpde.analysis.statistics), beside the published values and the difference. Runs follow
openmmgendpde.models.argon_runs (thermostat at T0, internal energies drawn at T0, isoenergetic equilibration and
production). A cell is marked when it differs from the published value by more than the published error bar (0.0001 for
T*, 0.001 otherwise) plus twice its own standard error.
"""

import csv
import dataclasses
import hashlib
import json
import math
import os
import pathlib
import shutil
import tempfile
import warnings

import numpy as np

from ..analysis.statistics import BlockAverageWarning, block_average
from ..internal.files import atomic_write
from ..models.argon import ARGON_STATE, PUBLISHED_ESTIMATORS, PUBLISHED_TABLE3
from ..models.argon_runs import run_argon

#: (published key, Samples field, label, published error bar)
QUANTITIES = (
    ("T", "kinetic_temperature", "T* (kinetic)", 0.0001),
    ("T", "harmonic_temperature", "T* (harmonic-mean theta)", 0.0001),
    ("n", "density", "n-bar*", 0.001),
    ("P", "pressure", "P*", 0.001),
)


@dataclasses.dataclass
class Cell:
    cutoff: float
    estimator: str
    quantity: str
    published: float
    reproduced: float
    error: float

    @property
    def difference(self):
        return self.reproduced - self.published

    @property
    def published_error(self):
        return next(bar for _, _, label, bar in QUANTITIES if label == self.quantity)

    @property
    def published_text(self):
        """The published value as printed in the paper, with its significant zeros (0.870, 1.000, 0.0111)."""
        decimals = round(-math.log10(self.published_error))
        return f"{self.published:.{decimals}f}"

    @property
    def outside(self):
        return abs(self.difference) > self.published_error + 2 * self.error


def cells_of(cutoff, estimator, samples):
    cells = []
    for key, field, label, _ in QUANTITIES:
        mean, error = block_average(getattr(samples, field), name=f"R_cut* = {cutoff} {estimator} {label}")
        published = PUBLISHED_TABLE3[cutoff].get(estimator, PUBLISHED_TABLE3[cutoff]["VB"])   # VC: against VB's
        cells.append(Cell(cutoff, estimator, label, published[key], mean, error))
    return cells


def format_table(cells):
    lines = ["| R_cut* | estimator | quantity | published | reproduced | difference |",
             "|---|---|---|---|---|---|"]
    for c in cells:
        digits = 5 if c.quantity.startswith("T*") else 4
        mark = " (!)" if c.outside else ""
        lines.append(f"| {c.cutoff} | {c.estimator} | {c.quantity} | {c.published_text} | {c.reproduced:.{digits}f} "
                     f"+- {c.error:.{digits}f} | {c.difference:+.{digits}f}{mark} |")
    return "\n".join(lines)


def pairing_signature(cells):
    """One line per cutoff: n-bar* with VA and VB."""
    lines = []
    for cutoff in sorted({c.cutoff for c in cells}):
        density = {c.estimator: c for c in cells if c.cutoff == cutoff and c.quantity == "n-bar*"}
        if set(density) == set(PUBLISHED_ESTIMATORS):
            traditional, partition = (density[estimator] for estimator in PUBLISHED_ESTIMATORS)
            lines.append(f"R_cut* = {cutoff}: n-bar* = {traditional.reproduced:.3f} with {traditional.estimator} "
                         f"(pairs clump towards the free-energy minimum n_min* = "
                         f"{ARGON_STATE.free_energy_minimum_density:.3f}) and {partition.reproduced:.3f} with "
                         f"{partition.estimator} (imposed n0* = 1)")
    return lines


def write_csv(cells, path):
    with atomic_write(path, newline="") as stream:
        writer = csv.writer(stream)
        writer.writerow(["R_cut*", "estimator", "quantity", "published", "reproduced", "standard error",
                         "difference", "outside error bars"])
        for c in cells:
            writer.writerow([c.cutoff, c.estimator, c.quantity, c.published_text, f"{c.reproduced:.6g}",
                             f"{c.error:.2g}", f"{c.difference:+.6g}", c.outside])


#: The manifest of a set of frame files (save_frames), written last: read_frames reads only a directory that has one
#: and whose files match it.
FRAMES_MANIFEST = "table3-frames.json"
FRAMES_FORMAT = "openmmgendpde-table3-frames-1"


def frames_file(cutoff, estimator):
    return f"frames-R{cutoff}-{estimator}.npz"


def _digest(path):
    with open(path, "rb") as stream:
        return hashlib.file_digest(stream, "sha256").hexdigest()


def save_frames(directory, frames):
    """Write the production frames of each case, ``frames``: (cutoff, estimator) -> (positions F x N x 3 in nm, box
    edge in nm), into ``directory`` as one set, complete or absent: every file is written into a temporary directory
    inside it first; then the old manifest is removed, the files are moved in and the manifest (each file with its
    SHA-256 digest) is written last, atomically. A run that fails or is interrupted before that leaves the previous
    set as it was; one interrupted while the files move in leaves no manifest, which read_frames refuses."""
    directory = pathlib.Path(directory)
    staging = pathlib.Path(tempfile.mkdtemp(dir=directory, prefix=".table3-frames-", suffix=".partial"))
    try:
        cases = []
        for (cutoff, estimator), (positions, box_edge) in frames.items():
            name = frames_file(cutoff, estimator)
            with open(staging / name, "wb") as stream:
                np.savez_compressed(stream, positions=np.asarray(positions, dtype=np.float32), box_edge=box_edge,
                                    cutoff=cutoff, estimator=estimator)
            cases.append({"file": name, "cutoff": cutoff, "estimator": estimator, "frames": len(positions),
                          "sha256": _digest(staging / name)})
        (directory / FRAMES_MANIFEST).unlink(missing_ok=True)
        for case in cases:
            os.replace(staging / case["file"], directory / case["file"])
        with atomic_write(directory / FRAMES_MANIFEST) as stream:
            json.dump({"format": FRAMES_FORMAT, "cases": cases}, stream, indent=1)
    finally:
        shutil.rmtree(staging, ignore_errors=True)


def read_frames(directory, cases):
    """The frames that save_frames wrote into ``directory`` for ``cases`` [(cutoff, estimator)]: (cutoff, estimator)
    -> (positions F x N x 3 in nm, box edge in nm). ValueError, naming what is wrong, unless the directory holds a
    complete set (its manifest) with every case and each file as written (its digest)."""
    directory = pathlib.Path(directory)
    manifest = directory / FRAMES_MANIFEST
    again = f"run `table3 --output {directory}` again"
    if not directory.is_dir():
        raise ValueError(f"{directory} is not a directory")
    if not manifest.is_file():
        raise ValueError(f"{directory} holds no complete set of table3 frames (no {FRAMES_MANIFEST}, which table3 "
                         f"writes last; an interrupted table3, or another directory); {again}")
    try:
        with open(manifest) as stream:
            table = json.load(stream)
        listed = {(float(case["cutoff"]), case["estimator"]): case for case in table["cases"]}
        if table["format"] != FRAMES_FORMAT:
            raise ValueError
    except (ValueError, KeyError, TypeError):
        raise ValueError(f"{manifest} is not a manifest of table3 frames ({FRAMES_FORMAT}); {again}") from None
    frames = {}
    for cutoff, estimator in cases:
        case = listed.get((cutoff, estimator))
        if case is None:
            held = ", ".join(f"R_cut* = {c} {e}" for c, e in listed)
            raise ValueError(f"{directory} has no frames of R_cut* = {cutoff} {estimator} (it has {held}); give "
                             f"--cutoffs of those, or run table3 for them")
        path = directory / case["file"]
        if not path.is_file() or _digest(path) != case["sha256"]:
            raise ValueError(f"{path} is {'missing' if not path.is_file() else 'not the file table3 wrote'} "
                             f"({manifest} lists it with its digest); {again}")
        with np.load(path) as data:
            frames[(cutoff, estimator)] = data["positions"], float(data["box_edge"])
    return frames


def sampling_summary(unsettled, count, verbose=False):
    """One line on the error bars (``count``) of which ``unsettled`` (BlockAverageWarnings) had not reached their
    plateau: those bars are too small (statistics.block_average). ``verbose``: each warning on a line of its own."""
    if not unsettled:
        return f"Sampling: every one of the {count} error bars reached its block-average plateau."
    line = (f"Sampling: {len(unsettled)} of the {count} error bars had not reached their block-average plateau, so "
            f"they are too small (runs too short for them; --production for longer ones)")
    return line + ("".join(f"\n  {w.message}" for w in unsettled) if verbose else "; --verbose names each.")


@dataclasses.dataclass
class Table3:
    """What reproduce found: the Cells (every quantity of every case), the production frames kept of each case
    {(cutoff, estimator): (positions F x N x 3 in nm, box edge in nm)} and the BlockAverageWarnings of the error bars
    that had not reached their plateau."""
    cells: list
    frames: dict
    unsettled: list


def reproduce(cutoffs, estimators, protocol, platform="Reference", frames=10, progress=None):
    """Table III for ``cutoffs`` x ``estimators`` by the protocol (models.argon_runs.run_argon on ``platform``),
    keeping ``frames`` production frames of each case; ``progress`` (cli.progress.Progress) advances by the steps
    and is labelled by the case. Returns a Table3."""
    cells, kept = [], {}
    with warnings.catch_warnings(record=True) as unsettled:
        warnings.simplefilter("always", BlockAverageWarning)
        for cutoff, estimator in [(cutoff, estimator) for cutoff in cutoffs for estimator in estimators]:
            if progress is not None:
                progress.label = f"table3 R*={cutoff} {estimator}"
            samples = run_argon(cutoff, estimator, protocol, platform, frames=frames, progress=progress).samples
            cells += cells_of(cutoff, estimator, samples)
            kept[(cutoff, estimator)] = (samples.frames, samples.box_edge)
    return Table3(cells, kept, [w for w in unsettled if issubclass(w.category, BlockAverageWarning)])
