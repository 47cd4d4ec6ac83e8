#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""The import graph of the Python package openmmgendpde, read from the source (nothing is imported or run).

    python3 devtools/import_graph.py             # each module and the package modules it imports; the circles
    python3 devtools/import_graph.py --packages  # the same between subpackages (models, analysis, ...)

Exits with status 1 if the graph has a circle (a module that, through its imports, imports itself), naming it.
Every import counts, at module level or inside a function.
"""

import argparse
import ast
import pathlib
import sys

PACKAGE = "openmmgendpde"
#: Modules the build generates (SWIG, CMake), absent from the source tree.
GENERATED = ("openmmgendpde.gendpde", "openmmgendpde._version")
SOURCE = pathlib.Path(__file__).resolve().parent.parent / "python" / PACKAGE


def module_of(path, root=SOURCE):
    parts = list(path.relative_to(root.parent).with_suffix("").parts)
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def imports(path, modules, root=SOURCE):
    """The package modules that ``path`` imports (a package's __init__ where a name is not a module)."""
    name = module_of(path, root)
    package = name.split(".") if path.name == "__init__.py" else name.split(".")[:-1]
    found = set()
    for node in ast.walk(ast.parse(path.read_text())):
        if isinstance(node, ast.Import):
            targets = [alias.name for alias in node.names]
        elif isinstance(node, ast.ImportFrom):
            base = node.module or "" if node.level == 0 else ".".join(
                package[:len(package) - node.level + 1] + ([node.module] if node.module else []))
            targets = [f"{base}.{alias.name}" if f"{base}.{alias.name}" in modules else base for alias in node.names]
        else:
            continue
        for target in targets:
            while target and target not in modules:
                target = target.rpartition(".")[0]
            if target and target != name:
                found.add(target)
    return found


def graph(root=SOURCE):
    paths = {module_of(path, root): path for path in sorted(root.rglob("*.py"))
             if module_of(path, root) not in GENERATED}   # (where a build copied them in: not sources)
    known = set(paths) | set(GENERATED)
    return {name: sorted(imports(path, known, root)) for name, path in paths.items()}


def package_graph(modules):
    """Edges between the subpackages (a top-level module is its own node)."""
    def node(name):
        parts = name.split(".")
        return ".".join(parts[:2]) if len(parts) > 2 else name
    edges = {}
    for name, targets in modules.items():
        for target in targets:
            if node(target) != node(name) and target != PACKAGE:   # everything may import the package's API
                edges.setdefault(node(name), set()).add(node(target))
        edges.setdefault(node(name), set())
    return {name: sorted(targets) for name, targets in edges.items()}


def circles(edges):
    """Each circle once, as a list of nodes (the strongly connected components with more than one node)."""
    index, low, stack, on_stack, found, counter = {}, {}, [], set(), [], [0]

    def visit(v):
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on_stack.add(v)
        for w in edges.get(v, ()):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on_stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            component = []
            while True:
                w = stack.pop()
                on_stack.discard(w)
                component.append(w)
                if w == v:
                    break
            if len(component) > 1:
                found.append(sorted(component))

    for v in sorted(edges):
        if v not in index:
            visit(v)
    return found


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--packages", action="store_true", help="the graph between subpackages")
    arguments = parser.parse_args(argv)
    edges = graph()
    if arguments.packages:
        edges = package_graph(edges)
    for name, targets in edges.items():
        print(f"{name} -> {', '.join(target.removeprefix(PACKAGE + '.') for target in targets) or '-'}")
    found = circles(edges)
    for circle in found:
        print("circle: " + " -> ".join(circle))
    print(f"{len(edges)} nodes, {sum(map(len, edges.values()))} imports, {len(found)} circles")
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main())
