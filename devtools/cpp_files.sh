#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
# The C++ sources that clang-format keeps in the project's style (.clang-format): every tracked .h and .cpp but the
# generated tables (VolumeVBTables.h, devtools/generate_vb_tables.py writes it) and the device kernels
# (platforms/common/src/kernels/*.cc: OpenMM's common dialect, embedded as text). One path a line.
#   devtools/cpp_files.sh | xargs .venv/bin/clang-format -i            # format them
#   devtools/cpp_files.sh | xargs .venv/bin/clang-format --dry-run --Werror   # check (scripts/run-tests.sh)
set -euo pipefail
cd "$(dirname "$0")/.."
git ls-files '*.h' '*.cpp' | grep -v -e '^platforms/common/src/kernels/' -e 'gendpde/VolumeVBTables\.h$'
