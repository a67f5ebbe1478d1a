#!/usr/bin/env bash
# Static analysis of the host code with cppcheck (Debian 12: 2.10), with the checked-in
# suppressions in .cppcheck-suppressions (cppcheck allows no comments there, so the reasons are
# here). Exits non-zero on any finding.
#   useInitializationList: cl::Kernel and cl::Buffer are reference-counted handles; creating them
#     in the constructor body, one per line beside their kernel names, costs the same.
#   passedByValue (device_scene.cpp, test_util.h): the double 3-vectors of the host references
#     (24 bytes, trivially copyable) are passed by value on purpose, as pbrt-v4 passes Vector3f.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
jobs=$(nproc 2>/dev/null || echo 2)
cppcheck --quiet --error-exitcode=1 --std=c++17 --language=c++ -j "$jobs" \
  --enable=warning,performance,portability --inline-suppr \
  --suppressions-list=.cppcheck-suppressions \
  -I src -I kernels -DCL_TARGET_OPENCL_VERSION=120 -DCLPPM_SOURCE_DIR='"."' \
  src tests/test_util.cpp
echo "check_static: cppcheck found nothing in src/"
