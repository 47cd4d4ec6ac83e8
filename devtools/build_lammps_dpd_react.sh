#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
# Build LAMMPS (Debian 12's source package, 20220106) with the DPD-REACT package, for benchmarks/compare_lammps_dpde.py:
# Debian's binary package lacks DPD-REACT. Packages DPD-REACT, MANYBODY, OPT and OPENMP; no MPI (threads only);
# -O2. About 4 minutes on 2 cores. Usage: devtools/build_lammps_dpd_react.sh [DIRECTORY] (default /tmp/lammps-dpd-react);
# prints the path of the lmp executable.
set -euo pipefail
directory=$(realpath -m "${1:-/tmp/lammps-dpd-react}")
source_dir=$("$(dirname "$0")/../lammps/fetch-source.sh" "$directory")
cd "$directory"
mkdir -p build
# CMAKE_DISABLE_FIND_PACKAGE_MPI: with openmpi-bin but not its headers installed, LAMMPS's MPI probe fails.
cmake -S "$source_dir/cmake" -B build -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_FLAGS=-O2 \
    -DCMAKE_DISABLE_FIND_PACKAGE_MPI=ON -DBUILD_MPI=off -DBUILD_OMP=on -DBUILD_TOOLS=off \
    -DPKG_DPD-REACT=on -DPKG_MANYBODY=on -DPKG_OPT=on -DPKG_OPENMP=on \
    -DWITH_JPEG=off -DWITH_PNG=off -DWITH_FFMPEG=off -DWITH_GZIP=off > build/configure.log 2>&1
cmake --build build -j "$(nproc)" > build/build.log 2>&1
echo "$directory/build/lmp"
