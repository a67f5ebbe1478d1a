#!/usr/bin/env python3
"""Writes the small glTF files that tests/gltf_load_test.cpp loads (python3 standard library).

One file per loader feature and one per error. Deterministic; run from anywhere:
    python3 tests/data/make_test_gltf.py
The expected numbers in the test follow from the geometry written here.
"""
import base64
import json
import math
import os
import struct
import sys
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))
sys.dont_write_bytecode = True  # keep scripts/ free of __pycache__
sys.path.insert(0, os.path.join(HERE, "..", "..", "scripts"))
from make_scenes import (ARRAY_BUFFER, BYTE, FLOAT, SHORT, UBYTE, UINT, USHORT, GltfBuilder,  # noqa: E402
                         add, check_front_faces, cross, dispersion_box, dot, look_rotation, normalize, quad, rounded, scale, sub,
                         uv_sphere, write_text)

NAN, INF = float("nan"), float("inf")
TRI = [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0)]
TRI_N = [(0.0, 0.0, 1.0)] * 3


def out(name):
    return os.path.join(HERE, name)


def write_doc(name, doc):
    write_text(out(name), json.dumps(rounded(doc), indent=1) + "\n")


def one_triangle(**material):
    """A builder holding one +z facing triangle under node 0 in scene 0."""
    b = GltfBuilder("clppm tests/data/make_test_gltf.py")
    mat = b.material("m", **material) if material else None
    mesh = b.mesh([b.primitive(TRI, [0, 1, 2], TRI_N, material=mat)], "tri")
    b.scene([b.node(name="tri", mesh=mesh)])
    return b


def quat_axis_angle(axis, angle):
    s = math.sin(angle / 2)
    return [axis[0] * s, axis[1] * s, axis[2] * s, math.cos(angle / 2)]


def write_lit_plate(b, name, prim, lamp):
    """The plate scenes' rig: `prim` under a point light of 4 W/sr at `lamp`, seen from (0, 1, 2)
    looking down at the origin; written as `name`."""
    light = b.light({"name": "lamp", "type": "point", "intensity": 4.0})
    cam = b.camera(0.9)
    tilt = quat_axis_angle((1, 0, 0), -math.atan2(1.0, 2.0))
    b.scene([
        b.node(name="plate", mesh=b.mesh([prim])),
        b.node(name="lamp", light=light, translation=lamp),
        b.node(name="camera", camera=cam, translation=[0.0, 1.0, 2.0], rotation=tilt),
    ])
    b.write_embedded(out(name))


def png_rgba(rows):
    """A PNG of 8-bit RGBA pixels; rows top first."""
    h, w = len(rows), len(rows[0])
    raw = b"".join(b"\x00" + bytes(c for px in row for c in px) for row in rows)

    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)

    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 6, 0, 0, 0)) +
            chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))


# ---- features ----------------------------------------------------------------------------------

def hierarchy():
    """TRS parent with a matrix child; non-uniform scale for inverse-transpose normals; scene 1
    is the default."""
    b = GltfBuilder("clppm tests/data/make_test_gltf.py")
    tri = b.mesh([b.primitive(TRI, [0, 1, 2], TRI_N)], "tri")
    s = 1 / math.sqrt(2)
    tilted = b.mesh([b.primitive([(0, 0, 0), (1, 0, 0), (0, 1, 1)], [0, 1, 2], [(0, -s, s)] * 3)], "tilted")
    child = b.node(name="child", mesh=tri, matrix=[1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 1, 1])
    parent = b.node(name="parent", children=[child], translation=[1, 2, 3],
                    rotation=quat_axis_angle((0, 0, 1), math.pi / 2), scale=[2, 2, 2])
    squashed = b.node(name="squashed", mesh=tilted, translation=[10, 0, 0], scale=[1, 4, 1])
    b.doc["scenes"] = [{"nodes": [squashed]}, {"nodes": [parent, squashed]}]
    b.doc["scene"] = 1
    b.write_embedded(out("hierarchy.gltf"))


def index_types():
    """Four quads at z = 0..3: u8, u16, u32 indices and non-indexed."""
    b = GltfBuilder("clppm tests/data/make_test_gltf.py")
    prims = []
    for z, index_type in enumerate((UBYTE, USHORT, UINT)):
        quad = [(0, 0, z), (1, 0, z), (1, 1, z), (0, 1, z)]
        prims.append(b.primitive(quad, [0, 1, 2, 0, 2, 3], [(0, 0, 1)] * 4, index_type=index_type))
    flat6 = [(0, 0, 3), (1, 0, 3), (1, 1, 3), (0, 0, 3), (1, 1, 3), (0, 1, 3)]
    prims.append(b.primitive(flat6, None, [(0, 0, 1)] * 6))
    b.scene([b.node(name="quads", mesh=b.mesh(prims, "quads"))])
    b.write_embedded(out("index_types.gltf"))


