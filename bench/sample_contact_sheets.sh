#!/bin/bash
# The Khronos sample models that use the material extensions, rendered by clppm as a user would
# (the file's own camera and lights, the built-in studio world, the default integrator, its PNG
# through the default tone curve) beside the sample set's own screenshot (the Khronos sample
# viewer's), as small contact sheets: clppm | screenshot, one PNG per model. The models come from
# a copy of the sample repository (issue 35 used DRx3D/glTF-Sample-Assets-OLD); none of their
# files is committed.
#   bench/sample_contact_sheets.sh REPO_DIR OUT_DIR [BUILD_DIR]
#   (env: BPY_PYTHON, SECONDS_EACH=20, SIZE=192, SHEET_HEIGHT=96, MODELS="ClearCoatTest ...")
# bench/contact_sheets/<Model>.png were made so (SECONDS_EACH=15).
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/bench_lib.sh"
here=$bench_root
repo=$1
out=$2
build=$(cd "${3:-$here/build}" && pwd)
bin=$build/clppm
py=${BPY_PYTHON:-$build/bpy-venv/bin/python}
seconds=${SECONDS_EACH:-20}
size=${SIZE:-192}
sheet_height=${SHEET_HEIGHT:-96}
models=${MODELS:-ClearCoatTest ClearCoatCarPaint ClearcoatWicker SheenChair SheenCloth GlamVelvetSofa \
  IridescenceDielectricSpheres IridescenceMetallicSpheres IridescenceSuzanne IridescentDishWithOlives \
  IridescenceAbalone AnisotropyStrengthTest AnisotropyRotationTest AnisotropyBarnLamp UnlitTest \
  MaterialsVariantsShoe SpecGlossVsMetalRough ToyCar TextureTransformMultiTest StainedGlassLamp \
  DamagedHelmet EmissiveStrengthTest}
mkdir -p "$out/models"
sheets=()
for m in $models; do
  d=$out/models/$m
  sample_model "$repo" "$m" "$d"
  if [ -z "$gltf" ] || [ -z "$shot" ]; then
    echo "$m: not in the copy"
    continue
  fi
  if ! (cd "$d/glTF" && "$bin" "$(basename "$gltf")" --env studio --height "$size" --width "$size" --time "$seconds" \
    -o "$out/$m.exr" > "$out/$m.log" 2>&1); then
    echo "$m: clppm failed: $(tail -1 "$out/$m.log")"
    continue
  fi
  "$py" "$here/bench/contact_sheet.py" "$out/$m.sheet.png" "$out/$m.png" "$shot" --height "$sheet_height" > /dev/null
  sheets+=("$out/$m.sheet.png")
  echo "$m: $(grep -c 'not supported' "$out/$m.log" || true) unsupported-extension warnings"
done
echo "${#sheets[@]} sheets in $out"
