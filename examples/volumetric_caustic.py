#!/usr/bin/env python3
"""A volumetric caustic and each integrator's error against time: the built-in Cornell box (or a
scene of yours) filled with fog by keyword, its glass sphere focusing the ceiling light into the
fog, rendered by every integrator that renders participating media, plotted with matplotlib.

    python3 examples/volumetric_caustic.py [SCENE.gltf] [--seconds 20] [--size 128] [--out volumetric_caustic.png]

The reference is a long render by SPPM with another seed (it shares SPPM's blur: for references
that do not, see bench/peers_media.py, which holds clppm against Mitsuba 3's volpath). Each
integrator then renders for --seconds, and after every pass the relative MSE of its image against
the reference is recorded with the time.
"""
import argparse
import os

import clppm
from error_curves import add_common_arguments, error_curve, plot

FOG = dict(medium_density=0.25, medium_albedo=0.95, medium_anisotropy=0.5)


def curves(scene, integrators, seconds, size, reference_passes, photons):
    common = dict(width=size, height=size, photons=photons, quiet=True, **FOG)
    reference = clppm.render(scene, seed=1000, passes=reference_passes, integrator="sppm", **common)
    result = {}
    for integrator in integrators:
        points = error_curve(scene, reference, integrator=integrator, time=seconds, **common)
        result[integrator] = points
        print(f"{integrator}: {len(points)} passes, rel MSE {points[-1][1]:.3g} after {points[-1][0]:.1f} s")
    return result


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    add_common_arguments(ap, photons=10000, out="volumetric_caustic.png")
    ap.add_argument("--integrators", default="sppm,pppm,ppm,pt")
    ap.add_argument("--seconds", type=float, default=20.0, help="render time per integrator")
    a = ap.parse_args()
    result = curves(a.scene, a.integrators.split(","), a.seconds, a.size, a.reference_passes, a.photons)
    plot(result, a.out, f"{a.scene or 'the Cornell box'} in fog, {a.size}x{a.size}")
    print("wrote", os.path.abspath(a.out))


if __name__ == "__main__":
    main()
