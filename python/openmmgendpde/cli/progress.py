# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""Progress of the long runs on stderr (tqdm): percentage, elapsed time and an estimate of the time remaining."""

import sys

from tqdm import tqdm


class Progress:
    """A progress bar on stderr (or ``stream``) over ``total`` units of work (steps, rounds), shown only when the
    stream is a terminal or ``always`` is set (--progress); it never writes to stdout. ``label`` (settable) names
    the current part of the work."""

    def __init__(self, total, label="", always=False, stream=None):
        stream = stream or sys.stderr
        self.total = max(1, total)
        self._label = label
        self._bar = tqdm(total=self.total, desc=label, file=stream, disable=not (always or stream.isatty()),
                         mininterval=0.5, dynamic_ncols=True,
                         bar_format="{desc} {percentage:5.1f}% |{bar}| elapsed {elapsed}, remaining ~{remaining}")

    @property
    def label(self):
        return self._label

    @label.setter
    def label(self, label):
        self._label = label
        self._bar.set_description_str(label, refresh=False)

    def advance(self, amount=1, label=None):
        """``amount`` more units done (never beyond ``total``); optionally a new label."""
        if label is not None:
            self.label = label
        self._bar.update(min(amount, self.total - self._bar.n))

    def finish(self):
        self._bar.close()
