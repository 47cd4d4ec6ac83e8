#!/usr/bin/env bash
# Every test: set up and build (scripts/setup.sh), then the C++ tests (ctest) and the Python tests (pytest).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
echo "== C++ tests (ctest)"
ctest --test-dir build --output-on-failure -E '^python$'
echo "== Python tests (pytest)"
PYTHONPATH="$PWD/build/python" /usr/bin/python3 -m pytest -q -ra -p no:cacheprovider python/tests
