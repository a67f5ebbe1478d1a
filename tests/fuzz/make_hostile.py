#!/usr/bin/env python3
"""Writes tests/fuzz/hostile/ and tests/fuzz/regressions/: small glTF files that
tests/fuzz_regression_test.cpp loads and tests/fuzz/run.sh uses as fuzzer seeds. python3 standard
library only; deterministic:
    python3 tests/fuzz/make_hostile.py
hostile/: hostile values the loader already handled, one file per case, named for what it
exercises (cases already in tests/data, from make_test_gltf.py, are not repeated).
regressions/: one minimal file per defect found by fuzzing and by this review, each of which made
the fuzz target report (sanitizer error, broken Scene invariant, canary opened, timeout, OOM)
before the fix named beside it in regressions(); tests/fuzz/README.md lists them.
The test states the expected outcome of every file.

JSON cannot spell NaN or Infinity (and 1e400 is a parse error), so non-finite values reach the
loader as float overflow (1e39 > FLT_MAX), as arithmetic (a zero quaternion, 1e308 * 1e308) or as
binary buffer data (positions and normals).
"""
import json
import os
import struct
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.dont_write_bytecode = True
sys.path.insert(0, os.path.join(HERE, "..", "..", "scripts"))
from make_scenes import FLOAT, UBYTE, UINT, GltfBuilder, write_text  # noqa: E402

OUT = os.path.join(HERE, "hostile")
REGRESSIONS = os.path.join(HERE, "regressions")
NAN, INF = float("nan"), float("inf")
TRI = [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0)]
TRI_N = [(0.0, 0.0, 1.0)] * 3
OVER_FLOAT = 1e39  # finite in JSON (a double), infinite as a float
GEN = "clppm tests/fuzz/make_hostile.py"


def out(name):
    return os.path.join(OUT, name)


def write_doc(name, doc):
    # Plain json.dumps: the values that matter here are extreme, not worth rounding.
    write_text(out(name), json.dumps(doc, indent=1) + "\n")


def builder():
    return GltfBuilder(GEN)


def triangle_doc(material=None, node=None):
    """One +z triangle under node 0 of scene 0; `material`: the material object (or None), `node`:
    extra node fields."""
    b = builder()
    mat = None
    if material is not None:
        mat = b._append("materials", material)
    mesh = b.mesh([b.primitive(TRI, [0, 1, 2], TRI_N, material=mat)], "tri")
    b.scene([b.node(name="tri", mesh=mesh, **(node or {}))])
    return b, b.document(b.data_uri())


def pbr(**factors):
    return {"name": "m", "pbrMetallicRoughness": dict(factors)}


# ---- non-finite values --------------------------------------------------------------------------

def positions():
    # Triangle 0 is finite in the file but 10x its 3e38 coordinates overflow float in world space:
    # skipped and counted, like the NaN/Inf positions of tests/data/degenerate.gltf.
    b = builder()
    big = b.mesh([b.primitive([(3e38, 0, 0), (3e38, 1, 0), (3e37, 0, 1)], [0, 1, 2], TRI_N, bounds=False)], "big")
    good = b.mesh([b.primitive(TRI, [0, 1, 2], TRI_N)], "good")
    b.scene([b.node(name="scaled", mesh=big, scale=[10, 10, 10]), b.node(name="good", mesh=good)])
    b.write_embedded(out("positions_overflow_in_world_space.gltf"))

    # Nothing but NaN triangles: all skipped, then "no triangle geometry".
    b = builder()
    nan_tris = [(NAN, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 0), (INF, 0, 0), (0, -INF, 0)]
    b.scene([b.node(mesh=b.mesh([b.primitive(nan_tris, None, [(0, 0, 1)] * 6, bounds=False)]))])
    b.write_embedded(out("positions_all_nonfinite.gltf"))


