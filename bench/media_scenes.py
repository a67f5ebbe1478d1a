#!/usr/bin/env python3
"""Writes issue 57's contact-sheet scenes into OUT_DIR (python3 standard library only):

    fog_box.gltf      the diffuse Cornell box (bench/cornell_diffuse.py) in fog
    fog_caustic.gltf  the Cornell box with its glass and mirror spheres in fog: the glass focuses
                      the ceiling light into it (a volumetric caustic of an area light)
    god_rays.gltf     scenes/doorway.gltf in fog, with a spot light in the lit room aimed through
                      the doorway: its beam crosses into the room the camera sees
    spot_caustic.gltf scenes/caustic.gltf in fog: the glass sphere focuses the spot light into a
                      caustic cone in the fog, which no path tracer finds (a delta light through
                      smooth glass)
    fog_cube.gltf     the Cornell box in a fog cube mesh instead of the world's medium (the Blender
                      way: an index-matched cube whose KHR_materials_volume_scatter volume holds
                      the walls, the spheres and the light; media nesting, volume_nesting.h)

The fog is the world's medium (extras.clppm_medium, docs/scenes.md "The world's medium"). The
translucent solid is tests/data/wax_block.gltf (KHR_materials_volume_scatter).

    bench/media_scenes.py OUT_DIR
"""
import base64
import json
import math
import os
import struct
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)

FOG = {"density": [0.3, 0.4, 0.5], "albedo": [0.9, 0.85, 0.8], "anisotropy": 0.3}


def with_medium(doc, medium):
    doc["scenes"][doc.get("scene", 0)].setdefault("extras", {})["clppm_medium"] = medium
    return doc


def write(doc, path):
    with open(path, "w") as f:
        json.dump(doc, f)


def add_box(doc, name, lo, hi, material):
    """Appends a node with an axis-aligned box mesh [lo, hi] (24 vertices, flat normals outwards,
    counter-clockwise from outside) in a buffer of its own (a data URI) to doc's scene."""
    positions, normals, indices = [], [], []
    for axis in range(3):
        for sign in (-1, 1):
            u, v = (axis + 1) % 3, (axis + 2) % 3
            if sign < 0:
                u, v = v, u  # keep (u, v, normal) right-handed
            base = len(positions)
            for a, b in ((0, 0), (1, 0), (1, 1), (0, 1)):
                p = [0.0, 0.0, 0.0]
                p[axis] = hi[axis] if sign > 0 else lo[axis]
                p[u] = hi[u] if a else lo[u]
                p[v] = hi[v] if b else lo[v]
                n = [0.0, 0.0, 0.0]
                n[axis] = float(sign)
                positions.append(p)
                normals.append(n)
            indices += [base, base + 1, base + 2, base, base + 2, base + 3]
    blob = b"".join(struct.pack("<3f", *p) for p in positions) + \
        b"".join(struct.pack("<3f", *n) for n in normals) + b"".join(struct.pack("<H", i) for i in indices)
    buf = len(doc["buffers"])
    doc["buffers"].append({"byteLength": len(blob),
                           "uri": "data:application/octet-stream;base64," + base64.b64encode(blob).decode()})
    views = len(doc["bufferViews"])
    doc["bufferViews"] += [{"buffer": buf, "byteOffset": 0, "byteLength": 288, "target": 34962},
                           {"buffer": buf, "byteOffset": 288, "byteLength": 288, "target": 34962},
                           {"buffer": buf, "byteOffset": 576, "byteLength": 72, "target": 34963}]
    acc = len(doc["accessors"])
    doc["accessors"] += [{"bufferView": views, "componentType": 5126, "count": 24, "type": "VEC3",
                          "min": list(lo), "max": list(hi)},
                         {"bufferView": views + 1, "componentType": 5126, "count": 24, "type": "VEC3"},
                         {"bufferView": views + 2, "componentType": 5123, "count": 36, "type": "SCALAR"}]
    doc["meshes"].append({"name": name, "primitives": [
        {"attributes": {"POSITION": acc, "NORMAL": acc + 1}, "indices": acc + 2, "material": material}]})
    doc["nodes"].append({"name": name, "mesh": len(doc["meshes"]) - 1})
    doc["scenes"][doc.get("scene", 0)]["nodes"].append(len(doc["nodes"]) - 1)


