#!/bin/bash
# Which integrator, with every other setting at its command-line default, reaches a given error
# first (issue 16: the default integrator by measurement). For each scene, a reference (SPPM, or
# the path tracer where no photon is needed: a scene lit only by its environment) of REF_SECONDS,
# then each integrator for each of TIMES seconds at 128x128, compared with `clppm compare --box 4`:
# the mean ratio, the box-4 relative MSE (bias more than noise) and p90_rel_error (the measure
# --target-error states). CPU time is reported with the wall time: these machines are shared.
#   bench/default_integrator.sh [BUILD_DIR]   (env: TIMES="10 30", REF_SECONDS=240, SCENES=...,
#   INTEGRATORS="ppm sppm pppm pt vcm bpt auto", REFS=sppm|pt|unbiased, REF_DIR=...)
# SCENES may name cornell_box (the built-in default), cornell_diffuse (the same box without its two
# spheres: diffuse only), asset_env or asset_sun (below) or glTF files. References: SPPM, and the path tracer for env_outdoor
# (issue 16); REFS=pt also for cornell_diffuse, doorway and bunny_100k (scenes/), diffuse only,
# where the path tracer misses no light and has no bias. Scenes with glass need a photon reference: a caustic seen through glass or in a mirror is a
# specular-diffuse-specular path that neither the path tracer nor BPT samples (BPT's reference
# for the caustic scene measured 0.66% darker than SPPM's and VCM's, which agree).
# REFS=unbiased: the path tracer wherever nothing casts caustics, and VCM (consistent, and without
# SPPM's edge bias: bench/ERROR_CALIBRATION.md) for scenes with glass: scenes/caustic.gltf and
# dispersion_box_plain. REF_DIR: a reference there named NAME-ref.exr (NAME: the scene's base name)
# is used instead of rendering one. `auto` in INTEGRATORS is the default; its row says what it picked.
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
bin=${1:-$here/build}/clppm
times=${TIMES:-10 30}
ref_seconds=${REF_SECONDS:-240}
scenes=${SCENES:-"cornell_box $here/scenes/caustic.gltf $here/scenes/bunny_100k.gltf $here/tests/data/env_outdoor.gltf"}
integrators=${INTEGRATORS:-ppm sppm pppm pt vcm bpt}
refs=${REFS:-sppm}
out=$(mktemp -d)
# The Cornell box without its glass and mirror spheres (nodes 2 and 3).
python3 "$here/bench/cornell_diffuse.py" "$here/scenes/cornell_box.gltf" "$out/cornell_diffuse.gltf"
# An asset in the open: bunny_100k's blob on an 8 x 8 floor, no walls, seen by the same camera;
# asset_env under the default white world, asset_sun under two directional lights (a key at 50
# degrees and a weaker fill from the other side) and a black world.
cp "$here/scenes/bunny_100k.bin" "$out/"
python3 - "$here/scenes/bunny_100k.gltf" "$out" <<'PY'
import base64, json, struct, sys, copy
src, out = sys.argv[1:]
d = json.load(open(src))
blob = [i for i, n in enumerate(d["nodes"]) if n.get("name") == "blob"][0]
cam = [i for i, n in enumerate(d["nodes"]) if n.get("name") == "camera"][0]
pos = [-4, -1, -4, 4, -1, -4, 4, -1, 4, -4, -1, 4]
nrm = [0, 1, 0] * 4
idx = [0, 2, 1, 0, 3, 2]
data = struct.pack("<12f", *pos) + struct.pack("<12f", *nrm) + struct.pack("<6H", *idx) + b"\0\0"
b = len(d["buffers"])
d["buffers"].append({"byteLength": len(data), "uri": "data:application/octet-stream;base64," + base64.b64encode(data).decode()})
v = len(d["bufferViews"])
d["bufferViews"] += [{"buffer": b, "byteOffset": 0, "byteLength": 48}, {"buffer": b, "byteOffset": 48, "byteLength": 48},
                     {"buffer": b, "byteOffset": 96, "byteLength": 12}]
