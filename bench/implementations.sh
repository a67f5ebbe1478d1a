#!/usr/bin/env bash
# Every integrator's speed on every CPU OpenCL implementation here, side by side (issue 58): PoCL
# and Intel's CPU runtime (installed from PyPI into BUILD_DIR/intel-opencl by
# scripts/intel_opencl_env.sh), on the Cornell box and the diffuse box at 128x128, SECONDS of
# rendering a run, rounds interleaved. Prints a Markdown table of passes per second (median of the
# rounds, from --stats-json) and CPU seconds per pass (GNU time, user + system), and the ratio of
# each implementation to PoCL.
#
#   bench/implementations.sh [BUILD_DIR]   (env: ROUNDS=3, SECONDS_PER_RUN=8, INTEGRATORS="ppm sppm pppm pt vcm bpt")
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/bench_lib.sh"
bench_binary "${1:-}"
rounds=${ROUNDS:-3}
seconds=${SECONDS_PER_RUN:-8}
integrators=${INTEGRATORS:-ppm sppm pppm pt vcm bpt}
set +e
source "$bench_root/scripts/intel_opencl_env.sh" "$build" || exit $?
set -e
bench_scratch
tmp=$out
devices=(pocl "Intel(R) OpenCL")
echo "machine: $(bench_machine)"
echo
echo "| scene | integrator | PoCL passes/s | Intel passes/s | Intel / PoCL | PoCL CPU s/pass | Intel CPU s/pass |"
echo "|---|---|---:|---:|---:|---:|---:|"
for scene in cornell_box cornell_diffuse; do
  use_scene "$scene"
  for integrator in $integrators; do
    declare -A pps=() cpu=()
    for r in $(seq "$rounds"); do
      for k in 0 1; do
        /usr/bin/time -f "%U %S" -o "$tmp/time" "$build/clppm" "$file" --device "${devices[$k]}" \
          --integrator "$integrator" --width 128 --height 128 --time "$seconds" --quiet --no-png \
          -o "$tmp/out.exr" --stats-json "$tmp/stats.json"
        read -r u s <"$tmp/time"
        read -r p n < <(python3 -c "import json; j = json.load(open('$tmp/stats.json')); print(j['passes_per_second'], j['passes'])")
        pps[$k]="${pps[$k]:-} $p"
        cpu[$k]="${cpu[$k]:-} $(python3 -c "print(($u + $s) / max($n, 1))")"
      done
    done
    python3 - "$scene" "$integrator" "${pps[0]}" "${pps[1]}" "${cpu[0]}" "${cpu[1]}" <<'EOF'
import statistics, sys
scene, integ = sys.argv[1:3]
p0, p1, c0, c1 = (statistics.median(map(float, a.split())) for a in sys.argv[3:7])
print(f"| {scene} | {integ} | {p0:.2f} | {p1:.2f} | {p1 / p0:.2f} | {c0:.4f} | {c1:.4f} |")
EOF
  done
done
