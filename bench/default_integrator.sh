#!/bin/bash
# Which integrator, with every other setting at its command-line default, reaches a given error
# first (issue 16: the default integrator by measurement). For each scene, a reference (SPPM, or
# the path tracer where no photon is needed: a scene lit only by its environment) of REF_SECONDS,
# then each integrator for each of TIMES seconds at 128x128, compared with `clppm compare --box 4`:
# the mean ratio, the box-4 relative MSE (bias more than noise) and p90_rel_error (the measure
# --target-error states). CPU time is reported with the wall time: these machines are shared.
#   bench/default_integrator.sh [BUILD_DIR]   (env: TIMES="10 30", REF_SECONDS=240, SCENES=...,
#   INTEGRATORS="ppm sppm pppm pt vcm bpt auto", REFS=sppm|pt|unbiased, REF_DIR=...)
# SCENES may name cornell_box (scenes/cornell_box.gltf, the built-in default), cornell_diffuse (the same box without its two
# spheres: diffuse only), asset_env or asset_sun (bench/asset_scenes.py) or glTF files. References: SPPM, and the path tracer for env_outdoor
# (issue 16); REFS=pt also for cornell_diffuse, doorway and bunny_100k (scenes/), diffuse only,
# where the path tracer misses no light and has no bias. Scenes with glass need a photon reference: a caustic seen through glass or in a mirror is a
# specular-diffuse-specular path that neither the path tracer nor BPT samples (BPT's reference
# for the caustic scene measured 0.66% darker than SPPM's and VCM's, which agree).
# REFS=unbiased: the path tracer wherever nothing casts caustics, and VCM (consistent, and without
# SPPM's edge bias: bench/ERROR_CALIBRATION.md) for scenes with glass: scenes/caustic.gltf and
# dispersion_box_plain. REF_DIR: a reference there named NAME-ref.exr (NAME: the scene's base name)
# is used instead of rendering one. `auto` in INTEGRATORS is the default; its row says what it picked.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/bench_lib.sh"
bench_binary "${1:-}"
times=${TIMES:-10 30}
ref_seconds=${REF_SECONDS:-240}
scenes=${SCENES:-"cornell_box caustic bunny_100k $bench_root/tests/data/env_outdoor.gltf"}
integrators=${INTEGRATORS:-ppm sppm pppm pt vcm bpt}
refs=${REFS:-sppm}
bench_scratch
common="--width 128 --height 128 --quiet --no-png"
echo "Reference: $ref_seconds s each; $(bench_machine)"
echo
echo "| scene | integrator | seconds | CPU s | passes | mean ratio | box-4 relative MSE | p90 relative error |"
echo "|---|---|---:|---:|---:|---:|---:|---:|"
for scene in $scenes; do
  use_scene "$scene"
  ref_integ=sppm
  [ "$name" = env_outdoor ] && ref_integ=pt
  [ "$refs" = pt ] && case "$name" in cornell_diffuse | doorway | bunny_100k | asset_env | asset_sun) ref_integ=pt ;; esac
  if [ "$refs" = unbiased ]; then
    case "$name" in caustic | dispersion_box_plain | cornell_box) ref_integ=vcm ;; *) ref_integ=pt ;; esac
  fi
  if [ -n "${REF_DIR:-}" ] && [ -f "$REF_DIR/$name-ref.exr" ]; then
    echo "reference for $name: $REF_DIR/$name-ref.exr" >&2
    cp "$REF_DIR/$name-ref.exr" "$out/$name-ref.exr"
  else
    echo "reference for $name: $ref_integ, $ref_seconds s" >&2
    "$bin" "$file" $common --integrator $ref_integ --time "$ref_seconds" --seed 1000 -o "$out/$name-ref.exr"
  fi
  for integ in $integrators; do
    for t in $times; do
      /usr/bin/time -f "%U %S" -o "$out/time" "$bin" "$file" $common --integrator "$integ" --time "$t" \
        -o "$out/$name-$integ$t.exr" --stats-json "$out/$name-$integ$t.json"
      python3 - "$out" "$name" "$integ" "$t" "$bin" <<'PY'
import json, subprocess, sys
out, name, integ, t, binary = sys.argv[1:]
st = json.load(open("%s/%s-%s%s.json" % (out, name, integ, t)))
cpu = sum(float(x) for x in open(out + "/time").read().split()[-2:])
c = json.loads(subprocess.run([binary, "compare", "%s/%s-%s%s.exr" % (out, name, integ, t),
                               "%s/%s-ref.exr" % (out, name), "--box", "4"],
                              capture_output=True, text=True, check=True).stdout)
if integ == "auto":
    integ = "auto (%s%s)" % (st.get("integrator", "?"), "+vi" if "visual_importance" in st else "")
print("| %s | %s | %s | %.0f | %d | %.4f | %.2e | %.4f |" % (name, integ, t, cpu, st["passes"], c["mean_ratio"],
                                                         c["box_rel_mse"], c["p90_rel_error"]))
PY
    done
  done
done
