# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""The plugin as part of an OpenMM 8 installation: loaded by `import openmm`, documented by help(), taking what
OpenMM's own classes take (numpy scalars, Quantity lists and arrays), and releasing the GIL in long calls."""

import pathlib
import pydoc
import re
import subprocess
import sys
import threading
import time

import numpy as np
import openmm
import pytest
import tomllib
from helpers import TEMPERATURE, argon_integrator, lattice_liquid, make_context
from openmm import unit
from packaging.requirements import Requirement

import openmmgendpde
from openmmgendpde import KERNEL_NAMES, GenDPDEForce, GenDPDEIntegrator


def test_import_openmm_loads_the_kernel_libraries_without_failures():
    # A fresh interpreter that imports only openmm, as a user's script would before it knows about the plugin.
    script = ("import openmm, os\n"
              "print(repr(openmm.Platform.getPluginLoadFailures()))\n"
              "print(repr(sorted(os.path.basename(p) for p in openmm.pluginLoadedLibNames)))\n"
              "print(repr({openmm.Platform.getPlatform(i).getName(): openmm.Platform.getPlatform(i).supportsKernels("
              f"{list(KERNEL_NAMES)!r}) for i in range(openmm.Platform.getNumPlatforms())}}))\n")
    lines = subprocess.run([sys.executable, "-c", script], check=True, capture_output=True, text=True,
                           env={"PATH": "/usr/bin:/bin"}).stdout.splitlines()
    failures, loaded, supported = (eval(line) for line in lines)
    assert failures == ()
    assert {"libOpenMMGenDPDEReference.so", "libOpenMMGenDPDECPU.so"} <= set(loaded)
    assert supported["Reference"] and supported["CPU"]


@pytest.mark.parametrize("method, fragments", [
    (GenDPDEForce.setTaitParameters, ["n0 (in nm^-3)", "pi0 (in kJ/mol/nm^3)", "gamma_T (dimensionless)"]),
    (GenDPDEForce.getParticleDensities, ["(in nm^-3)"]),
    (GenDPDEForce.getVirial, ["(in kJ/mol)"]),
    (GenDPDEIntegrator.__init__, ["gamma (in amu/ps)", "kappa (in kJ K/(mol ps))", "(in kJ/(mol K))"]),
    (GenDPDEIntegrator.setInternalEnergiesToTemperature, ["T (in K)", "Gamma law"]),
])
def test_help_shows_the_cpp_documentation_with_units(method, fragments):
    text = pydoc.render_doc(method, renderer=pydoc.plaintext)
    for fragment in fragments:
        assert fragment in text


NUMPY_SCALARS = [np.float32(1.25), np.float64(1.25), np.int32(2), np.int64(2), np.array(1.25)]


@pytest.mark.parametrize("value", NUMPY_SCALARS, ids=lambda v: type(v).__name__ + str(np.ndim(v)))
def test_numpy_scalars_are_numbers(value):
    expected = float(value)
    force = GenDPDEForce(value)
    assert force.getCutoffDistance() == expected * unit.nanometer
    force.setCutoffDistance(value * unit.nanometer)
    assert force.getCutoffDistance() == expected * unit.nanometer
    force.setCutoffScaling(value)
    assert force.getCutoffScaling() == expected
    force.setTaitParameters(value, value, value, value + 1)
    assert [q.value_in_unit(q.unit) if unit.is_quantity(q) else q for q in force.getTaitParameters()] == \
        [expected, expected, expected, expected + 1]
    integrator = GenDPDEIntegrator(value, value, value, value)
    assert integrator.getFriction() == expected * unit.amu / unit.picosecond
    integrator.setTemperature(value * unit.kelvin)
    assert integrator.getTemperature() == expected * unit.kelvin


@pytest.mark.parametrize("value", [np.int32(3), np.int64(3)], ids=lambda v: type(v).__name__)
def test_numpy_integers_are_integers(value):
    integrator = GenDPDEIntegrator(0.01, 1, 1, 1)
    integrator.setRandomNumberSeed(value)
    assert integrator.getRandomNumberSeed() == 3
    integrator.setMode(np.int64(GenDPDEIntegrator.Isothermal))
    assert integrator.getMode() == GenDPDEIntegrator.Isothermal
    force = GenDPDEForce(1.0)
    force.setDensityEstimator(np.int32(GenDPDEForce.VA))
    assert force.getDensityEstimator() == GenDPDEForce.VA
    with pytest.raises(TypeError):
        integrator.setRandomNumberSeed(np.float64(2.5))   # as OpenMM: a non-integral value is not an int


