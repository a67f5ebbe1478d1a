#!/usr/bin/env python3
"""Converts .gltf files whose buffers are all data URIs or plain file names beside them into
.glb seeds for the fuzzer (python3 standard library only):
    python3 tests/fuzz/gltf_to_glb.py OUT_DIR FILE.gltf...
Buffers are concatenated into the BIN chunk (4-byte aligned) and the buffer views re-pointed
into it. Files that do not convert (malformed JSON, a missing .bin, a URI naming another
directory, a result over 256 KiB) are skipped silently: they are seeds in their .gltf form."""
import base64
import json
import os
import struct
import sys

MAX_SEED_BYTES = 256 * 1024


def buffer_bytes(buf, base):
    uri = buf.get("uri", "")
    if uri.startswith("data:"):
        return base64.b64decode(uri.split(",", 1)[1])
    if os.path.basename(uri) != uri or uri in ("", ".", ".."):
        raise ValueError("not a file beside the .gltf: " + uri)
    with open(os.path.join(base, uri), "rb") as f:
        return f.read()


def to_glb(path):
    with open(path, "rb") as f:
        doc = json.loads(f.read())
    base = os.path.dirname(path)
    blob, starts = bytearray(), []
    for buf in doc.get("buffers", []):
        while len(blob) % 4:
            blob.append(0)
        starts.append(len(blob))
        blob += buffer_bytes(buf, base)
    for view in doc.get("bufferViews", []):
        view["byteOffset"] = view.get("byteOffset", 0) + starts[view.get("buffer", 0)]
        view["buffer"] = 0
    if starts:
        doc["buffers"] = [{"byteLength": len(blob)}]
    while len(blob) % 4:
        blob.append(0)
    text = json.dumps(doc, separators=(",", ":")).encode("utf-8")
    text += b" " * ((4 - len(text) % 4) % 4)
    chunks = struct.pack("<I4s", len(text), b"JSON") + text
    if blob:
        chunks += struct.pack("<I4s", len(blob), b"BIN\0") + bytes(blob)
    if len(chunks) > MAX_SEED_BYTES:
        raise ValueError("too big for a seed")
    return struct.pack("<4sII", b"glTF", 2, 12 + len(chunks)) + chunks


def main():
    out = sys.argv[1]
    os.makedirs(out, exist_ok=True)
    for path in sys.argv[2:]:
        try:
            glb = to_glb(path)
        except (ValueError, OSError, KeyError, IndexError, TypeError, AttributeError):
            continue
        name = os.path.splitext(os.path.basename(path))[0] + ".glb"
        with open(os.path.join(out, name), "wb") as f:
            f.write(glb)


if __name__ == "__main__":
    main()
