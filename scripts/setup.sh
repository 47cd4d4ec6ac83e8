#!/usr/bin/env bash
# Install what the plugin needs from Debian's repositories (only what is missing), then configure and build it in
# ./build. Safe to run again: a no-op install and an incremental build. Used by run-main.sh and run-tests.sh.
set -euo pipefail
cd "$(dirname "$0")/.."

PACKAGES=(cmake make g++ swig libopenmm-dev libopenmm-plugins python3-simtk python3-dev python3-numpy
          python3-pytest python3-mpmath python3-scipy python3-matplotlib python3-mdtraj)

missing=()
for package in "${PACKAGES[@]}"; do
    dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed" || missing+=("$package")
done
if [ ${#missing[@]} -gt 0 ]; then
    echo "Installing: ${missing[*]}"
    sudo_prefix=()
    [ "$(id -u)" -eq 0 ] || sudo_prefix=(sudo)
    "${sudo_prefix[@]}" env DEBIAN_FRONTEND=noninteractive apt-get update -q
    "${sudo_prefix[@]}" env DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends "${missing[@]}"
fi

# Only Debian's interpreter sees python3-simtk (another python3 may come first on PATH).
if ! /usr/bin/python3 -c "import openmm" 2>/dev/null; then
    echo "error: /usr/bin/python3 cannot import openmm (Debian package python3-simtk)" >&2
    exit 1
fi

cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DPython3_EXECUTABLE=/usr/bin/python3 > build.log 2>&1 \
    || { cat build.log >&2; exit 1; }
cmake --build build -j "$(nproc)" >> build.log 2>&1 || { tail -n 60 build.log >&2; exit 1; }
echo "Built in ./build (log: build.log)"
