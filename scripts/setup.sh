#!/usr/bin/env bash
# Set up everything the plugin needs on a Debian 12 machine, then build and install it into ./.venv. Safe to run
# again: a no-op install, an incremental build. Used by run-main.sh and run-tests.sh.
#   1. Debian packages (only the missing ones): compilers, CMake, OpenCL ICD loader, headers and PoCL.
#   2. .venv (python3 -m venv) with the pinned Python packages of requirements.txt (OpenMM 8.6.1 from PyPI).
#   3. pip install . into .venv (scikit-build-core drives CMake; build tree ./build, C++ tests included; log in
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

# Build against the OpenMM in .venv (no build isolation) with the C++ tests, and install.
if ! .venv/bin/python -m pip install --disable-pip-version-check --no-build-isolation --no-deps \
        -C build-dir=build -C cmake.define.GENDPDE_BUILD_TESTS=ON . > build.log 2>&1; then
    tail -n 60 build.log >&2
    exit 1
fi
echo "Built in ./build and installed into .venv (log: build.log)"
