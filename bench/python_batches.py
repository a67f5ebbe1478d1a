"""Stepping the Python module's Renderer a pass at a time (iteration) against a launch at a time
(Renderer.batches()): wall and CPU seconds, launches, and whether the images agree.

    PYTHONPATH=build/python python3 bench/python_batches.py SCENE.gltf [PASSES] [ROUNDS]

The path tracer at 128x128; the two ways take turns for ROUNDS rounds (default 3), so that load
from other processes hits both alike (bench/RESULTS.md, "The Python module and the Blender add-on
batch too"; the asset scene comes from bench/asset_scenes.py)."""
import resource
import sys
import time

import numpy as np

import clppm


def cpu_seconds():
    u = resource.getrusage(resource.RUSAGE_SELF)
    return u.ru_utime + u.ru_stime


def main():
    scene = sys.argv[1]
    passes = int(sys.argv[2]) if len(sys.argv) > 2 else 1600
    rounds = int(sys.argv[3]) if len(sys.argv) > 3 else 3
    options = dict(integrator="pt", passes=passes, width=128, height=128, quiet=True)
    images = {}
    print("| stepping | round | launches | wall s | CPU s |")
    print("|---|---:|---:|---:|---:|")
    for rnd in range(rounds):
        for mode in ("a pass a step", "batches()"):
            with clppm.Renderer(scene, **options) as r:
                wall, cpu = time.monotonic(), cpu_seconds()
                for _ in (r if mode == "a pass a step" else r.batches()):
                    pass
                wall, cpu = time.monotonic() - wall, cpu_seconds() - cpu
                print(f"| {mode} | {rnd + 1} | {r.stats()['pass_launches']} | {wall:.2f} | {cpu:.2f} |")
                images.setdefault(mode, r.image())
    same = np.array_equal(images["a pass a step"], images["batches()"])
    print(f"images identical: {'yes' if same else 'NO'}")
    return 0 if same else 1


if __name__ == "__main__":
    sys.exit(main())
