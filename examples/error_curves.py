"""What the examples share: the relative MSE that `clppm compare` reports, a render's error after
every pass against a reference, and the plot of such curves (matplotlib)."""
import time

import numpy as np

import clppm


def rel_mse(image, reference):
    """Mean over pixels and channels of (a - b)^2 / (b^2 + 0.01), as `clppm compare` reports it."""
    return float(np.mean((image - reference) ** 2 / (reference**2 + 1e-2)))


def error_curve(scene, reference, **options):
    """[(seconds, relative MSE)] after each pass of a render of `scene` with `options` (which
    bound it, e.g. time=20), against `reference`."""
    points = []
    with clppm.Renderer(scene, **options) as r:
        start = time.perf_counter()
        for _ in r:
            points.append((time.perf_counter() - start, rel_mse(r.image(), reference)))
    return points


def add_common_arguments(ap, photons, out):
    """The arguments both examples take: the scene, the size, the photons per pass (default
    `photons`), the reference's passes and the plot's file (default `out`)."""
    ap.add_argument("scene", nargs="?", help="a .gltf or .glb file (default: the built-in Cornell box)")
    ap.add_argument("--size", type=int, default=128)
    ap.add_argument("--photons", type=int, default=photons)
    ap.add_argument("--reference-passes", type=int, default=400)
    ap.add_argument("--out", default=out)


def plot(curves, path, title):
    """Writes the curves ({label: [(seconds, error)]}) on log-log axes to the PNG `path`."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(6, 4))
    for label, points in curves.items():
        t, e = zip(*points)
        ax.loglog(t, e, label=label)
    ax.set_xlabel("render time (s)")
    ax.set_ylabel("relative MSE against the reference")
    ax.set_title(title)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend()
    fig.tight_layout()
    fig.savefig(path, dpi=100)
