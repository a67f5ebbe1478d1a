#!/bin/bash
# Issue 57's contact sheet: fog (the diffuse Cornell box), a volumetric caustic (the Cornell box's
# glass sphere focusing its ceiling light into fog), a beam through a doorway (a spot light in
# fog), a translucent solid (tests/data/wax_block.gltf, KHR_materials_volume_scatter), a spot
# light's caustic cone through a glass sphere in fog, and the Cornell box in a fog cube mesh (media
# nesting), each rendered by the default integrator as a user would, side by side in one PNG.
#   bench/media_contact_sheet.sh OUT_PNG [BUILD_DIR]
#   (env: BPY_PYTHON, SECONDS_EACH=60, SIZE=256, SHEET_HEIGHT=192)
# bench/contact_sheets/media.png was made so.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
out=$1
build=$(cd "${2:-$here/build}" && pwd)
py=${BPY_PYTHON:-$build/bpy-venv/bin/python}
seconds=${SECONDS_EACH:-60}
size=${SIZE:-256}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
python3 "$here/bench/media_scenes.py" "$tmp"
images=()
for scene in "$tmp/fog_box.gltf" "$tmp/fog_caustic.gltf" "$tmp/god_rays.gltf" "$here/tests/data/wax_block.gltf" \
  "$tmp/spot_caustic.gltf" "$tmp/fog_cube.gltf"; do
  name=$(basename "$scene" .gltf)
  "$build/clppm" "$scene" --width "$size" --height "$size" --time "$seconds" --quiet -o "$tmp/$name.exr"
  images+=("$tmp/$name.exr")
done
"$py" "$here/bench/contact_sheet.py" "$out" "${images[@]}" --height "${SHEET_HEIGHT:-192}"
