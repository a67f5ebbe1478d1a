#!/bin/bash
# shellcheck disable=SC2086 # $common and the options are lists of words
# Two ways of rendering, A and B, at equal time: their error against one reference per scene.
# A way is a clppm binary and options (another build, other kernels by --kernel-dir, another
# --sampler ...). For each scene a reference (the path tracer, independent numbers, seed 777,
# REF_PASSES passes; cached under REF_DIR), then ROUNDS alternating runs of A and B for SECONDS_EACH
# each, a new seed every round, compared with `clppm compare --box 4`. Prints one row per run and
# the geometric means of B over A per scene; CPU time beside wall time (the machines are shared).
#   bench/ab_error.sh [BUILD_DIR]
#   env: A_LABEL, A_BIN (BUILD_DIR/clppm), A_OPTS; the same for B;
#        INTEGRATOR=pt, SCENES="cornell_diffuse ...", SECONDS_EACH=10, ROUNDS=3, REF_PASSES=40000,
#        SIZE=128, REF_DIR=/tmp/clppm-sampler-refs
# SCENES may name cornell_diffuse (the Cornell box without its two spheres) or glTF files; the
# path tracer must be unbiased on them (no caustics of small lights). bench/sampler.sh is this
# script with A = --sampler independent, B = --sampler sobol.
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$here/build}
bin=$build/clppm
a_label=${A_LABEL:-A} a_bin=${A_BIN:-$bin} a_opts=${A_OPTS:-}
b_label=${B_LABEL:-B} b_bin=${B_BIN:-$bin} b_opts=${B_OPTS:-}
integrator=${INTEGRATOR:-pt}
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
common="--width $size --height $size --quiet --no-png"
echo "$(nproc) cores, $(date -u +%F), ${size}x${size}, $integrator, $secs s per run, references of $ref_passes passes"
echo "A = $a_label: $a_bin $a_opts"
echo "B = $b_label: $b_bin $b_opts"
echo
echo "| scene | run | seed | CPU s | passes | mean ratio | box-4 relative MSE | p90 relative error |"
echo "|---|---|---:|---:|---:|---:|---:|---:|"
for scene in $scenes; do
  name=$(basename "$scene" .gltf)
  arg=$scene
  [ "$scene" = cornell_diffuse ] && arg="$out/cornell_diffuse.gltf"
  ref="$refdir/$name-$size-$ref_passes.exr"
  [ -f "$ref" ] || "$bin" "$arg" $common --integrator pt --sampler independent --seed 777 --passes "$ref_passes" -o "$ref"
  for r in $(seq 1 "$rounds"); do
    for which in a b; do
      if [ $which = a ]; then run_bin=$a_bin opts=$a_opts label=$a_label; else run_bin=$b_bin opts=$b_opts label=$b_label; fi
      /usr/bin/time -f "%U %S" -o "$out/time" "$run_bin" "$arg" $common --integrator "$integrator" $opts --seed "$r" \
        --time "$secs" -o "$out/run.exr" --stats-json "$out/run.json"
      python3 "$here/bench/run_row.py" "$out" "$name" "$label" "$r" "$run_bin" "$ref" | tee -a "$out/rows"
    done
  done
done
echo
echo "Geometric means over the rounds ($b_label / $a_label at equal time):"
python3 - "$out/rows" "$a_label" "$b_label" <<'PY'
import math, sys, collections
rows = [l.split("|")[1:-1] for l in open(sys.argv[1])]
a_label, b_label = sys.argv[2:4]
g = collections.defaultdict(list)
for r in rows:
    g[(r[0].strip(), r[1].strip())].append([float(x) for x in r[3:]])
def gm(v): return math.exp(sum(math.log(x) for x in v) / len(v))
print("| scene | passes/s ratio | box-4 MSE ratio | p90 ratio |")
print("|---|---:|---:|---:|")
for scene in dict.fromkeys(k[0] for k in g):
    a, b = g[(scene, a_label)], g[(scene, b_label)]
    col = lambda rows, k: gm([r[k] for r in rows])
    print("| %s | %.3f | %.3f | %.3f |" % (scene, col(b, 1) / col(a, 1), col(b, 3) / col(a, 3), col(b, 4) / col(a, 4)))
PY
