#!/usr/bin/env python3
"""Writes clppm's shipped glTF 2.0 scenes into scenes/ (python3 standard library only).

Deterministic: the same script writes the same bytes. Run from anywhere:
    python3 scripts/make_scenes.py [output_dir]
    python3 scripts/make_scenes.py --large DIR   # bunny_1m.gltf (1.0M triangles) for bench/scaling_10x.sh

The GltfBuilder class here is also used by tests/data/make_test_gltf.py.
"""
import base64
import json
import math
import os
import struct
import sys

# glTF 2.0 enums
FLOAT, BYTE, UBYTE, SHORT, USHORT, UINT = 5126, 5120, 5121, 5122, 5123, 5125
ARRAY_BUFFER, ELEMENT_ARRAY_BUFFER = 34962, 34963
COMPONENTS = {"SCALAR": 1, "VEC2": 2, "VEC3": 3, "VEC4": 4, "MAT4": 16}
PACK = {FLOAT: "f", BYTE: "b", UBYTE: "B", SHORT: "h", USHORT: "H", UINT: "I"}


def rounded(x, digits=6):
    """Floats in the JSON are rounded so the files stay small and diff-friendly."""
    if isinstance(x, float):
        r = round(x, digits)
        return 0.0 if r == 0 else r
    if isinstance(x, (list, tuple)):
        return [rounded(v, digits) for v in x]
    if isinstance(x, dict):
        return {k: rounded(v, digits) for k, v in x.items()}
    return x