def normals():
    # Three good triangles: normals all +Inf, all zero, and huge but finite (1e38, 1e38, 1e38).
    # The first two fall back to the flat normal (+z); the third normalises to (1,1,1)/sqrt(3).
    b = builder()
    big = 1e38
    tris = [[(x, y, z) for x, y, _ in TRI] for z in (0.0, 1.0, 2.0)]
    nrm = [(INF, INF, INF)] * 3 + [(0, 0, 0)] * 3 + [(big, big, big)] * 3
    pos = [p for t in tris for p in t]
    b.scene([b.node(mesh=b.mesh([b.primitive(pos, None, nrm, bounds=False)]))])
    b.write_embedded(out("normals_inf_zero_huge.gltf"))

    # A flattening transform (scale z by 0) has no inverse transpose: flat normals instead.
    b = builder()
    b.scene([b.node(mesh=b.mesh([b.primitive(TRI, [0, 1, 2], [(0, 0.6, 0.8)] * 3)]), scale=[1, 1, 0])])
    b.write_embedded(out("normals_singular_transform.gltf"))


def factors():
    cases = {
        "factor_metallic_overflow.gltf": pbr(metallicFactor=OVER_FLOAT),
        "factor_roughness_overflow.gltf": pbr(roughnessFactor=-OVER_FLOAT),
        "factor_base_color_overflow.gltf": pbr(baseColorFactor=[1, 1, -OVER_FLOAT, 1]),
        "factor_emissive_overflow.gltf": {"name": "m", "emissiveFactor": [0, OVER_FLOAT, 0]},
        "factor_emissive_strength_overflow.gltf": {
            "name": "m", "emissiveFactor": [1, 1, 1],
            "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": OVER_FLOAT}}},
        "factor_transmission_overflow.gltf": {
            "name": "m", "extensions": {"KHR_materials_transmission": {"transmissionFactor": OVER_FLOAT}}},
        "factor_ior_overflow.gltf": {"name": "m", "extensions": {"KHR_materials_ior": {"ior": OVER_FLOAT}}},
        "factor_base_color_wrong_length.gltf": pbr(baseColorFactor=[1, 1, 1]),
    }
    for name, material in cases.items():
        _, doc = triangle_doc(material)
        write_doc(name, doc)


def lights():
    def light_doc(light, node=None):
        b, doc = triangle_doc()
        doc["extensionsUsed"] = ["KHR_lights_punctual"]
        doc["extensions"] = {"KHR_lights_punctual": {"lights": [light]}}
        lit = {"name": "lamp", "extensions": {"KHR_lights_punctual": {"light": 0}}}
        lit.update(node or {})
        doc["nodes"].append(lit)
        doc["scenes"][0]["nodes"].append(len(doc["nodes"]) - 1)
        return doc

    write_doc("light_intensity_overflow.gltf", light_doc({"type": "point", "intensity": OVER_FLOAT}))
    write_doc("light_color_wrong_length.gltf", light_doc({"type": "point", "color": [1, 1]}))
    write_doc("light_index_out_of_range.gltf", light_doc({"type": "point"}, {
        "extensions": {"KHR_lights_punctual": {"light": 7}}}))


