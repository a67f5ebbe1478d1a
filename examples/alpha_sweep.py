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

import clppm
from error_curves import add_common_arguments, error_curve, plot


def sweep(scene, alphas, seconds, size, reference_passes, photons):
    common = dict(width=size, height=size, photons=photons, integrator="sppm", quiet=True)
    reference = clppm.render(scene, seed=1000, passes=reference_passes, **common)
    curves = {}
    for alpha in alphas:
        points = error_curve(scene, reference, alpha=alpha, time=seconds, **common)
        curves[f"alpha {alpha}"] = points
        print(f"alpha {alpha}: {len(points)} passes, rel MSE {points[-1][1]:.3g} after {points[-1][0]:.1f} s")
    return curves


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    add_common_arguments(ap, photons=100000, out="alpha_sweep.png")
    ap.add_argument("--alphas", default="0.3,0.5,0.7,0.9")
    ap.add_argument("--seconds", type=float, default=20.0, help="render time per alpha")
    a = ap.parse_args()
    alphas = [float(x) for x in a.alphas.split(",")]
    curves = sweep(a.scene, alphas, a.seconds, a.size, a.reference_passes, a.photons)
    plot(curves, a.out, f"SPPM on {a.scene or 'the Cornell box'}, {a.size}x{a.size}")
    print("wrote", a.out)


if __name__ == "__main__":
    main()
