# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""Outputs written atomically: a file is complete or absent (or still the previous one), never partly written.

``atomic_write(path)`` opens a temporary file in the target's directory and, when the block ends without an
error, renames it over the target (os.replace, atomic on one file system); on an error or Ctrl-C the temporary file
is removed and the target is left as it was. Every file the package writes at the end of a run goes through it
(--json, calibrate's --output model, figures, tables, table3's frames). A target that exists and is not a regular file
(/dev/stdout, a pipe) cannot be replaced and is written in place.

A failed write raises OSError naming the target (``filename``), so that a command reports it in one line
(cli.failure_message).
"""

import contextlib
import os
import tempfile


@contextlib.contextmanager
def atomic_write(path, mode="w", **options):
    """A context manager yielding a stream (``open``'s ``mode`` and ``options``: 'w' for text, 'wb' for bytes) whose
    contents replace the file ``path`` when the block ends without an exception; OSError (with the target as its
    filename) if it cannot be written."""
    path = os.fspath(path)
    if os.path.exists(path) and not os.path.isfile(path):
        with _naming(path), open(path, mode, **options) as stream:
            yield stream
        return
    target = os.path.realpath(path)   # a link stays a link: the file it names is replaced
    directory = os.path.dirname(target)
    with _naming(path):
        descriptor, temporary = tempfile.mkstemp(dir=directory, prefix=f".{os.path.basename(target)}.",
                                                 suffix=".partial")
    try:
        with _naming(path), os.fdopen(descriptor, mode, **options) as stream:
            yield stream
            stream.flush()
            os.fsync(stream.fileno())
        with _naming(path):
            os.chmod(temporary, 0o666 & ~_umask())   # (mkstemp makes it 0600; an ordinary file is 0666 - umask)
            os.replace(temporary, target)
    except BaseException:
        with contextlib.suppress(OSError):
            os.unlink(temporary)
        raise


@contextlib.contextmanager
def _naming(path):
    """OSError inside the block re-raised with ``path`` as its filename (write errors such as ENOSPC carry none)."""
    try:
        yield
    except OSError as error:
        raise OSError(error.errno, error.strerror or str(error), path) from None


def _umask():
    mask = os.umask(0)
    os.umask(mask)
    return mask