def byte_stride():
    """Interleaved POSITION/NORMAL/TEXCOORD_0 (u16 normalized) with byteStride 32, and a second
    primitive with u8 normalized TEXCOORD_0."""
    b = GltfBuilder("clppm tests/data/make_test_gltf.py")
    uv16 = [(0, 0), (65535, 0), (32768, 65535)]
    data = b"".join(struct.pack("<3f3f2H4x", *p, 0.0, 0.0, 1.0, *uv) for p, uv in zip(TRI, uv16))
    view = b.buffer_view(data, ARRAY_BUFFER, stride=32)
    pos = b.raw_accessor({"bufferView": view, "byteOffset": 0, "componentType": FLOAT, "count": 3,
                          "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]})
    nrm = b.raw_accessor({"bufferView": view, "byteOffset": 12, "componentType": FLOAT, "count": 3, "type": "VEC3"})
    uv = b.raw_accessor({"bufferView": view, "byteOffset": 24, "componentType": USHORT, "normalized": True,
                         "count": 3, "type": "VEC2"})
    first = {"attributes": {"POSITION": pos, "NORMAL": nrm, "TEXCOORD_0": uv}}
    second = b.primitive([(0, 0, 1), (1, 0, 1), (0, 1, 1)], None, TRI_N)
    second["attributes"]["TEXCOORD_0"] = b.accessor([0, 255, 51, 0, 255, 102], UBYTE, "VEC2", ARRAY_BUFFER,
                                                    normalized=True)
    b.scene([b.node(name="strided", mesh=b.mesh([first, second]))])
    b.write_embedded(out("byte_stride.gltf"))


def containers():
    """The same quad as .glb, as .gltf with an external .bin, and with an embedded data URI."""
    for name in ("box.glb", "external.gltf", "embedded.gltf"):
        b = GltfBuilder("clppm tests/data/make_test_gltf.py")
        mat = b.material("grey", (0.5, 0.5, 0.5))
        quad = [(-1, 0, -1), (1, 0, -1), (1, 0, 1), (-1, 0, 1)]
        prim = b.primitive(quad, [0, 2, 1, 0, 3, 2], [(0, 1, 0)] * 4, material=mat)
        b.scene([b.node(name="quad", mesh=b.mesh([prim]), translation=[0, 0.5, 0])])
        if name.endswith(".glb"):
            b.write_glb(out(name))
        elif name.startswith("external"):
            b.write_external(out(name))
        else:
            b.write_embedded(out(name))


def no_normals():
    """One mesh without NORMAL, instanced by two nodes: flat normals, counted once."""
    b = GltfBuilder("clppm tests/data/make_test_gltf.py")
    mesh = b.mesh([b.primitive([(0, 0, 0), (1, 0, 0), (0, 0, -1)], [0, 1, 2])], "bare")
    b.scene([b.node(name="a", mesh=mesh), b.node(name="b", mesh=mesh, translation=[0, 1, 0])])
    b.write_embedded(out("no_normals.gltf"))


def degenerate():
    """Non-indexed: 1 good triangle, 4 degenerate (repeated vertex, collinear, NaN, Inf), then a
    good triangle with tilted normals, one NaN (kept, all three normals flat +z)."""
    b = GltfBuilder("clppm tests/data/make_test_gltf.py")
    z, tilt = (0.0, 0.0, 1.0), (0.0, math.sqrt(0.5), math.sqrt(0.5))
    tris = [
        (TRI, [z, z, z]),
        ([(0, 0, 0), (1, 0, 0), (1, 0, 0)], [z, z, z]),
        ([(0, 0, 0), (1, 1, 1), (2, 2, 2)], [z, z, z]),
        ([(0, 0, 0), (NAN, 0, 0), (0, 1, 0)], [z, z, z]),
        ([(0, 0, 0), (1, 0, 0), (0, INF, 0)], [z, z, z]),
        ([(0, 0, 2), (1, 0, 2), (0, 1, 2)], [tilt, (NAN, 0.0, 1.0), tilt]),
    ]
    pos = [p for t, _ in tris for p in t]
    nrm = [n for _, ns in tris for n in ns]
    b.scene([b.node(name="mixed", mesh=b.mesh([b.primitive(pos, None, nrm, bounds=False)]))])
    b.write_embedded(out("degenerate.gltf"))


def mirror():
    """x -> -x mirror: winding must be flipped so the front face keeps agreeing with the normals."""
    b = GltfBuilder("clppm tests/data/make_test_gltf.py")
    smooth = b.primitive(TRI, [0, 1, 2], TRI_N)
    bare = b.primitive([(0, 0, 1), (1, 0, 1), (0, 1, 1)], [0, 1, 2])
    b.scene([b.node(name="mirrored", mesh=b.mesh([smooth, bare]), scale=[-1, 1, 1])])
    b.write_embedded(out("mirror.gltf"))


def skinned():
    """A triangle skinned to two joints (glTF 2.0 Sec. 3.7.3): joint 0 a node at (0, 1, 0), joint 1
    a node at (2, 0, 0) whose inverse bind matrix undoes that (so it moves nothing); corner 0 on
    joint 0, corner 1 on joint 1, corner 2 half on each. The mesh node's own translation
    (5, 0, 0) must not apply: the corners land at (0, 1, 0), (1, 0, 0) and (0, 1.5, 0)."""
    b = GltfBuilder("clppm tests/data/make_test_gltf.py")
    j0 = b.node(name="joint0", translation=[0.0, 1.0, 0.0])
    j1 = b.node(name="joint1", translation=[2.0, 0.0, 0.0])
    prim = b.primitive(TRI, [0, 1, 2], TRI_N)
    prim["attributes"]["JOINTS_0"] = b.accessor([0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0], UBYTE, "VEC4", ARRAY_BUFFER)
    prim["attributes"]["WEIGHTS_0"] = b.accessor([1.0, 0, 0, 0, 1.0, 0, 0, 0, 0.5, 0.5, 0, 0], FLOAT, "VEC4",
                                                 ARRAY_BUFFER)
    identity = [1.0, 0, 0, 0, 0, 1.0, 0, 0, 0, 0, 1.0, 0, 0, 0, 0, 1.0]
    undo_j1 = [1.0, 0, 0, 0, 0, 1.0, 0, 0, 0, 0, 1.0, 0, -2.0, 0, 0, 1.0]  # column-major T(-2, 0, 0)
    tri = b.node(name="skinned", mesh=b.mesh([prim]), translation=[5.0, 0.0, 0.0])
    b.doc["nodes"][tri]["skin"] = 0
    b.doc["skins"] = [{"joints": [j0, j1], "inverseBindMatrices": b.accessor(identity + undo_j1, FLOAT, "MAT4")}]
    b.scene([tri, j0, j1])
    b.write_embedded(out("skinned.gltf"))


def animated():
    """The pose at the start of the first animation (src/scene/gltf/gltf_animation_pose.h). The
    triangle's node rests at (5, 0, 0); animation 0 moves it LINEAR from (1, 2, 3) at t = 0.5 to
    (9, 9, 9) at t = 1, and scales it CUBICSPLINE by (2, 2, 2) at its first keyframe (in-tangents
    and out-tangents of 7 that must not be read); animation 1, never applied, moves it to (-4, 0,
    0). The corners land at 2 TRI + (1, 2, 3). animated_bad.gltf: a translation output of VEC2."""
    b = GltfBuilder("clppm tests/data/make_test_gltf.py")
    tri = b.node(name="tri", mesh=b.mesh([b.primitive(TRI, [0, 1, 2], TRI_N)]), translation=[5.0, 0.0, 0.0])
    b.scene([tri])
    times = b.accessor([0.5, 1.0], FLOAT, "SCALAR", minmax=True)
    moves = b.accessor([1.0, 2.0, 3.0, 9.0, 9.0, 9.0], FLOAT, "VEC3")
    scales = b.accessor([7.0] * 3 + [2.0] * 3 + [7.0] * 3 + [7.0] * 3 + [3.0] * 3 + [7.0] * 3, FLOAT, "VEC3")
    other = b.accessor([-4.0, 0.0, 0.0, -4.0, 0.0, 0.0], FLOAT, "VEC3")
    b.doc["animations"] = [
        {"name": "first", "samplers": [{"input": times, "output": moves},
                                       {"input": times, "output": scales, "interpolation": "CUBICSPLINE"}],
         "channels": [{"sampler": 0, "target": {"node": tri, "path": "translation"}},
                      {"sampler": 1, "target": {"node": tri, "path": "scale"}}]},
        {"name": "second", "samplers": [{"input": times, "output": other}],
         "channels": [{"sampler": 0, "target": {"node": tri, "path": "translation"}}]}]
    b.write_embedded(out("animated.gltf"))
    b.doc["animations"][0]["samplers"][0]["output"] = b.accessor([1.0, 2.0, 3.0, 4.0], FLOAT, "VEC2")
    b.write_embedded(out("animated_bad.gltf"))


def materials():
    """One triangle per material (z = material index) and one without a material."""
    b = GltfBuilder("clppm tests/data/make_test_gltf.py")
    b.material("diffuse", (0.5, 0.25, 0.125), metallic=0.0, roughness=0.7)
    b.material("emissive", (0.1, 0.1, 0.1), emissive=(1.0, 0.5, 0.25), emissive_strength=8.0)
    b.material("glass", (1, 1, 1), metallic=0.0, roughness=0.3, transmission=1.0, ior=1.33)
    b.material("mirror", (0.9, 0.9, 0.9), metallic=1.0, roughness=0.0)
    b.material("metal_mix", (0.8, 0.7, 0.6), metallic=0.4, roughness=0.5)
    b.material("two_sided", (0.3, 0.3, 0.3), double_sided=True)
    b._append("materials", {"name": "pbr_default"})
    b.material("glass_default_ior", (1, 1, 1), metallic=0.0, transmission=0.5)
    b.material("specular", (0.5, 0.5, 0.5), metallic=0.0, roughness=0.4, specular=0.5,
               specular_color=(1.0, 0.5, 0.25))
    prims = []
    for i in range(10):
        tri = [(x, y, float(i)) for x, y, _ in TRI]
        prims.append(b.primitive(tri, [0, 1, 2], TRI_N, material=i if i < 9 else None))
    b.scene([b.node(name="swatches", mesh=b.mesh(prims))])
    b.write_embedded(out("materials.gltf"))


TEXTURE_PIXELS = [[(0, 0, 0, 255), (255, 255, 255, 255)],
                  [(128, 64, 188, 255), (10, 200, 30, 128)]]


def texture():
    """A 2x2 sRGB PNG as a data URI (sampler: clamp s, magFilter LINEAR) and from a bufferView
    (clamp s and t, magFilter NEAREST, a minFilter that is not read);
    a texture on TEXCOORD_2 (not read) and one whose image is not an image."""
    b = GltfBuilder("clppm tests/data/make_test_gltf.py")
    png = png_rgba(TEXTURE_PIXELS)
    b.doc["images"] = [
        {"uri": "data:image/png;base64," + base64.b64encode(png).decode("ascii")},
        {"uri": "data:image/png;base64," + base64.b64encode(b"this is not a PNG file").decode("ascii")},
        {"bufferView": b.buffer_view(png), "mimeType": "image/png"},
    ]
    b.doc["samplers"] = [{"wrapS": 33071, "wrapT": 10497, "magFilter": 9729},
                         {"wrapS": 33071, "wrapT": 33071, "magFilter": 9728, "minFilter": 9987}]
    b.doc["textures"] = [{"source": 0, "sampler": 0}, {"source": 0}, {"source": 1}, {"source": 2, "sampler": 1}]
    b.material("textured", (1, 1, 1), base_color_texture={"index": 0})
    b.material("third_uv_set", (1, 1, 1), base_color_texture={"index": 1, "texCoord": 2})
    b.material("broken_image", (1, 1, 1), base_color_texture={"index": 2})
    b.material("from_buffer_view", (1, 1, 1), base_color_texture={"index": 3})
    uvs = [(0, 0), (1, 0), (0, 1)]
    prims = [b.primitive([(x, y, float(i)) for x, y, _ in TRI], [0, 1, 2], TRI_N, uvs=uvs, material=i)
             for i in range(4)]
    b.scene([b.node(name="textured", mesh=b.mesh(prims))])
    b.write_embedded(out("texture.gltf"))


MR_PIXEL = (0, 128, 255, 255)  # G: roughness 128/255, B: metallic 1 (linear, not sRGB)


def metallic_roughness():
    """A lit plane whose metallic and roughness come from a uniform metallicRoughnessTexture,
    the same plane with the texture's values as factors, and with the factors the texture would
    leave if it were ignored (metallic 1, roughness 1)."""
    variants = {
        "mr_texture.gltf": dict(metallic=1.0, roughness=1.0, texture=True),
        "mr_factors.gltf": dict(metallic=1.0, roughness=128 / 255, texture=False),
        "mr_untextured.gltf": dict(metallic=1.0, roughness=1.0, texture=False),
        # roughness 0.18 (alpha 0.032): smooth enough for the eye pass to sample through
        "smooth_metal_plate.gltf": dict(metallic=1.0, roughness=0.18, texture=False),
    }
    for name, v in variants.items():
        b = GltfBuilder("clppm tests/data/make_test_gltf.py")
        tex = None
        if v["texture"]:
            png = png_rgba([[MR_PIXEL, MR_PIXEL], [MR_PIXEL, MR_PIXEL]])
            b.doc["images"] = [{"uri": "data:image/png;base64," + base64.b64encode(png).decode("ascii")}]
            b.doc["textures"] = [{"source": 0}]
            tex = {"index": 0}
        b.material("plate", (0.9, 0.6, 0.3), metallic=v["metallic"], roughness=v["roughness"],
                   metallic_roughness_texture=tex)
        quad = [(-1.0, 0.0, -1.0), (-1.0, 0.0, 1.0), (1.0, 0.0, 1.0), (1.0, 0.0, -1.0)]
        uvs = [(0, 0), (0, 1), (1, 1), (1, 0)]
        prim = b.primitive(quad, [0, 1, 2, 0, 2, 3], [(0.0, 1.0, 0.0)] * 4, uvs=uvs, material=0)
        write_lit_plate(b, name, prim, lamp=[0.0, 0.8, -0.6])


def lights():
    """Point (with range), spot under a translated parent, spot with default cones, directional."""
    b = GltfBuilder("clppm tests/data/make_test_gltf.py")
    point = b.light({"name": "point", "type": "point", "color": [1.0, 0.5, 0.25], "intensity": 10.0, "range": 5.0})
    spot = b.light({"name": "spot", "type": "spot", "intensity": 20.0,
                    "spot": {"innerConeAngle": 0.2, "outerConeAngle": 0.4}})
    spot_default = b.light({"name": "spot_default", "type": "spot", "intensity": 1.0, "spot": {}})
    sun = b.light({"name": "sun", "type": "directional", "color": [1.0, 1.0, 1.0], "intensity": 3.0})
    down = quat_axis_angle((1, 0, 0), -math.pi / 2)
    spot_node = b.node(name="spot", light=spot, translation=[0, 5, 0], rotation=down)
    mesh = b.mesh([b.primitive(TRI, [0, 1, 2], TRI_N)], "tri")
    b.scene([
        b.node(name="tri", mesh=mesh),
        b.node(name="point", light=point, translation=[1, 2, 3]),
        b.node(name="rig", children=[spot_node], translation=[1, 0, 0]),
        b.node(name="spot_default", light=spot_default),
        b.node(name="sun", light=sun, rotation=quat_axis_angle((0, 1, 0), math.pi / 2)),
    ])
    b.write_embedded(out("lights.gltf"))


def cameras():
    """Perspective cameras in traversal order: extras on the node, extras on the camera under a
    translated parent, a sheared matrix (up re-orthogonalised); an orthographic one."""
    b = GltfBuilder("clppm tests/data/make_test_gltf.py")
    with_extras = b.camera(0.5, 1.5, "with_extras", extras={"aperture_radius": 0.05, "focus_distance": 4.0})
    plain = b.camera(0.8, None, "plain")
    sheared = b.camera(0.7, 2.0, "sheared")
    ortho = b._append("cameras", {"type": "orthographic", "name": "ortho",
                                  "orthographic": {"xmag": 1, "ymag": 1, "znear": 0.1, "zfar": 10}})
    mesh = b.mesh([b.primitive(TRI, [0, 1, 2], TRI_N)], "tri")
    lens_node = b.node(name="lens", camera=with_extras, translation=[0, 1, 4])
    b.scene([
        b.node(name="side", camera=plain, rotation=quat_axis_angle((0, 1, 0), math.pi / 2),
               extras={"aperture_radius": 0.1, "focus_distance": 2.0}),
        b.node(name="rig", children=[lens_node], translation=[0, 0, 1]),
        b.node(name="sheared", camera=sheared, matrix=[1, 0, 0, 0, 0, 1, 1, 0, 0, 0, 1, 0, 0, 0, 0, 1]),
        b.node(name="ortho", camera=ortho),
        b.node(name="tri", mesh=mesh),
    ])
    b.write_embedded(out("cameras.gltf"))


def quantized():
    """KHR_mesh_quantization: a quad of SHORT positions dequantized by the node's scale 1/100 with
    normalized BYTE normals and normalized SHORT texcoords; a triangle of normalized UNSIGNED_BYTE
    positions with unnormalized UNSIGNED_BYTE texcoords."""
    b = GltfBuilder("clppm tests/data/make_test_gltf.py")
    quad = b.accessor([0, 0, 0, 0, 100, 0, 0, 0, 100, 200, 0, 0, 0, 200, 0, 0], SHORT, "VEC4", ARRAY_BUFFER)
    b.doc["accessors"][quad].update({"type": "VEC3", "min": [0, 0, 0], "max": [100, 200, 0]})
    b.doc["bufferViews"][b.doc["accessors"][quad]["bufferView"]]["byteStride"] = 8  # 4-byte aligned
    nrm = b.accessor([0, 0, 127, 0] * 4, BYTE, "VEC4", ARRAY_BUFFER, normalized=True)
    b.doc["accessors"][nrm]["type"] = "VEC3"  # 4-byte aligned elements: VEC3 through byteStride 4
    b.doc["bufferViews"][b.doc["accessors"][nrm]["bufferView"]]["byteStride"] = 4
    uv = b.accessor([0, 0, 32767, 0, 32767, -32767, 0, -32767], SHORT, "VEC2", ARRAY_BUFFER, normalized=True)
    idx = b.accessor([0, 1, 2, 0, 2, 3], USHORT, "SCALAR")
    first = {"attributes": {"POSITION": quad, "NORMAL": nrm, "TEXCOORD_0": uv}, "indices": idx}
    pos8 = b.accessor([0, 0, 0, 0, 255, 0, 0, 0, 0, 51, 0, 0], UBYTE, "VEC4", ARRAY_BUFFER, normalized=True)
    b.doc["accessors"][pos8].update({"type": "VEC3", "count": 3})  # padded to 4 bytes per vertex
    b.doc["bufferViews"][b.doc["accessors"][pos8]["bufferView"]]["byteStride"] = 4
    uv8 = b.accessor([0, 0, 2, 0, 0, 3], UBYTE, "VEC2", ARRAY_BUFFER)
    second = {"attributes": {"POSITION": pos8, "TEXCOORD_0": uv8}}
    b.scene([b.node(name="quantized", mesh=b.mesh([first]), scale=[0.01, 0.01, 0.01]),
             b.node(name="unorm", mesh=b.mesh([second]), translation=[0, 0, 1])])
    b.doc["extensionsUsed"] = b.doc["extensionsRequired"] = ["KHR_mesh_quantization"]
    b.write_embedded(out("quantized.gltf"))


def sparse():
    """Sparse accessors: a triangle whose vertex 1 is moved by a sparse substitution (u8 indices),
    and one whose positions have no bufferView: zeros with vertices 1 and 2 set (u16 indices)."""
    b = GltfBuilder("clppm tests/data/make_test_gltf.py")
    base = b.accessor([v for p in TRI for v in p], FLOAT, "VEC3", ARRAY_BUFFER)
    idx8 = b.buffer_view(struct.pack("<B", 1))
    val = b.buffer_view(struct.pack("<3f", 2.0, 0.0, 0.0))
    b.doc["accessors"][base]["sparse"] = {"count": 1, "indices": {"bufferView": idx8, "componentType": UBYTE},
                                          "values": {"bufferView": val}}
    idx16 = b.buffer_view(struct.pack("<2H", 1, 2))
    vals = b.buffer_view(struct.pack("<6f", 1.0, 0.0, 5.0, 0.0, 1.0, 5.0))
    zeros = b.raw_accessor({"componentType": FLOAT, "count": 3, "type": "VEC3",
                            "sparse": {"count": 2, "indices": {"bufferView": idx16, "componentType": USHORT},
                                       "values": {"bufferView": vals}}})
    mesh = b.mesh([{"attributes": {"POSITION": base}}, {"attributes": {"POSITION": zeros}}], "sparse")
    b.scene([b.node(name="sparse", mesh=mesh)])
    b.write_embedded(out("sparse.gltf"))
    doc = b.document(b.data_uri())
    b.bin[doc["bufferViews"][idx16]["byteOffset"]:doc["bufferViews"][idx16]["byteOffset"] + 4] = struct.pack("<2H", 2, 1)
    doc = b.document(b.data_uri())
    write_doc("sparse_unsorted.gltf", doc)
    b.bin[doc["bufferViews"][idx16]["byteOffset"]:doc["bufferViews"][idx16]["byteOffset"] + 4] = struct.pack("<2H", 1, 7)
    write_doc("sparse_index_range.gltf", b.document(b.data_uri()))


def strips_fans():
    """TRIANGLE_STRIP of 5 vertices (3 triangles), TRIANGLE_FAN of 5 (3 triangles), and an indexed
    strip of two quads joined by repeated vertices (4 real triangles, 4 joining ones dropped); all face +z."""
    b = GltfBuilder("clppm tests/data/make_test_gltf.py")
    strip = [(0, 1, 0), (0, 0, 0), (1, 1, 0), (1, 0, 0), (2, 1, 0)]
    fan = [(0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1), (-1, 1, 1)]
    quads = [(0, 1, 2), (0, 0, 2), (1, 1, 2), (1, 0, 2), (5, 1, 2), (5, 0, 2), (6, 1, 2), (6, 0, 2)]
    p_strip = b.primitive(strip, None, None)
    p_strip["mode"] = 5
    p_fan = b.primitive(fan, None, None)
    p_fan["mode"] = 6
    p_joined = b.primitive(quads, [0, 1, 2, 3, 3, 4, 4, 5, 6, 7], None)
    p_joined["mode"] = 5
    b.scene([b.node(name="strips", mesh=b.mesh([p_strip, p_fan, p_joined], "strips"))])
    b.write_embedded(out("strips_fans.gltf"))


def gpu_instancing():
    """EXT_mesh_gpu_instancing: the unit triangle drawn three times under a node translated by
    (0, 0, 10): at x = 0, at x = 5 turned 90 degrees about z, at x = 10 scaled by 2."""
    b = GltfBuilder("clppm tests/data/make_test_gltf.py")
    mesh = b.mesh([b.primitive(TRI, [0, 1, 2], TRI_N)], "tri")
    t = b.accessor([0, 0, 0, 5, 0, 0, 10, 0, 0], FLOAT, "VEC3")
    q = quat_axis_angle((0, 0, 1), math.pi / 2)
    r = b.accessor([0, 0, 0, 1] + [round(v * 32767) for v in q] + [0, 0, 0, 32767], SHORT, "VEC4", normalized=True)
    s = b.accessor([1, 1, 1, 1, 1, 1, 2, 2, 2], FLOAT, "VEC3")
    node = b.node(name="forest", mesh=mesh, translation=[0, 0, 10])
    b.doc["nodes"][node]["extensions"] = {"EXT_mesh_gpu_instancing": {"attributes": {
        "TRANSLATION": t, "ROTATION": r, "SCALE": s}}}
    b.scene([node])
    b.doc["extensionsUsed"] = b.doc["extensionsRequired"] = ["EXT_mesh_gpu_instancing"]
    b.write_embedded(out("gpu_instancing.gltf"))
    doc = b.document(b.data_uri())
    doc["accessors"][s]["count"] = 2
    write_doc("gpu_instancing_counts.gltf", doc)


def emissive_texture():
    """A floor lit by a downward-facing emissive square whose emissiveTexture (64x1, clamped) is
    white on its left half (u < 0.5) and black on its right; and the same scene with only the
    left half of the square emitting, untextured. With bilinear filtering the texture's edge is a
    ramp 1/64 wide and symmetric about u = 0.5, so both emit the same power, from (to 0.1%) the
    same place."""
    white, black = (255, 255, 255, 255), (0, 0, 0, 255)
    for name, textured in (("emissive_texture.gltf", True), ("emissive_split.gltf", False)):
        b = GltfBuilder("clppm tests/data/make_test_gltf.py")
        floor = b.material("floor", (0.5, 0.5, 0.5), specular=0.0)
        lamp = b.material("lamp", (0.0, 0.0, 0.0), emissive=(1.0, 1.0, 1.0), emissive_strength=4.0, specular=0.0)
        dark = b.material("lamp_off", (0.0, 0.0, 0.0), specular=0.0)
        prims = [b.primitive([(-1.5, 0, -1.5), (-1.5, 0, 1.5), (1.5, 0, 1.5), (1.5, 0, -1.5)], [0, 1, 2, 0, 2, 3],
                             [(0, 1, 0)] * 4, material=floor)]
        if textured:
            png = png_rgba([[white] * 32 + [black] * 32])
            b.doc["images"] = [{"uri": "data:image/png;base64," + base64.b64encode(png).decode("ascii")}]
            b.doc["samplers"] = [{"wrapS": 33071, "wrapT": 33071}]
            b.doc["textures"] = [{"source": 0, "sampler": 0}]
            b.doc["materials"][lamp]["emissiveTexture"] = {"index": 0}
            quad = [(-0.5, 1, -0.5), (0.5, 1, -0.5), (0.5, 1, 0.5), (-0.5, 1, 0.5)]
            uvs = [(0, 0), (1, 0), (1, 1), (0, 1)]
            prims.append(b.primitive(quad, [0, 1, 2, 0, 2, 3], [(0, -1, 0)] * 4, uvs=uvs, material=lamp))
        else:
            left = [(-0.5, 1, -0.5), (0.0, 1, -0.5), (0.0, 1, 0.5), (-0.5, 1, 0.5)]
            right = [(0.0, 1, -0.5), (0.5, 1, -0.5), (0.5, 1, 0.5), (0.0, 1, 0.5)]
            prims.append(b.primitive(left, [0, 1, 2, 0, 2, 3], [(0, -1, 0)] * 4, material=lamp))
            prims.append(b.primitive(right, [0, 1, 2, 0, 2, 3], [(0, -1, 0)] * 4, material=dark))
        cam = b.camera(1.0)
        b.scene([b.node(name="room", mesh=b.mesh(prims)),
                 b.node(name="camera", camera=cam, translation=[0.0, 0.45, 2.2])])
        b.write_embedded(out(name))


NORMAL_TEXEL = (200, 128, 220, 255)  # a normal tilted about 38 degrees towards the tangent (+x)


def texel_normal(texel):
    c = [v / 255 * 2 - 1 for v in texel[:3]]
    n = math.sqrt(sum(v * v for v in c))
    return tuple(v / n for v in c)


def normal_maps():
    """normal_map.gltf: a +z quad whose uv runs +x and down (glTF's v), with a 2x2 normalTexture
    (scale 0.8) and no TANGENT; a second quad with TANGENT (0, 1, 0, -1); the first mesh again
    under a mirroring node (scale x by -1).
    normal_plate_*.gltf: a lit plate with a uniform normal map, the same plate with that normal as
    its vertex normals, and the flat plate; normal_plate_terminator*.gltf: the map on a plate
    whose smooth normals face away from the lamp, and the plate with the mapped normals."""
    b = GltfBuilder("clppm tests/data/make_test_gltf.py")
    png = png_rgba([[NORMAL_TEXEL, (128, 128, 255, 255)], [(128, 200, 220, 255), (60, 100, 230, 255)]])
    b.doc["images"] = [{"uri": "data:image/png;base64," + base64.b64encode(png).decode("ascii")}]
    b.doc["textures"] = [{"source": 0}]
    mat = b.material("bumpy", (0.8, 0.8, 0.8))
    b.doc["materials"][mat]["normalTexture"] = {"index": 0, "scale": 0.8}
    quad = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0)]
    uvs = [(0, 1), (1, 1), (1, 0), (0, 0)]
    generated = b.primitive(quad, [0, 1, 2, 0, 2, 3], [(0, 0, 1)] * 4, uvs=uvs, material=mat)
    given = b.primitive([(x, y, 1) for x, y, _ in quad], [0, 1, 2, 0, 2, 3], [(0, 0, 1)] * 4, uvs=uvs, material=mat)
    given["attributes"]["TANGENT"] = b.accessor([0, 1, 0, -1] * 4, FLOAT, "VEC4", ARRAY_BUFFER)
    m0 = b.mesh([generated], "generated")
    lamp = b.light({"name": "lamp", "type": "point", "intensity": 1.0})
    b.scene([b.node(name="generated", mesh=m0), b.node(name="given", mesh=b.mesh([given], "given")),
             b.node(name="mirrored", mesh=m0, translation=[5, 0, 0], scale=[-1, 1, 1]),
             b.node(name="lamp", light=lamp, translation=[0.5, 0.5, 3])])
    b.write_embedded(out("normal_map.gltf"))

    tilted = texel_normal(NORMAL_TEXEL)
    # (t, b, n) = (+x, -z, +y): the tilted normal in world space.
    world = (tilted[0], tilted[2], -tilted[1])
    flat = (0.0, 1.0, 0.0)
    lit_plate("normal_plate_mapped.gltf", flat, mapped=True)
    lit_plate("normal_plate_geometry.gltf", world, mapped=False)
    lit_plate("normal_plate_flat.gltf", flat, mapped=False)
    # Past the terminator: the same plate and map, but smooth (vertex) normals tilted 45 degrees
    # away from the lamp, so that the lamp lies below the smooth normal everywhere on the plate
    # (though above the flat triangles), while the map tilts the shading normal 38 degrees back
    # towards it; and the unmapped plate whose vertex normals are that mapped normal.
    smooth = (-math.sqrt(0.5), math.sqrt(0.5), 0.0)
    c, s = tilted[2], tilted[0]  # the map's tilt about z, from smooth towards +x
    shading = (smooth[0] * c + smooth[1] * s, smooth[1] * c - smooth[0] * s, 0.0)
    lit_plate("normal_plate_terminator.gltf", smooth, mapped=True)
    lit_plate("normal_plate_terminator_geometry.gltf", shading, mapped=False)


