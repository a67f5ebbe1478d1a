#!/usr/bin/env bash
# Renders the default scene (the built-in Cornell box) to cornell.exr and cornell.png in the
# repository root; extra arguments go to clppm (e.g. --passes 256, --device gpu). Works from any
# directory.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

./scripts/install-deps.sh
jobs=$(nproc 2>/dev/null || echo 2)
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
cmake --build build -j "$jobs" --target clppm
exec build/clppm -o cornell.exr "$@"
