#!/bin/bash
# shellcheck disable=SC2086 # $common is a list of words
# --sampler zsobol against --sampler sobol at equal passes (the layout costs nothing per pass, so
# equal passes is equal time): the per-pixel and the box-4 relative MSE against one reference per
# scene, for ROUNDS seeds at each pass count, and the geometric means of zsobol over sobol.
#   bench/zsobol.sh [BUILD_DIR]
#   env: SCENES="cornell_diffuse tests/data/env_outdoor.gltf", PASSES="64 256 1024", ROUNDS=4,
#        SIZE=128, REF_PASSES=40000, REF_DIR=/tmp/clppm-sampler-refs (shared with bench/ab_error.sh)
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
bin=${1:-$here/build}/clppm
scenes=${SCENES:-"cornell_diffuse $here/tests/data/env_outdoor.gltf"}
passes_list=${PASSES:-"64 256 1024"}
rounds=${ROUNDS:-4}
size=${SIZE:-128}
ref_passes=${REF_PASSES:-40000}
refdir=${REF_DIR:-/tmp/clppm-sampler-refs}
mkdir -p "$refdir"
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
python3 "$here/bench/cornell_diffuse.py" "$here/scenes/cornell_box.gltf" "$out/cornell_diffuse.gltf"
common="--width $size --height $size --quiet --no-png --integrator pt"
echo "$(nproc) cores, $(date -u +%F), ${size}x${size}, references of $ref_passes passes"
echo "| scene | passes | seed | sampler | CPU s | relative MSE | box-4 relative MSE |"
echo "|---|---:|---:|---|---:|---:|---:|"
for scene in $scenes; do
  name=$(basename "$scene" .gltf)
  arg=$scene
  [ "$scene" = cornell_diffuse ] && arg="$out/cornell_diffuse.gltf"
  ref="$refdir/$name-$size-$ref_passes.exr"
  [ -f "$ref" ] || "$bin" "$arg" $common --sampler independent --seed 777 --passes "$ref_passes" -o "$ref"
  for p in $passes_list; do
    for r in $(seq 11 $((10 + rounds))); do
      for sampler in sobol zsobol; do
        /usr/bin/time -f "%U %S" -o "$out/time" "$bin" "$arg" $common --sampler $sampler --seed "$r" --passes "$p" \
          -o "$out/run.exr"
        cpu=$(awk '{print $1 + $2}' "$out/time")
        "$bin" compare "$out/run.exr" "$ref" --box 4 >"$out/cmp.json"
        python3 -c 'import json, sys; j = json.load(open(sys.argv[1])); print("| %s | %s | %s | %s | %s | %.3e | %.3e |" % (*sys.argv[2:7], j["rel_mse"], j["box_rel_mse"]))' \
          "$out/cmp.json" "$name" "$p" "$r" "$sampler" "$cpu" | tee -a "$out/rows"
      done
    done
  done
done
echo
echo "Geometric means, zsobol / sobol at equal passes (relative MSE, box-4 relative MSE):"
python3 - "$out/rows" <<'PY'
import collections, math, sys
v = collections.defaultdict(list)
for line in open(sys.argv[1]):
    c = [x.strip() for x in line.split("|")[1:-1]]
    v[(c[0], int(c[1]), c[3])].append((float(c[5]), float(c[6])))
g = lambda xs: math.exp(sum(math.log(x) for x in xs) / len(xs))
for (scene, p, s) in sorted(k for k in v if k[2] == "sobol"):
    a, b = v[(scene, p, "sobol")], v[(scene, p, "zsobol")]
    print("%s, %d passes: %.2f, %.2f" % (scene, p, g([x[0] for x in b]) / g([x[0] for x in a]),
                                         g([x[1] for x in b]) / g([x[1] for x in a])))
PY
