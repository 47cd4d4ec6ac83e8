#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
# Set up everything the plugin needs on a Debian 12 machine, then build and install it into ./.venv. Safe to run
# again: a no-op install, an incremental build. Used by run-main.sh and run-tests.sh.
#   1. Debian packages (only the missing ones): compilers, CMake, OpenCL ICD loader, headers and PoCL.
#   2. .venv (python3 -m venv) with the pinned Python packages of requirements.txt (OpenMM 8.6.1 from PyPI).
#   3. Where a CUDA toolkit is installed, OpenMM's CUDA platform library to build against (openmm-cuda-13, unpacked).
#   4. pip install . into .venv (scikit-build-core drives CMake; build tree ./build, C++ tests included; log in
#      build.log): libraries into OpenMM's directories, the Python package into site-packages.
set -euo pipefail
cd "$(dirname "$0")/.."

PACKAGES=(g++ make cmake ocl-icd-opencl-dev opencl-c-headers pocl-opencl-icd clinfo)
# A python3 without venv or headers is Debian's own: add its packages.
python3 -c "import ensurepip, os, sysconfig; assert os.path.exists(sysconfig.get_paths()['include'] + '/Python.h')" \
    2>/dev/null || PACKAGES+=(python3-venv python3-dev)
missing=()
for package in "${PACKAGES[@]}"; do
    dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed" || missing+=("$package")
done
if [ ${#missing[@]} -gt 0 ]; then
    echo "Installing Debian packages: ${missing[*]}"
    sudo_prefix=()
    [ "$(id -u)" -eq 0 ] || sudo_prefix=(sudo)
    "${sudo_prefix[@]}" env DEBIAN_FRONTEND=noninteractive apt-get update -q
    "${sudo_prefix[@]}" env DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends "${missing[@]}"
fi

if [ ! -x .venv/bin/python ]; then
    echo "Creating .venv"
    python3 -m venv .venv
fi
# Reinstall the pinned packages only when requirements.txt changed.
stamp=.venv/.requirements.sha256
if ! sha256sum --status -c "$stamp" 2>/dev/null; then
    echo "Installing the pinned Python packages (requirements.txt) into .venv"
    .venv/bin/python -m pip install -q --disable-pip-version-check -r requirements.txt
    sha256sum requirements.txt > "$stamp"
fi

# OpenMM's CUDA platform library, to build the CUDA kernel library against where a CUDA toolkit is installed (its
# headers and driver stub suffice; nothing CUDA runs without a GPU): the openmm-cuda-13 wheel of the pinned OpenMM,
# unpacked into .venv without its ~1 GB of NVIDIA runtime wheels, fetched once.
cuda_args=()
if [ -e /usr/local/cuda/include/cuda.h ]; then
    openmm_version=$(sed -n 's/^openmm==\([0-9.]*\).*/\1/p' requirements.txt)
    cuda_dir=.venv/openmm-cuda-13-$openmm_version
    if [ ! -e "$cuda_dir/OpenMM.libs/lib/plugins/libOpenMMCUDA.so" ]; then
        echo "Fetching openmm-cuda-13==$openmm_version (to build the CUDA kernel library against)"
        if .venv/bin/python -m pip download -q --no-deps --disable-pip-version-check \
                "openmm-cuda-13==$openmm_version" -d "$cuda_dir.download"; then
            .venv/bin/python -m zipfile -e "$cuda_dir.download"/openmm_cuda_13-*.whl "$cuda_dir"
        else
            echo "No openmm-cuda-13 wheel: the CUDA kernel library is not built" >&2
        fi
    fi
    cuda_args=(-C "cmake.define.GENDPDE_OPENMM_CUDA_DIR=$PWD/$cuda_dir")
fi
# Build against the OpenMM in .venv (no build isolation) with the C++ tests, and install.
if ! .venv/bin/python -m pip install --disable-pip-version-check --no-build-isolation --no-deps \
        -C build-dir=build -C cmake.define.GENDPDE_BUILD_TESTS=ON "${cuda_args[@]}" . > build.log 2>&1; then
    tail -n 60 build.log >&2
    exit 1
fi
echo "Built in ./build and installed into .venv (log: build.log)"