def lit_plate(name, normal, mapped):
    """A 2 x 2 plate in y = 0 facing +y with vertex normals `normal`, under write_lit_plate's rig
    with the lamp low towards +x; with `mapped`, a uniform normalTexture of NORMAL_TEXEL. u runs
    along +x and v along +z (down the image), so the tangent is +x and the bitangent (the map's +Y)
    is -z."""
    b = GltfBuilder("clppm tests/data/make_test_gltf.py")
    plate = b.material("plate", (0.8, 0.8, 0.8), roughness=0.5)
    if mapped:
        png = png_rgba([[NORMAL_TEXEL] * 2] * 2)
        b.doc["images"] = [{"uri": "data:image/png;base64," + base64.b64encode(png).decode("ascii")}]
        b.doc["textures"] = [{"source": 0}]
        b.doc["materials"][plate]["normalTexture"] = {"index": 0}
    quad = [(-1.0, 0.0, -1.0), (-1.0, 0.0, 1.0), (1.0, 0.0, 1.0), (1.0, 0.0, -1.0)]
    uvs = [(0, 0), (0, 1), (1, 1), (1, 0)]
    prim = b.primitive(quad, [0, 1, 2, 0, 2, 3], [normal] * 4, uvs=uvs, material=plate)
    write_lit_plate(b, name, prim, lamp=[1.6, 0.5, 0.0])


def vertex_colors():
    """COLOR_0: a lit plate whose vertex colours (0.5, 0.25, 1) multiply its base colour 0.8, and
    the same plate with base colour (0.4, 0.2, 0.8); a triangle with normalized UNSIGNED_BYTE RGBA
    colours next to one without COLOR_0."""
    for name, colored in (("color_plate_vertex.gltf", True), ("color_plate_factor.gltf", False)):
        b = GltfBuilder("clppm tests/data/make_test_gltf.py")
        plate = b.material("plate", (0.8, 0.8, 0.8) if colored else (0.4, 0.2, 0.8), roughness=0.5)
        quad = [(-1.0, 0.0, -1.0), (-1.0, 0.0, 1.0), (1.0, 0.0, 1.0), (1.0, 0.0, -1.0)]
        prim = b.primitive(quad, [0, 1, 2, 0, 2, 3], [(0.0, 1.0, 0.0)] * 4, material=plate)
        if colored:
            prim["attributes"]["COLOR_0"] = b.accessor([0.5, 0.25, 1.0] * 4, FLOAT, "VEC3", ARRAY_BUFFER)
        write_lit_plate(b, name, prim, lamp=[0.0, 0.8, -0.3])
    b = GltfBuilder("clppm tests/data/make_test_gltf.py")
    first = b.primitive(TRI, [0, 1, 2], TRI_N)
    first["attributes"]["COLOR_0"] = b.accessor([255, 0, 0, 255, 0, 255, 0, 128, 0, 0, 51, 0], UBYTE, "VEC4",
                                                ARRAY_BUFFER, normalized=True)
    second = b.primitive([(x, y, 1.0) for x, y, _ in TRI], [0, 1, 2], TRI_N)
    b.scene([b.node(name="colored", mesh=b.mesh([first, second]))])
    b.write_embedded(out("vertex_colors.gltf"))


