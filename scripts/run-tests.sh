#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
# Every test: set up, build and install (scripts/setup.sh), then the style checks (ruff), the C++ tests (ctest) and
# the Python tests of every tier (pytest against the installed package; a plain `pytest` runs the fast tier only).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
# PoCL (OpenCL on the CPU) compiles kernels slowly: both test suites share one cache of compiled kernels.
export POCL_CACHE_DIR="${POCL_CACHE_DIR:-$PWD/build/pocl-cache}"
echo "== Style (ruff, pyproject.toml; clang-format, .clang-format)"
.venv/bin/ruff check --no-cache .
devtools/cpp_files.sh | xargs .venv/bin/clang-format --dry-run --Werror
echo "== C++ tests (ctest)"
# The C++ tests are separate processes that share nothing but the kernel cache: run them two (or one per core) at a
# time (cold cache, 2 cores: 223 s against 314 s one at a time, measured back to back).
ctest --test-dir build --output-on-failure -j "$(nproc)"
echo "== The LAMMPS package (lammps/build.sh: LAMMPS with MPI once, ~3.5 minutes on 2 cores, then the plugin)"
lammps/build.sh
# and with 64-bit atom IDs (-DLAMMPS_SIZES=bigbig, which LAMMPS asks contributions to build and run with): LAMMPS once,
# ~4 minutes on 2 cores, then the plugin; test_lammps_package runs it
lammps/build.sh --bigbig
echo "== Python tests (pytest)"
# The Python tests, one worker per core, each test file on one worker (its module fixtures made once): 317 s against
# 544 s in one process, on 2 cores.
# -m "": every tier (fast, validation, gpu, lammps; pyproject.toml's markers).
.venv/bin/python -m pytest -q -ra -m "" -n "$(nproc)" --dist loadfile python/tests