@pytest.mark.parametrize("temperatures", [
    [100 * unit.kelvin, 110 * unit.kelvin],
    (100 * unit.kelvin, 110.0),                          # plain numbers are in OpenMM units
    unit.Quantity(np.array([100.0, 110.0]), unit.kelvin),
    unit.Quantity([100, 110], unit.kelvin),
    np.array([100 * unit.kelvin, 110 * unit.kelvin], dtype=object),
    np.array([100, 110], dtype=np.int32),
    np.array([100, 110], dtype=np.float32),
    [np.float32(100), np.int64(110)],
], ids=["quantities", "mixed tuple", "quantity array", "quantity list", "object array", "int32", "float32",
        "numpy scalars"])
def test_per_particle_arrays_take_quantities_and_numpy(temperatures):
    integrator = GenDPDEIntegrator(0.01, 1, 1, 1)
    integrator.setParticleTemperatures(temperatures)
    np.testing.assert_array_equal(integrator.getParticleTemperatures().value_in_unit(unit.kelvin), [100.0, 110.0])


def test_per_particle_quantities_of_the_wrong_dimension_are_refused():
    integrator = GenDPDEIntegrator(0.01, 1, 1, 1)
    with pytest.raises(TypeError, match=r"temperatures\)\[1\]"):
        integrator.setParticleTemperatures([100 * unit.kelvin, 1 * unit.nanometer])


def _argon_context(platform, seed):
    system, _, positions = lattice_liquid(6)                          # 216 particles
    integrator = argon_integrator(0.005)
    integrator.setTemperature(TEMPERATURE)
    integrator.setRandomNumberSeed(seed)
    context = make_context(system, positions, platform, integrator)
    return context, integrator


def test_step_releases_the_gil_so_other_threads_run():
    """While step() runs in C++, a Python thread keeps ticking. With the GIL held it could not tick at all until
    step() returned; the check is functional (ticks happen), not a timing bound."""
    context, integrator = _argon_context(openmm.Platform.getPlatformByName("Reference"), seed=5)
    integrator.step(10)
    start = time.perf_counter()
    integrator.step(10)
    steps = max(20, int(0.3 / max(time.perf_counter() - start, 1e-6) * 10))   # about 0.3 s of stepping
    ticks = []
    stop = threading.Event()

    def ticker():
        while not stop.is_set():
            ticks.append(time.perf_counter())
            time.sleep(0.001)

    thread = threading.Thread(target=ticker)
    thread.start()
    time.sleep(0.01)
    begin = time.perf_counter()
    integrator.step(steps)
    end = time.perf_counter()
    stop.set()
    thread.join()
    during = [t for t in ticks if begin < t < end]
    assert len(during) >= 10, f"{len(during)} ticks during {end - begin:.3f} s of step()"


def test_two_contexts_in_two_threads_match_sequential_runs():
    """Two Contexts stepped at once from two Python threads give exactly the trajectories they give one after the
    other (the plugin keeps no shared mutable state between Contexts)."""
    platform = openmm.Platform.getPlatformByName("Reference")

    def run(seed, results):
        context, integrator = _argon_context(platform, seed)
        integrator.step(200)
        results[seed] = context.getState(getPositions=True).getPositions(asNumpy=True).value_in_unit(unit.nanometer)

    sequential, concurrent = {}, {}
    for seed in (11, 12):
        run(seed, sequential)
    threads = [threading.Thread(target=run, args=(seed, concurrent)) for seed in (11, 12)]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join()
    for seed in (11, 12):
        np.testing.assert_array_equal(concurrent[seed], sequential[seed])
    assert not np.array_equal(sequential[11], sequential[12])


def test_pins_agree_with_the_package_metadata():
    """requirements.txt pins the supported environment; pyproject.toml states what the package accepts and builds
    with. The pinned OpenMM must be in both of pyproject's ranges and the pinned SWIG must be the build's."""
    root = pathlib.Path(__file__).resolve().parents[2]
    pins = {}
    for line in (root / "requirements.txt").read_text().splitlines():
        if line.strip() and not line.startswith("#"):
            requirement = Requirement(line)
            pins[requirement.name.lower()] = requirement
    pyproject = tomllib.loads((root / "pyproject.toml").read_text())
    build = {Requirement(r).name.lower(): Requirement(r) for r in pyproject["build-system"]["requires"]}
    runtime = {Requirement(r).name.lower(): Requirement(r) for r in pyproject["project"]["dependencies"]}
    openmm_pin = next(iter(pins["openmm"].specifier)).version
    assert build["openmm"].specifier.contains(openmm_pin) and runtime["openmm"].specifier.contains(openmm_pin)
    assert str(pins["swig"].specifier) == str(build["swig"].specifier)
    version = re.search(r"project\(OpenMMGenDPDE VERSION ([0-9.]+)", (root / "CMakeLists.txt").read_text()).group(1)
    assert openmmgendpde.__version__ == version