def alpha_modes():
    """alphaMode. alpha_mask_card.gltf: a black card between a point light and a floor whose
    baseColorTexture (64x1, clamped) is transparent on its left half, alphaMode MASK; it renders
    (image and shadow) as alpha_mask_half.gltf, the right half of the card alone.
    alpha_blend_*.gltf: a black vertical card of alpha 0.5 between the camera and the floor, the
    light beyond it: "blend" (BLEND), "opaque" (OPAQUE) and "none" (no card). No light path
    crosses the card twice, so blend = (opaque + none) / 2 in expectation."""
    clear, solid = (0, 0, 0, 0), (0, 0, 0, 255)
    for name, kind in (("alpha_mask_card.gltf", "card"), ("alpha_mask_half.gltf", "half")):
        b = GltfBuilder("clppm tests/data/make_test_gltf.py")
        floor = b.material("floor", (0.5, 0.5, 0.5), specular=0.0)
        card = b.material("card", (1.0, 1.0, 1.0) if kind == "card" else (0.0, 0.0, 0.0), specular=0.0,
                          double_sided=True)
        prims = [b.primitive([(-1.5, 0, -1.5), (-1.5, 0, 1.5), (1.5, 0, 1.5), (1.5, 0, -1.5)], [0, 1, 2, 0, 2, 3],
                             [(0, 1, 0)] * 4, material=floor)]
        if kind == "card":
            png = png_rgba([[clear] * 32 + [solid] * 32])
            b.doc["images"] = [{"uri": "data:image/png;base64," + base64.b64encode(png).decode("ascii")}]
            b.doc["samplers"] = [{"wrapS": 33071, "wrapT": 33071}]
            b.doc["textures"] = [{"source": 0, "sampler": 0}]
            b.doc["materials"][card]["pbrMetallicRoughness"]["baseColorTexture"] = {"index": 0}
            b.doc["materials"][card]["alphaMode"] = "MASK"
            quad = [(-0.5, 1, -0.5), (-0.5, 1, 0.5), (0.5, 1, 0.5), (0.5, 1, -0.5)]
            uvs = [(0, 0), (0, 1), (1, 1), (1, 0)]
        else:
            quad = [(0.0, 1, -0.5), (0.0, 1, 0.5), (0.5, 1, 0.5), (0.5, 1, -0.5)]
            uvs = None
        prims.append(b.primitive(quad, [0, 1, 2, 0, 2, 3], [(0, 1, 0)] * 4, uvs=uvs, material=card))
        light = b.light({"name": "lamp", "type": "point", "intensity": 6.0})
        cam = b.camera(0.9)
        tilt = quat_axis_angle((1, 0, 0), -math.atan2(1.4, 2.4))
        b.scene([b.node(name="room", mesh=b.mesh(prims)),
                 b.node(name="lamp", light=light, translation=[0.1, 2.0, 0.0]),
                 b.node(name="camera", camera=cam, translation=[0.0, 1.8, 2.4], rotation=tilt)])
        b.write_embedded(out(name))
    for kind in ("blend", "opaque", "none"):
        b = GltfBuilder("clppm tests/data/make_test_gltf.py")
        floor = b.material("floor", (0.5, 0.5, 0.5), specular=0.0)
        card = b.material("card", (0.0, 0.0, 0.0, 0.5), specular=0.0, double_sided=True)
        if kind == "blend":
            b.doc["materials"][card]["alphaMode"] = "BLEND"
        prims = [b.primitive([(-1.5, 0, -1.5), (-1.5, 0, 1.5), (1.5, 0, 1.5), (1.5, 0, -1.5)], [0, 1, 2, 0, 2, 3],
                             [(0, 1, 0)] * 4, material=floor)]
        if kind != "none":
            quad = [(-0.6, 0.2, 1.0), (0.6, 0.2, 1.0), (0.6, 0.8, 1.0), (-0.6, 0.8, 1.0)]
            prims.append(b.primitive(quad, [0, 1, 2, 0, 2, 3], [(0, 0, 1)] * 4, material=card))
        light = b.light({"name": "lamp", "type": "point", "intensity": 6.0})
        cam = b.camera(0.9)
        tilt = quat_axis_angle((1, 0, 0), -math.atan2(0.7, 3.0))
        b.scene([b.node(name="room", mesh=b.mesh(prims)),
                 b.node(name="lamp", light=light, translation=[0.0, 2.0, -1.0]),
                 b.node(name="camera", camera=cam, translation=[0.0, 1.0, 3.0], rotation=tilt)])
        b.write_embedded(out("alpha_blend_%s.gltf" % kind))


def texture_transform():
    """KHR_texture_transform and TEXCOORD_1: the extension's own example (offset (0, 1), rotation
    pi/2, scale 0.5: the lower left quadrant turned clockwise) on TEXCOORD_0; a second reference
    to the same texture moved to TEXCOORD_1 by the extension's texCoord; a MIRRORED_REPEAT
    sampler. The triangle's TEXCOORD_1 is (2, 0), (3, 0), (2, 1)."""
    b = GltfBuilder("clppm tests/data/make_test_gltf.py")
    png = png_rgba(TEXTURE_PIXELS)
    b.doc["images"] = [{"uri": "data:image/png;base64," + base64.b64encode(png).decode("ascii")}]
    b.doc["samplers"] = [{"wrapS": 33648, "wrapT": 10497}]
    b.doc["textures"] = [{"source": 0, "sampler": 0}]
    example = {"KHR_texture_transform": {"offset": [0, 1], "rotation": math.pi / 2, "scale": [0.5, 0.5]}}
    b.material("example", (1, 1, 1), base_color_texture={"index": 0, "extensions": example})
    b.material("second_set", (1, 1, 1), base_color_texture={
        "index": 0, "extensions": {"KHR_texture_transform": {"texCoord": 1, "offset": [0.25, 0]}}})
    prims = []
    for i in range(2):
        prim = b.primitive([(x, y, float(i)) for x, y, _ in TRI], [0, 1, 2], TRI_N, uvs=[(0, 0), (1, 0), (0, 1)],
                           material=i)
        prim["attributes"]["TEXCOORD_1"] = b.accessor([2, 0, 3, 0, 2, 1], FLOAT, "VEC2", ARRAY_BUFFER)
        prims.append(prim)
    b.scene([b.node(name="transformed", mesh=b.mesh(prims))])
    b.doc["extensionsUsed"] = ["KHR_texture_transform"]
    b.write_embedded(out("texture_transform.gltf"))


def uv1_plates():
    """A lit plate textured through TEXCOORD_1 and a KHR_texture_transform (scale 0.5, offset
    (0.25, 0.25), rotation 0.3), its TEXCOORD_0 all zeros; and the same plate whose TEXCOORD_0
    holds the transformed coordinates, untransformed. They render alike."""
    c, s_ = math.cos(0.3), math.sin(0.3)

    def xf(u, v):
        return (0.5 * c * u + 0.5 * s_ * v + 0.25, -0.5 * s_ * u + 0.5 * c * v + 0.25)
    uvs = [(0, 0), (0, 1), (1, 1), (1, 0)]
    for name, via_set1 in (("uv1_plate_set1.gltf", True), ("uv1_plate_set0.gltf", False)):
        b = GltfBuilder("clppm tests/data/make_test_gltf.py")
        png = png_rgba(TEXTURE_PIXELS)
        b.doc["images"] = [{"uri": "data:image/png;base64," + base64.b64encode(png).decode("ascii")}]
        b.doc["textures"] = [{"source": 0}]
        ref = {"index": 0}
        if via_set1:
            ref["extensions"] = {"KHR_texture_transform": {"texCoord": 1, "offset": [0.25, 0.25], "rotation": 0.3,
                                                           "scale": [0.5, 0.5]}}
            b.doc["extensionsUsed"] = ["KHR_texture_transform"]
        plate = b.material("plate", (1, 1, 1), roughness=0.6, base_color_texture=ref)
        quad = [(-1.0, 0.0, -1.0), (-1.0, 0.0, 1.0), (1.0, 0.0, 1.0), (1.0, 0.0, -1.0)]
        prim = b.primitive(quad, [0, 1, 2, 0, 2, 3], [(0.0, 1.0, 0.0)] * 4,
                           uvs=[(0, 0)] * 4 if via_set1 else [xf(u, v) for u, v in uvs], material=plate)
        if via_set1:
            prim["attributes"]["TEXCOORD_1"] = b.accessor([x for uv in uvs for x in uv], FLOAT, "VEC2", ARRAY_BUFFER)
        write_lit_plate(b, name, prim, lamp=[0.0, 0.8, -0.3])


def box_primitive(b, lo, hi, material):
    """A closed box from lo to hi, each face its own 4 vertices with outward normals."""
    prims_pos, normals, idx = [], [], []
    for axis in range(3):
        for side in (0, 1):
            n = [0.0, 0.0, 0.0]
            n[axis] = 1.0 if side else -1.0
            u, v = (axis + 1) % 3, (axis + 2) % 3
            corners = []
            for a, c in ((0, 0), (1, 0), (1, 1), (0, 1)):
                p = [0.0, 0.0, 0.0]
                p[axis] = hi[axis] if side else lo[axis]
                p[u] = hi[u] if a else lo[u]
                p[v] = hi[v] if c else lo[v]
                corners.append(tuple(p))
            if not side:  # keep the winding counter-clockwise seen from outside
                corners = [corners[0], corners[3], corners[2], corners[1]]
            base = len(prims_pos)
            prims_pos += corners
            normals += [tuple(n)] * 4
            idx += [base, base + 1, base + 2, base + 0, base + 2, base + 3]
    return b.primitive(prims_pos, idx, normals, material=material)


def volumes():
    """KHR_materials_volume: a smooth glass slab 0.5 thick between the camera and an emitter,
    attenuationColor (0.5, 0.25, 1) at attenuationDistance 0.5, so exp(-sigma d) = (0.5, 0.25, 1);
    the same slab without attenuation; and transmissionTexture: the slab at transmission 1 with
    a uniform texture of R = 51 against transmissionFactor 0.2. The rough_ pair is the slab at
    roughness 0.5 lit by a point light behind it: what the camera sees of it comes through both
    faces, and bidirectional methods connect vertices on the two faces through the inside."""
    variants = (("volume_slab.gltf", "volume"), ("volume_clear.gltf", "clear"),
                ("transmission_texture.gltf", "texture"), ("transmission_factor.gltf", "factor"),
                ("rough_volume_slab.gltf", "volume"), ("rough_volume_clear.gltf", "clear"))
    for name, kind in variants:
        b = GltfBuilder("clppm tests/data/make_test_gltf.py")
        # A solid slab in every variant (thicknessFactor 0.5); only "volume" absorbs.
        glass = b.material("glass", (1.0, 1.0, 1.0), roughness=0.5 if name.startswith("rough_") else 0.0,
                           transmission=0.2 if kind == "factor" else 1.0, ior=1.5, thickness=0.5)
        if kind == "volume":
            b.doc["materials"][glass]["extensions"]["KHR_materials_volume"].update(
                {"attenuationDistance": 0.5, "attenuationColor": [0.5, 0.25, 1.0]})
        if kind == "texture":
            png = png_rgba([[(51, 0, 0, 255)] * 2] * 2)  # 51 / 255 = 0.2, the same float
            b.doc["images"] = [{"uri": "data:image/png;base64," + base64.b64encode(png).decode("ascii")}]
            b.doc["textures"] = [{"source": 0}]
            b.doc["materials"][glass]["extensions"]["KHR_materials_transmission"]["transmissionTexture"] = {"index": 0}
        lamp = b.material("lamp", (0.0, 0.0, 0.0), emissive=(1.0, 1.0, 1.0), specular=0.0)
        slab = box_primitive(b, (-3.0, -3.0, -0.25), (3.0, 3.0, 0.25), glass)
        if kind in ("texture", "factor"):
            slab["attributes"]["TEXCOORD_0"] = b.accessor([0.5] * (2 * 24), FLOAT, "VEC2", ARRAY_BUFFER)
        emitter = b.primitive([(-5, -5, -1), (5, -5, -1), (5, 5, -1), (-5, 5, -1)], [0, 1, 2, 0, 2, 3],
                              [(0, 0, 1)] * 4, material=lamp)
        cam = b.camera(0.1)
        if name.startswith("rough_"):  # lit by a point light behind the slab instead
            lamp = b.light({"name": "lamp", "type": "point", "intensity": 10.0})
            b.scene([b.node(name="slab", mesh=b.mesh([slab])),
                     b.node(name="camera", camera=cam, translation=[0.0, 0.0, 2.0]),
                     b.node(name="lamp", light=lamp, translation=[0.0, 0.0, -1.0])])
        else:
            b.scene([b.node(name="slab", mesh=b.mesh([slab, emitter])),
                     b.node(name="camera", camera=cam, translation=[0.0, 0.0, 2.0])])
        b.write_embedded(out(name))


def unlit():
    """KHR_materials_unlit: a wall (diffuse 0.8, no specular layer) at z = -1 facing the camera
    and, before its left half at z = 0, an unlit panel of base colour (0.2, 0.5, 0.8) times a
    COLOR_0 of (1, 0.5, 1); a point light at (1, 0, 1) lights the wall, and the panel shadows part
    of it. unlit_dark.gltf: the same panel with base colour 0. unlit_alone.gltf: the panel without
    the lamp, nothing but the unlit panel to see. A black world."""
    for name, color in (("unlit_panel.gltf", (0.2, 0.5, 0.8)), ("unlit_dark.gltf", (0.0, 0.0, 0.0)),
                        ("unlit_alone.gltf", (0.2, 0.5, 0.8))):
        b = GltfBuilder("clppm tests/data/make_test_gltf.py")
        wall = b.material("wall", (0.8, 0.8, 0.8), specular=0.0)
        panel = b.material("panel", color, metallic=1.0, roughness=0.0, extensions={"KHR_materials_unlit": {}})
        w = b.primitive([(-4, -4, -1), (4, -4, -1), (4, 4, -1), (-4, 4, -1)], [0, 1, 2, 0, 2, 3],
                        [(0, 0, 1)] * 4, material=wall)
        p = b.primitive([(-2, -1, 0), (-0.2, -1, 0), (-0.2, 1, 0), (-2, 1, 0)], [0, 1, 2, 0, 2, 3],
                        [(0, 0, 1)] * 4, material=panel)
        p["attributes"]["COLOR_0"] = b.accessor([1.0, 0.5, 1.0] * 4, FLOAT, "VEC3", ARRAY_BUFFER)
        lamp = b.light({"name": "lamp", "type": "point", "intensity": 4.0}) if name != "unlit_alone.gltf" else None
        nodes = [b.node(name="scene", mesh=b.mesh([w, p]))]
        if lamp is not None:
            nodes.append(b.node(name="lamp", light=lamp, translation=[1.0, 0.0, 1.0]))
        nodes.append(b.node(name="camera", camera=b.camera(0.8), translation=[0.0, 0.0, 3.0]))
        b.scene(nodes)
        if lamp is None:
            b.world(color=(0.0, 0.0, 0.0))
        b.write_embedded(out(name))


