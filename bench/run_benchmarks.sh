#!/usr/bin/env bash
# Runs every benchmark and collects their outputs in one folder.
#   bench/run_benchmarks.sh [--quick] [OUT_DIR]
# --quick: a smoke run of each program (under a minute; the test suite runs it as bench_smoke).
# Without it: the full run behind bench/RESULTS.md (about 35 minutes on a 2-core CPU with PoCL).
# The binaries are taken from $CLPPM_BENCH_BIN; without it the script installs the dependencies
# and builds them in build/ (Release) first, as scripts/render.sh builds clppm, so it works right
# after the README's render command (measured on the 2-core machine: building the first three
# benchmarks on top of a built clppm takes 13 s and shading_simd 4 s more; the quick run takes 19 to
# 21 s with the kernel cache warm).
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
quick=""
if [[ ${1:-} == --quick ]]; then quick=--quick; shift; fi
if [[ -n ${CLPPM_BENCH_BIN:-} ]]; then
  bin=$CLPPM_BENCH_BIN
else
  "$root/scripts/install-deps.sh"
  cmake -S "$root" -B "$root/build" -DCMAKE_BUILD_TYPE=Release > /dev/null
  cmake --build "$root/build" -j "$(nproc 2>/dev/null || echo 2)" --target traversal_bench throughput_bench convergence_bench shading_simd
  bin=$root/build/bench
fi
out=${1:-$root/build/bench-results}
mkdir -p "$out"
start=$(date +%s)

if [[ -n $quick ]]; then
  "$bin/traversal_bench" --quick --rays 20000 --json "$out/traversal.json" > "$out/traversal.txt"
  "$bin/throughput_bench" --quick --out "$out" > /dev/null
  "$bin/convergence_bench" --quick --out "$out" > /dev/null
  python3 "$root/bench/cornell_diffuse.py" "$root/scenes/cornell_box.gltf" "$out/cornell_diffuse.gltf"
  "$bin/shading_simd" "$out/cornell_diffuse.gltf" --size 64 --reps 2 --rounds 1 > "$out/shading_simd.md"
  for f in traversal.json throughput.json throughput.md convergence_cornell_box.csv convergence_cornell_box.md \
    shading_simd.md; do
    [[ -s $out/$f ]] || { echo "run_benchmarks: $out/$f missing or empty" >&2; exit 1; }
  done
else
  "$bin/traversal_bench" --json "$out/traversal.json" | tee "$out/traversal.txt"
  "$bin/throughput_bench" --out "$out" | tee "$out/throughput_stdout.md"
  "$bin/convergence_bench" --scene cornell_box --size 128 --seconds 32 --reference-seconds 400 --out "$out"
  "$bin/convergence_bench" --scene caustic --size 128 --seconds 32 --reference-seconds 400 --out "$out"
  python3 "$root/bench/cornell_diffuse.py" "$root/scenes/cornell_box.gltf" "$out/cornell_diffuse.gltf"
  "$bin/shading_simd" "$out/cornell_diffuse.gltf" | tee "$out/shading_simd.md"
fi
echo "run_benchmarks: done in $(( $(date +%s) - start )) s, results in $out"