def fog_cube(doc):
    """doc with a fog cube mesh just outside its walls, around everything but the camera (see the header)."""
    doc["materials"].append({"name": "fog", "pbrMetallicRoughness": {"baseColorFactor": [1, 1, 1, 1],
                                                                     "metallicFactor": 0.0, "roughnessFactor": 0.0},
                             "extensions": {
                                 "KHR_materials_transmission": {"transmissionFactor": 1.0},
                                 "KHR_materials_ior": {"ior": 1.0},
                                 "KHR_materials_volume": {"thicknessFactor": 1.0, "attenuationDistance": 4.0,
                                                          "attenuationColor": [0.37, 0.37, 0.37]},
                                 "KHR_materials_volume_scatter": {"multiscatterColor": [0.8, 0.8, 0.8],
                                                                  "scatterAnisotropy": 0.5}}})
    for ext in ("KHR_materials_transmission", "KHR_materials_ior", "KHR_materials_volume",
                "KHR_materials_volume_scatter"):
        if ext not in doc.setdefault("extensionsUsed", []):
            doc["extensionsUsed"].append(ext)
    add_box(doc, "fog_cube", (-1.001, -1.001, -1.001), (1.001, 1.001, 1.001), len(doc["materials"]) - 1)
    return doc


def spot_rotation(direction):
    """The quaternion that turns -Z (a glTF spot's axis) onto the unit direction: about the axis
    (0, 0, -1) x d = (d_y, -d_x, 0) by acos(-d_z)."""
    fx, fy, fz = direction
    ax, ay, az = fy, -fx, 0.0
    n = math.sqrt(ax * ax + ay * ay + az * az)
    angle = math.acos(max(-1.0, min(1.0, -fz)))
    if n < 1e-12:
        return [0.0, 0.0, 0.0, 1.0]
    s = math.sin(angle / 2) / n
    return [ax * s, ay * s, az * s, math.cos(angle / 2)]


def main():
    out = sys.argv[1]
    os.makedirs(out, exist_ok=True)
    box = os.path.join(out, "cornell_diffuse.gltf")
    subprocess.run([sys.executable, os.path.join(HERE, "cornell_diffuse.py"),
                    os.path.join(ROOT, "scenes", "cornell_box.gltf"), box], check=True)
    write(with_medium(json.load(open(box)), FOG), os.path.join(out, "fog_box.gltf"))
    write(with_medium(json.load(open(os.path.join(ROOT, "scenes", "cornell_box.gltf"))),
                      {"density": 0.25, "albedo": 0.95, "anisotropy": 0.5}),
          os.path.join(out, "fog_caustic.gltf"))
    doc = json.load(open(os.path.join(ROOT, "scenes", "doorway.gltf")))
    doc.setdefault("extensionsUsed", []).append("KHR_lights_punctual")
    doc.setdefault("extensions", {})["KHR_lights_punctual"] = {"lights": [
        {"name": "beam", "type": "spot", "intensity": 400.0, "color": [1.0, 0.9, 0.75],
         "spot": {"innerConeAngle": 0.12, "outerConeAngle": 0.18}}]}
    pos, target = (1.9, 1.9, 0.2), (-1.2, 0.0, 0.3)
    d = [t - p for t, p in zip(target, pos)]
    n = math.sqrt(sum(x * x for x in d))
    doc["nodes"].append({"name": "beam", "translation": list(pos),
                         "rotation": spot_rotation([x / n for x in d]),
                         "extensions": {"KHR_lights_punctual": {"light": 0}}})
    doc["scenes"][doc.get("scene", 0)]["nodes"].append(len(doc["nodes"]) - 1)
    write(with_medium(doc, {"density": 0.3, "albedo": 0.8, "anisotropy": 0.2}), os.path.join(out, "god_rays.gltf"))
    write(with_medium(json.load(open(os.path.join(ROOT, "scenes", "caustic.gltf"))),
                      {"density": 0.08, "albedo": 0.9, "anisotropy": 0.3}),
          os.path.join(out, "spot_caustic.gltf"))
    write(fog_cube(json.load(open(os.path.join(ROOT, "scenes", "cornell_box.gltf")))), os.path.join(out, "fog_cube.gltf"))


if __name__ == "__main__":
    main()
