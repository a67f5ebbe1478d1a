#!/usr/bin/env bash
# The test command (README, .ci/run): installs dependencies, builds Release into build/ and runs
# the whole suite with ctest; exits with ctest's status. Works from any directory.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

./scripts/install-deps.sh
jobs=$(nproc 2>/dev/null || echo 2)
# The Python module is built for, and tested with, Debian's python3 (its numpy and pytest come
# from install-deps.sh), whatever python3 comes first on PATH.
python=/usr/bin/python3
[[ -x $python ]] || python=$(command -v python3)
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DPython_EXECUTABLE="$python"
cmake --build build -j "$jobs"
# Generous: rendering tests run on PoCL's CPU device, which is slow on small machines.
exec ctest --test-dir build --output-on-failure -j "$jobs" --timeout 1800
