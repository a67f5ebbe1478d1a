#!/bin/bash
# The path tracer's Sobol' points against independent random numbers at equal time (issue 36).
# For each scene a reference (the path tracer, independent numbers, another seed, REF_PASSES
# passes; cached under REF_DIR), then ROUNDS alternating runs of each sampler for SECONDS each, with
# a new seed every round, compared with `clppm compare --box 4`. Prints one row per run and the
# geometric means per scene; CPU time beside wall time (the machines are shared).
#   bench/sampler.sh [BUILD_DIR]   (env: SCENES="cornell_diffuse ...", SECONDS_EACH=10, ROUNDS=3,
#                                   REF_PASSES=40000, SIZE=128, REF_DIR=/tmp/clppm-sampler-refs)
# SCENES may name cornell_diffuse (the Cornell box without its two spheres) or glTF files; the
# path tracer must be unbiased on them (no caustics of small lights).
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
bin=${1:-$here/build}/clppm
scenes=${SCENES:-"cornell_diffuse $here/scenes/bunny_100k.gltf $here/scenes/doorway.gltf $here/tests/data/env_outdoor.gltf"}
secs=${SECONDS_EACH:-10}
rounds=${ROUNDS:-3}
ref_passes=${REF_PASSES:-40000}
size=${SIZE:-128}
refdir=${REF_DIR:-/tmp/clppm-sampler-refs}
mkdir -p "$refdir"
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
python3 "$here/bench/cornell_diffuse.py" "$here/scenes/cornell_box.gltf" "$out/cornell_diffuse.gltf"
common="--integrator pt --width $size --height $size --quiet --no-png"
echo "$(nproc) cores, $(date -u +%F), ${size}x${size}, $secs s per run, references of $ref_passes passes"
echo
echo "| scene | sampler | seed | CPU s | passes | mean ratio | box-4 relative MSE | p90 relative error |"
echo "|---|---|---:|---:|---:|---:|---:|---:|"
for scene in $scenes; do
  name=$(basename "$scene" .gltf)
  arg=$scene
  [ "$scene" = cornell_diffuse ] && arg="$out/cornell_diffuse.gltf"
  ref="$refdir/$name-$size-$ref_passes.exr"
  [ -f "$ref" ] || "$bin" "$arg" $common --sampler independent --seed 777 --passes "$ref_passes" -o "$ref"
  for r in $(seq 1 "$rounds"); do
    for sampler in independent sobol; do
      /usr/bin/time -f "%U %S" -o "$out/time" "$bin" "$arg" $common --sampler $sampler --seed $r --time "$secs" \
        -o "$out/run.exr" --stats-json "$out/run.json"
      python3 "$here/bench/run_row.py" "$out" "$name" "$sampler" "$r" "$bin" "$ref" | tee -a "$out/rows"
    done
  done
done
echo
echo "Geometric means over the rounds (sobol / independent at equal time):"
python3 - "$out/rows" <<'PY'
import math, sys, collections
rows = [l.split("|")[1:-1] for l in open(sys.argv[1])]
g = collections.defaultdict(list)
for r in rows:
    g[(r[0].strip(), r[1].strip())].append([float(x) for x in r[3:]])
def gm(v): return math.exp(sum(math.log(x) for x in v) / len(v))
print("| scene | passes/s ratio | box-4 MSE ratio | p90 ratio |")
print("|---|---:|---:|---:|")
for scene in dict.fromkeys(k[0] for k in g):
    i, s = g[(scene, "independent")], g[(scene, "sobol")]
    col = lambda rows, k: gm([r[k] for r in rows])
    print("| %s | %.3f | %.3f | %.3f |" % (scene, col(s, 1) / col(i, 1), col(s, 3) / col(i, 3), col(s, 4) / col(i, 4)))
PY
