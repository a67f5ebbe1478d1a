#!/usr/bin/env python3
"""The scenes of bench/material_extensions.sh: one per material extension, clppm against Cycles.

Each is a UV sphere of radius 1 (with texture coordinates, so that tangents exist) on a grey
Lambertian floor, seen from the front and a little above, lit by a directional light of 3 lux
from the upper left and a white world of radiance 1 (the default world, written out). The sphere
carries the extension under test; the diffuse transmission scene turns the light to come from
behind the sphere, so that what it shows comes through it.

    python3 bench/material_extension_scenes.py OUT_DIR
"""
import math
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "scripts"))
from make_scenes import GltfBuilder, uv_sphere  # noqa: E402

# name: (sphere material keyword arguments, extensions, light from behind)
SCENES = {
    "clearcoat": (dict(base_color=(0.7, 0.08, 0.05), roughness=0.6),
                  {"KHR_materials_clearcoat": {"clearcoatFactor": 1.0, "clearcoatRoughnessFactor": 0.1}}, False),
    "sheen": (dict(base_color=(0.05, 0.05, 0.2), roughness=0.8),
              {"KHR_materials_sheen": {"sheenColorFactor": [1.0, 0.8, 0.6], "sheenRoughnessFactor": 0.5}}, False),
    "iridescence": (dict(base_color=(0.9, 0.9, 0.9), metallic=1.0, roughness=0.25),
                    {"KHR_materials_iridescence": {"iridescenceFactor": 1.0, "iridescenceIor": 1.3,
                                                   "iridescenceThicknessMaximum": 400.0}}, False),
    "anisotropy": (dict(base_color=(0.95, 0.64, 0.54), metallic=1.0, roughness=0.4),
                   {"KHR_materials_anisotropy": {"anisotropyStrength": 0.8, "anisotropyRotation": 0.0}}, False),
    "diffuse_transmission": (dict(base_color=(0.8, 0.8, 0.8), roughness=1.0, specular=0.0),
                             {"KHR_materials_diffuse_transmission": {"diffuseTransmissionFactor": 0.6,
                                                                     "diffuseTransmissionColorFactor": [1.0, 0.5,
                                                                                                        0.2]}},
                             True),
}


def quat_look(direction):
    """The rotation taking a directional light's -Z to direction (unit)."""
    fx, fy, fz = direction
    # -Z to d: axis = cross(-Z, d), angle = acos(dot(-Z, d)).
    ax, ay, az = fy, -fx, 0.0
    s = math.sqrt(ax * ax + ay * ay + az * az)
    angle = math.acos(max(-1.0, min(1.0, -fz)))
    if s < 1e-9:
        return [0.0, 0.0, 0.0, 1.0] if fz < 0 else [1.0, 0.0, 0.0, 0.0]
    h = math.sin(angle / 2) / s
    return [ax * h, ay * h, az * h, math.cos(angle / 2)]


def write(name, out_dir):
    mat_args, ext, from_behind = SCENES[name]
    b = GltfBuilder("clppm bench/material_extension_scenes.py")
    sphere_mat = b.material(name, extensions=ext, **mat_args)
    floor_mat = b.material("floor", (0.5, 0.5, 0.5), specular=0.0)
    pos, normals, idx = uv_sphere(64, 32)
    uvs = []
    for p in pos:
        u = (math.atan2(-p[2], p[0]) / (2 * math.pi)) % 1.0
        v = math.acos(max(-1.0, min(1.0, p[1]))) / math.pi
        uvs.append((u, v))
    sphere = b.primitive(pos, idx, normals, uvs=uvs, material=sphere_mat)
    floor = b.primitive([(-6, -1, -6), (-6, -1, 6), (6, -1, 6), (6, -1, -6)], [0, 1, 2, 0, 2, 3], [(0, 1, 0)] * 4,
                        material=floor_mat)
    d = (0.4, -0.6, 0.7) if from_behind else (0.5, -0.6, -0.6)
    n = math.sqrt(sum(c * c for c in d))
    light = b.light({"name": "key", "type": "directional", "intensity": 3.0})
    b.scene([b.node(name="sphere", mesh=b.mesh([sphere])),
             b.node(name="floor", mesh=b.mesh([floor])),
             b.node(name="key", light=light, rotation=quat_look(tuple(c / n for c in d))),
             b.node(name="camera", camera=b.camera(0.6), translation=[0.0, 0.6, 4.5],
                    rotation=[-0.0665, 0.0, 0.0, 0.9978])])
    b.world(color=(1.0, 1.0, 1.0))
    path = os.path.join(out_dir, "ext_" + name + ".gltf")
    b.write_embedded(path)
    return path


def main():
    out_dir = sys.argv[1] if len(sys.argv) > 1 else "."
    os.makedirs(out_dir, exist_ok=True)
    for name in SCENES:
        print(write(name, out_dir))


if __name__ == "__main__":
    main()
