"""Shared pytest configuration: run against the build tree and name every platform explicitly."""

import pathlib
import sys

import openmm
import pytest

try:
    import openmmgendpde  # noqa: F401  (PYTHONPATH=build/python, as the README's test command sets)
except ImportError:
    sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[2] / "build" / "python"))
    import openmmgendpde  # noqa: F401

#: The platforms this plugin runs on that are present here (never rely on OpenMM's default choice: with
#: pocl-opencl-icd installed, OpenCL would be picked).
PLATFORMS = [name for name in ("Reference", "CPU")
             if name in [openmm.Platform.getPlatform(i).getName() for i in range(openmm.Platform.getNumPlatforms())]]


@pytest.fixture(params=PLATFORMS)
def platform(request):
    return openmm.Platform.getPlatformByName(request.param)
