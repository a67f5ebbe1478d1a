#!/usr/bin/env bash
# Passes per second of every integrator, two clppm binaries alternating (A B A B ...), on the
# default scene at its default size, each run 10 s of rendering: for "no change may slow passes/s
# by more than 3%" (README, bench/RESULTS.md). Prints one line per run (passes/s from
# --stats-json, CPU seconds) and the medians per binary and integrator. Runs of a second or two
# differ by 15% here from one to the next; 10 s runs by a few percent.
# Usage: bench/ab_passes.sh OLD_CLPPM NEW_CLPPM [ROUNDS] [extra clppm options]
set -euo pipefail
a=$1 b=$2 rounds=${3:-3}
shift $(( $# < 3 ? $# : 3 ))
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
for integ in ppm sppm pppm pt vcm bpt; do
  for ((r = 0; r < rounds; ++r)); do
    for which in A B; do
      bin=$a; [[ $which == B ]] && bin=$b
      /usr/bin/time -f "%U %S" -o "$dir/time" "$bin" --integrator "$integ" --time 10 --quiet --no-png \
        -o "$dir/x.exr" --stats-json "$dir/s.json" "$@"
      pps=$(python3 -c "import json; print(json.load(open('$dir/s.json'))['passes_per_second'])")
      cpu=$(awk '{print $1 + $2}' "$dir/time")
      echo "$integ $which $pps $cpu"
    done
  done
done | tee "$dir/runs" | awk '{print}'
python3 - "$dir/runs" <<'PY'
import statistics, sys
runs = {}
for line in open(sys.argv[1]):
    integ, which, pps, cpu = line.split()
    runs.setdefault(integ, {}).setdefault(which, []).append(float(pps))
print("integrator  A passes/s  B passes/s  B/A (medians)")
for integ, r in runs.items():
    a, b = statistics.median(r["A"]), statistics.median(r["B"])
    print(f"{integ:10s}  {a:10.3f}  {b:10.3f}  {b / a:.3f}")
PY
