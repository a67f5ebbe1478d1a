"""The small subset of glTF that the reference and peer scripts read (buffers embedded or in files
beside the glTF, float positions and normals, 8-, 16- or 32-bit indices, node translation, rotation
and scale), and the binary PLY files they hand to other renderers: pure Python, so that renderers
whose libraries cannot share a process (Mitsuba's Dr.Jit and pyluxcore abort when both load) use
the same triangles."""
import struct


def quat_rotate(q, v):
    x, y, z, w = q
    # v + 2 w (q x v) + 2 q x (q x v)
    cx = (y * v[2] - z * v[1], z * v[0] - x * v[2], x * v[1] - y * v[0])
    ccx = (y * cx[2] - z * cx[1], z * cx[0] - x * cx[2], x * cx[1] - y * cx[0])
    return tuple(v[i] + 2 * w * cx[i] + 2 * ccx[i] for i in range(3))


def read_buffers(doc, path):
    """The bytes of each of the glTF's buffers: base64 data URIs, or files beside the glTF."""
    import base64
    import os
    blobs = []
    for b in doc["buffers"]:
        uri = b["uri"]
        if uri.startswith("data:"):
            blobs.append(base64.b64decode(uri[uri.index(",") + 1:]))
        else:
            with open(os.path.join(os.path.dirname(os.path.abspath(path)), uri), "rb") as f:
                blobs.append(f.read())
    return blobs


def read_accessor(doc, blob, index):
    """Accessor `index` as a list; blob: the only buffer's bytes, or read_buffers' list."""
    acc = doc["accessors"][index]
    view = doc["bufferViews"][acc["bufferView"]]
    if isinstance(blob, list):
        blob = blob[view.get("buffer", 0)]
    comps = {"SCALAR": 1, "VEC2": 2, "VEC3": 3}[acc["type"]]
    fmt = {5126: "f", 5121: "B", 5123: "H", 5125: "I"}[acc["componentType"]]
    start = view.get("byteOffset", 0) + acc.get("byteOffset", 0)
    n = acc["count"] * comps
    vals = struct.unpack_from("<%d%s" % (n, fmt), blob, start)
    return [vals[i:i + comps] for i in range(0, n, comps)] if comps > 1 else list(vals)


def write_ply(path, tris, uvs=None, normals=None):
    """Triangles, per-corner glTF uvs as they are (Mitsuba 3's bitmaps, like glTF, put v = 0 at the
    image's top row; flipped, the textured reference differs from clppm by a relative MSE of 0.63,
    as is 0.002), and per-corner shading normals when given."""
    with open(path, "wb") as f:
        f.write(("ply\nformat binary_little_endian 1.0\nelement vertex %d\nproperty float x\n"
                 "property float y\nproperty float z\n%s%selement face %d\nproperty list uchar int vertex_indices\n"
                 "end_header\n" % (3 * len(tris), "property float nx\nproperty float ny\nproperty float nz\n"
                                    if normals else "", "property float u\nproperty float v\n" if uvs else "",
                                    len(tris))).encode())
        for k, t in enumerate(tris):
            for j, p in enumerate(t):
                f.write(struct.pack("<3f", *p))
                if normals:
                    f.write(struct.pack("<3f", *normals[k][j]))
                if uvs:
                    f.write(struct.pack("<2f", *uvs[k][j]))
        for i in range(len(tris)):
            f.write(struct.pack("<B3i", 3, 3 * i, 3 * i + 1, 3 * i + 2))
