#!/usr/bin/env python3
"""Error against time for several values of alpha (the fraction of new photons SPPM keeps per pass,
Hachisuka et al. 2008: R' = R sqrt((N + aM)/(N + M))), on the built-in Cornell box or a scene of
yours, plotted with matplotlib.

    python3 examples/alpha_sweep.py [SCENE.gltf] [--seconds 20] [--size 128] [--out alpha_sweep.png]

A long render with another seed is the reference; each alpha then renders passes for --seconds,
and after every pass the relative MSE of its image against the reference is recorded with the
time. Small alpha shrinks the radius fast (less bias, more noise); large alpha the reverse.
"""
import argparse
import time

import numpy as np

import clppm


def rel_mse(image, reference):
    """Mean over pixels and channels of (a - b)^2 / (b^2 + 0.01), as `clppm compare` reports it."""
    return float(np.mean((image - reference) ** 2 / (reference**2 + 1e-2)))


def sweep(scene, alphas, seconds, size, reference_passes, photons):
    common = dict(width=size, height=size, photons=photons, integrator="sppm", quiet=True)
    reference = clppm.render(scene, seed=1000, passes=reference_passes, **common)
    curves = {}
    for alpha in alphas:
        points = []
        with clppm.Renderer(scene, alpha=alpha, time=seconds, **common) as r:
            start = time.perf_counter()
            for _ in r:  # until --time
                points.append((time.perf_counter() - start, rel_mse(r.image(), reference)))
        curves[alpha] = points
        print(f"alpha {alpha}: {len(points)} passes, rel MSE {points[-1][1]:.3g} after {points[-1][0]:.1f} s")
    return curves


def plot(curves, path, title):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(6, 4))
    for alpha, points in curves.items():
        t, e = zip(*points)
        ax.loglog(t, e, label=f"alpha {alpha}")
    ax.set_xlabel("render time (s)")
    ax.set_ylabel("relative MSE against the reference")
    ax.set_title(title)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend()
    fig.tight_layout()
    fig.savefig(path, dpi=100)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("scene", nargs="?", help="a .gltf or .glb file (default: the built-in Cornell box)")
    ap.add_argument("--alphas", default="0.3,0.5,0.7,0.9")
    ap.add_argument("--seconds", type=float, default=20.0, help="render time per alpha")
    ap.add_argument("--size", type=int, default=128)
    ap.add_argument("--photons", type=int, default=100000)
    ap.add_argument("--reference-passes", type=int, default=400)
    ap.add_argument("--out", default="alpha_sweep.png")
    a = ap.parse_args()
    alphas = [float(x) for x in a.alphas.split(",")]
    curves = sweep(a.scene, alphas, a.seconds, a.size, a.reference_passes, a.photons)
    plot(curves, a.out, f"SPPM on {a.scene or 'the Cornell box'}, {a.size}x{a.size}")
    print("wrote", a.out)


if __name__ == "__main__":
    main()
