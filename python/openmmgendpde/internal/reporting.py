# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""The checks that every reporter of this package makes of its arguments, and how it opens its file: each refusal an
OpenMMException naming the reporter, the parameter, the value and what is allowed."""

import numbers
import os
import reprlib

import openmm


def checked_report_interval(reporter, value):
    """``value`` as a reporter's interval in steps (an integer >= 1), or an OpenMMException naming ``reporter`` (its
    class name), the parameter and the value: the check of every reporter of this package."""
    if isinstance(value, bool) or not isinstance(value, numbers.Integral) or value < 1:
        raise openmm.OpenMMException(f"{reporter}: reportInterval = {value!r} is not allowed; it must be an integer "
                                     f">= 1")
    return int(value)


def checked_file(reporter, file):
    """``file`` as a reporter's output, checked before anything is created: a path (str or os.PathLike) to a file whose
    directory exists (it is opened, for writing or appending, by open_file), or an open text stream (an object with a
    write method); else an OpenMMException naming ``reporter``, the parameter, the value and what is allowed."""
    if isinstance(file, (str, os.PathLike)):
        path = os.fspath(file)
        directory = os.path.dirname(os.path.abspath(path))
        problem = ("it is a directory" if os.path.isdir(path) else
                   f"the directory {directory} does not exist" if not os.path.isdir(directory) else None)
        if problem is None:
            return path
    elif callable(getattr(file, "write", None)):
        return file
    else:
        problem = f"it is a {type(file).__name__}"
    raise openmm.OpenMMException(f"{reporter}: file = {reprlib.repr(file)} is not allowed ({problem}); it must be a "
                                 f"path to a file in an existing directory, or an open text stream (with a write "
                                 f"method)")


def open_file(reporter, file, append=False):
    """(stream, whether the reporter opened it) for a checked_file: a path is opened for writing (or appending); a
    failure is an OpenMMException naming ``reporter`` and the file."""
    if not isinstance(file, (str, bytes)):
        return file, False
    try:
        return open(file, "a" if append else "w"), True
    except OSError as error:
        raise openmm.OpenMMException(f"{reporter}: file = {file!r} cannot be opened for writing "
                                     f"({error.strerror or error})") from None


def checked_choice(reporter, name, value, allowed, text):
    """``value`` if ``allowed(value)``, else an OpenMMException naming ``reporter``, the parameter ``name``, the value
    (an OpenMM object by its class) and ``text`` (what is allowed)."""
    if not allowed(value):
        shown = f"a {type(value).__name__}" if isinstance(value, (openmm.Force, openmm.Integrator)) \
            else reprlib.repr(value)
        raise openmm.OpenMMException(f"{reporter}: {name} = {shown} is not allowed; it must be {text}")
    return value
