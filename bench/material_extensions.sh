#!/bin/bash
# clppm against Cycles, one scene per material extension (bench/material_extension_scenes.py):
# clearcoat, sheen, iridescence, anisotropy, diffuse transmission, each a sphere on a floor under a
# directional light and a white world. Cycles (PyPI's bpy, bench/cycles_reference.py: Blender's
# glTF importer, with iridescence and diffuse transmission, which it does not read, set by hand)
# at CYCLES_SPP samples; clppm's path tracer at PT_PASSES and SPPM at SPPM_PASSES passes; compared
# with `clppm compare --box 4`: the mean ratio (clppm over Cycles) and the box-4 relative MSE.
# Writes a contact sheet per scene, clppm pt | clppm sppm | Cycles (bench/contact_sheet.py, plain
# sRGB), and the table on stdout.
#   bench/material_extensions.sh [BUILD_DIR] [OUT_DIR]   (env: BPY_PYTHON, SIZE=128,
#   CYCLES_SPP=1024, PT_PASSES=1024, SPPM_PASSES=256, SHEET_HEIGHT=96, SCENES="clearcoat sheen ...")
# bench/contact_sheets/ext_<scene>.png were made so.
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
build=$(cd "${1:-$here/build}" && pwd)
out=${2:-$(mktemp -d)}
bin=$build/clppm
py=${BPY_PYTHON:-$build/bpy-venv/bin/python}
size=${SIZE:-128}
spp=${CYCLES_SPP:-1024}
pt_passes=${PT_PASSES:-1024}
sppm_passes=${SPPM_PASSES:-256}
scenes=${SCENES:-clearcoat sheen iridescence anisotropy diffuse_transmission}
mkdir -p "$out"
python3 "$here/bench/material_extension_scenes.py" "$out" > /dev/null
echo "$(nproc) cores; $(date -u +%F); ${size}x${size}; Cycles $("$py" -c 'import bpy; print(bpy.app.version_string)' 2>/dev/null) at $spp samples"
echo
echo "| scene | clppm | passes | CPU s | Cycles CPU s | mean ratio | box-4 relative MSE |"
echo "|---|---|---:|---:|---:|---:|---:|"
field() { sed -n "s/.*\"$1\": \([-0-9.e+]*\).*/\1/p" "$2"; }
for name in $scenes; do
  scene=$out/ext_$name.gltf
  /usr/bin/time -f %U,%S -o "$out/$name.cycles.time" "$py" "$here/bench/cycles_reference.py" "$scene" \
    "$out/$name.cycles.exr" --size "$size" --spp "$spp" > "$out/$name.cycles.log" 2>&1
  cy_cpu=$(awk -F, '{printf "%.0f", $1 + $2}' "$out/$name.cycles.time")
  for integ in pt sppm; do
    passes=$pt_passes
    [ "$integ" = sppm ] && passes=$sppm_passes
    /usr/bin/time -f %U,%S -o "$out/$name.$integ.time" "$bin" "$scene" --width "$size" --height "$size" \
      --passes "$passes" --integrator "$integ" --quiet -o "$out/$name.$integ.exr" 2> "$out/$name.$integ.log"
    cpu=$(awk -F, '{printf "%.0f", $1 + $2}' "$out/$name.$integ.time")
    "$bin" compare "$out/$name.$integ.exr" "$out/$name.cycles.exr" --box 4 > "$out/$name.$integ.json"
    printf "| %s | %s | %s | %s | %s | %.4f | %.5f |\n" "$name" "$integ" "$passes" "$cpu" "$cy_cpu" \
      "$(field mean_ratio "$out/$name.$integ.json")" "$(field box_rel_mse "$out/$name.$integ.json")"
  done
done
for name in $scenes; do
  "$py" "$here/bench/contact_sheet.py" "$out/$name.sheet.png" "$out/$name.pt.exr" "$out/$name.sppm.exr" \
    "$out/$name.cycles.exr" --height "${SHEET_HEIGHT:-96}" > /dev/null
done
echo
echo "Images and logs: $out"