def plate_in_white_world(name, **material):
    """A 2 x 2 plate of the given material facing a camera of yfov 0.1 at distance 3 (views within
    3 degrees of the normal), in a uniform white world of radiance 1, which lights both sides."""
    b = GltfBuilder("clppm tests/data/make_test_gltf.py")
    plate = b.material("plate", **material)
    p = b.primitive([(-1, -1, 0), (1, -1, 0), (1, 1, 0), (-1, 1, 0)], [0, 1, 2, 0, 2, 3], [(0, 0, 1)] * 4,
                    material=plate)
    b.scene([b.node(name="plate", mesh=b.mesh([p])),
             b.node(name="camera", camera=b.camera(0.1), translation=[0.0, 0.0, 3.0])])
    b.world(color=(1.0, 1.0, 1.0))
    b.write_embedded(out(name))


def clearcoat():
    """KHR_materials_clearcoat: a plate facing the camera (yfov 0.1, so views within 3 degrees of
    the normal) of a black base without specular layer under a full coat, in a uniform white
    world of radiance 1: what it shows is the coat's directional albedo, exactly 0.04 (Schlick at
    normal incidence) for coat_plate.gltf (smooth) and the GGX layer's for coat_rough_plate.gltf
    (clearcoatRoughnessFactor 0.5). coat_textured.gltf: factors and textures of every kind, for
    the loader."""
    for name, rough in (("coat_plate.gltf", 0.0), ("coat_rough_plate.gltf", 0.5)):
        plate_in_white_world(name, base_color=(0.0, 0.0, 0.0), specular=0.0,
                             extensions={"KHR_materials_clearcoat": {"clearcoatFactor": 1.0,
                                                                     "clearcoatRoughnessFactor": rough}})
    b = GltfBuilder("clppm tests/data/make_test_gltf.py")
    png = png_rgba([[(128, 64, 0, 255)] * 2] * 2)
    b.doc["images"] = [{"uri": "data:image/png;base64," + base64.b64encode(png).decode("ascii")}]
    b.doc["textures"] = [{"source": 0}]
    coat = {"clearcoatFactor": 0.8, "clearcoatRoughnessFactor": 0.3, "clearcoatTexture": {"index": 0},
            "clearcoatRoughnessTexture": {"index": 0}, "clearcoatNormalTexture": {"index": 0, "scale": 0.5}}
    plate = b.material("plate", (0.5, 0.5, 0.5), extensions={"KHR_materials_clearcoat": coat})
    p = b.primitive([(-1, -1, 0), (1, -1, 0), (1, 1, 0), (-1, 1, 0)], [0, 1, 2, 0, 2, 3], [(0, 0, 1)] * 4,
                    material=plate)
    p["attributes"]["TEXCOORD_0"] = b.accessor([0.0, 0.0, 1.0, 0.0, 1.0, 1.0, 0.0, 1.0], FLOAT, "VEC2", ARRAY_BUFFER)
    b.scene([b.node(name="plate", mesh=b.mesh([p]))])
    b.write_embedded(out("coat_textured.gltf"))


def sheen():
    """KHR_materials_sheen: a plate facing the camera (views within 3 degrees of the normal) of a
    black base without specular layer under a white sheen of roughness 1 in a uniform white world:
    it shows the sheen lobe's directional albedo (kernels/sheen_albedo.h). sheen_textured.gltf:
    factors and textures, for the loader."""
    plate_in_white_world("sheen_plate.gltf", base_color=(0.0, 0.0, 0.0), specular=0.0,
                         extensions={"KHR_materials_sheen": {"sheenColorFactor": [1.0, 1.0, 1.0],
                                                             "sheenRoughnessFactor": 1.0}})
    b = GltfBuilder("clppm tests/data/make_test_gltf.py")
    png = png_rgba([[(128, 64, 0, 128)] * 2] * 2)
    b.doc["images"] = [{"uri": "data:image/png;base64," + base64.b64encode(png).decode("ascii")}]
    b.doc["textures"] = [{"source": 0}]
    ext = {"sheenColorFactor": [0.5, 0.25, 1.0], "sheenRoughnessFactor": 0.6, "sheenColorTexture": {"index": 0},
           "sheenRoughnessTexture": {"index": 0}}
    plate = b.material("plate", (0.5, 0.5, 0.5), extensions={"KHR_materials_sheen": ext})
    p = b.primitive([(-1, -1, 0), (1, -1, 0), (1, 1, 0), (-1, 1, 0)], [0, 1, 2, 0, 2, 3], [(0, 0, 1)] * 4,
                    material=plate)
    p["attributes"]["TEXCOORD_0"] = b.accessor([0.0, 0.0, 1.0, 0.0, 1.0, 1.0, 0.0, 1.0], FLOAT, "VEC2", ARRAY_BUFFER)
    b.scene([b.node(name="plate", mesh=b.mesh([p]))])
    b.write_embedded(out("sheen_textured.gltf"))


def diffuse_transmission():
    """KHR_materials_diffuse_transmission. dt_plate_*.gltf: a plate facing the camera (views within
    3 degrees of the normal) in a uniform white world of radiance 1, which lights both of its
    sides: it shows (1 - dt) base + dt colour under no layer, and E + (1 - E)((1 - dt) base + dt
    colour) under a smooth layer (E = 0.04 head-on). dt_full: dt 1, colour (1, 0.5, 0.25), black
    base, no layer; dt_half: dt 0.5, base 0.2 and that colour, no layer; dt_layer: dt_half under
    the default specular layer at roughness 0. dt_box_*.gltf: a closed box 0.5 thick, dt 1,
    between the camera and a point light, lit only through it: dt_box_volume absorbs inside
    (attenuationColor (0.5, 0.25, 1) at distance 0.5), dt_box_clear does not. dt_textured.gltf:
    factors and textures, for the loader."""
    color = [1.0, 0.5, 0.25]
    for name, dt, base, spec, rough in (("dt_full_plate.gltf", 1.0, 0.0, 0.0, 1.0),
                                        ("dt_half_plate.gltf", 0.5, 0.2, 0.0, 1.0),
                                        ("dt_layer_plate.gltf", 0.5, 0.2, None, 0.0)):
        ext = {"KHR_materials_diffuse_transmission": {"diffuseTransmissionFactor": dt,
                                                      "diffuseTransmissionColorFactor": color}}
        plate_in_white_world(name, base_color=(base, base, base), roughness=rough, specular=spec, extensions=ext)
    for name, absorb in (("dt_box_volume.gltf", True), ("dt_box_clear.gltf", False)):
        b = GltfBuilder("clppm tests/data/make_test_gltf.py")
        ext = {"KHR_materials_diffuse_transmission": {"diffuseTransmissionFactor": 1.0},
               "KHR_materials_volume": {"thicknessFactor": 0.5}}
        if absorb:
            ext["KHR_materials_volume"].update({"attenuationDistance": 0.5, "attenuationColor": [0.5, 0.25, 1.0]})
        box = b.material("box", (0.0, 0.0, 0.0), specular=0.0, extensions=ext)
        slab = box_primitive(b, (-3.0, -3.0, -0.25), (3.0, 3.0, 0.25), box)
        lamp = b.light({"name": "lamp", "type": "point", "intensity": 10.0})
        b.scene([b.node(name="box", mesh=b.mesh([slab])),
                 b.node(name="camera", camera=b.camera(0.3), translation=[0.0, 0.0, 2.0]),
                 b.node(name="lamp", light=lamp, translation=[0.0, 0.0, -1.0])])
        b.world(color=(0.0, 0.0, 0.0))
        b.write_embedded(out(name))
    b = GltfBuilder("clppm tests/data/make_test_gltf.py")
    png = png_rgba([[(128, 64, 0, 128)] * 2] * 2)
    b.doc["images"] = [{"uri": "data:image/png;base64," + base64.b64encode(png).decode("ascii")}]
    b.doc["textures"] = [{"source": 0}]
    ext = {"diffuseTransmissionFactor": 0.75, "diffuseTransmissionTexture": {"index": 0},
           "diffuseTransmissionColorFactor": [0.5, 0.25, 1.0], "diffuseTransmissionColorTexture": {"index": 0}}
    plate = b.material("plate", (0.5, 0.5, 0.5), extensions={"KHR_materials_diffuse_transmission": ext})
    p = b.primitive([(-1, -1, 0), (1, -1, 0), (1, 1, 0), (-1, 1, 0)], [0, 1, 2, 0, 2, 3], [(0, 0, 1)] * 4,
                    material=plate)
    p["attributes"]["TEXCOORD_0"] = b.accessor([0.0, 0.0, 1.0, 0.0, 1.0, 1.0, 0.0, 1.0], FLOAT, "VEC2", ARRAY_BUFFER)
    b.scene([b.node(name="plate", mesh=b.mesh([p]))])
    b.write_embedded(out("dt_textured.gltf"))


def camera_clipping():
    """Cameras. ortho_square*.gltf: an unlit square (0.2, 0.5, 0.8) of side 1 at the origin, seen
    by an orthographic camera of xmag = ymag = 1 from 5 and from 50 along +z, in a white world:
    it covers the middle half of the image at any distance. znear_*.gltf: the lit wall and unlit panel of
    unlit_panel.gltf with, 0.3 before the camera, a black unlit occluder over the whole view:
    clipped at znear 0.5 (znear_clipped.gltf), seen at znear 0.1 (znear_seen.gltf); znear_open.gltf
    without it."""
    for name, z in (("ortho_square.gltf", 5.0), ("ortho_square_far.gltf", 50.0)):
        b = GltfBuilder("clppm tests/data/make_test_gltf.py")
        square = b.material("square", (0.2, 0.5, 0.8), extensions={"KHR_materials_unlit": {}})
        p = b.primitive([(-0.5, -0.5, 0), (0.5, -0.5, 0), (0.5, 0.5, 0), (-0.5, 0.5, 0)], [0, 1, 2, 0, 2, 3],
                        [(0, 0, 1)] * 4, material=square)
        cam = b._append("cameras", {"type": "orthographic",
                                    "orthographic": {"xmag": 1.0, "ymag": 1.0, "znear": 0.01, "zfar": 100.0}})
        b.scene([b.node(name="square", mesh=b.mesh([p])), b.node(name="camera", camera=cam, translation=[0, 0, z])])
        b.world(color=(1.0, 1.0, 1.0))
        b.write_embedded(out(name))
    for name, znear, occluded in (("znear_clipped.gltf", 0.5, True), ("znear_seen.gltf", 0.1, True),
                                  ("znear_open.gltf", 0.5, False)):
        b = GltfBuilder("clppm tests/data/make_test_gltf.py")
        wall = b.material("wall", (0.8, 0.8, 0.8), specular=0.0)
        panel = b.material("panel", (0.2, 0.5, 0.8), extensions={"KHR_materials_unlit": {}})
        prims = [b.primitive([(-4, -4, -1), (4, -4, -1), (4, 4, -1), (-4, 4, -1)], [0, 1, 2, 0, 2, 3],
                             [(0, 0, 1)] * 4, material=wall),
                 b.primitive([(-2, -1, 0), (-0.2, -1, 0), (-0.2, 1, 0), (-2, 1, 0)], [0, 1, 2, 0, 2, 3],
                             [(0, 0, 1)] * 4, material=panel)]
        if occluded:
            black = b.material("occluder", (0.0, 0.0, 0.0), extensions={"KHR_materials_unlit": {}})
            prims.append(b.primitive([(-2, -2, 2.7), (2, -2, 2.7), (2, 2, 2.7), (-2, 2, 2.7)], [0, 1, 2, 0, 2, 3],
                                     [(0, 0, 1)] * 4, material=black))
        lamp = b.light({"name": "lamp", "type": "point", "intensity": 4.0})
        cam = b._append("cameras", {"type": "perspective", "perspective": {"yfov": 0.8, "znear": znear}})
        b.scene([b.node(name="scene", mesh=b.mesh(prims)),
                 b.node(name="lamp", light=lamp, translation=[1.0, 0.0, 1.0]),
                 b.node(name="camera", camera=cam, translation=[0.0, 0.0, 3.0])])
        b.write_embedded(out(name))


