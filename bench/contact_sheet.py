#!/usr/bin/env python3
"""Puts images side by side in one PNG, each scaled to the same height: clppm's renders (linear
EXR) beside Cycles' or beside a sample model's screenshot (sRGB PNG or JPEG). Runs in PyPI's bpy
(its image loading, scaling and colour management; numpy comes with it), since Debian's Python
here has no imaging library. EXR is written out with the Standard view transform (plain sRGB),
as clppm's own PNGs are; 8-bit images are decoded from sRGB to linear first, so they come back
as they were.

    BPY_PYTHON bench/contact_sheet.py OUT.png IMAGE [IMAGE ...] [--height 160]
"""
import argparse
import sys

import bpy
import numpy as np

GAP = 4  # white pixels between images


def load_linear(path, height):
    img = bpy.data.images.load(path)
    w, h = img.size
    if h == 0:
        raise SystemExit("contact_sheet: cannot read " + path)
    if h != height:
        img.scale(max(1, int(round(w * height / h))), height)
        w, h = img.size
    px = np.array(img.pixels[:], dtype=np.float32).reshape(h, w, 4)
    if not img.is_float:  # 8-bit: stored as sRGB codes
        c = px[..., :3]
        px[..., :3] = np.where(c <= 0.04045, c / 12.92, ((c + 0.055) / 1.055) ** 2.4)
    px[..., 3] = 1.0
    return px


def main():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else sys.argv[1:]
    ap = argparse.ArgumentParser()
    ap.add_argument("out")
    ap.add_argument("images", nargs="+")
    ap.add_argument("--height", type=int, default=160)
    a = ap.parse_args(argv)
    tiles = [load_linear(p, a.height) for p in a.images]
    gap = np.ones((a.height, GAP, 4), dtype=np.float32)
    parts = []
    for t in tiles:
        if parts:
            parts.append(gap)
        parts.append(t)
    sheet = np.concatenate(parts, axis=1)
    h, w = sheet.shape[:2]
    out = bpy.data.images.new("sheet", w, h, alpha=False, float_buffer=True)
    out.pixels.foreach_set(sheet.ravel())
    scene = bpy.context.scene
    scene.view_settings.view_transform = "Standard"
    scene.view_settings.look = "None"
    scene.view_settings.exposure = 0.0
    scene.view_settings.gamma = 1.0
    scene.render.image_settings.file_format = "PNG"
    scene.render.image_settings.color_mode = "RGB"
    scene.render.image_settings.color_depth = "8"
    out.save_render(a.out, scene=scene)
    print("wrote", a.out)


if __name__ == "__main__":
    main()
