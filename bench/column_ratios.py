#!/usr/bin/env python3
"""The ratio of two renders' light, column band by column band: for sample models laid out as a
grid (AnisotropyStrengthTest: roughness 0 to 1 from left to right), how clppm's image compares
with Cycles' in each column. The lit width of the reference (pixels with any light) is cut into N
equal bands; each band's sum in IMAGE over its sum in REFERENCE, and each band's share of the
reference's light. Runs in PyPI's bpy (its EXR reading; numpy comes with it).

    BPY_PYTHON bench/column_ratios.py IMAGE.exr REFERENCE.exr [--bands 7]
"""
import argparse
import sys

import bpy
import numpy as np


def load(path):
    img = bpy.data.images.load(path)
    w, h = img.size
    if h == 0:
        raise SystemExit("column_ratios: cannot read " + path)
    return np.array(img.pixels[:], dtype=np.float64).reshape(h, w, 4)[::-1, :, :3].mean(axis=2)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("image")
    ap.add_argument("reference")
    ap.add_argument("--bands", type=int, default=7)
    a = ap.parse_args(sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else sys.argv[1:])
    img, ref = load(a.image), load(a.reference)
    if img.shape != ref.shape:
        raise SystemExit("column_ratios: the images differ in size")
    lit = np.nonzero(ref.sum(axis=0) > 1e-6)[0]
    if lit.size == 0:
        raise SystemExit("column_ratios: the reference is black")
    edges = np.linspace(lit.min(), lit.max() + 1, a.bands + 1).astype(int)
    total = ref.sum()
    for i in range(a.bands):
        x0, x1 = edges[i], edges[i + 1]
        r = ref[:, x0:x1].sum()
        print("band %d (x %d-%d): ratio %.3f, share of the reference's light %.2f" %
              (i + 1, x0, x1 - 1, img[:, x0:x1].sum() / r if r > 0 else float("nan"), r / total))


if __name__ == "__main__":
    main()
