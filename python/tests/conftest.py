# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""Shared pytest configuration: the installed plugin (pip install .), every platform named explicitly."""

import openmm
import pytest

#: The platforms this plugin runs on that are present here (never rely on OpenMM's default choice: with
#: pocl-opencl-icd installed, OpenCL would be picked).
AVAILABLE = [openmm.Platform.getPlatform(i).getName() for i in range(openmm.Platform.getNumPlatforms())]
#: The GPU platforms (OpenCL is PoCL on a machine without a GPU: slow to compile, so few and small cases).
GPU_PLATFORMS = [name for name in ("OpenCL", "CUDA") if name in AVAILABLE]
PLATFORMS = [name for name in ("Reference", "CPU") if name in AVAILABLE] + GPU_PLATFORMS
# The GPU platforms' default precision here is double, so that the shared tests' tolerances apply to them; the
# single and mixed precisions are compared with Reference in test_gpu_platforms.py.
for _name in GPU_PLATFORMS:
    openmm.Platform.getPlatformByName(_name).setPropertyDefaultValue("Precision", "double")


#: PLATFORMS as parameters of a test: the GPU platforms' cases in the gpu tier (pyproject.toml's markers).
PLATFORM_PARAMETERS = [pytest.param(name, marks=pytest.mark.gpu) if name in GPU_PLATFORMS else name
                       for name in PLATFORMS]


@pytest.fixture(params=PLATFORM_PARAMETERS)
def platform(request):
    return openmm.Platform.getPlatformByName(request.param)
