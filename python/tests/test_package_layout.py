# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""The package's layout (README, "The package"): no import circles, each subpackage importing only the layers below
it, and the flat package's module names still importable (until 0.3), with a warning naming the new place."""

import importlib
import pathlib
import sys
import warnings

import pytest
from helpers import load_file

REPOSITORY = pathlib.Path(__file__).resolve().parents[2]
#: The layers, lowest first: a module may import its own layer's and those below (the package's __init__, which
#: re-exports the API, is importable from everywhere).
LAYERS = ["internal", "gendpde", "api", "units", "physics", "analysis", "reporter", "models", "calibration", "studies",
          "benchmarks", "cli", "__main__"]


def _import_graph():
    return load_file(REPOSITORY / "devtools" / "import_graph.py")


def test_the_circle_finder_finds_a_circle():
    graph = _import_graph()
    assert graph.circles({"a": ["b"], "b": ["c"], "c": ["a"], "d": ["a"]}) == [["a", "b", "c"]]
    assert graph.circles({"a": ["b"], "b": [], "d": ["a", "b"]}) == []


def test_no_module_or_subpackage_imports_itself_in_a_circle():
    graph = _import_graph()
    modules = graph.graph()
    assert len(modules) > 40 and "openmmgendpde.calibration.calibrate" in modules
    assert graph.circles(modules) == []
    assert graph.circles(graph.package_graph(modules)) == []


def test_each_subpackage_imports_only_the_layers_below_it():
    graph = _import_graph()
    edges = graph.package_graph(graph.graph())
    rank = {name: index for index, name in enumerate(LAYERS)}
    wrong = []
    for source, targets in edges.items():
        if source == "openmmgendpde":
            continue
        layer = rank[source.split(".")[1]]
        wrong += [f"{source} -> {target}" for target in targets if rank[target.split(".")[1]] > layer]
    assert wrong == []


@pytest.mark.parametrize("old, new", [("fluid", "models.fluid"), ("presets", "models.argon"),
                                      ("calibrate", "calibration.calibrate"), ("thermodynamics",
                                                                               "analysis.thermodynamics")])
def test_the_flat_package_s_module_names_still_import_with_a_warning(old, new):
    sys.modules.pop(f"openmmgendpde.{old}", None)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        module = importlib.import_module(f"openmmgendpde.{old}")
    assert module is importlib.import_module(f"openmmgendpde.{new}")
    assert [str(w.message) for w in caught if w.category is FutureWarning] == [
        f"openmmgendpde.{old} is now openmmgendpde.{new}; the old name is removed in version 0.3"]


def test_the_api_reference_is_generated_from_the_current_docstrings():
    """docs/api.md is devtools/api_reference.py's output for the installed package: a docstring changed without
    regenerating it fails here (the fix: .venv/bin/python devtools/api_reference.py > docs/api.md)."""
    text = load_file(REPOSITORY / "devtools" / "api_reference.py").generate()
    assert "### class `GenDPDEForce`" in text and "## `openmmgendpde.calibration.results`" in text
    assert text == (REPOSITORY / "docs" / "api.md").read_text()