def iridescence():
    """KHR_materials_iridescence: a smooth plate (black base, ior 1.5) under a film of index 1.3
    and 400 nm, facing the camera (views within 0.3 degrees of the normal) in a uniform white world:
    it shows the film's reflectance at normal incidence. film_textured.gltf: factors and textures,
    for the loader."""
    b = GltfBuilder("clppm tests/data/make_test_gltf.py")
    plate = b.material("plate", (0.0, 0.0, 0.0), roughness=0.0,
                       extensions={"KHR_materials_iridescence": {"iridescenceFactor": 1.0,
                                                                 "iridescenceThicknessMaximum": 400.0}})
    p = b.primitive([(-1, -1, 0), (1, -1, 0), (1, 1, 0), (-1, 1, 0)], [0, 1, 2, 0, 2, 3], [(0, 0, 1)] * 4,
                    material=plate)
    b.scene([b.node(name="plate", mesh=b.mesh([p])),
             b.node(name="camera", camera=b.camera(0.01), translation=[0.0, 0.0, 3.0])])
    b.world(color=(1.0, 1.0, 1.0))
    b.write_embedded(out("film_plate.gltf"))
    b = GltfBuilder("clppm tests/data/make_test_gltf.py")
    png = png_rgba([[(128, 64, 0, 255)] * 2] * 2)
    b.doc["images"] = [{"uri": "data:image/png;base64," + base64.b64encode(png).decode("ascii")}]
    b.doc["textures"] = [{"source": 0}]
    ext = {"iridescenceFactor": 0.8, "iridescenceIor": 1.8, "iridescenceThicknessMinimum": 200.0,
           "iridescenceThicknessMaximum": 600.0, "iridescenceTexture": {"index": 0},
           "iridescenceThicknessTexture": {"index": 0}}
    plate = b.material("plate", (0.5, 0.5, 0.5), metallic=1.0, extensions={"KHR_materials_iridescence": ext})
    p = b.primitive([(-1, -1, 0), (1, -1, 0), (1, 1, 0), (-1, 1, 0)], [0, 1, 2, 0, 2, 3], [(0, 0, 1)] * 4,
                    material=plate)
    p["attributes"]["TEXCOORD_0"] = b.accessor([0.0, 0.0, 1.0, 0.0, 1.0, 1.0, 0.0, 1.0], FLOAT, "VEC2", ARRAY_BUFFER)
    b.scene([b.node(name="plate", mesh=b.mesh([p]))])
    b.write_embedded(out("film_textured.gltf"))


def anisotropy():
    """KHR_materials_anisotropy: a textured plate with strength, rotation and a direction texture,
    for the loader (tangents are generated for it), in a white world."""
    b = GltfBuilder("clppm tests/data/make_test_gltf.py")
    png = png_rgba([[(255, 128, 255, 255)] * 2] * 2)
    b.doc["images"] = [{"uri": "data:image/png;base64," + base64.b64encode(png).decode("ascii")}]
    b.doc["textures"] = [{"source": 0}]
    ext = {"anisotropyStrength": 0.6, "anisotropyRotation": 0.5, "anisotropyTexture": {"index": 0}}
    plate = b.material("plate", (0.8, 0.8, 0.8), metallic=1.0, roughness=0.3,
                       extensions={"KHR_materials_anisotropy": ext})
    p = b.primitive([(-1, -1, 0), (1, -1, 0), (1, 1, 0), (-1, 1, 0)], [0, 1, 2, 0, 2, 3], [(0, 0, 1)] * 4,
                    material=plate)
    p["attributes"]["TEXCOORD_0"] = b.accessor([0.0, 0.0, 1.0, 0.0, 1.0, 1.0, 0.0, 1.0], FLOAT, "VEC2", ARRAY_BUFFER)
    b.scene([b.node(name="plate", mesh=b.mesh([p])),
             b.node(name="camera", camera=b.camera(0.6), translation=[0.0, 0.0, 3.0])])
    b.world(color=(1.0, 1.0, 1.0))
    b.write_embedded(out("aniso_plate.gltf"))


def reference_scenes():
    """Scenes with images from an independent renderer (tests/references/make_references.py,
    Mitsuba 3): a glass block on a floor before a wall, a red box half behind it, under a 1 x 1
    ceiling lamp of Le = 12 facing down. ref_rough_glass: the block is rough glass (roughness 0.3,
    ior 1.5, solid through KHR_materials_volume); ref_tinted_volume: smooth glass absorbing to
    attenuationColor (0.9, 0.5, 0.2) per 0.5 units. Diffuse surfaces have specularFactor 0 (plain
    Lambertian, as Mitsuba's diffuse)."""
    for name, roughness, attenuation in (("ref_rough_glass.gltf", 0.3, None),
                                         ("ref_tinted_volume.gltf", 0.0, (0.9, 0.5, 0.2))):
        b = GltfBuilder("clppm tests/data/make_test_gltf.py")
        floor = b.material("floor", (0.8, 0.8, 0.8), specular=0.0)
        wall = b.material("wall", (0.6, 0.6, 0.6), specular=0.0)
        red = b.material("red", (0.7, 0.15, 0.1), specular=0.0)
        glass = b.material("glass", (1.0, 1.0, 1.0), roughness=roughness, transmission=1.0, ior=1.5,
                           thickness=1.0)
        if attenuation is not None:
            b.doc["materials"][glass]["extensions"]["KHR_materials_volume"].update(
                {"attenuationDistance": 0.5, "attenuationColor": list(attenuation)})
        lamp = b.material("lamp", (0.0, 0.0, 0.0), emissive=(1.0, 1.0, 1.0), emissive_strength=12.0, specular=0.0)
        fpos, fnrm, fidx = quad((0.0, 0.0, 0.0), (0.0, 0.0, 3.0), (3.0, 0.0, 0.0))
        wpos, wnrm, widx = quad((0.0, 1.5, -1.5), (3.0, 0.0, 0.0), (0.0, 1.5, 0.0))
        lpos, lnrm, lidx = quad((0.3, 2.4, 0.6), (0.5, 0.0, 0.0), (0.0, 0.0, 0.5))
        prims = [b.primitive(fpos, fidx, fnrm, material=floor), b.primitive(wpos, widx, wnrm, material=wall),
                 b.primitive(lpos, lidx, lnrm, material=lamp),
                 box_primitive(b, (-0.9, 0.0, -1.0), (-0.3, 0.5, -0.4), red),
                 # Lifted off the floor: a face coplanar with the floor would leave which one a ray
                 # meets first to each renderer's rounding.
                 box_primitive(b, (-0.4, 0.005, -0.3), (0.6, 0.705, 0.5), glass)]
        cam = b.camera(0.75)
        tilt = quat_axis_angle((1, 0, 0), -math.atan2(1.3 - 0.35, 3.0))
        b.scene([b.node(name="set", mesh=b.mesh(prims)),
                 b.node(name="camera", camera=cam, translation=[0.0, 1.3, 3.0], rotation=tilt)])
        b.write_embedded(out(name))
    textured_reference()


def textured_reference():
    """ref_textured.gltf, the same rig with textures: the floor's base colour an 8 x 8 sRGB
    texture (an asymmetric pattern, so that a flip shows) repeated 3 times over it (REPEAT), and
    a vertical leaf card before the wall whose 16 x 16 texture cuts it out (alphaMode MASK,
    cutoff 0.5: a diamond with a hole), double-sided green."""
    b = GltfBuilder("clppm tests/data/make_test_gltf.py")
    pattern = [[(200 if (x + 2 * y) % 5 < 2 else 40, 90 + 20 * x, 240 - 25 * y, 255) for x in range(8)]
               for y in range(8)]
    leaf = []
    for y in range(16):
        row = []
        for x in range(16):
            d = abs(x - 7.5) + abs(y - 7.5)
            inside = d < 7.5 and not (abs(x - 9.5) < 2 and abs(y - 5.5) < 2)
            row.append((60, 170, 50, 255 if inside else 0))
        leaf.append(row)
    b.doc["images"] = [{"uri": "data:image/png;base64," + base64.b64encode(png_rgba(pattern)).decode("ascii")},
                       {"uri": "data:image/png;base64," + base64.b64encode(png_rgba(leaf)).decode("ascii")}]
    b.doc["samplers"] = [{"wrapS": 10497, "wrapT": 10497}, {"wrapS": 33071, "wrapT": 33071}]
    b.doc["textures"] = [{"source": 0, "sampler": 0}, {"source": 1, "sampler": 1}]
    floor = b.material("floor", (1.0, 1.0, 1.0), specular=0.0, base_color_texture={"index": 0})
    wall = b.material("wall", (0.6, 0.6, 0.6), specular=0.0)
    card = b.material("leaf", (1.0, 1.0, 1.0), specular=0.0, base_color_texture={"index": 1}, double_sided=True)
    b.doc["materials"][card]["alphaMode"] = "MASK"
    lamp = b.material("lamp", (0.0, 0.0, 0.0), emissive=(1.0, 1.0, 1.0), emissive_strength=12.0, specular=0.0)
    fpos, fnrm, fidx = quad((0.0, 0.0, 0.0), (0.0, 0.0, 3.0), (3.0, 0.0, 0.0))
    fuv = [(0.0, 0.0), (0.0, 3.0), (3.0, 3.0), (3.0, 0.0)]  # corners (-z,-x), (+z,-x), (+z,+x), (-z,+x)
    wpos, wnrm, widx = quad((0.0, 1.5, -1.5), (3.0, 0.0, 0.0), (0.0, 1.5, 0.0))
    lpos, lnrm, lidx = quad((0.3, 2.4, 0.6), (0.5, 0.0, 0.0), (0.0, 0.0, 0.5))
    cpos, cnrm, cidx = quad((0.1, 0.75, -0.2), (0.6, 0.0, 0.0), (0.0, 0.6, 0.0))
    cuv = [(0.0, 1.0), (1.0, 1.0), (1.0, 0.0), (0.0, 0.0)]  # image top at the card's top
    prims = [b.primitive(fpos, fidx, fnrm, uvs=fuv, material=floor), b.primitive(wpos, widx, wnrm, material=wall),
             b.primitive(lpos, lidx, lnrm, material=lamp), b.primitive(cpos, cidx, cnrm, uvs=cuv, material=card)]
    cam = b.camera(0.75)
    tilt = quat_axis_angle((1, 0, 0), -math.atan2(1.3 - 0.35, 3.0))
    b.scene([b.node(name="set", mesh=b.mesh(prims)),
             b.node(name="camera", camera=cam, translation=[0.0, 1.3, 3.0], rotation=tilt)])
    b.write_embedded(out("ref_textured.gltf"))
    normal_panel_reference()


def normal_panel_reference():
    """ref_normal_panel.gltf: the rig's back wall normal-mapped (a 16 x 16 linear normalTexture
    repeated twice each way, no TANGENT: horizontal ridges tilting up and down in the map's Y on
    its upper half, vertical ridges tilting left and right in X on its right half), lit from
    the ceiling at a grazing angle, so that the frame's orientation shows."""
    b = GltfBuilder("clppm tests/data/make_test_gltf.py")
    texels = []
    for y in range(16):
        row = []
        for x in range(16):
            nx = 0.6 if 8 <= x < 12 else (-0.6 if x >= 12 else 0.0)
            ny = (0.6 if y % 4 < 2 else -0.6) if y < 8 else 0.0
            length = math.sqrt(nx * nx + ny * ny + 1.0)
            row.append(tuple(int(round((c / length * 0.5 + 0.5) * 255)) for c in (nx, ny, 1.0)) + (255,))
        texels.append(row)
    b.doc["images"] = [{"uri": "data:image/png;base64," + base64.b64encode(png_rgba(texels)).decode("ascii")}]
    b.doc["samplers"] = [{"wrapS": 10497, "wrapT": 10497}]
    b.doc["textures"] = [{"source": 0, "sampler": 0}]
    floor = b.material("floor", (0.8, 0.8, 0.8), specular=0.0)
    wall = b.material("wall", (0.7, 0.7, 0.7), specular=0.0)
    b.doc["materials"][wall]["normalTexture"] = {"index": 0}
    lamp = b.material("lamp", (0.0, 0.0, 0.0), emissive=(1.0, 1.0, 1.0), emissive_strength=12.0, specular=0.0)
    fpos, fnrm, fidx = quad((0.0, 0.0, 0.0), (0.0, 0.0, 3.0), (3.0, 0.0, 0.0))
    wpos, wnrm, widx = quad((0.0, 1.5, -1.5), (3.0, 0.0, 0.0), (0.0, 1.5, 0.0))
    wuv = [(0.0, 2.0), (2.0, 2.0), (2.0, 0.0), (0.0, 0.0)]  # u along +x, v down the wall
    lpos, lnrm, lidx = quad((0.3, 2.4, -0.9), (0.5, 0.0, 0.0), (0.0, 0.0, 0.5))
    prims = [b.primitive(fpos, fidx, fnrm, material=floor), b.primitive(wpos, widx, wnrm, uvs=wuv, material=wall),
             b.primitive(lpos, lidx, lnrm, material=lamp)]
    cam = b.camera(0.75)
    tilt = quat_axis_angle((1, 0, 0), -math.atan2(1.3 - 0.35, 3.0))
    b.scene([b.node(name="set", mesh=b.mesh(prims)),
             b.node(name="camera", camera=cam, translation=[0.0, 1.3, 3.0], rotation=tilt)])
    b.write_embedded(out("ref_normal_panel.gltf"))