a = len(d["accessors"])
d["accessors"] += [{"bufferView": v, "componentType": 5126, "count": 4, "type": "VEC3", "min": [-4, -1, -4], "max": [4, -1, 4]},
                   {"bufferView": v + 1, "componentType": 5126, "count": 4, "type": "VEC3"},
                   {"bufferView": v + 2, "componentType": 5123, "count": 6, "type": "SCALAR"}]
d["meshes"].append({"name": "floor", "primitives": [{"attributes": {"POSITION": a, "NORMAL": a + 1}, "indices": a + 2, "material": 0}]})
d["nodes"].append({"name": "floor", "mesh": len(d["meshes"]) - 1})
floor = len(d["nodes"]) - 1
env = copy.deepcopy(d)
env["scenes"][0]["nodes"] = [blob, floor, cam]
env["scenes"][0].pop("extras", None)
json.dump(env, open(out + "/asset_env.gltf", "w"))
sun = copy.deepcopy(d)
sun["extensionsUsed"] = sorted(set(sun.get("extensionsUsed", []) + ["KHR_lights_punctual"]))
sun["extensions"] = {"KHR_lights_punctual": {"lights": [{"type": "directional", "intensity": 3.0, "color": [1, 0.95, 0.9]},
                                                        {"type": "directional", "intensity": 0.6, "color": [0.8, 0.9, 1]}]}}
# glTF directional lights shine along the node's -Z: pitch down by `down` degrees about X, then
# turn by `turn` degrees about Y.
import math
def aim(down, turn):
    p, y = math.radians(-down) / 2, math.radians(turn) / 2
    qp, qy = (math.sin(p), 0, 0, math.cos(p)), (0, math.sin(y), 0, math.cos(y))
    (x1, y1, z1, w1), (x2, y2, z2, w2) = qy, qp
    return [w1 * x2 + x1 * w2 + y1 * z2 - z1 * y2, w1 * y2 - x1 * z2 + y1 * w2 + z1 * x2,
            w1 * z2 + x1 * y2 - y1 * x2 + z1 * w2, w1 * w2 - x1 * x2 - y1 * y2 - z1 * z2]
sun["nodes"].append({"name": "key", "rotation": aim(50, 35), "extensions": {"KHR_lights_punctual": {"light": 0}}})
sun["nodes"].append({"name": "fill", "rotation": aim(25, -140), "extensions": {"KHR_lights_punctual": {"light": 1}}})
sun["scenes"][0]["nodes"] = [blob, floor, cam, len(sun["nodes"]) - 2, len(sun["nodes"]) - 1]
json.dump(sun, open(out + "/asset_sun.gltf", "w"))
PY
common="--width 128 --height 128 --quiet --no-png"
echo "Reference: $ref_seconds s each; $(nproc) cores; $(date -u +%F)"
echo
echo "| scene | integrator | seconds | CPU s | passes | mean ratio | box-4 relative MSE | p90 relative error |"
echo "|---|---|---:|---:|---:|---:|---:|---:|"
for scene in $scenes; do
  name=$(basename "$scene" .gltf)
  arg=$scene
  [ "$scene" = cornell_box ] && arg=""
  [ "$scene" = cornell_diffuse ] && arg="$out/cornell_diffuse.gltf"
  case "$scene" in asset_env | asset_sun) arg="$out/$scene.gltf" ;; esac
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
    "$bin" $arg $common --integrator $ref_integ --time "$ref_seconds" --seed 1000 -o "$out/$name-ref.exr"
  fi
  for integ in $integrators; do
    for t in $times; do
      /usr/bin/time -f "%U %S" -o "$out/time" "$bin" $arg $common --integrator "$integ" --time "$t" \
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
rm -rf "$out"
