#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
# Build openmm-gendpde's LAMMPS package: LAMMPS itself (Debian 12's source package, LAMMPS 29 Sep 2021 Update 2,
# lammps/fetch-source.sh) with MPI (Debian's Open MPI), the PLUGIN package and shared libraries, MOLECULE (bonds: the
# polymers' atom styles), plus DPD-REACT, MANYBODY and OPT for the benchmarks against LAMMPS's own styles; then the plugin gendpdeplugin.so
# (pair_style gendpde, fix gendpde; lammps/CMakeLists.txt). Everything goes into build/lammps/ (git-ignored):
#   build/lammps/source/   the LAMMPS source       build/lammps/lammps/lmp   the LAMMPS executable (MPI)
#   build/lammps/plugin/gendpdeplugin.so           the plugin (plugin load ...)
# Run again: a no-op or an incremental build (LAMMPS once: ~3.5 minutes on 2 cores). Prints the two paths.
#
# lammps/build.sh --bigbig: the same LAMMPS source and plugin with -DLAMMPS_SIZES=bigbig (64-bit atom IDs and image
# flags; LAMMPS asks every contribution to build and run so), MPI and the PLUGIN package only, into
# build/lammps-bigbig/{lammps,plugin} (LAMMPS once: ~4 minutes on 2 cores); the tests run the package there too.
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
sizes=smallbig
packages=(-DPKG_PLUGIN=on -DPKG_MOLECULE=on -DPKG_DPD-REACT=on -DPKG_MANYBODY=on -DPKG_OPT=on)
out=$root/build/lammps
if [ "${1:-}" = "--bigbig" ]; then
    sizes=bigbig
    packages=(-DPKG_PLUGIN=on)
    out=$root/build/lammps-bigbig
elif [ $# -gt 0 ]; then
    echo "usage: lammps/build.sh [--bigbig]" >&2
    exit 2
fi
missing=()
for package in libopenmpi-dev openmpi-bin xz-utils dpkg-dev; do
    dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed" || missing+=("$package")
done
if [ ${#missing[@]} -gt 0 ]; then
    echo "Installing Debian packages: ${missing[*]}" >&2
    sudo_prefix=()
    [ "$(id -u)" -eq 0 ] || sudo_prefix=(sudo)
    "${sudo_prefix[@]}" env DEBIAN_FRONTEND=noninteractive apt-get update -q > /dev/null
    "${sudo_prefix[@]}" env DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends \
        "${missing[@]}" > /dev/null
fi
mkdir -p "$out"
source_dir=$(lammps/fetch-source.sh "$root/build/lammps/source")
jobs=$(nproc)
# (configured again when the package list changes: a build tree made before MOLECULE was added gets it)
if [ ! -f "$out/lammps/CMakeCache.txt" ] || [ "$(cat "$out/lammps/packages.txt" 2>/dev/null)" != "${packages[*]}" ]; then
    echo "Configuring LAMMPS ($source_dir) into $out/lammps" >&2
    cmake -S "$source_dir/cmake" -B "$out/lammps" -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_FLAGS=-O2 \
        -DBUILD_MPI=on -DBUILD_OMP=off -DBUILD_SHARED_LIBS=on -DBUILD_TOOLS=off -DLAMMPS_SIZES=$sizes \
        "${packages[@]}" \
        -DWITH_JPEG=off -DWITH_PNG=off -DWITH_FFMPEG=off -DWITH_GZIP=off > "$out/lammps-configure.log" 2>&1 \
        || { tail -30 "$out/lammps-configure.log" >&2; exit 1; }
    echo "${packages[*]}" > "$out/lammps/packages.txt"
fi
echo "Building LAMMPS (log: $out/lammps-build.log)" >&2
cmake --build "$out/lammps" -j "$jobs" > "$out/lammps-build.log" 2>&1 \
    || { tail -30 "$out/lammps-build.log" >&2; exit 1; }
if [ ! -f "$out/plugin/CMakeCache.txt" ]; then
    cmake -S lammps -B "$out/plugin" -DLAMMPS_SOURCE_DIR="$source_dir" -DBUILD_MPI=on -DLAMMPS_SIZES=$sizes \
        -DBUILD_OMP=off > "$out/plugin-configure.log" 2>&1 || { tail -30 "$out/plugin-configure.log" >&2; exit 1; }
fi
echo "Building the plugin (log: $out/plugin-build.log)" >&2
cmake --build "$out/plugin" -j "$jobs" > "$out/plugin-build.log" 2>&1 \
    || { tail -30 "$out/plugin-build.log" >&2; exit 1; }
echo "$out/lammps/lmp"
echo "$out/plugin/gendpdeplugin.so"
