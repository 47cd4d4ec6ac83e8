"""Shared pytest configuration: the installed plugin (pip install .), every platform named explicitly."""

import openmm
import pytest

#: The platforms this plugin runs on that are present here (never rely on OpenMM's default choice: with
#: pocl-opencl-icd installed, OpenCL would be picked).
PLATFORMS = [name for name in ("Reference", "CPU")
             if name in [openmm.Platform.getPlatform(i).getName() for i in range(openmm.Platform.getNumPlatforms())]]


@pytest.fixture(params=PLATFORMS)
def platform(request):
    return openmm.Platform.getPlatformByName(request.param)
