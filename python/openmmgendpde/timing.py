"""Measuring speed on a noisy machine: every comparison is made side by side in one run.

Candidates are called in alternating rounds (the order rotates every round), each call is timed on its own, and
results are reported as medians: the median time per call, and the median over rounds of the per-round ratio
between two candidates (robust to another process slowing down part of the run).
"""

import statistics
import sys
import time


def alternating_rounds(candidates, rounds, progress=None):
    """Call each of ``candidates`` (name -> callable) once per round for ``rounds`` rounds, rotating the order.
    Returns name -> list of seconds per call (one entry per round)."""
    names = list(candidates)
    seconds = {name: [] for name in names}
    for round_index in range(rounds):
        shift = round_index % len(names)
        for name in names[shift:] + names[:shift]:
            start = time.perf_counter()
            candidates[name]()
            seconds[name].append(time.perf_counter() - start)
        if progress is not None:
            progress.advance()
    return seconds


def median(values):
    return statistics.median(values)


def median_ratio(seconds, numerator, denominator):
    """Median over rounds of seconds[numerator] / seconds[denominator]."""
    return statistics.median(a / b for a, b in zip(seconds[numerator], seconds[denominator]))


def quartiles(values):
    ordered = sorted(values)
    if len(ordered) < 4:
        return ordered[0], ordered[-1]
    q = statistics.quantiles(ordered, n=4)
    return q[0], q[2]


class Progress:
    """A one-line progress display on stderr with the time remaining, for long runs (silent when not a terminal
    unless ``always`` is set)."""

    def __init__(self, total, label="", always=False, stream=None):
        self.total, self.done, self.label = max(1, total), 0, label
        self.stream = stream or sys.stderr
        self.enabled = always or self.stream.isatty()
        self.start = time.perf_counter()
        self.last_print = 0.0

    def advance(self, amount=1, label=None):
        self.done = min(self.total, self.done + amount)
        if label is not None:
            self.label = label
        now = time.perf_counter()
        if self.enabled and (now - self.last_print > 0.5 or self.done == self.total):
            self.last_print = now
            elapsed = now - self.start
            remaining = elapsed / self.done * (self.total - self.done)
            self.stream.write(f"\r{self.label} {100 * self.done / self.total:5.1f}%  elapsed {format_duration(elapsed)}"
                              f"  remaining ~{format_duration(remaining)}   ")
            self.stream.flush()

    def finish(self):
        if self.enabled:
            self.stream.write("\n")
            self.stream.flush()


def format_duration(seconds):
    seconds = int(round(seconds))
    if seconds < 60:
        return f"{seconds}s"
    if seconds < 3600:
        return f"{seconds // 60}m{seconds % 60:02d}s"
    return f"{seconds // 3600}h{seconds % 3600 // 60:02d}m"
