#!/usr/bin/env python3
"""A glTF model under sharp light (issue 62): a copy of the file with a key directional light of
3 W/m^2 and a fill of 1 W/m^2 from the other side added, and a black world
(scenes[].extras.clppm_environment), so that every lobe shows its shape (a white world shows only
its albedo). The model's buffers and images are copied beside the copy (clppm refuses URIs that
leave a scene's folder).

    python3 bench/key_fill_lights.py MODEL.gltf OUT.gltf [--without EXTENSION ...]

--without drops a material extension from every material (and from extensionsUsed and
extensionsRequired), to measure how much of a difference between renderers one extension's model
makes.
"""
import json
import math
import os
import shutil
import sys
import urllib.parse


def rotation_taking_minus_z_to(d):
    """The quaternion (x, y, z, w) that turns -Z, a glTF light's direction, to d."""
    n = math.sqrt(sum(x * x for x in d))
    d = [x / n for x in d]
    c = [d[1], -d[0], 0.0]  # (0, 0, -1) x d
    w = 1 - d[2]  # 1 + (0, 0, -1) . d
    q = c + [w]
    n = math.sqrt(sum(x * x for x in q))
    return [x / n for x in q]


def main():
    src, out = sys.argv[1:3]
    rest = sys.argv[3:]
    without = [rest[i + 1] for i in range(len(rest) - 1) if rest[i] == "--without"]
    with open(src) as f:
        doc = json.load(f)
    for ext in without:
        for m in doc.get("materials", []):
            m.get("extensions", {}).pop(ext, None)
        for key in ("extensionsUsed", "extensionsRequired"):
            if ext in doc.get(key, []):
                doc[key].remove(ext)
    src_dir, out_dir = os.path.dirname(os.path.abspath(src)), os.path.dirname(os.path.abspath(out))
    for item in doc.get("buffers", []) + doc.get("images", []):
        uri = urllib.parse.unquote(item.get("uri", ""))
        if uri and not uri.startswith("data:") and src_dir != out_dir:
            os.makedirs(os.path.dirname(os.path.join(out_dir, uri)), exist_ok=True)
            shutil.copyfile(os.path.join(src_dir, uri), os.path.join(out_dir, uri))
    doc.setdefault("extensionsUsed", [])
    if "KHR_lights_punctual" not in doc["extensionsUsed"]:
        doc["extensionsUsed"].append("KHR_lights_punctual")
    lights = doc.setdefault("extensions", {}).setdefault("KHR_lights_punctual", {}).setdefault("lights", [])
    first = len(lights)
    lights += [{"type": "directional", "intensity": 3.0, "color": [1, 1, 1], "name": "key"},
               {"type": "directional", "intensity": 1.0, "color": [1, 1, 1], "name": "fill"}]
    nodes = doc.setdefault("nodes", [])
    node = len(nodes)
    # The key from the upper right and in front, the fill from the left, lower (travel directions).
    nodes.append({"name": "key", "rotation": rotation_taking_minus_z_to([0.6, -0.5, -0.7]),
                  "extensions": {"KHR_lights_punctual": {"light": first}}})
    nodes.append({"name": "fill", "rotation": rotation_taking_minus_z_to([-0.7, -0.2, -0.6]),
                  "extensions": {"KHR_lights_punctual": {"light": first + 1}}})
    scene = doc["scenes"][doc.get("scene", 0)]
    scene.setdefault("nodes", []).extend([node, node + 1])
    scene.setdefault("extras", {})["clppm_environment"] = {"color": [0, 0, 0]}
    with open(out, "w") as f:
        json.dump(doc, f)


if __name__ == "__main__":
    main()
