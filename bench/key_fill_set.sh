#!/bin/bash
# Materials under sharp light (issue 62): each Khronos sample model of the list under a key and a
# fill directional light and a black world (bench/key_fill_lights.py), rendered by clppm (its
# default integrator) and by Cycles (bench/cycles_reference.py, PyPI's bpy), compared with
# `clppm compare --box 4`, and put side by side with the sample set's screenshot (the Khronos
# viewer's, under its own lights) as a contact sheet: clppm | Cycles | screenshot. A white world
# shows a lobe's albedo only; these lights show where each lobe sends light.
#   bench/key_fill_set.sh REPO_DIR OUT_DIR [BUILD_DIR]
#   (env: BPY_PYTHON, SECONDS_EACH=60, SPP=4096, SIZE=256, SHEET_HEIGHT=128, MODELS="...",
#    KERNEL_DIR: other kernels for clppm, e.g. an older checkout's, through CLPPM_KERNEL_DIR;
#    WITHOUT="KHR_materials_sheen ...": the models with those extensions dropped, in both renderers)
# REPO_DIR: a copy of the sample repository (DRx3D/glTF-Sample-Assets-OLD); none of it is committed.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/bench_lib.sh"
repo=$1
out=$2
bench_binary "${3:-}"
py=${BPY_PYTHON:-$build/bpy-venv/bin/python}
seconds=${SECONDS_EACH:-60}
spp=${SPP:-4096}
size=${SIZE:-256}
sheet_height=${SHEET_HEIGHT:-128}
models=${MODELS:-AnisotropyStrengthTest AnisotropyRotationTest SheenChair ClearCoatTest IridescenceSuzanne \
  IridescenceMetallicSpheres}
mkdir -p "$out/models"
echo "$(bench_machine), ${size}x${size}, clppm $seconds s (default integrator), Cycles $spp spp"
echo
echo "| model | integrator | passes | CPU s | mean ratio to Cycles | box-4 relative MSE |"
echo "|---|---|---:|---:|---:|---:|"
for m in $models; do
  d=$out/models/$m
  sample_model "$repo" "$m" "$d"
  if [ -z "$gltf" ]; then
    echo "| $m | not in the copy | | | | |"
    continue
  fi
  lit=$d/lit/$m.gltf
  mkdir -p "$d/lit"
  without=()
  for e in ${WITHOUT:-}; do without+=(--without "$e"); done
  if ! python3 "$bench_root/bench/key_fill_lights.py" "$gltf" "$lit" "${without[@]}" 2> "$out/$m.lights.log"; then
    echo "| $m | files missing in the copy ($(tail -1 "$out/$m.lights.log" | cut -c1-80)) | | | | |"
    continue
  fi
  [ -f "$out/$m.cycles.exr" ] ||
    "$py" "$bench_root/bench/cycles_reference.py" "$lit" "$out/$m.cycles.exr" --size "$size" --spp "$spp" --world 0 \
      > "$out/$m.cycles.log" 2>&1
  env ${KERNEL_DIR:+CLPPM_KERNEL_DIR=$KERNEL_DIR} /usr/bin/time -f "%U %S" -o "$out/time" "$bin" "$lit" --width "$size" \
    --height "$size" --time "$seconds" --quiet --no-png -o "$out/$m.exr" --stats-json "$out/$m.json"
  "$bin" compare "$out/$m.exr" "$out/$m.cycles.exr" --box 4 > "$out/$m.compare.json"
  python3 - "$out/$m.json" "$out/$m.compare.json" "$out/time" "$m" <<'PY'
import json, sys
st, c = json.load(open(sys.argv[1])), json.load(open(sys.argv[2]))
cpu = sum(float(x) for x in open(sys.argv[3]).read().split()[-2:])
print("| %s | %s | %d | %.0f | %.3f | %.4f |" % (sys.argv[4], st["integrator"], st["passes"], cpu, c["mean_ratio"],
                                                 c["box_rel_mse"]))
PY
  images=("$out/$m.exr" "$out/$m.cycles.exr")
  [ -n "$shot" ] && images+=("$shot")
  "$py" "$bench_root/bench/contact_sheet.py" "$out/$m.sheet.png" "${images[@]}" --height "$sheet_height" > /dev/null
done
