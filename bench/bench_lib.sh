# shellcheck shell=bash
# Sourced by the benchmark scripts: a scratch folder that goes when the script ends, the scenes the
# benchmarks derive from scenes/ (the Cornell box without its spheres, the asset under the default
# world and under directional lights), and what clppm takes for each name a SCENES list may hold.
#   source "$(dirname "${BASH_SOURCE[0]}")/bench_lib.sh"; bench_scratch
# bench_root is the checkout; after bench_scratch, $out is the scratch folder.

bench_root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)

# bench_binary [BUILD_DIR]: $build (absolute; the checkout's build/ by default) and $bin, its clppm.
bench_binary() {
  build=$(cd "${1:-$bench_root/build}" && pwd)
  bin=$build/clppm
}

# bench_machine: one line for a table's head: cores, processor, date.
bench_machine() {
  echo "$(nproc) cores of $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs), $(date -u +%F)"
}

# bench_scratch: $out, a temporary folder removed on exit, holding cornell_diffuse.gltf,
# asset_env.gltf and asset_sun.gltf (bench/cornell_diffuse.py, bench/asset_scenes.py).
bench_scratch() {
  out=$(mktemp -d)
  trap 'rm -rf "$out"' EXIT
  python3 "$bench_root/bench/cornell_diffuse.py" "$bench_root/scenes/cornell_box.gltf" "$out/cornell_diffuse.gltf"
  python3 "$bench_root/bench/asset_scenes.py" "$bench_root/scenes/bunny_100k.gltf" "$out" >/dev/null
}

# scene_name SCENE: the scene's short name (a file's base name without .gltf).
scene_name() { basename "$1" .gltf; }

# use_scene SCENE: $name and $file of a name of SCENES (scene_name, scene_file).
# shellcheck disable=SC2034 # set for the caller
use_scene() {
  name=$(scene_name "$1")
  file=$(scene_file "$1")
}

# scene_file SCENE: the file clppm renders for a name of SCENES: cornell_box is scenes/cornell_box.gltf
# (the built-in default), the derived scenes are in $out, a scenes/ name without its path is found
# there, and anything else is a glTF file as given.
scene_file() {
  case "$1" in
    cornell_diffuse | asset_env | asset_sun) echo "$out/$1.gltf" ;;
    */* | *.gltf | *.glb) echo "$1" ;;
    *) echo "$bench_root/scenes/$1.gltf" ;;
  esac
}

# sample_model REPO MODEL DIR: the model's glTF folder and screenshot from a copy of the Khronos
# sample repository (git archive, so a bare mirror serves) into DIR; $gltf is its .gltf file and
# $shot its screenshot, each empty when the copy has none.
sample_model() {
  mkdir -p "$3"
  (cd "$1" && git archive HEAD "Models/$2/glTF" "Models/$2/screenshot" 2> /dev/null) | tar -x -C "$3" --strip-components=2 || true
  gltf=$(ls "$3"/glTF/*.gltf 2> /dev/null | head -1 || true)
  shot=$(ls "$3"/screenshot/screenshot.jpg "$3"/screenshot/screenshot.png 2> /dev/null | head -1 || true)
}

# cpu_seconds FILE: user + system seconds from `/usr/bin/time -f "%U %S" -o FILE`.
cpu_seconds() { awk '{print $(NF - 1) + $NF}' "$1"; }

# pt_reference BIN SCENE SIZE PASSES DIR: the path tracer's reference for SCENE (independent numbers,
# seed 777), rendered into DIR once and reused; prints its path. For scenes where the path tracer
# is unbiased (no caustic of a small light).
pt_reference() {
  local bin=$1 scene=$2 size=$3 passes=$4 dir=$5
  local ref
  ref="$dir/$(scene_name "$scene")-$size-$passes.exr"
  mkdir -p "$dir"
  [ -f "$ref" ] || "$bin" "$(scene_file "$scene")" --width "$size" --height "$size" --quiet --no-png \
    --integrator pt --sampler independent --seed 777 --passes "$passes" -o "$ref" >&2
  echo "$ref"
}
