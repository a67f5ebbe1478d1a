"""Blender's area lights as clppm sees them: emissive geometry of the same power, shape and
orientation, appended to the glTF file the exporter wrote (glTF has no area lights).

Cycles' area light of power P watts (times 2^exposure, and times its area when "normalize" is
off) emits from one side, towards its local -Z, as a Lambertian surface: radiance
L = P / (pi A) over its area A. The same surface in clppm, an emissive material of that radiance
(emissiveFactor = colour, KHR_materials_emissive_strength = L) on single-sided triangles facing
-Z, emits the same power the same way. A disk or an ellipse is a polygon of SEGMENTS sides; its
radiance uses the polygon's area, so that the power is the light's exactly. A spread below 180
degrees narrows the emission as Cycles' soft box does (max(tan h - tan a, 0) / (tan h - h), the
power kept): the material's extras "clppm_area_light_spread" in degrees (kernels/scene.cl).
"""
import base64
import math
import struct

SEGMENTS = 64

# Blender is Z up, glTF Y up: the exporter maps (x, y, z) to (x, z, -y).
Y_UP = ((1.0, 0.0, 0.0, 0.0), (0.0, 0.0, 1.0, 0.0), (0.0, -1.0, 0.0, 0.0), (0.0, 0.0, 0.0, 1.0))


def outline(shape, size_x, size_y):
    """The light's outline in its local XY plane (counter-clockwise seen from +Z)."""
    hx, hy = 0.5 * size_x, 0.5 * (size_x if shape in ("SQUARE", "DISK") else size_y)
    if shape in ("SQUARE", "RECTANGLE"):
        return [(-hx, -hy), (hx, -hy), (hx, hy), (-hx, hy)]
    return [(hx * math.cos(2 * math.pi * i / SEGMENTS), hy * math.sin(2 * math.pi * i / SEGMENTS))
            for i in range(SEGMENTS)]


def polygon_area(points):
    return 0.5 * abs(sum(x0 * y1 - x1 * y0 for (x0, y0), (x1, y1) in zip(points, points[1:] + points[:1])))


def radiance(power, area):
    """Radiance of a one-sided Lambertian emitter of `power` watts over `area` (Cycles' area light)."""
    return power / (math.pi * area) if area > 0 else 0.0


def matmul(a, b):
    return [[sum(a[i][k] * b[k][j] for k in range(4)) for j in range(4)] for i in range(4)]


def gltf_matrix(blender_world):
    """A Blender world matrix (rows) as glTF's column-major node matrix, in glTF's Y-up axes."""
    m = matmul(Y_UP, [list(r) for r in blender_world])
    return [m[r][c] for c in range(4) for r in range(4)]


def append(gltf, lights):
    """Appends each light of `lights` ({name, points, radiance, color, matrix}) to the glTF
    document `gltf` (a dict, modified) as a node with a single-sided emissive mesh, and lists the
    nodes in its default scene. The geometry goes into a buffer of its own, as a data URI."""
    if not lights:
        return
    data = bytearray()
    buffers = gltf.setdefault("buffers", [])
    views = gltf.setdefault("bufferViews", [])
    accessors = gltf.setdefault("accessors", [])
    materials = gltf.setdefault("materials", [])
    meshes = gltf.setdefault("meshes", [])
    nodes = gltf.setdefault("nodes", [])
    used = gltf.setdefault("extensionsUsed", [])
    for ext in ("KHR_materials_emissive_strength", "KHR_materials_specular"):
        if ext not in used:
            used.append(ext)
    buffer_index = len(buffers)
    scene = gltf.setdefault("scenes", [{"nodes": []}])[gltf.get("scene", 0)]
    for light in lights:
        pts = light["points"]
        # A fan about the centre, facing -Z: clockwise seen from +Z.
        positions = [(0.0, 0.0, 0.0)] + [(x, y, 0.0) for x, y in pts]
        indices = []
        for i in range(len(pts)):
            indices += [0, 1 + (i + 1) % len(pts), 1 + i]
        pos_bytes = b"".join(struct.pack("<3f", *p) for p in positions)
        nrm_bytes = struct.pack("<3f", 0.0, 0.0, -1.0) * len(positions)
        idx_bytes = struct.pack("<%dI" % len(indices), *indices)
        first_view = len(views)
        for chunk, target in ((pos_bytes, 34962), (nrm_bytes, 34962), (idx_bytes, 34963)):
            while len(data) % 4:
                data.append(0)
            views.append({"buffer": buffer_index, "byteOffset": len(data), "byteLength": len(chunk), "target": target})
            data += chunk
        xs, ys = [p[0] for p in positions], [p[1] for p in positions]
        accessors.append({"bufferView": first_view, "componentType": 5126, "count": len(positions), "type": "VEC3",
                          "min": [min(xs), min(ys), 0.0], "max": [max(xs), max(ys), 0.0]})
        accessors.append({"bufferView": first_view + 1, "componentType": 5126, "count": len(positions), "type": "VEC3"})
        accessors.append({"bufferView": first_view + 2, "componentType": 5125, "count": len(indices),
                          "type": "SCALAR"})
        materials.append({
            "name": light["name"] + " (area light)",
            "pbrMetallicRoughness": {"baseColorFactor": [0.0, 0.0, 0.0, 1.0], "metallicFactor": 0.0,
                                     "roughnessFactor": 1.0},
            "emissiveFactor": list(light["color"]),
            "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": light["radiance"]},
                           "KHR_materials_specular": {"specularFactor": 0.0}},
        })
        if light.get("spread", 180.0) < 180.0:
            materials[-1]["extras"] = {"clppm_area_light_spread": light["spread"]}
        meshes.append({"name": light["name"], "primitives": [{
            "attributes": {"POSITION": len(accessors) - 3, "NORMAL": len(accessors) - 2},
            "indices": len(accessors) - 1, "material": len(materials) - 1}]})
        nodes.append({"name": light["name"], "mesh": len(meshes) - 1, "matrix": light["matrix"]})
        scene.setdefault("nodes", []).append(len(nodes) - 1)
    buffers.append({"byteLength": len(data),
                    "uri": "data:application/octet-stream;base64," + base64.b64encode(bytes(data)).decode()})