def environment_scenes():
    """Scenes without lights, for the environment (tests/environment_test.cpp): env_sphere, a
    Lambertian sphere of albedo 0.5 (radius 1, 64 x 48) seen from z = 4, background around it;
    env_floor, a Lambertian floor of albedo 0.8 (20 x 20) seen straight down from y = 2, filling
    the frame; env_outdoor, that floor with a grey box and a rough metal sphere on it, seen from
    the side, for the sun-map comparison of the integrators."""
    b = GltfBuilder("clppm tests/data/make_test_gltf.py")
    grey = b.material("grey", (0.5, 0.5, 0.5), specular=0.0)
    pos, nrm, idx = uv_sphere(64, 48)
    b.scene([b.node(name="sphere", mesh=b.mesh([b.primitive(pos, idx, nrm, material=grey)])),
             b.node(name="camera", camera=b.camera(0.6), translation=[0.0, 0.0, 4.0])])
    b.write_embedded(out("env_sphere.gltf"))
    for name in ("env_floor.gltf", "env_outdoor.gltf"):
        b = GltfBuilder("clppm tests/data/make_test_gltf.py")
        floor = b.material("floor", (0.8, 0.8, 0.8), specular=0.0)
        fpos, fnrm, fidx = quad((0.0, 0.0, 0.0), (0.0, 0.0, 10.0), (10.0, 0.0, 0.0))
        prims = [b.primitive(fpos, fidx, fnrm, material=floor)]
        if name == "env_floor.gltf":
            cam = b.node(name="camera", camera=b.camera(0.5), translation=[0.0, 2.0, 0.0],
                         rotation=quat_axis_angle((1, 0, 0), -math.pi / 2))
        else:
            box = b.material("box", (0.6, 0.5, 0.4), roughness=0.6)
            metal = b.material("metal", (0.9, 0.8, 0.6), metallic=1.0, roughness=0.3)
            prims.append(box_primitive(b, (-1.2, 0.0, -0.6), (-0.2, 1.0, 0.4), box))
            spos, snrm, sidx = uv_sphere(32, 24, radius=0.5, center=(0.7, 0.5, 0.0))
            prims.append(b.primitive(spos, sidx, snrm, material=metal))
            cam = b.node(name="camera", camera=b.camera(0.8), translation=[0.0, 1.5, 4.0],
                         rotation=quat_axis_angle((1, 0, 0), -math.atan2(1.0, 4.0)))
        b.scene([b.node(name="set", mesh=b.mesh(prims)), cam])
        b.write_embedded(out(name))


def spread_light():
    """A small square emitter (0.1 x 0.1, radiance 100, facing down) 5 above a Lambertian floor of
    albedo 0.5 (20 x 20), seen from the side at 45 degrees, black world: the point of the floor
    under it sees the emitter within 0.6 degrees of its axis, where a spread multiplies its
    radiance by f(0) = tan h / (tan h - h) (tests/emission_spread_test.cpp adds the spread)."""
    b = GltfBuilder("clppm tests/data/make_test_gltf.py")
    floor = b.material("floor", (0.5, 0.5, 0.5), specular=0.0)
    lamp = b.material("lamp", (0.0, 0.0, 0.0), specular=0.0, emissive=(1.0, 1.0, 1.0), emissive_strength=100.0)
    fpos, fnrm, fidx = quad((0.0, 0.0, 0.0), (0.0, 0.0, 10.0), (10.0, 0.0, 0.0))
    lpos, lnrm, lidx = quad((0.0, 5.0, 0.0), (0.05, 0.0, 0.0), (0.0, 0.0, 0.05))
    assert lnrm[0] == (0.0, -1.0, 0.0)
    prims = [b.primitive(fpos, fidx, fnrm, material=floor), b.primitive(lpos, lidx, lnrm, material=lamp)]
    cam = b.node(name="camera", camera=b.camera(0.3), translation=[0.0, 3.0, 3.0],
                 rotation=quat_axis_angle((1, 0, 0), -math.pi / 4))
    b.scene([b.node(name="set", mesh=b.mesh(prims)), cam])
    b.write_embedded(out("spread_light.gltf"))


def specular_textures():
    """KHR_materials_specular textures: a plate whose uniform specularTexture (A = 51: 0.2) and
    specularColorTexture (sRGB (255, 0, 255)) scale factors of 1, against the plate with factors
    0.2 and (1, 0, 1), and the plate with factors 1 (what ignoring the textures would give)."""
    for name, textured in (("specular_texture.gltf", True), ("specular_factor.gltf", False),
                           ("specular_untextured.gltf", None)):
        b = GltfBuilder("clppm tests/data/make_test_gltf.py")
        plate = b.material("plate", (0.3, 0.5, 0.7), roughness=0.4, specular=0.2 if textured is False else 1.0,
                           specular_color=(1.0, 0.0, 1.0) if textured is False else (1.0, 1.0, 1.0))
        if textured:
            pngs = [png_rgba([[(0, 0, 0, 51)] * 2] * 2), png_rgba([[(255, 0, 255, 255)] * 2] * 2)]
            b.doc["images"] = [{"uri": "data:image/png;base64," + base64.b64encode(p).decode("ascii")} for p in pngs]
            b.doc["textures"] = [{"source": 0}, {"source": 1}]
            spec = b.doc["materials"][plate]["extensions"]["KHR_materials_specular"]
            spec["specularTexture"] = {"index": 0}
            spec["specularColorTexture"] = {"index": 1}
        quad = [(-1.0, 0.0, -1.0), (-1.0, 0.0, 1.0), (1.0, 0.0, 1.0), (1.0, 0.0, -1.0)]
        prim = b.primitive(quad, [0, 1, 2, 0, 2, 3], [(0.0, 1.0, 0.0)] * 4, uvs=[(0, 0), (0, 1), (1, 1), (1, 0)],
                           material=plate)
        write_lit_plate(b, name, prim, lamp=[0.0, 0.8, -0.6])


# ---- errors -------------------------------------------------------------------------------------

def triangle_doc(**material):
    b = one_triangle(**material)
    return b, b.document(b.data_uri())


