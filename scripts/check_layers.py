#!/usr/bin/env python3
"""Checks that every #include in src/ runs downwards through the layers (docs/development.md, "Layout"):

    util < io < device < scene < integrators < render < cli, python

A file may include its own layer and any layer below it, never one above; the front ends (cli/,
python/) stand side by side and include neither each other. Kernel headers
(kernels/, e.g. shared_types.h) and system headers sit below every layer. Exits 1 and names each
offending include."""
import pathlib
import re
import sys

LAYERS = ["util", "io", "device", "scene", "integrators", "render", "cli", "python"]
RANK = {name: i for i, name in enumerate(LAYERS)}
RANK["python"] = RANK["cli"]  # front ends of the same rank


def main() -> int:
    src = pathlib.Path(__file__).resolve().parent.parent / "src"
    bad = []
    for path in sorted(src.rglob("*")):
        if path.suffix not in (".h", ".cpp"):
            continue
        layer = path.relative_to(src).parts[0]
        if layer not in RANK:
            bad.append(f"{path.relative_to(src)}: not inside a layer folder ({', '.join(LAYERS)})")
            continue
        for number, line in enumerate(path.read_text().splitlines(), 1):
            m = re.match(r'\s*#\s*include\s+"([^"]+)"', line)
            if not m:
                continue
            target = m.group(1).split("/")[0]
            if target not in RANK:
                if "/" in m.group(1):
                    bad.append(f"{path.relative_to(src)}:{number}: include of unknown layer \"{m.group(1)}\"")
                continue  # a kernel header (shared_types.h) or generated file
            if RANK[target] > RANK[layer] or (RANK[target] == RANK[layer] and target != layer):
                bad.append(f"{path.relative_to(src)}:{number}: {layer}/ includes \"{m.group(1)}\" from the "
                           f"higher layer {target}/")
    for b in bad:
        print(b, file=sys.stderr)
    if not bad:
        print("check_layers: every include runs downwards (" + " < ".join(LAYERS[:-1]) + ", " + LAYERS[-1] + ")")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
