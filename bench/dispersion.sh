#!/usr/bin/env bash
# What dispersion costs per pass (issue 37): scenes/dispersion_box.gltf (a dispersive glass sphere,
# KHR_materials_dispersion 2) against tests/data/dispersion_box_plain.gltf (the same sphere without
# dispersion, kernels built without HAS_DISPERSION) at the default size, each integrator, runs of
# SECONDS s alternating plain / dispersive ROUNDS times; passes/s from --stats-json and CPU
# seconds. Prints one line per run and the medians.
# Usage: bench/dispersion.sh [BUILD_DIR] [ROUNDS] [SECONDS]
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
bin=$(cd "${1:-$here/build}" && pwd)/clppm
rounds=${2:-2} seconds=${3:-10}
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
echo "$(nproc) cores; $(date -u +%F)"
for integ in sppm pppm ppm pt vcm bpt; do
  for ((r = 0; r < rounds; ++r)); do
    for which in plain dispersive; do
      scene=$here/scenes/dispersion_box.gltf
      [[ $which == plain ]] && scene=$here/tests/data/dispersion_box_plain.gltf
      /usr/bin/time -f "%U %S" -o "$dir/time" "$bin" "$scene" --integrator "$integ" --time "$seconds" --quiet \
        --no-png -o "$dir/x.exr" --stats-json "$dir/s.json"
      pps=$(python3 -c "import json; print(json.load(open('$dir/s.json'))['passes_per_second'])")
      echo "$integ $which $pps $(awk '{print $1 + $2}' "$dir/time")"
    done
  done
done | tee "$dir/runs"
python3 - "$dir/runs" <<'PY'
import statistics, sys
runs = {}
for line in open(sys.argv[1]):
    integ, which, pps, cpu = line.split()
    runs.setdefault(integ, {}).setdefault(which, []).append(float(pps))
print("\n| integrator | plain passes/s | dispersive passes/s | ratio |\n|---|---:|---:|---:|")
for integ, r in runs.items():
    p, d = statistics.median(r["plain"]), statistics.median(r["dispersive"])
    print(f"| {integ} | {p:.2f} | {d:.2f} | {d / p:.3f} |")
PY