def cameras():
    def camera_doc(camera, node=None):
        b, doc = triangle_doc()
        doc["cameras"] = [camera]
        cam = {"name": "eye", "camera": 0}
        cam.update(node or {})
        doc["nodes"].append(cam)
        doc["scenes"][0]["nodes"].append(len(doc["nodes"]) - 1)
        return doc

    write_doc("camera_yfov_overflow.gltf", camera_doc({"type": "perspective",
                                                      "perspective": {"yfov": OVER_FLOAT, "znear": 0.1}}))
    write_doc("camera_aperture_overflow.gltf", camera_doc(
        {"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.1}, "extras": {"aperture_radius": OVER_FLOAT}}))
    write_doc("camera_aspect_overflow.gltf", camera_doc(
        {"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.1, "aspectRatio": OVER_FLOAT}}))


def transforms():
    _, doc = triangle_doc(node={"rotation": [0, 0, 0, 0]})
    write_doc("node_rotation_zero_quaternion.gltf", doc)
    big = 1e308
    _, doc = triangle_doc(node={"matrix": [big, big, big, 0, big, big, big, 0, big, big, big, 0, 0, 0, 0, 1]})
    write_doc("node_matrix_overflow.gltf", doc)
    _, doc = triangle_doc(node={"translation": [OVER_FLOAT * 1e268, 0, 0]})  # 1e307: finite, positions not
    write_doc("node_translation_huge.gltf", doc)
    _, doc = triangle_doc(node={"matrix": [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0]})
    write_doc("node_matrix_wrong_length.gltf", doc)
    _, doc = triangle_doc(node={"scale": [1, 1]})
    write_doc("node_scale_wrong_length.gltf", doc)


# ---- indices, accessors, buffers ------------------------------------------------------------------

def indices():
    b = builder()
    b.scene([b.node(mesh=b.mesh([b.primitive(TRI, [0, 1, 0xFFFFFFFF], TRI_N, index_type=UINT)]))])
    b.write_embedded(out("index_u32_max.gltf"))
    b = builder()
    b.scene([b.node(mesh=b.mesh([b.primitive(TRI, [0, 200, 1], TRI_N, index_type=UBYTE)]))])
    b.write_embedded(out("index_u8_out_of_range.gltf"))
    # Indices as FLOAT (3.0e9 would become a huge index if read as a number).
    _, doc = triangle_doc()
    doc["accessors"][2]["componentType"] = FLOAT
    write_doc("index_float_type.gltf", doc)


def accessors():
    u64_max = 18446744073709551615

    def edit(name, fn):
        _, doc = triangle_doc()
        fn(doc)
        write_doc(name, doc)

    edit("accessor_offset_u64_max.gltf", lambda d: d["accessors"][0].update(byteOffset=u64_max))
    edit("accessor_offset_wraps.gltf", lambda d: d["accessors"][0].update(byteOffset=u64_max - 3))
    edit("view_offset_u64_max.gltf", lambda d: d["bufferViews"][0].update(byteOffset=u64_max - 7, byteLength=16))
    edit("view_length_u64_max.gltf", lambda d: d["bufferViews"][0].update(byteLength=u64_max))
    edit("accessor_count_times_stride.gltf",
         lambda d: (d["accessors"][0].update(count=2147483647), d["bufferViews"][0].update(byteStride=252)))
    edit("accessor_count_negative.gltf", lambda d: d["accessors"][0].update(count=-1))
    edit("accessor_count_u64_max.gltf", lambda d: d["accessors"][0].update(count=u64_max))
    edit("view_stride_too_small.gltf", lambda d: d["bufferViews"][0].update(byteStride=4))
    edit("view_buffer_out_of_range.gltf", lambda d: d["bufferViews"][0].update(buffer=5))
    # Sparse accessors are read (expanded once); these claim more substitutions than elements,
    # or values past their bufferView.
    edit("accessor_sparse.gltf", lambda d: d["accessors"][0].update(sparse={
        "count": 1000, "indices": {"bufferView": 2, "componentType": 5123}, "values": {"bufferView": 0}}))
    edit("accessor_sparse_values_past_view.gltf", lambda d: d["accessors"][0].update(sparse={
        "count": 3, "indices": {"bufferView": 2, "componentType": 5123}, "values": {"bufferView": 2}}))
    edit("accessor_type_mat4_position.gltf", lambda d: d["accessors"][0].update(type="MAT4", count=1))
    # A buffer that claims a petabyte around a few bytes of data URI.
    edit("buffer_length_petabyte.gltf", lambda d: d["buffers"][0].update(byteLength=10 ** 15))
    edit("buffer_length_short.gltf", lambda d: d["buffers"][0].update(byteLength=4))


def glb():
    b = builder()
    mesh = b.mesh([b.primitive(TRI, [0, 1, 2], TRI_N)])
    b.scene([b.node(mesh=mesh)])
    path = out("glb_ok.glb")
    b.write_glb(path)
    with open(path, "rb") as f:
        good = bytearray(f.read())
    os.remove(path)
    json_len = struct.unpack_from("<I", good, 12)[0]
    bin_at = 20 + json_len  # BIN chunk header: length, type

    def variant(name, offset, value):
        data = bytearray(good)
        struct.pack_into("<I", data, offset, value)
        with open(out(name), "wb") as f:
            f.write(bytes(data))

    variant("glb_total_length_huge.glb", 8, 0xFFFFFFFF)
    variant("glb_total_length_short.glb", 8, 24)
    variant("glb_json_length_huge.glb", 12, 0xFFFFFFF0)
    variant("glb_json_length_zero.glb", 12, 0)
    variant("glb_bin_length_huge.glb", bin_at, 0xFFFFFFF0)
    variant("glb_bin_length_unaligned.glb", bin_at, 7)
    variant("glb_version_1.glb", 4, 1)
    with open(out("glb_header_only.glb"), "wb") as f:
        f.write(bytes(good[:12]))


# ---- sizes ----------------------------------------------------------------------------------------

def png_header(width, height):
    """A PNG that declares width x height and holds one row of data: decoders that trust the
    header allocate for the whole image."""
    import zlib

    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)

    raw = zlib.compress(b"\x00" + b"\x00" * (4 * 16), 9)
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 6, 0, 0, 0)) +
            chunk(b"IDAT", raw) + chunk(b"IEND", b""))


def sizes():
    import base64
    for name, (w, h) in (("image_claims_1e5_by_1e5.gltf", (100000, 100000)),
                         ("image_claims_16384_square.gltf", (16384, 16384)),
                         ("image_claims_8192_square_truncated.gltf", (8192, 8192))):
        b = builder()
        b.doc["images"] = [{"uri": "data:image/png;base64," + base64.b64encode(png_header(w, h)).decode("ascii")}]
        b.doc["textures"] = [{"source": 0}]
        mat = b.material("textured", (1, 1, 1), base_color_texture={"index": 0})
        mesh = b.mesh([b.primitive(TRI, [0, 1, 2], TRI_N, uvs=[(0, 0), (1, 0), (0, 1)], material=mat)])
        b.scene([b.node(mesh=mesh)])
        b.write_embedded(out(name))

    # 40 levels of nodes, each with two references to the next: 2^40 instances of one triangle.
    b = builder()
    mesh = b.mesh([b.primitive(TRI, [0, 1, 2], TRI_N)])
    levels = 40
    b.doc["nodes"] = [{"children": [i + 1, i + 1]} for i in range(levels)] + [{"mesh": mesh}]
    b.scene([0])
    b.write_embedded(out("node_instancing_bomb.gltf"))


# ---- node graphs ----------------------------------------------------------------------------------

def graphs():
    _, doc = triangle_doc()
    doc["nodes"][0]["children"] = [0]
    write_doc("cycle_self.gltf", doc)

    # A cycle that no scene reaches is harmless: only the scene's nodes are visited.
    _, doc = triangle_doc()
    doc["nodes"] += [{"name": "x", "children": [2]}, {"name": "y", "children": [1]}]
    write_doc("cycle_unreachable.gltf", doc)

    # Without "scenes" the roots are the parentless nodes: a cycle has none, the triangle is one.
    _, doc = triangle_doc()
    del doc["scenes"], doc["scene"]
    doc["nodes"] += [{"name": "x", "children": [2], "mesh": 0}, {"name": "y", "children": [1]}]
    write_doc("cycle_without_scenes.gltf", doc)

    # A diamond (two parents share a child) is a DAG, not a cycle: two instances.
    _, doc = triangle_doc()
    doc["nodes"] = [{"name": "left", "children": [2]}, {"name": "right", "children": [2], "translation": [0, 0, 1]},
                    {"name": "shared", "mesh": 0}]
    doc["scenes"][0]["nodes"] = [0, 1]
    write_doc("dag_shared_child.gltf", doc)

    _, doc = triangle_doc()
    doc["nodes"][0]["children"] = [-1]
    write_doc("child_negative.gltf", doc)
    _, doc = triangle_doc()
    doc["scenes"][0]["nodes"] = [3]
    write_doc("scene_root_out_of_range.gltf", doc)
    _, doc = triangle_doc()
    doc["scene"] = 4
    write_doc("default_scene_out_of_range.gltf", doc)


# ---- URIs -----------------------------------------------------------------------------------------

# Loaded from a copy in <tmp>/scene/ beside <tmp>/outside.bin, which holds a valid buffer: a URI
# that escaped would load instead of failing.
URIS = {
    "uri_percent_dots.gltf": "%2e%2e/outside.bin",
    "uri_percent_dots_upper.gltf": "%2E%2E%2Foutside.bin",
    "uri_percent_all.gltf": "%2e%2e%2f%6f%75%74%73%69%64%65%2e%62%69%6e",
    "uri_double_encoded.gltf": "%252e%252e/outside.bin",
    "uri_backslash_parent.gltf": "..\\outside.bin",
    "uri_backslash_absolute.gltf": "\\tmp\\outside.bin",
    "uri_file_scheme.gltf": "file:///etc/passwd",
    "uri_http.gltf": "http://example.com/outside.bin",
    "uri_dot_dot_only.gltf": "..",
    "uri_nul_byte.gltf": "external.bin%00.png",
    "uri_shell_expansion.gltf": "$(touch pwned)",
    "uri_tilde.gltf": "~/outside.bin",
    "uri_directory.gltf": "sub",
    "uri_dot.gltf": ".",
    "uri_symlink_out.gltf": "link_out.bin",          # the test makes link_out.bin -> ../outside.bin
    "uri_symlink_dir_out.gltf": "link_dir/outside.bin",  # link_dir -> ..
    "uri_symlink_inside.gltf": "link_in.bin",         # link_in.bin -> external.bin: allowed
    "uri_plain_inside.gltf": "external.bin",          # allowed
    "uri_sub_dot_dot_inside.gltf": "sub/../external.bin",  # allowed: stays inside
}


def uris():
    for name, uri in URIS.items():
        b, doc = triangle_doc()
        doc["buffers"][0]["uri"] = uri
        write_doc(name, doc)
    # The same buffer, for the directory: loads when a URI resolves to it.
    b, _ = triangle_doc()
    b._pad()
    with open(out("external.bin"), "wb") as f:
        f.write(bytes(b.bin))


# ---- regressions: the defects found ---------------------------------------------------------------

def regression(name):
    return os.path.join(REGRESSIONS, name)


def minimal_glb(json_doc, bin_data, bin_length):
    text = json.dumps(json_doc, separators=(",", ":")).encode("utf-8")
    text += b" " * ((4 - len(text) % 4) % 4)
    chunks = struct.pack("<I4s", len(text), b"JSON") + text + struct.pack("<I4s", bin_length, b"BIN\0") + bin_data
    return struct.pack("<4sII", b"glTF", 2, 12 + len(chunks)) + chunks


def regressions():
    asset = {"version": "2.0"}
    # tinygltf 2.7.0 checks the BIN chunk length against the GLB length without the 8-byte chunk
    # header, then copies byteLength bytes: 8 bytes read past the end of the file (ASan
    # heap-buffer-overflow in tinygltf::ParseBuffer). Fixed in glb_json_chunk().
    with open(regression("glb_bin_chunk_past_end.glb"), "wb") as f:
        f.write(minimal_glb({"asset": asset, "buffers": [{"byteLength": 12}]}, b"\0" * 4, 12))

    # tinygltf reads indices as int (GetInt: a cast of the int64), so bufferView 2^32 is
    # bufferView 0, which the pre-scan had skipped as out of range: the image decoder then read
    # 64 bytes at offset 4096 of a 4-byte buffer (ASan heap-buffer-overflow in stb_image).
    # Fixed by index_member() in check_image_buffer_views().
    def image_doc(image_view, view_buffer):
        return {"asset": asset,
                "buffers": [{"byteLength": 4, "uri": "data:application/octet-stream;base64,AAAAAA=="}],
                "bufferViews": [{"buffer": view_buffer, "byteOffset": 4096, "byteLength": 64}],
                "images": [{"bufferView": image_view, "mimeType": "image/png"}]}

    write_text(regression("image_buffer_view_index_wraps.gltf"), json.dumps(image_doc(2 ** 32, 0)) + "\n")
    write_text(regression("image_buffer_view_negative_index_wraps.gltf"), json.dumps(image_doc(-2 ** 32, 0)) + "\n")
    write_text(regression("buffer_view_buffer_index_wraps.gltf"), json.dumps(image_doc(0, 2 ** 32)) + "\n")

    # emissiveFactor 2 and emissiveStrength 3e38 are each finite as floats, their product is
    # not: an infinite emission reached the renderer. Fixed in convert_material().
    _, doc = triangle_doc({"emissiveFactor": [2, 0, 0],
                           "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 3e38}}})
    write_text(regression("emission_product_overflow.gltf"), json.dumps(doc) + "\n")

    # Radiance 3e38 is a finite float; the light's power (4 pi I, or the spot's cone integral)
    # is not. Fixed in add_light().
    for name, light in (("point_light_power_overflow.gltf", {"type": "point", "intensity": 3e38}),
                        ("spot_light_power_overflow.gltf",
                         {"type": "spot", "intensity": 3e38, "spot": {"outerConeAngle": 1.5}})):
        _, doc = triangle_doc()
        doc["extensions"] = {"KHR_lights_punctual": {"lights": [light]}}
        doc["nodes"].append({"extensions": {"KHR_lights_punctual": {"light": 0}}})
        doc["scenes"][0]["nodes"].append(1)
        write_text(regression(name), json.dumps(doc) + "\n")

    # A symbolic link inside the scene directory led out of it: the containment check was
    # lexical only (the fuzz target's canary ../outside.bin was opened). The test and the fuzz
    # target make link_out.bin -> ../outside.bin and link_dir -> .. beside these files. Fixed by
    # resolves_inside() in guarded_read_file().
    for name, uri in (("symlink_file_escape.gltf", "link_out.bin"), ("symlink_dir_escape.gltf", "link_dir/outside.bin")):
        _, doc = triangle_doc()
        doc["buffers"][0]["uri"] = uri
        write_text(regression(name), json.dumps(doc) + "\n")

    # 2^18 instances (inside the 2^20 node-visit limit) of a 256-triangle mesh: 2^26 triangles.
    # The loader built 2^25 of them (3.3 GB) before it failed: std::bad_alloc under a 4 GB
    # address-space limit. Fixed by the counting pass in SceneBuilder::build().
    b = builder()
    grid = [(float(i % 17), float(i // 17), 0.0) for i in range(17 * 9)]
    quads = []
    for y in range(8):
        for x in range(16):
            v = y * 17 + x
            quads += [v, v + 1, v + 18, v, v + 18, v + 17]
    mesh = b.mesh([b.primitive(grid, quads, None)])
    levels = 18
    b.doc["nodes"] = [{"children": [i + 1, i + 1]} for i in range(levels)] + [{"mesh": mesh}]
    b.scene([0])
    write_text(regression("triangle_instancing_bomb.gltf"), json.dumps(b.document(b.data_uri())) + "\n")


def main():
    os.makedirs(OUT, exist_ok=True)
    os.makedirs(REGRESSIONS, exist_ok=True)
    for make in (positions, normals, factors, lights, cameras, transforms, indices, accessors, glb, sizes,
                 graphs, uris, regressions):
        make()


if __name__ == "__main__":
    main()
