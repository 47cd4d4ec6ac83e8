#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""The API reference, docs/api.md, generated from the docstrings of the installed package (the C++ documentation of
GenDPDEForce and GenDPDEIntegrator reaches Python through SWIG):

    .venv/bin/python devtools/api_reference.py > docs/api.md     # after scripts/setup.sh
    .venv/bin/python devtools/api_reference.py --check           # status 1 if docs/api.md is not what it generates

Covered: the package's classes (every public method), and each public module of its subpackages (its docstring's
first paragraph, then each public class and function defined there with its signature and docstring). Modules of
internal/ and the command line's glue are left out.
"""

import argparse
import importlib
import inspect
import pathlib
import pkgutil
import sys

PACKAGE = "openmmgendpde"
DOCUMENT = pathlib.Path(__file__).resolve().parent.parent / "docs" / "api.md"
#: Subpackages in the order of the README's tree, and the top modules.
SECTIONS = ["units", "physics", "models", "analysis", "calibration", "studies", "benchmarks", "cli"]


def _first_paragraph(text):
    return inspect.cleandoc(text or "").split("\n\n")[0].replace("\n", " ")


def _signature(obj):
    try:
        return str(inspect.signature(obj))
    except (TypeError, ValueError):
        return "(...)"


def _doc(obj):
    return inspect.cleandoc(inspect.getdoc(obj) or "(no docstring)")


def _block(text):
    return "\n".join("    " + line if line else "" for line in text.splitlines())


def _members(module):
    """Public classes and functions defined in ``module`` (not imported into it), in source order."""
    found = []
    for name, obj in vars(module).items():
        if name.startswith("_") or not (inspect.isclass(obj) or inspect.isfunction(obj)):
            continue
        if getattr(obj, "__module__", None) != module.__name__:
            continue
        try:
            line = inspect.getsourcelines(obj)[1]
        except (OSError, TypeError):
            line = 0
        found.append((line, name, obj))
    return [(name, obj) for _, name, obj in sorted(found, key=lambda item: item[:2])]


def _class_section(name, cls, heading="###"):
    """A class and the public methods and properties it defines (those of its bases are theirs)."""
    lines = [f"{heading} class `{name}`", "", _block(_doc(cls)), ""]
    for attribute in sorted(vars(cls)):
        member = vars(cls)[attribute]
        if attribute.startswith("_") or inspect.isclass(member):
            continue
        if isinstance(member, property):
            lines += [f"- `{attribute}` (property)", "", _block(_doc(member)), ""]
        elif callable(member) or isinstance(member, (staticmethod, classmethod)):
            function = getattr(cls, attribute)
            lines += [f"- `{attribute}{_signature(function)}`", "", _block(_doc(function)), ""]
    return lines


def _module_section(module_name):
    module = importlib.import_module(module_name)
    lines = [f"## `{module_name}`", "", _first_paragraph(module.__doc__), ""]
    exported = [(name, getattr(module, name)) for name in getattr(module, "__all__", [])]
    for name, obj in _members(module) or exported:
        if inspect.isclass(obj):
            lines += _class_section(name, obj)
        else:
            lines += [f"### `{name}{_signature(obj)}`", "", _block(_doc(obj)), ""]
    return lines


def _modules(section):
    name = f"{PACKAGE}.{section}"
    module = importlib.import_module(name)
    if not hasattr(module, "__path__"):
        return [name]
    return [name] * bool(module.__doc__) + sorted(
        info.name for info in pkgutil.iter_modules(module.__path__, name + ".") if not info.name.rsplit(".", 1)[1]
        .startswith("_"))


def generate():
    package = importlib.import_module(PACKAGE)
    lines = ["# API reference", "",
             "Generated from the docstrings by `devtools/api_reference.py` (do not edit by hand; "
             "`python/tests/test_package_layout.py` checks that it is current). Units: OpenMM's (nm, ps, amu, "
             "kJ/mol, K) unless a docstring says otherwise.", "",
             f"## `{PACKAGE}`", "", _first_paragraph(package.__doc__), ""]
    for name in package.__all__:
        lines += _class_section(name, getattr(package, name))
    for section in SECTIONS:
        for module_name in _modules(section):
            lines += _module_section(module_name)
    return "\n".join(line.rstrip() for line in lines).rstrip() + "\n"


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--check", action="store_true", help=f"compare with {DOCUMENT} instead of printing")
    arguments = parser.parse_args(argv)
    text = generate()
    if not arguments.check:
        sys.stdout.write(text)
        return 0
    if DOCUMENT.exists() and DOCUMENT.read_text() == text:
        return 0
    print(f"{DOCUMENT} is not current: run .venv/bin/python devtools/api_reference.py > docs/api.md", file=sys.stderr)
    return 1


if __name__ == "__main__":
    sys.exit(main())
