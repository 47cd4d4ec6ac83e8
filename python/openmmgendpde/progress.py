"""A one-line progress display with elapsed time and an estimate of the time remaining."""

import sys
import time


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
