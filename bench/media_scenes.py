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

The fog is the world's medium (extras.clppm_medium, docs/scenes.md "The world's medium"). The
translucent solid is tests/data/wax_block.gltf (KHR_materials_volume_scatter).

    bench/media_scenes.py OUT_DIR
"""
import json
import math
import os
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


if __name__ == "__main__":
    main()
