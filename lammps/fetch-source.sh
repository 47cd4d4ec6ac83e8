#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
# Fetch and unpack the LAMMPS source this package is built and tested against: Debian 12's source package lammps
# 20220106.git7586adbb6a+ds1 (LAMMPS "29 Sep 2021 - Update 2"), into DIRECTORY; check its version; print the path of
# the source tree. Usage: lammps/fetch-source.sh DIRECTORY. apt's deb-src lines are added if missing (root or sudo).
set -euo pipefail
directory=$(realpath -m "$1")
expected_version='"29 Sep 2021"'
expected_update='"Update 2"'
sudo_prefix=()
[ "$(id -u)" -eq 0 ] || sudo_prefix=(sudo)
mkdir -p "$directory"
cd "$directory"
if ! ls -d lammps-0~20220106*/cmake > /dev/null 2>&1; then
    # The source package needs deb-src lines; Debian 12's default sources file has only "Types: deb".
    if ! apt-get source --download-only -q lammps=20220106.git7586adbb6a+ds1-2 > /dev/null 2>&1; then
        "${sudo_prefix[@]}" sed -i 's/^Types: deb$/Types: deb deb-src/' /etc/apt/sources.list.d/debian.sources
        "${sudo_prefix[@]}" apt-get update -q > /dev/null
        apt-get source --download-only -q lammps=20220106.git7586adbb6a+ds1-2 > /dev/null
    fi
    tar xf lammps_20220106.git7586adbb6a+ds1.orig.tar.xz
fi
source_dir=$(ls -d "$directory"/lammps-0~20220106*/ | head -1)
version=$(sed -n 's/^#define LAMMPS_VERSION //p' "$source_dir/src/version.h")
update=$(sed -n 's/^#define LAMMPS_UPDATE //p' "$source_dir/src/version.h")
if [ "$version" != "$expected_version" ] || [ "$update" != "$expected_update" ]; then
    echo "lammps/fetch-source.sh: $source_dir is LAMMPS $version $update, not $expected_version $expected_update" >&2
    exit 1
fi
echo "${source_dir%/}"