class GltfBuilder:
    """Accumulates one binary buffer and the glTF objects that point into it."""

    def __init__(self, generator="clppm scripts/make_scenes.py"):
        self.bin = bytearray()
        self.doc = {"asset": {"version": "2.0", "generator": generator}}
        self.extensions_used = set()

    def _list(self, key):
        return self.doc.setdefault(key, [])

    def _append(self, key, obj):
        items = self._list(key)
        items.append(obj)
        return len(items) - 1

    # -- buffer data --

    def buffer_view(self, data, target=None, stride=None):
        self._pad()
        view = {"buffer": 0, "byteOffset": len(self.bin), "byteLength": len(data)}
        if target is not None:
            view["target"] = target
        if stride is not None:
            view["byteStride"] = stride
        self.bin += data
        return self._append("bufferViews", view)

    def accessor(self, values, component_type, type_, target=None, normalized=False, minmax=False):
        """values: flat list of numbers (len = count * components)."""
        n = COMPONENTS[type_]
        data = struct.pack("<%d%s" % (len(values), PACK[component_type]), *values)
        acc = {"bufferView": self.buffer_view(data, target), "componentType": component_type,
               "count": len(values) // n, "type": type_}
        if normalized:
            acc["normalized"] = True
        if minmax:
            acc["min"] = [min(values[i::n]) for i in range(n)]
            acc["max"] = [max(values[i::n]) for i in range(n)]
        return self._append("accessors", acc)

    def raw_accessor(self, acc):
        return self._append("accessors", acc)

    # -- objects --

    def primitive(self, positions, indices=None, normals=None, uvs=None, material=None,
                  index_type=None, bounds=True):
        """positions/normals: lists of (x,y,z); uvs: list of (u,v); indices: flat list.
        bounds=False leaves out POSITION min/max (needed when positions hold NaN)."""
        attrs = {"POSITION": self.accessor(flat(positions), FLOAT, "VEC3", ARRAY_BUFFER, minmax=bounds)}
        if normals is not None:
            attrs["NORMAL"] = self.accessor(flat(normals), FLOAT, "VEC3", ARRAY_BUFFER)
        if uvs is not None:
            attrs["TEXCOORD_0"] = self.accessor(flat(uvs), FLOAT, "VEC2", ARRAY_BUFFER)
        prim = {"attributes": attrs}
        if indices is not None:
            if index_type is None:
                index_type = USHORT if max(indices) < 65536 else UINT
            prim["indices"] = self.accessor(list(indices), index_type, "SCALAR", ELEMENT_ARRAY_BUFFER)
        if material is not None:
            prim["material"] = material
        return prim

    def mesh(self, primitives, name=None):
        m = {"primitives": primitives}
        if name:
            m["name"] = name
        return self._append("meshes", m)

    def material(self, name, base_color=(0.8, 0.8, 0.8), metallic=0.0, roughness=1.0,
                 emissive=None, emissive_strength=None, transmission=None, ior=None,
                 double_sided=False, base_color_texture=None, specular=None, specular_color=None,
                 metallic_roughness_texture=None, thickness=None, extensions=None):
        pbr = {"baseColorFactor": list(base_color) + [1.0] * (4 - len(base_color)),
               "metallicFactor": metallic, "roughnessFactor": roughness}
        if base_color_texture is not None:
            pbr["baseColorTexture"] = base_color_texture
        if metallic_roughness_texture is not None:
            pbr["metallicRoughnessTexture"] = metallic_roughness_texture
        m = {"name": name, "pbrMetallicRoughness": pbr}
        ext = {}
        if emissive is not None:
            m["emissiveFactor"] = list(emissive)
        if emissive_strength is not None:
            ext["KHR_materials_emissive_strength"] = {"emissiveStrength": emissive_strength}
        if transmission is not None:
            ext["KHR_materials_transmission"] = {"transmissionFactor": transmission}
        if ior is not None:
            ext["KHR_materials_ior"] = {"ior": ior}
        if thickness is not None:  # a solid dielectric, not a thin wall (KHR_materials_volume)
            ext["KHR_materials_volume"] = {"thicknessFactor": thickness}
        if specular is not None or specular_color is not None:
            spec = {}
            if specular is not None:
                spec["specularFactor"] = specular
            if specular_color is not None:
                spec["specularColorFactor"] = list(specular_color)
            ext["KHR_materials_specular"] = spec
        ext.update(extensions or {})  # any other material extension, as the file spells it
        if ext:
            m["extensions"] = ext
            self.extensions_used.update(ext)
        if double_sided:
            m["doubleSided"] = True
        return self._append("materials", m)

    def light(self, light):
        self.extensions_used.add("KHR_lights_punctual")
        exts = self.doc.setdefault("extensions", {})
        lights = exts.setdefault("KHR_lights_punctual", {"lights": []})["lights"]
        lights.append(light)
        return len(lights) - 1

    def camera(self, yfov, aspect=None, name=None, extras=None):
        persp = {"yfov": yfov, "znear": 0.01}
        if aspect is not None:
            persp["aspectRatio"] = aspect
        cam = {"type": "perspective", "perspective": persp}
        if name:
            cam["name"] = name
        if extras:
            cam["extras"] = extras
        return self._append("cameras", cam)

    def node(self, **fields):
        """fields: name, mesh, camera, light, children, translation, rotation, scale, matrix."""
        node = {}
        for key in ("name", "mesh", "camera", "children", "translation", "rotation", "scale", "matrix", "extras"):
            if key in fields and fields[key] is not None:
                node[key] = fields[key]
        if fields.get("light") is not None:
            node["extensions"] = {"KHR_lights_punctual": {"light": fields["light"]}}
        return self._append("nodes", node)

    def scene(self, roots):
        self.doc["scene"] = self._append("scenes", {"nodes": roots})

    def world(self, **world):
        """The default scene's own world (extras.clppm_environment): color=(r, g, b), or
        image=URI with strength and rotation (docs/scenes.md, "A file's own world")."""
        scenes = self._list("scenes")
        if not scenes:
            self.scene([])
        world = {k: list(v) if isinstance(v, tuple) else v for k, v in world.items()}
        scenes[self.doc.get("scene", 0)].setdefault("extras", {})["clppm_environment"] = world

    def medium(self, **medium):
        """The default scene's world medium (extras.clppm_medium): density, albedo, anisotropy
        (docs/scenes.md, "The world's medium")."""
        scenes = self._list("scenes")
        if not scenes:
            self.scene([])
        medium = {k: list(v) if isinstance(v, tuple) else v for k, v in medium.items()}
        scenes[self.doc.get("scene", 0)].setdefault("extras", {})["clppm_medium"] = medium

    def has_lights(self):
        """Emissive materials or punctual lights: a scene lit by lights of its own."""
        return any(max(m.get("emissiveFactor", [0.0])) > 0 for m in self.doc.get("materials", [])) or bool(
            self.doc.get("extensions", {}).get("KHR_lights_punctual", {}).get("lights"))

    # -- output --

    def _pad(self):
        while len(self.bin) % 4:
            self.bin.append(0)

    def document(self, uri):
        # A scene with lights of its own, written here, is meant to be seen by them alone: a black
        # world, unless it says otherwise (every scene without a world of its own is lit by the
        # default environment; docs/scenes.md, "Environment").
        scenes = self.doc.get("scenes", [])
        if self.has_lights() and scenes and "clppm_environment" not in scenes[self.doc.get("scene", 0)].get("extras", {}):
            self.world(color=(0.0, 0.0, 0.0))
        doc = dict(self.doc)
        self._pad()
        if self.bin:
            doc["buffers"] = [{"byteLength": len(self.bin), "uri": uri}]
        if self.extensions_used:
            doc["extensionsUsed"] = sorted(self.extensions_used)
        return rounded(doc)

    def data_uri(self):
        self._pad()
        return "data:application/octet-stream;base64," + base64.b64encode(bytes(self.bin)).decode("ascii")

    def write_embedded(self, path):
        write_text(path, json.dumps(self.document(self.data_uri()), indent=1) + "\n")

    def write_external(self, path):
        bin_name = os.path.splitext(os.path.basename(path))[0] + ".bin"
        write_text(path, json.dumps(self.document(bin_name), indent=1) + "\n")
        with open(os.path.join(os.path.dirname(path), bin_name), "wb") as f:
            f.write(bytes(self.bin))

    def write_glb(self, path):
        doc = dict(self.doc)
        self._pad()
        doc["buffers"] = [{"byteLength": len(self.bin)}]
        text = json.dumps(rounded(doc), separators=(",", ":")).encode("utf-8")
        text += b" " * ((4 - len(text) % 4) % 4)
        total = 12 + 8 + len(text) + 8 + len(self.bin)
        with open(path, "wb") as f:
            f.write(struct.pack("<4sII", b"glTF", 2, total))
            f.write(struct.pack("<I4s", len(text), b"JSON") + text)
            f.write(struct.pack("<I4s", len(self.bin), b"BIN\0") + bytes(self.bin))


def write_text(path, text):
    with open(path, "w", newline="\n") as f:
        f.write(text)


def flat(vectors):
    return [float(c) for v in vectors for c in v]


# ---- vector math --------------------------------------------------------------------------------

def add(a, b): return tuple(x + y for x, y in zip(a, b))
def sub(a, b): return tuple(x - y for x, y in zip(a, b))
def scale(a, s): return tuple(x * s for x in a)
def dot(a, b): return sum(x * y for x, y in zip(a, b))
def cross(a, b): return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def normalize(a):
    n = math.sqrt(dot(a, a))
    return tuple(x / n for x in a)


def quat_from_basis(right, up, back):
    """Unit quaternion (x, y, z, w) of the rotation whose columns are right, up, back."""
    m00, m10, m20 = right
    m01, m11, m21 = up
    m02, m12, m22 = back
    tr = m00 + m11 + m22
    if tr > 0:
        s = math.sqrt(tr + 1.0) * 2
        q = ((m21 - m12) / s, (m02 - m20) / s, (m10 - m01) / s, 0.25 * s)
    elif m00 > m11 and m00 > m22:
        s = math.sqrt(1.0 + m00 - m11 - m22) * 2
        q = (0.25 * s, (m01 + m10) / s, (m02 + m20) / s, (m21 - m12) / s)
    elif m11 > m22:
        s = math.sqrt(1.0 + m11 - m00 - m22) * 2
        q = ((m01 + m10) / s, 0.25 * s, (m12 + m21) / s, (m02 - m20) / s)
    else:
        s = math.sqrt(1.0 + m22 - m00 - m11) * 2
        q = ((m02 + m20) / s, (m12 + m21) / s, 0.25 * s, (m10 - m01) / s)
    return list(normalize(q))


def look_rotation(forward, up_hint=(0.0, 1.0, 0.0)):
    """Rotation that turns the node's -Z axis to `forward` and +Y towards `up_hint`."""
    f = normalize(forward)
    right = normalize(cross(f, up_hint))
    up = cross(right, f)
    return quat_from_basis(right, up, scale(f, -1.0))


# ---- geometry -----------------------------------------------------------------------------------

def quad(center, u, v):
    """Quad center +- u +- v; front face (counter-clockwise) normal along u x v."""
    corners = [add(center, add(scale(u, su), scale(v, sv))) for su, sv in ((-1, -1), (1, -1), (1, 1), (-1, 1))]
    n = normalize(cross(u, v))
    return corners, [n] * 4, [0, 1, 2, 0, 2, 3]


def uv_sphere(segments, rings, radius=1.0, center=(0.0, 0.0, 0.0), inward=False, displace=None):
    """UV sphere with single pole vertices; smooth normals (area-weighted when displaced).
    Triangles: 2 * segments * (rings - 1)."""
    dirs = [(0.0, 1.0, 0.0)]
    for i in range(1, rings):
        theta = math.pi * i / rings
        for j in range(segments):
            phi = 2 * math.pi * j / segments
            dirs.append((math.sin(theta) * math.cos(phi), math.cos(theta), -math.sin(theta) * math.sin(phi)))
    dirs.append((0.0, -1.0, 0.0))
    south = len(dirs) - 1

    def ring(i, j):  # vertex of ring i (1..rings-1), segment j
        return 1 + (i - 1) * segments + j % segments

    idx = []
    for j in range(segments):
        idx += [0, ring(1, j), ring(1, j + 1)]
        idx += [south, ring(rings - 1, j + 1), ring(rings - 1, j)]
    for i in range(1, rings - 1):
        for j in range(segments):
            a, b, c, d = ring(i, j), ring(i + 1, j), ring(i + 1, j + 1), ring(i, j + 1)
            idx += [a, b, c, a, c, d]
    r = [radius * (1.0 + (displace(d) if displace else 0.0)) for d in dirs]
    pos = [add(center, scale(d, ri)) for d, ri in zip(dirs, r)]
    normals = list(dirs) if not displace else vertex_normals(pos, idx)
    if inward:
        normals = [scale(n, -1.0) for n in normals]
        for t in range(0, len(idx), 3):
            idx[t + 1], idx[t + 2] = idx[t + 2], idx[t + 1]
    return pos, normals, idx


def vertex_normals(pos, idx):
    acc = [[0.0, 0.0, 0.0] for _ in pos]
    for t in range(0, len(idx), 3):
        a, b, c = idx[t], idx[t + 1], idx[t + 2]
        n = cross(sub(pos[b], pos[a]), sub(pos[c], pos[a]))  # length = 2 * area: area weighting
        for v in (a, b, c):
            acc[v][0] += n[0]
            acc[v][1] += n[1]
            acc[v][2] += n[2]
    return [normalize(n) for n in acc]


def check_front_faces(pos, normals, idx):
    """Every triangle's counter-clockwise normal agrees with its vertex normals."""
    for t in range(0, len(idx), 3):
        a, b, c = idx[t], idx[t + 1], idx[t + 2]
        g = cross(sub(pos[b], pos[a]), sub(pos[c], pos[a]))
        assert dot(g, normals[a]) > 0, "triangle %d faces away from its normals" % (t // 3)


# ---- scenes -------------------------------------------------------------------------------------

# Cornell box materials (the classic measured reflectances, roughly)
WHITE, RED, GREEN = (0.75, 0.75, 0.75), (0.63, 0.065, 0.05), (0.14, 0.45, 0.091)
LIGHT_RADIANCE = 16.0  # emissiveFactor [1,1,1] * emissiveStrength
CORNELL_CAMERA = {"translation": [0.0, 0.0, 3.9], "yfov": 0.68}


def cornell_walls(b, left=RED, right=GREEN):
    """Box [-1,1]^3 open at z = +1, normals into the box, and the ceiling light; the left and right
    walls red and green unless said otherwise. Returns the mesh indices (walls, light)."""
    white = b.material("white", WHITE, specular=0.0)
    red = b.material("red" if left == RED else "left", left, specular=0.0)
    green = b.material("green" if right == GREEN else "right", right, specular=0.0)
    light = b.material("light", (0.78, 0.78, 0.78), specular=0.0, emissive=(1.0, 1.0, 1.0),
                       emissive_strength=LIGHT_RADIANCE)
    walls = [
        (quad((0, -1, 0), (0, 0, 1), (1, 0, 0)), white),   # floor, normal +y
        (quad((0, 1, 0), (1, 0, 0), (0, 0, 1)), white),    # ceiling, normal -y
        (quad((0, 0, -1), (1, 0, 0), (0, 1, 0)), white),   # back wall, normal +z
        (quad((-1, 0, 0), (0, 1, 0), (0, 0, 1)), red),     # left wall, normal +x
        (quad((1, 0, 0), (0, 0, 1), (0, 1, 0)), green),    # right wall, normal -x
    ]
    prims = []
    for (pos, nrm, idx), mat in walls:
        check_front_faces(pos, nrm, idx)
        prims.append(b.primitive(pos, idx, nrm, material=mat, index_type=UBYTE))
    wall_mesh = b.mesh(prims, "walls")
    # The classic 130 x 105 light of a 555 box, just below the ceiling, facing down.
    lpos, lnrm, lidx = quad((0, 0.995, 0), (0.235, 0, 0), (0, 0, 0.19))
    assert lnrm[0] == (0.0, -1.0, 0.0)
    check_front_faces(lpos, lnrm, lidx)
    light_mesh = b.mesh([b.primitive(lpos, lidx, lnrm, material=light, index_type=UBYTE)], "ceiling_light")
    return wall_mesh, light_mesh


def cornell_camera(b):
    cam = b.camera(CORNELL_CAMERA["yfov"], 1.0, "front")
    return b.node(name="camera", camera=cam, translation=CORNELL_CAMERA["translation"])


def cornell_box(out_dir):
    b = GltfBuilder()
    walls, light = cornell_walls(b)
    glass = b.material("glass", (1.0, 1.0, 1.0), metallic=0.0, roughness=0.0, transmission=1.0, ior=1.5,
                       thickness=1.0)
    mirror = b.material("mirror", (0.95, 0.95, 0.95), metallic=1.0, roughness=0.0)
    pos, nrm, idx = uv_sphere(48, 32)
    check_front_faces(pos, nrm, idx)
    unit_sphere = b.primitive(pos, idx, nrm)
    glass_mesh = b.mesh([dict(unit_sphere, material=glass)], "glass_sphere")
    mirror_mesh = b.mesh([dict(unit_sphere, material=mirror)], "mirror_sphere")
    r = 0.33
    roots = [
        b.node(name="walls", mesh=walls),
        b.node(name="light", mesh=light),
        b.node(name="glass_sphere", mesh=glass_mesh, translation=[0.42, -1 + r, 0.35], scale=[r, r, r]),
        b.node(name="mirror_sphere", mesh=mirror_mesh, translation=[-0.42, -1 + r, -0.3], scale=[r, r, r]),
        cornell_camera(b),
    ]
    b.scene(roots)
    b.write_embedded(os.path.join(out_dir, "cornell_box.gltf"))
    return 10 + 2 + 2 * len(idx) // 3


def dispersion_box(out_dir, dispersion=2.0, name="dispersion_box.gltf"):
    """The Cornell box all white, with the glass sphere of cornell_box.gltf alone, dispersive:
    KHR_materials_dispersion 2 (Abbe number 10) on ior 1.5. Issue 37's target scene."""
    b = GltfBuilder()
    walls, light = cornell_walls(b, WHITE, WHITE)
    ext = {"KHR_materials_dispersion": {"dispersion": dispersion}} if dispersion else None
    glass = b.material("glass", (1.0, 1.0, 1.0), metallic=0.0, roughness=0.0, transmission=1.0, ior=1.5,
                       thickness=1.0, extensions=ext)
    pos, nrm, idx = uv_sphere(48, 32)
    check_front_faces(pos, nrm, idx)
    glass_mesh = b.mesh([b.primitive(pos, idx, nrm, material=glass)], "glass_sphere")
    r = 0.33
    b.scene([
        b.node(name="walls", mesh=walls),
        b.node(name="light", mesh=light),
        b.node(name="glass_sphere", mesh=glass_mesh, translation=[0.42, -1 + r, 0.35], scale=[r, r, r]),
        cornell_camera(b),
    ])
    b.write_embedded(os.path.join(out_dir, name))
    return 10 + 2 + len(idx) // 3


def caustic(out_dir):
    b = GltfBuilder()
    floor = b.material("floor", (0.8, 0.8, 0.8), specular=0.0)
    wall = b.material("wall", (0.6, 0.6, 0.6), specular=0.0)
    glass = b.material("glass", (1.0, 1.0, 1.0), metallic=0.0, roughness=0.0, transmission=1.0, ior=1.5,
                       thickness=1.0)
    fpos, fnrm, fidx = quad((0, 0, 0), (0, 0, 4), (4, 0, 0))
    wpos, wnrm, widx = quad((0, 2, -3), (4, 0, 0), (0, 2, 0))
    spos, snrm, sidx = uv_sphere(64, 48, radius=0.5, center=(0.0, 0.5, 0.0))
    for p, n, i in ((fpos, fnrm, fidx), (wpos, wnrm, widx), (spos, snrm, sidx)):
        check_front_faces(p, n, i)
    room = b.mesh([b.primitive(fpos, fidx, fnrm, material=floor), b.primitive(wpos, widx, wnrm, material=wall)], "room")
    sphere = b.mesh([b.primitive(spos, sidx, snrm, material=glass)], "glass_sphere")
    # Spot light 45 degrees above the horizon, aimed at the sphere's centre: the ball lens (focal
    # length n R / (2 (n - 1)) = 0.75 from its centre) focuses onto the floor around (0.5, 0, 0).
    spot_pos = (-3.0, 3.5, 0.0)
    spot = b.light({"name": "spot", "type": "spot", "color": [1.0, 1.0, 1.0], "intensity": 100.0,
                    "spot": {"innerConeAngle": 0.25, "outerConeAngle": 0.35}})
    cam_pos, target = (2.6, 2.2, 3.4), (0.6, 0.3, 0.0)
    cam = b.camera(0.6, 1.5, "view")
    roots = [
        b.node(name="room", mesh=room),
        b.node(name="glass_sphere", mesh=sphere),
        b.node(name="spot", light=spot, translation=list(spot_pos),
               rotation=look_rotation(sub((0.0, 0.5, 0.0), spot_pos))),
        b.node(name="camera", camera=cam, translation=list(cam_pos), rotation=look_rotation(sub(target, cam_pos))),
    ]
    b.scene(roots)
    b.write_embedded(os.path.join(out_dir, "caustic.gltf"))
    return 4 + len(sidx) // 3


def furnace(out_dir):
    b = GltfBuilder()
    mat = b.material("furnace", (0.5, 0.5, 0.5), emissive=(1.0, 1.0, 1.0), double_sided=True, specular=0.0)
    pos, nrm, idx = uv_sphere(32, 16, radius=1.0, inward=True)
    check_front_faces(pos, nrm, idx)
    mesh = b.mesh([b.primitive(pos, idx, nrm, material=mat)], "furnace_sphere")
    cam = b.camera(1.2, 1.0, "centre")
    b.scene([b.node(name="furnace", mesh=mesh), b.node(name="camera", camera=cam)])
    b.write_embedded(os.path.join(out_dir, "furnace.gltf"))
    return len(idx) // 3


def plane_point_light(out_dir):
    b = GltfBuilder()
    mat = b.material("plane", (0.5, 0.5, 0.5), specular=0.0)
    pos, nrm, idx = quad((0, 0, 0), (0, 0, 2), (2, 0, 0))
    assert nrm[0] == (0.0, 1.0, 0.0)
    mesh = b.mesh([b.primitive(pos, idx, nrm, material=mat)], "plane")
    light = b.light({"name": "point", "type": "point", "color": [1.0, 1.0, 1.0], "intensity": 10.0})
    cam = b.camera(0.9, 1.0, "top")
    b.scene([
        b.node(name="plane", mesh=mesh),
        b.node(name="point_light", light=light, translation=[0.0, 1.0, 0.0]),
        # Looking straight down (-y), image up = -z.
        b.node(name="camera", camera=cam, translation=[0.0, 3.0, 0.0],
               rotation=[-math.sqrt(0.5), 0.0, 0.0, math.sqrt(0.5)]),
    ])
    b.write_embedded(os.path.join(out_dir, "plane_point_light.gltf"))
    return 2


def blob_displacement(d):
    x, y, z = d
    return 0.16 * math.sin(3.1 * x + 1.0) * math.sin(4.3 * y + 2.0) * math.sin(5.2 * z + 0.5) \
        + 0.05 * math.sin(11.0 * x) * math.sin(9.0 * z)


def bunny_100k(out_dir, segments=320, name="bunny_100k"):
    b = GltfBuilder()
    walls, light = cornell_walls(b)
    mat = b.material("blob", (0.72, 0.62, 0.45), specular=0.0)
    pos, nrm, idx = uv_sphere(segments, segments // 2, radius=0.5, displace=blob_displacement)
    # Rest the lowest vertex just above the floor (y = -1).
    lift = -0.999 - min(p[1] for p in pos)
    pos = [(p[0], p[1] + lift, p[2] - 0.05) for p in pos]
    assert all(abs(p[0]) < 0.95 and abs(p[2]) < 0.95 and p[1] < 0.9 for p in pos)
    blob = b.mesh([b.primitive(pos, idx, nrm, material=mat, index_type=UINT)], "blob")
    b.scene([b.node(name="walls", mesh=walls), b.node(name="light", mesh=light),
             b.node(name="blob", mesh=blob), cornell_camera(b)])
    b.write_external(os.path.join(out_dir, name + ".gltf"))
    return 12 + len(idx) // 3


def box_room(b, lo, hi, skip_x=None):
    """The inward faces of the box [lo, hi] as (quad, ...) tuples; skip_x leaves out the wall at
    that x (a partition built separately)."""
    c = scale(add(lo, hi), 0.5)
    h = scale(sub(hi, lo), 0.5)
    faces = [
        quad((c[0], lo[1], c[2]), (0, 0, h[2]), (h[0], 0, 0)),    # floor, +y
        quad((c[0], hi[1], c[2]), (h[0], 0, 0), (0, 0, h[2])),    # ceiling, -y
        quad((c[0], c[1], lo[2]), (h[0], 0, 0), (0, h[1], 0)),    # back, +z
        quad((c[0], c[1], hi[2]), (0, h[1], 0), (h[0], 0, 0)),    # front, -z
        quad((lo[0], c[1], c[2]), (0, h[1], 0), (0, 0, h[2])),    # low x, +x
        quad((hi[0], c[1], c[2]), (0, 0, h[2]), (0, h[1], 0)),    # high x, -x
    ]
    x_of = [None, None, None, None, lo[0], hi[0]]
    return [f for f, x in zip(faces, x_of) if x is None or x != skip_x]


def doorway(out_dir):
    """Two rooms side by side, the light in the one the camera cannot see: everything the camera
    sees is lit through a doorway, by light that has bounced at least once (issue 36's 'light
    through a gap'). Diffuse only, one ceiling light."""
    b = GltfBuilder()
    white = b.material("white", WHITE, specular=0.0)
    light = b.material("light", (0.78, 0.78, 0.78), specular=0.0, emissive=(1.0, 1.0, 1.0),
                       emissive_strength=4 * LIGHT_RADIANCE)
    faces = box_room(b, (-2.0, 0.0, -1.0), (0.0, 2.0, 1.0), skip_x=0.0) + box_room(b, (0.0, 0.0, -1.0),
                                                                                  (2.0, 2.0, 1.0), skip_x=0.0)
    # The partition at x = 0 with a door z in [-0.3, 0.3], y in [0, 1.4]; both sides face their room.
    for zc, zh, yc, yh in ((-0.65, 0.35, 1.0, 1.0), (0.65, 0.35, 1.0, 1.0), (0.0, 0.3, 1.7, 0.3)):
        faces.append(quad((0.0, yc, zc), (0, 0, zh), (0, yh, 0)))   # facing -x (room A)
        faces.append(quad((0.0, yc, zc), (0, yh, 0), (0, 0, zh)))   # facing +x (room B)
    prims = []
    for pos, nrm, idx in faces:
        check_front_faces(pos, nrm, idx)
        prims.append(b.primitive(pos, idx, nrm, material=white, index_type=UBYTE))
    rooms = b.mesh(prims, "rooms")
    lpos, lnrm, lidx = quad((1.2, 1.995, 0.0), (0.2, 0, 0), (0, 0, 0.2))
    assert lnrm[0] == (0.0, -1.0, 0.0)
    lamp = b.mesh([b.primitive(lpos, lidx, lnrm, material=light, index_type=UBYTE)], "lamp")
    cam_pos, target = (-1.9, 1.1, 0.9), (-0.2, 0.7, -0.3)
    cam = b.camera(1.0, 1.0, "room_a")
    b.scene([
        b.node(name="rooms", mesh=rooms),
        b.node(name="lamp", mesh=lamp),
        b.node(name="camera", camera=cam, translation=list(cam_pos), rotation=look_rotation(sub(target, cam_pos))),
    ])
    b.write_embedded(os.path.join(out_dir, "doorway.gltf"))
    return 2 * len(faces) + 2


def skylight(out_dir):
    """A closed room lit only by the sun through a small skylight: the photons of a directional
    light cover the scene's bounding disc, and about one in fifty enters (issue 36's 'light through a
    gap', for visual importance: Hachisuka and Jensen 2009). Double-sided white walls, diffuse only."""
    b = GltfBuilder()
    white = b.material("white", WHITE, specular=0.0, double_sided=True)
    faces = [f for i, f in enumerate(box_room(b, (-1.0, 0.0, -1.0), (1.0, 2.0, 1.0))) if i != 1]
    # The ceiling (y = 2, facing down) around a 0.4 x 0.4 opening centred at (0.3, -0.2).
    hx, hz, h = 0.3, -0.2, 0.2
    for (x0, x1, z0, z1) in ((-1.0, 1.0, -1.0, hz - h), (-1.0, 1.0, hz + h, 1.0), (-1.0, hx - h, hz - h, hz + h),
                             (hx + h, 1.0, hz - h, hz + h)):
        faces.append(quad(((x0 + x1) / 2, 2.0, (z0 + z1) / 2), ((x1 - x0) / 2, 0, 0), (0, 0, (z1 - z0) / 2)))
    prims = []
    for pos, nrm, idx in faces:
        check_front_faces(pos, nrm, idx)
        prims.append(b.primitive(pos, idx, nrm, material=white, index_type=UBYTE))
    room = b.mesh(prims, "room")
    sun_dir = normalize((-0.35, -1.0, 0.25))
    sun = b.light({"name": "sun", "type": "directional", "color": [1.0, 1.0, 1.0], "intensity": 20.0})
    cam_pos, target = (-0.85, 1.2, 0.9), (0.3, 0.4, -0.6)
    cam = b.camera(1.1, 1.0, "inside")
    b.scene([
        b.node(name="room", mesh=room),
        b.node(name="sun", light=sun, rotation=look_rotation(sun_dir)),
        b.node(name="camera", camera=cam, translation=list(cam_pos), rotation=look_rotation(sub(target, cam_pos))),
    ])
    b.write_embedded(os.path.join(out_dir, "skylight.gltf"))
    return 2 * len(faces)


def bunny_1m(out_dir):
    """The same blob with 10x the triangles (1.0M), for bench/scaling_10x.sh: not shipped."""
    return bunny_100k(out_dir, 1012, "bunny_1m")


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    if len(sys.argv) > 2 and sys.argv[1] == "--large":
        os.makedirs(sys.argv[2], exist_ok=True)
        print("%-20s %7d triangles" % ("bunny_1m", bunny_1m(sys.argv[2])))
        return
    out_dir = sys.argv[1] if len(sys.argv) > 1 else os.path.join(here, "..", "scenes")
    os.makedirs(out_dir, exist_ok=True)
    for make in (cornell_box, caustic, furnace, plane_point_light, bunny_100k, doorway, dispersion_box, skylight):
        print("%-20s %7d triangles" % (make.__name__, make(out_dir)))


if __name__ == "__main__":
    main()
