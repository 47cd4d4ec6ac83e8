# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""The names of the density estimators and of the laws are spelt once, in the core's tables (api.ESTIMATORS,
api.LAWS): no module of the Python package holds its own list of them (a command's choices, a model file's allowed
values, a dict keyed by them), so that a new estimator or law is known to every command and file without a Python
change. Read from the source (the AST), nothing is run; the published results of the argon model, which are data
keyed by the estimators the paper ran, are the one exception."""

import ast
import pathlib

from openmmgendpde.api import ESTIMATOR_NAMES, LAW_NAMES

PACKAGE = pathlib.Path(__file__).resolve().parents[1] / "openmmgendpde"
#: Modules whose literals of names are data: the published tables of the argon model (Tables III and IV).
DATA = {"models/argon.py"}
#: Modules the build generates (SWIG, CMake), not sources.
GENERATED = {"gendpde.py", "_version.py"}
NAMES = set(ESTIMATOR_NAMES.values()) | set(LAW_NAMES.values())


def _strings(nodes):
    return [node.value for node in nodes if isinstance(node, ast.Constant) and isinstance(node.value, str)]


def spelt_lists(source, names=NAMES):
    """(line, what) of each list of ``names`` spelt in ``source``: a tuple, list or set literal of two or more strings
    that are all names, a dict literal with two or more keys that are all names, or a choices= argument with a name
    among its literal strings."""
    found = []
    for node in ast.walk(ast.parse(source)):
        if isinstance(node, (ast.Tuple, ast.List, ast.Set)):
            strings = _strings(node.elts)
            if len(strings) == len(node.elts) >= 2 and set(strings) <= names:
                found.append((node.lineno, f"literal {strings}"))
        elif isinstance(node, ast.Dict):
            keys = _strings(node.keys)
            if len(keys) == len(node.keys) >= 2 and set(keys) <= names:
                found.append((node.lineno, f"dict keyed by {keys}"))
        elif isinstance(node, ast.keyword) and node.arg == "choices":
            strings = _strings(ast.walk(node.value))
            if set(strings) & names:
                found.append((node.value.lineno, f"choices {strings}"))
    return found


def test_the_finder_finds_a_spelt_list_and_passes_the_table_s():
    planted = ('choices = ("VA", "VB")\nx = ["Tait", "VB"]\nstyles = {"VA": 1, "VB": 2}\n'
               'parser.add_argument("--e", choices=["VB"])\nparser.add_argument("--f", choices=("VB", "VC"))\n')
    assert [line for line, _ in spelt_lists(planted)] == [1, 2, 3, 4, 5, 5]
    clean = ('choices = list(ESTIMATOR_NAMES.values())\nparser.add_argument("--e", choices=names, default="VB")\n'
             'pair = ("VB", 1.35)\nrow = ("mass", "VB")\n')
    assert spelt_lists(clean) == []


def _sources():
    paths = [path for path in sorted(PACKAGE.rglob("*.py")) if path.name not in GENERATED]
    assert len(paths) > 40
    return {path.relative_to(PACKAGE).as_posix(): path.read_text() for path in paths}


def test_no_module_spells_a_list_of_estimators_or_laws():
    found = {name: spelt for name, source in _sources().items() if name not in DATA
             for spelt in [spelt_lists(source)] if spelt}
    assert found == {}

