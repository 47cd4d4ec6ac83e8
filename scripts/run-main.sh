#!/usr/bin/env bash
# The main job: set up and build (scripts/setup.sh), then evaluate liquid argon with the VA and VB estimators.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
PYTHONPATH="$PWD/build/python" /usr/bin/python3 examples/argon_state_point.py "$@"
