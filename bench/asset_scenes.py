#!/usr/bin/env python3
"""An asset in the open (issue 36's "asset under the default environment" and "the same asset under
directional lights"): bunny_100k's blob on an 8 x 8 floor, no walls, seen by the same camera.
asset_env.gltf is under the default white world, asset_sun.gltf under two directional lights (a
key at 50 degrees and a weaker fill from the other side) and a black world. Both refer to
bunny_100k.bin, copied beside them.

    python3 bench/asset_scenes.py scenes/bunny_100k.gltf OUT_DIR
"""
import base64
import copy
import json
import math
import os
import shutil
import struct
import sys

src, out = sys.argv[1:]
shutil.copy(os.path.join(os.path.dirname(os.path.abspath(src)), "bunny_100k.bin"), out)
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
