# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""The module names of the flat package (version 0.1 and 0.2's development), kept importable in 0.2: ``import
openmmgendpde.fluid`` gives ``openmmgendpde.models.fluid`` with a FutureWarning that names the new place. Version 0.3
removes them."""

import importlib
import importlib.abc
import importlib.util
import sys
import warnings

#: Old module (under openmmgendpde) -> its place now.
MOVED = {
    "_wrapping": "internal.wrapping", "files": "internal.files", "forked": "internal.forked",
    "plotting": "internal.plotting", "progress": "cli.progress", "cli": "cli.options",
    "model": "models.lattice", "presets": "models.argon", "fluid": "models.fluid",
    "fluid_files": "models.fluid_files", "customgb": "models.customgb",
    "statistics": "analysis.statistics", "thermodynamics": "analysis.thermodynamics",
    "pressure": "analysis.pressure", "profiles": "analysis.profiles", "transport": "analysis.transport",
    "hugoniot": "analysis.hugoniot", "interfaces": "analysis.interfaces", "rdf": "studies.rdf",
    "stability": "calibration.stability", "calibrate": "calibration.calibrate", "tune_fcut": "calibration.fcut",
    "expansion": "calibration.expansion", "study": "models.argon_runs", "table3": "studies.table3",
    "slab": "studies.slab", "compression": "studies.compression", "speed_vs_error": "studies.speed_vs_error",
    "benchmark_cpu": "benchmarks.cpu", "benchmark_force": "benchmarks.force",
    "benchmark_integrator": "benchmarks.integrator", "timing": "benchmarks.timing",
    "measurement": "benchmarks.measurement",
}
PACKAGE = __name__.rsplit(".", 2)[0]


class _MovedModules(importlib.abc.MetaPathFinder, importlib.abc.Loader):
    """Finds ``openmmgendpde.<old name>`` and loads the module at its new place under that name too."""

    def find_spec(self, fullname, path=None, target=None):
        package, _, name = fullname.rpartition(".")
        if package == PACKAGE and name in MOVED:
            return importlib.util.spec_from_loader(fullname, self)
        return None

    def create_module(self, spec):
        new = f"{PACKAGE}.{MOVED[spec.name.rpartition('.')[2]]}"
        warnings.warn(f"{spec.name} is now {new}; the old name is removed in version 0.3",
                      FutureWarning, stacklevel=2)
        return importlib.import_module(new)

    def exec_module(self, module):
        pass


def install():
    """Make the old names importable (once)."""
    if not any(isinstance(finder, _MovedModules) for finder in sys.meta_path):
        sys.meta_path.append(_MovedModules())
