#!/bin/bash
# Visual importance for photons (--visual-importance, Hachisuka and Jensen 2009) against
# independent photons at equal time (issue 36), with the path tracer and VCM beside them.
# For each scene a reference (the path tracer, another seed, REF_PASSES passes, or REF_<name>=FILE;
# cached under REF_DIR), then ROUNDS rounds of every method for SECONDS each, a new seed every
# round, compared with `clppm compare --box 4`. Prints one row per run and the geometric means
# per scene and method; CPU time beside wall time (the machines are shared).
#   bench/visual_importance.sh [BUILD_DIR]   (env: SCENES="skylight doorway", SECONDS_EACH=30,
#                                            ROUNDS=2, REF_PASSES=100000, SIZE=128,
#                                            REF_DIR=/tmp/clppm-vi-refs)
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
bin=${1:-$here/build}/clppm
scenes=${SCENES:-"skylight doorway"}
secs=${SECONDS_EACH:-30}
rounds=${ROUNDS:-2}
ref_passes=${REF_PASSES:-100000}
size=${SIZE:-128}
refdir=${REF_DIR:-/tmp/clppm-vi-refs}
mkdir -p "$refdir"
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
common="--width $size --height $size --quiet --no-png"
methods="sppm sppm+vi ppm ppm+vi pt vcm"
echo "$(nproc) cores, $(date -u +%F), ${size}x${size}, $secs s per run, references: the path tracer, $ref_passes passes"
echo
echo "| scene | method | seed | wall s | CPU s | passes | mean ratio | box-4 relative MSE | p90 relative error | relative MSE |"
echo "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|"
for name in $scenes; do
  scene="$here/scenes/$name.gltf"
  var="REF_$name"
  ref=${!var:-$refdir/$name-$size-pt-$ref_passes.exr}
  [ -f "$ref" ] || "$bin" "$scene" $common --integrator pt --seed 777 --passes "$ref_passes" -o "$ref"
  for r in $(seq 1 "$rounds"); do
    for m in $methods; do
      args="--integrator ${m%+vi}"
      [ "$m" != "${m%+vi}" ] && args="$args --visual-importance"
      /usr/bin/time -f "%U %S" -o "$out/time" "$bin" "$scene" $common $args --seed $r --time "$secs" \
        -o "$out/run.exr" --stats-json "$out/run.json"
      python3 "$here/bench/run_row.py" "$out" "$name" "$m" "$r" "$bin" "$ref" --wall | tee -a "$out/rows"
    done
  done
done
echo
echo "Geometric means over the rounds; MSE x CPU s compares methods at equal error (error ~ 1/time):"
python3 - "$out/rows" <<'PY'
import math, sys, collections
rows = [l.split("|")[1:-1] for l in open(sys.argv[1])]
g = collections.defaultdict(list)
for r in rows:
    g[(r[0].strip(), r[1].strip())].append([float(x) for x in r[3:]])
def gm(v): return math.exp(sum(math.log(x) for x in v) / len(v))
print("| scene | method | box-4 MSE | p90 | MSE x CPU s | vs sppm |")
print("|---|---|---:|---:|---:|---:|")
for scene in dict.fromkeys(k[0] for k in g):
    base = None
    for (s, m), v in g.items():
        if s != scene: continue
        mse, p90, cpu = gm([x[4] for x in v]), gm([x[5] for x in v]), gm([x[1] for x in v])
        if m == "sppm": base = mse * cpu
        print("| %s | %s | %.3e | %.4f | %.3e | %s |" % (scene, m, mse, p90, mse * cpu,
              "%.3f" % (mse * cpu / base) if base else "-"))
PY
