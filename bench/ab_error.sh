#!/bin/bash
# shellcheck disable=SC2086 # $common and the options are lists of words
# Two ways of rendering, A and B, at equal time (or at equal passes): their error against one
# reference per scene.
# A way is a clppm binary and options (another build, other kernels by --kernel-dir, another
# --sampler ...). For each scene a reference (the path tracer, independent numbers, seed 777,
# REF_PASSES passes; cached under REF_DIR), then ROUNDS alternating runs of A and B for SECONDS_EACH
# each (or, with PASSES, for each of those pass counts), a new seed every round from FIRST_SEED,
# compared with `clppm compare --box 4`. Prints one row per run and the geometric means of B over
# A per scene; CPU time beside wall time (the machines are shared).
#   bench/ab_error.sh [BUILD_DIR]
#   env: A_LABEL, A_BIN (BUILD_DIR/clppm), A_OPTS; the same for B;
#        INTEGRATOR=pt, SCENES="cornell_diffuse ...", SECONDS_EACH=10, ROUNDS=3, REF_PASSES=40000,
#        SIZE=128, REF_DIR=/tmp/clppm-sampler-refs, PASSES="" (e.g. "64 256": equal passes), FIRST_SEED=1
# SCENES may name cornell_diffuse (the Cornell box without its two spheres) or glTF files; the
# path tracer must be unbiased on them (no caustics of small lights). bench/sampler.sh is this
# script with A = --sampler independent, B = --sampler sobol; bench/zsobol.sh with sobol and zsobol
# at equal passes.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/bench_lib.sh"
bench_binary "${1:-}"
a_label=${A_LABEL:-A} a_bin=${A_BIN:-$bin} a_opts=${A_OPTS:-}
b_label=${B_LABEL:-B} b_bin=${B_BIN:-$bin} b_opts=${B_OPTS:-}
integrator=${INTEGRATOR:-pt}
scenes=${SCENES:-"cornell_diffuse bunny_100k doorway $bench_root/tests/data/env_outdoor.gltf"}
secs=${SECONDS_EACH:-10}
rounds=${ROUNDS:-3}
ref_passes=${REF_PASSES:-40000}
size=${SIZE:-128}
refdir=${REF_DIR:-/tmp/clppm-sampler-refs}
passes_list=${PASSES:-}
first_seed=${FIRST_SEED:-1}
budget="$secs s per run"
[ -n "$passes_list" ] && budget="equal passes ($passes_list)"
bench_scratch
common="--width $size --height $size --quiet --no-png"
echo "$(bench_machine), ${size}x${size}, $integrator, $budget, references of $ref_passes passes"
echo "A = $a_label: $a_bin $a_opts"
echo "B = $b_label: $b_bin $b_opts"
echo
echo "| scene | run | seed | CPU s | passes | mean ratio | box-4 relative MSE | p90 relative error | relative MSE |"
echo "|---|---|---:|---:|---:|---:|---:|---:|---:|"
for scene in $scenes; do
  use_scene "$scene"
  ref=$(pt_reference "$bin" "$scene" "$size" "$ref_passes" "$refdir")
  for passes in ${passes_list:-0}; do
    stop="--time $secs" row=$name
    [ "$passes" != 0 ] && stop="--passes $passes" row="$name, $passes passes"
    for r in $(seq "$first_seed" $((first_seed + rounds - 1))); do
      for which in a b; do
        if [ $which = a ]; then run_bin=$a_bin opts=$a_opts label=$a_label; else run_bin=$b_bin opts=$b_opts label=$b_label; fi
        /usr/bin/time -f "%U %S" -o "$out/time" "$run_bin" "$file" $common --integrator "$integrator" $opts \
          --seed "$r" $stop -o "$out/run.exr" --stats-json "$out/run.json"
        python3 "$bench_root/bench/run_row.py" "$out" "$row" "$label" "$r" "$run_bin" "$ref" | tee -a "$out/rows"
      done
    done
  done
done
echo
echo "Geometric means over the rounds ($b_label / $a_label, $budget):"
python3 - "$out/rows" "$a_label" "$b_label" <<'PY'
import math, sys, collections
rows = [l.split("|")[1:-1] for l in open(sys.argv[1])]
a_label, b_label = sys.argv[2:4]
g = collections.defaultdict(list)
for r in rows:
    g[(r[0].strip(), r[1].strip())].append([float(x) for x in r[3:]])
def gm(v): return math.exp(sum(math.log(x) for x in v) / len(v))
print("| scene | CPU s ratio | passes ratio | relative MSE ratio | box-4 MSE ratio | p90 ratio |")
print("|---|---:|---:|---:|---:|---:|")
for scene in dict.fromkeys(k[0] for k in g):
    a, b = g[(scene, a_label)], g[(scene, b_label)]
    ratio = lambda k: gm([r[k] for r in b]) / gm([r[k] for r in a])
    print("| %s | %.3f | %.3f | %.3f | %.3f | %.3f |" % (scene, ratio(0), ratio(1), ratio(5), ratio(3), ratio(4)))
PY
