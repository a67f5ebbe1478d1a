#!/usr/bin/env bash
# The library from several threads under ThreadSanitizer (issue 61): tests/library_threads_test.cpp
# (eight renders at once, every integrator; a render's own cancel) in a build with
# -fsanitize=thread (build-tsan/, only that test and the library). Any report of a data race in our
# code fails it. PoCL, the ICD loader and LLVM are not instrumented: what TSan cannot see inside
# them (their worker threads' writes into our buffers, ordered by clFinish) is suppressed by
# library in scripts/tsan.supp, never by a function of ours.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
jobs=$(nproc 2>/dev/null || echo 2)
cmake -S . -B build-tsan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCLPPM_SANITIZE_THREAD=ON -DCLPPM_BUILD_BENCH=OFF \
  -DCLPPM_MPI=OFF -DCLPPM_PYTHON=OFF >/dev/null
cmake --build build-tsan -j "$jobs" --target library_threads_test
export TSAN_OPTIONS="halt_on_error=1:second_deadlock_stack=1:suppressions=$PWD/scripts/tsan.supp"
exec build-tsan/tests/library_threads_test
