# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""Independent runs side by side in forked processes, one CPU thread each: the replicas of a transport measurement
(calibrate.Calibration.replicas).

A Context of ~1000 particles barely uses a second CPU thread (water's calibrated model, 1024 particles, CPU
platform: 1.1-1.5 ms per step on one thread, 1.2-1.35 ms on two), while two replicas in two processes of one thread
each take the time of one: docs/fluids.md gives the measured ratio for a whole calibration.
"""

import contextlib
import io
import multiprocessing
import sys

import openmm

_WORK = None   # the function fork_map runs, inherited by its forked workers (closures do not pickle)


def _one_thread():
    openmm.Platform.getPlatformByName("CPU").setPropertyDefaultValue("Threads", "1")


def _call(index):
    printed = io.StringIO()
    with contextlib.redirect_stdout(printed):
        result = _WORK(index)
    return result, printed.getvalue()


def fork_map(function, count, workers):
    """[function(i) for i in range(count)], in up to ``workers`` processes at once when workers > 1 (each forked
    from this one for its call alone, so that it starts from this process's state, and computing on one CPU thread:
    the CPU platform's default Threads set to 1), else in this process. The results come back in order, and so
    does what each call printed (written to stdout as its result arrives); they must pickle. An exception in a call
    is raised here, and the other calls are stopped. Without fork (Windows) the calls run in this process."""
    global _WORK
    workers = min(workers, count)
    if workers <= 1 or "fork" not in multiprocessing.get_all_start_methods():
        return [function(index) for index in range(count)]
    sys.stdout.flush()
    sys.stderr.flush()
    _WORK = function
    pool = multiprocessing.get_context("fork").Pool(workers, initializer=_one_thread, maxtasksperchild=1)
    try:
        results = []
        for result, printed in pool.imap(_call, range(count)):
            sys.stdout.write(printed)
            sys.stdout.flush()
            results.append(result)
        pool.close()
        return results
    finally:
        pool.terminate()
        pool.join()
        _WORK = None