def errors():
    write_text(out("malformed.gltf"), '{"asset": {"version": "2.0"}, "nodes": [\n')
    write_text(out("not_gltf.gltf"), '{"hello": 1}\n')

    _, doc = triangle_doc()
    doc["extensionsRequired"] = ["KHR_lights_punctual", "EXT_meshopt_compression"]
    doc["extensionsUsed"] = doc["extensionsRequired"]
    write_doc("ext_required.gltf", doc)

    _, doc = triangle_doc()
    doc["meshes"][0]["primitives"][0]["attributes"]["POSITION"] = 99
    write_doc("accessor_range.gltf", doc)

    b = GltfBuilder("clppm tests/data/make_test_gltf.py")
    b.scene([b.node(mesh=b.mesh([b.primitive(TRI, [0, 1, 7], TRI_N)]))])
    b.write_embedded(out("index_range.gltf"))

    _, doc = triangle_doc()
    doc["accessors"][0]["count"] = 10
    write_doc("accessor_past_view.gltf", doc)

    _, doc = triangle_doc()
    doc["bufferViews"][0]["byteLength"] = 1000
    write_doc("view_past_buffer.gltf", doc)

    _, doc = triangle_doc()
    doc["accessors"][0]["count"] = 3000000000
    write_doc("huge_count.gltf", doc)

    b = GltfBuilder("clppm tests/data/make_test_gltf.py")
    mesh = b.mesh([b.primitive(TRI, [0, 1, 2], TRI_N)])
    inner = b.node(name="overflow", mesh=mesh, scale=[1e200, 1, 1])
    b.scene([b.node(name="huge", children=[inner], scale=[1e200, 1, 1])])
    b.write_embedded(out("nonfinite_node.gltf"))

    _, doc = triangle_doc()
    doc["nodes"] = [{"name": "a", "mesh": 0, "children": [1]}, {"name": "b", "children": [2]},
                    {"name": "c", "children": [0]}]
    write_doc("cycle.gltf", doc)

    _, doc = triangle_doc()
    doc["meshes"][0]["primitives"][0]["mode"] = 0  # POINTS
    write_doc("no_triangles.gltf", doc)

    for name, uri in (("uri_parent.gltf", "../outside.bin"), ("uri_absolute.gltf", "/etc/passwd"),
                      ("uri_sneaky.gltf", "sub/../../outside.bin")):
        b, doc = triangle_doc()
        doc["buffers"][0]["uri"] = uri
        write_doc(name, doc)
    _, doc = triangle_doc()
    doc["images"] = [{"uri": "..%2F..%2Fsecret.png"}]
    write_doc("uri_image_parent.gltf", doc)

    _, doc = triangle_doc()
    doc["buffers"][0]["uri"] = "missing.bin"
    write_doc("missing_bin.gltf", doc)

    _, doc = triangle_doc(base_color=(1e300, 0.0, 0.0))
    doc["materials"][0]["name"] = "hot"
    write_doc("nonfinite_material.gltf", doc)

    _, doc = triangle_doc()
    nested = 1
    for _ in range(200):
        nested = [nested]
    doc["extras"] = {"deep": nested}
    write_doc("deep_json.gltf", doc)

    b, doc = triangle_doc()
    doc["bufferViews"].append({"buffer": 0, "byteOffset": 0, "byteLength": 100000})
    doc["images"] = [{"bufferView": len(doc["bufferViews"]) - 1, "mimeType": "image/png"}]
    write_doc("image_view_past_buffer.gltf", doc)

    with open(out("box.glb"), "rb") as f:
        glb = f.read()
    with open(out("truncated.glb"), "wb") as f:
        f.write(glb[:len(glb) // 2])


def dispersion():
    """KHR_materials_dispersion. prism.gltf: an equilateral glass prism (ior 1.5, dispersion 2, so
    Abbe number 10; a volume) whose section lies in the xy plane, apex (0, sqrt(3)/2), base from
    (-0.5, 0) to (0.5, 0), extruded over z in [-0.5, 0.5]. A directional light travels along
    PRISM_LIGHT (18.59 degrees above +x: minimum deviation for n = 1.5) through a 0.15 x 0.4 hole
    in a black occluder (perpendicular to it, centred on the light's line through the left face's
    middle) into the left face; the spectrum falls on a white Lambertian screen 1.6 x 0.8,
    perpendicular to PRISM_EXIT (the light's direction turned down by the minimum deviation,
    37.18 degrees) at 2 from the right face's middle, seen head-on by an orthographic camera
    (xmag 0.8, ymag 0.4; its right is PRISM_EXIT x +z, up +z). tests/dispersion_test.cpp traces
    each wavelength through the prism by Snell's law and compares where the colours fall.
    prism_plain.gltf: the same without dispersion. dispersion_box_plain.gltf: scenes/dispersion_box.gltf
    without its dispersion. dispersion_thin.gltf, dispersion_negative.gltf:
    one triangle of thin-walled glass asking for dispersion, and one with a negative dispersion.
    rainbow.gltf: a dispersive water drop's bow on a screen (described where it is made)."""
    h = math.sqrt(3.0) / 2.0
    a, bl, c = (0.0, h), (-0.5, 0.0), (0.5, 0.0)
    th_in = math.radians(18.59)
    d = (math.cos(th_in), math.sin(th_in), 0.0)
    th_out = th_in - math.radians(37.18)
    e = (math.cos(th_out), math.sin(th_out), 0.0)
    left_mid = ((a[0] + bl[0]) / 2, (a[1] + bl[1]) / 2, 0.0)
    right_mid = ((a[0] + c[0]) / 2, (a[1] + c[1]) / 2, 0.0)
    for name, disp in (("prism.gltf", 2.0), ("prism_plain.gltf", None)):
        b = GltfBuilder("clppm tests/data/make_test_gltf.py")
        ext = {"KHR_materials_volume": {"thicknessFactor": 1.0}}
        if disp is not None:
            ext["KHR_materials_dispersion"] = {"dispersion": disp}
        glass = b.material("glass", (1.0, 1.0, 1.0), roughness=0.0, transmission=1.0, ior=1.5, extensions=ext)
        black = b.material("black", (0.0, 0.0, 0.0), specular=0.0)
        white = b.material("screen", (0.8, 0.8, 0.8), specular=0.0)
        # The prism: three sides and two caps, each face its own vertices, normals outwards.
        pos, nrm, idx = [], [], []

        def face(corners, n):
            base = len(pos)
            pos.extend(corners)
            nrm.extend([n] * len(corners))
            for k in range(1, len(corners) - 1):
                idx.extend([base, base + k, base + k + 1])
        for p0, p1 in ((bl, c), (c, a), (a, bl)):
            n = normalize((p1[1] - p0[1], -(p1[0] - p0[0]), 0.0))
            face([(p0[0], p0[1], -0.5), (p1[0], p1[1], -0.5), (p1[0], p1[1], 0.5), (p0[0], p0[1], 0.5)], n)
        face([(bl[0], bl[1], 0.5), (c[0], c[1], 0.5), (a[0], a[1], 0.5)], (0.0, 0.0, 1.0))
        face([(bl[0], bl[1], -0.5), (a[0], a[1], -0.5), (c[0], c[1], -0.5)], (0.0, 0.0, -1.0))
        check_front_faces(pos, nrm, idx)
        prism = b.primitive(pos, idx, nrm, material=glass)
        # The occluder: 5 x 5, perpendicular to the light, 0.6 before the left face, with the hole.
        side = normalize(cross(d, (0.0, 0.0, 1.0)))
        up = (0.0, 0.0, 1.0)
        centre = sub(left_mid, scale(d, 0.6))
        hw, hh, big = 0.075, 0.2, 2.5
        occ = []
        for (u0, u1, v0, v1) in ((-big, -hw, -big, big), (hw, big, -big, big), (-hw, hw, hh, big), (-hw, hw, -big, -hh)):
            qc = add(centre, add(scale(side, (u0 + u1) / 2), scale(up, (v0 + v1) / 2)))
            qp, qn, qi = quad(qc, scale(up, (v1 - v0) / 2), scale(side, (u1 - u0) / 2))
            if dot(qn[0], d) > 0:  # face the light
                qp = [qp[0], qp[3], qp[2], qp[1]]
                qn = [scale(qn[0], -1.0)] * 4
            occ.append(b.primitive(qp, qi, qn, material=black))
        # The screen, facing the prism.
        scentre = add(right_mid, scale(e, 2.0))
        sright = normalize(cross(e, up))
        sp, sn, si = quad(scentre, scale(sright, 0.8), scale(up, 0.4))
        if dot(sn[0], e) > 0:
            sp = [sp[0], sp[3], sp[2], sp[1]]
            sn = [scale(sn[0], -1.0)] * 4
        check_front_faces(sp, sn, si)
        screen = b.primitive(sp, si, sn, material=white)
        sun = b.light({"name": "sun", "type": "directional", "color": [1.0, 1.0, 1.0], "intensity": 10.0})
        cam = b._append("cameras", {"type": "orthographic",
                                    "orthographic": {"xmag": 0.8, "ymag": 0.4, "znear": 0.01, "zfar": 10.0}})
        b.scene([b.node(name="prism", mesh=b.mesh([prism])), b.node(name="occluder", mesh=b.mesh(occ)),
                 b.node(name="screen", mesh=b.mesh([screen])),
                 b.node(name="sun", light=sun, rotation=look_rotation(d)),
                 b.node(name="camera", camera=cam, translation=list(sub(scentre, scale(e, 1.0))),
                        rotation=look_rotation(e, up))])
        b.world(color=(0.0, 0.0, 0.0))
        b.write_embedded(out(name))
    # rainbow.gltf: a water drop (sphere of radius 1 at the origin, 128 x 96, ior 1.333,
    # dispersion 2: Abbe number 10, a volume) under a directional light travelling along -z that
    # reaches it through a 2.2 x 2.2 hole in a white Lambertian screen 10 x 10 at z = 3, facing the
    # drop; an orthographic camera (xmag = ymag = 5) at z = 2.5 looks at the screen along +z. The
    # light the drop sends back once reflected inside lands on the screen as a bow near Descartes'
    # 42 degrees from the axis (tests/dispersion_test.cpp traces it).
    b = GltfBuilder("clppm tests/data/make_test_gltf.py")
    water = b.material("water", (1.0, 1.0, 1.0), roughness=0.0, transmission=1.0, ior=1.333,
                       extensions={"KHR_materials_volume": {"thicknessFactor": 1.0},
                                   "KHR_materials_dispersion": {"dispersion": 2.0}})
    white = b.material("screen", (0.8, 0.8, 0.8), specular=0.0)
    pos, nrm, idx = uv_sphere(128, 96)
    check_front_faces(pos, nrm, idx)
    drop = b.primitive(pos, idx, nrm, material=water)
    quads = []
    for (x0, x1, y0, y1) in ((-5.0, -1.1, -5.0, 5.0), (1.1, 5.0, -5.0, 5.0), (-1.1, 1.1, 1.1, 5.0),
                             (-1.1, 1.1, -5.0, -1.1)):
        qp, qn, qi = quad(((x0 + x1) / 2, (y0 + y1) / 2, 3.0), (0.0, (y1 - y0) / 2, 0.0), ((x1 - x0) / 2, 0.0, 0.0))
        assert qn[0] == (0.0, 0.0, -1.0)
        quads.append(b.primitive(qp, qi, qn, material=white))
    sun = b.light({"name": "sun", "type": "directional", "color": [1.0, 1.0, 1.0], "intensity": 10.0})
    cam = b._append("cameras", {"type": "orthographic",
                                "orthographic": {"xmag": 5.0, "ymag": 5.0, "znear": 0.01, "zfar": 10.0}})
    b.scene([b.node(name="drop", mesh=b.mesh([drop])), b.node(name="screen", mesh=b.mesh(quads)),
             b.node(name="sun", light=sun),
             b.node(name="camera", camera=cam, translation=[0.0, 0.0, 2.5], rotation=look_rotation((0.0, 0.0, 1.0)))])
    b.world(color=(0.0, 0.0, 0.0))
    b.write_embedded(out("rainbow.gltf"))
    # The dispersion box without its dispersion (scenes/dispersion_box.gltf is the other).
    dispersion_box(os.path.dirname(out("x")), dispersion=None, name="dispersion_box_plain.gltf")
    # For the loader: dispersion on a thin wall (no volume) and a negative one.
    b = one_triangle(transmission=1.0, roughness=0.0, extensions={"KHR_materials_dispersion": {"dispersion": 1.0}})
    b.write_embedded(out("dispersion_thin.gltf"))
    b = one_triangle(transmission=1.0, thickness=1.0, extensions={"KHR_materials_dispersion": {"dispersion": -1.0}})
    b.write_embedded(out("dispersion_negative.gltf"))


def media():
    """Media. fog_room.gltf: the world's medium (extras.clppm_medium: chromatic density 0.3, 0.4, 0.6,
    albedo 0.9, 0.8, 0.7, g 0.4) in a closed white room [-2, 2]^3 whose walls face outwards (the
    camera at (0, 0, 1.5) sees their back faces, which leave the fog where it is), lit by a square
    ceiling light and a point light, with a glass cube (ior 1.5, a volume that absorbs) that holds
    its own volume in the fog."""
    b = GltfBuilder("clppm tests/data/make_test_gltf.py")
    white = b.material("white", (0.7, 0.7, 0.7), specular=0.0)
    glass = b.material("glass", (1.0, 1.0, 1.0), roughness=0.0, transmission=1.0, ior=1.5, thickness=1.0,
                       extensions={"KHR_materials_volume": {"thicknessFactor": 1.0, "attenuationDistance": 1.0,
                                                            "attenuationColor": [0.9, 0.6, 0.3]}})
    lamp = b.material("lamp", (0.0, 0.0, 0.0), emissive=(1.0, 1.0, 1.0), emissive_strength=8.0, specular=0.0)
    room = box_primitive(b, (-2.0, -2.0, -2.0), (2.0, 2.0, 2.0), white)
    cube = box_primitive(b, (-0.5, -2.0, -1.0), (0.5, -1.0, 0.0), glass)
    lpos, lnrm, lidx = quad((0.0, 1.99, -0.5), (0.5, 0.0, 0.0), (0.0, 0.0, 0.5))
    assert lnrm[0] == (0.0, -1.0, 0.0)
    light = b.primitive(lpos, lidx, lnrm, material=lamp)
    point = b.light({"name": "point", "type": "point", "color": [1.0, 0.9, 0.8], "intensity": 3.0})
    cam = b.camera(1.2, 1.0)
    b.scene([b.node(name="room", mesh=b.mesh([room, cube, light])),
             b.node(name="point", light=point, translation=[1.0, 0.5, -1.0]),
             b.node(name="camera", camera=cam, translation=[0.0, 0.0, 1.5])])
    b.world(color=(0.0, 0.0, 0.0))
    b.medium(density=(0.3, 0.4, 0.6), albedo=(0.9, 0.8, 0.7), anisotropy=0.4)
    b.write_embedded(out("fog_room.gltf"))
    # fog_cube_room.gltf: the same room with its fog in a mesh instead of the world: an
    # index-matched cube [-2.005, 2.005]^3 whose KHR_materials_volume_scatter volume (the same
    # extinction, multiscatterColor 0.9, 0.8, 0.7) holds the room, the glass cube, both lights and the camera
    # (media nesting, src/scene/volume_nesting.h).
    b = GltfBuilder("clppm tests/data/make_test_gltf.py")
    white = b.material("white", (0.7, 0.7, 0.7), specular=0.0)
    glass = b.material("glass", (1.0, 1.0, 1.0), roughness=0.0, transmission=1.0, ior=1.5, thickness=1.0,
                       extensions={"KHR_materials_volume": {"thicknessFactor": 1.0, "attenuationDistance": 1.0,
                                                            "attenuationColor": [0.9, 0.6, 0.3]}})
    fog = b.material("fog", (1.0, 1.0, 1.0), roughness=0.0, transmission=1.0, ior=1.0, thickness=1.0,
                     extensions={"KHR_materials_volume": {"thicknessFactor": 1.0, "attenuationDistance": 1.0,
                                                          "attenuationColor": [math.exp(-0.3), math.exp(-0.4),
                                                                               math.exp(-0.6)]},
                                 "KHR_materials_volume_scatter": {"multiscatterColor": [0.9, 0.8, 0.7],
                                                                  "scatterAnisotropy": 0.4}})
    lamp = b.material("lamp", (0.0, 0.0, 0.0), emissive=(1.0, 1.0, 1.0), emissive_strength=8.0, specular=0.0)
    room = box_primitive(b, (-2.0, -2.0, -2.0), (2.0, 2.0, 2.0), white)
    cube = box_primitive(b, (-0.5, -2.0, -1.0), (0.5, -1.0, 0.0), glass)
    fog_cube = box_primitive(b, (-2.005, -2.005, -2.005), (2.005, 2.005, 2.005), fog)
    light = b.primitive(lpos, lidx, lnrm, material=lamp)
    point = b.light({"name": "point", "type": "point", "color": [1.0, 0.9, 0.8], "intensity": 3.0})
    cam = b.camera(1.2, 1.0)
    b.scene([b.node(name="room", mesh=b.mesh([room, cube, fog_cube, light])),
             b.node(name="point", light=point, translation=[1.0, 0.5, -1.0]),
             b.node(name="camera", camera=cam, translation=[0.0, 0.0, 1.5])])
    b.world(color=(0.0, 0.0, 0.0))
    b.write_embedded(out("fog_cube_room.gltf"))
    # wax_block.gltf: a translucent solid (KHR_materials_volume_scatter): a block 1 x 1 x 1 on a
    # white floor whose surface transmits diffusely (diffuseTransmissionFactor 1, colour white)
    # into a volume of attenuationColor (0.5, 0.3, 0.2) at attenuationDistance 0.2 that scatters
    # (multiscatterColor 0.9, 0.7, 0.5; scatterAnisotropy 0.2), lit by a point light above and
    # behind it and a small area light in front, in a black world.
    b = GltfBuilder("clppm tests/data/make_test_gltf.py")
    floor = b.material("floor", (0.7, 0.7, 0.7), specular=0.0)
    wax = b.material("wax", (1.0, 0.95, 0.9), roughness=0.4,
                     extensions={"KHR_materials_diffuse_transmission": {"diffuseTransmissionFactor": 1.0},
                                 "KHR_materials_volume": {"thicknessFactor": 1.0, "attenuationDistance": 0.2,
                                                          "attenuationColor": [0.5, 0.3, 0.2]},
                                 "KHR_materials_volume_scatter": {"multiscatterColor": [0.9, 0.7, 0.5],
                                                                  "scatterAnisotropy": 0.2}})
    lamp = b.material("lamp", (0.0, 0.0, 0.0), emissive=(1.0, 1.0, 1.0), emissive_strength=20.0, specular=0.0)
    fpos, fnrm, fidx = quad((0.0, 0.0, 0.0), (0.0, 0.0, 3.0), (3.0, 0.0, 0.0))
    assert fnrm[0] == (0.0, 1.0, 0.0)
    lpos, lnrm, lidx = quad((0.0, 1.0, 2.0), (0.2, 0.0, 0.0), (0.0, 0.2, 0.0))
    assert lnrm[0] == (0.0, 0.0, 1.0)
    lpos, lnrm = [lpos[0], lpos[3], lpos[2], lpos[1]], [(0.0, 0.0, -1.0)] * 4  # facing the block
    check_front_faces(lpos, lnrm, lidx)
    block = box_primitive(b, (-0.5, 0.0, -0.5), (0.5, 1.0, 0.5), wax)
    point = b.light({"name": "point", "type": "point", "color": [1.0, 1.0, 1.0], "intensity": 20.0})
    cam = b.camera(0.7, 1.0)
    b.scene([b.node(name="scene", mesh=b.mesh([b.primitive(fpos, fidx, fnrm, material=floor), block,
                                               b.primitive(lpos, lidx, lnrm, material=lamp)])),
             b.node(name="point", light=point, translation=[0.5, 2.5, -1.5]),
             b.node(name="camera", camera=cam, translation=[1.2, 1.4, 3.2],
                    rotation=look_rotation(sub((0.0, 0.5, 0.0), (1.2, 1.4, 3.2))))])
    b.world(color=(0.0, 0.0, 0.0))
    b.write_embedded(out("wax_block.gltf"))


def main():
    for make in (hierarchy, index_types, byte_stride, containers, no_normals, degenerate, mirror, metallic_roughness,
                 materials, texture, lights, cameras, quantized, sparse, strips_fans, gpu_instancing, emissive_texture,
                 normal_maps, vertex_colors, alpha_modes,
                 texture_transform, uv1_plates, volumes, skinned, animated,
                 specular_textures, unlit, clearcoat, sheen, iridescence, anisotropy, diffuse_transmission, dispersion,
                 camera_clipping, reference_scenes, environment_scenes, spread_light, media, errors):
        make()


if __name__ == "__main__":
    main()
