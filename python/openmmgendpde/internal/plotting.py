# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""Figures of the studies, saved as PNG and PDF. Built on matplotlib's Figure directly, not pyplot, so that no
display and no global backend are involved (nothing here selects a backend for the user's session).

matplotlib belongs to the optional ``studies`` dependencies (pyproject.toml): it is imported where a figure is
made, so that the subcommands without figures run without it.
"""

import numpy as np

from .files import atomic_write


def panels(count, width=4.2, height=3.6, **options):
    """A figure with `count` panels side by side: (figure, list of axes)."""
    from matplotlib.figure import Figure  # optional dependency (studies), see the module docstring
    figure = Figure(figsize=(width * count, height))
    axes = figure.subplots(1, count, **options)
    return figure, list(np.atleast_1d(axes))


def save(figure, path_stem, legend_axis=None):
    """Save as path_stem.png and path_stem.pdf, each atomically (files.atomic_write)."""
    if legend_axis is not None:
        legend_axis.legend(frameon=False)
    figure.tight_layout()
    for suffix in (".png", ".pdf"):
        with atomic_write(str(path_stem) + suffix, "wb") as stream:
            figure.savefig(stream, format=suffix[1:], dpi=150)
