#!/usr/bin/env bash
# The path tracer's passes several to a launch (integrators/pt_integrator.h) against one launch a
# pass (CLPPM_PASS_BATCH=1), on the diffuse Cornell box, the asset under the default world and
# under directional lights, and the doorway, at 128x128 and 256x256: the same passes each way,
# rounds interleaved, wall and CPU seconds (GNU time) and the images compared bit for bit.
#
#   bench/pass_batching.sh [BUILD_DIR]   (env: ROUNDS=3, SAMPLES=26214400 pixel samples a run)
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/bench_lib.sh"
bench_binary "${1:-}"
rounds=${ROUNDS:-3}
samples=${SAMPLES:-26214400}
bench_scratch
tmp=$out
echo "| scene | size | passes | batched wall s | one a launch wall s | batched CPU s | one a launch CPU s | launches | same image |"
echo "|---|---|---:|---:|---:|---:|---:|---:|---|"
for scene in cornell_diffuse asset_env asset_sun doorway; do
  use_scene "$scene"
  for size in 128 256; do
    passes=$((samples / (size * size)))
    args=("$file" --integrator pt --width "$size" --height "$size" --passes "$passes" --quiet --no-png)
    declare -A wall=() cpu=()
    for r in $(seq "$rounds"); do
      for mode in batched single; do
        env=()
        [ "$mode" = single ] && env=(CLPPM_PASS_BATCH=1)
        /usr/bin/time -f "%e %U %S" -o "$tmp/time" env "${env[@]}" "$build/clppm" "${args[@]}" \
          -o "$tmp/$mode.exr" --stats-json "$tmp/$mode.json"
        read -r w u s < "$tmp/time"
        wall[$mode]="${wall[$mode]:-} $w"
        cpu[$mode]="${cpu[$mode]:-} $(python3 -c "print($u + $s)")"
      done
    done
    launches=$(python3 -c "import json; print(json.load(open('$tmp/batched.json'))['pass_launches'])")
    same=no
    cmp -s "$tmp/batched.exr" "$tmp/single.exr" && same=yes
    python3 - "$scene" "$size" "$passes" "${wall[batched]}" "${wall[single]}" "${cpu[batched]}" "${cpu[single]}" \
      "$launches" "$same" <<'EOF'
import statistics, sys
s, size, passes, wb, ws, cb, cs, launches, same = sys.argv[1:]
med = lambda v: statistics.median(float(x) for x in v.split())
print("| %s | %s | %s | %.2f | %.2f | %.2f | %.2f | %s | %s |"
      % (s, size, passes, med(wb), med(ws), med(cb), med(cs), launches, same))
EOF
  done
done
