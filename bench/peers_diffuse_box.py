#!/usr/bin/env python3
"""clppm's path tracer against Mitsuba 3's `path` on the diffuse Cornell box, side by side in one
run at equal wall time (issue 36), Mitsuba with each of its samplers in MI_SAMPLERS (default
independent, ldsampler and multijitter: its best is the peer): each image against one reference, by `clppm compare --box 4`,
with the wall and CPU time each took. Run offline with Mitsuba 3 from PyPI:

    python3 -m venv /tmp/mi && /tmp/mi/bin/pip install mitsuba numpy
    apt-get install libllvm19; DRJIT_LIBLLVM_PATH=/usr/lib/x86_64-linux-gnu/libLLVM-19.so \\
        /tmp/mi/bin/python bench/peers_diffuse_box.py [BUILD_DIR] [SECONDS] [SIZE] [REF_PASSES]

The scene reaches Mitsuba through tests/references/make_references.py (the same triangles, twosided
diffuse surfaces, a one-sided area emitter, the same camera and box pixel filter), with max_depth
17: clppm's 16 bounces. The reference is clppm's path tracer with independent numbers and another
seed (REF_PASSES passes; PEERS_REF=FILE reuses one) for clppm, and Mitsuba's own of REF_FACTOR (20)
times its spp for Mitsuba; the two references against each other say whether the renderers agree. Mitsuba runs the
llvm_ad_rgb variant when DRJIT_LIBLLVM_PATH lets it, else scalar_rgb; its spp is chosen from a
timed render so that the render takes about SECONDS, and the time it took is reported. clppm's
wall time is its passes' (--stats-json render_seconds), Mitsuba's its render's, both without
loading and kernel compilation; CPU times include them. Since the error falls as 1/time, MSE x CPU
time compares the two at equal error."""
import os
import sys
import tempfile
import time

import drjit as dr
import mitsuba as mi

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.join(ROOT, "tests", "references"))
import make_references  # noqa: E402
from peer_runs import (arguments, clppm_timed, compare, diffuse_box, mitsuba_fastest_variant,  # noqa: E402
                       print_report)


def render(scene, spp, seed):
    """Mitsuba's image, evaluated (the llvm variant computes lazily, when the image is used)."""
    img = mi.render(scene, spp=spp, seed=seed)
    dr.eval(img)
    dr.sync_thread()
    return img


def timed_render(scene, seconds, tmp, ref_factor, name):
    """Mitsuba's image of about `seconds` (its spp chosen from timed renders, the kernels compiled
    first), written to tmp/NAME.exr, and, when ref_factor > 0, its own reference of ref_factor
    times the samples in tmp/mitsuba_ref.exr: (image path, reference path or None, spp, wall s,
    CPU s)."""
    render(scene, 4, 0)  # compiles the kernels (llvm) outside the timed renders
    spp = 16
    for _ in range(2):  # the first estimate is mostly the fixed cost of a render
        t0 = time.time()
        render(scene, spp, 1)
        spp = max(16, int(spp * seconds / max(time.time() - t0, 1e-3) / (4 if spp == 16 else 1)))
    # Dr.Jit may compile a kernel for each new spp: a render at the chosen spp first, so the timed
    # one runs what is already compiled, as clppm's timed passes do.
    render(scene, spp, 3)
    t0, c0 = time.time(), time.process_time()
    img = render(scene, spp, 2)
    wall, cpu = time.time() - t0, time.process_time() - c0
    out = os.path.join(tmp, name + ".exr")
    mi.Bitmap(img).write(out)
    if ref_factor <= 0:
        return out, None, spp, wall, cpu
    # Mitsuba's own reference, ref_factor times the samples: each renderer is measured against a
    # converged image of its own, so what differs between the two renderers' models (a pixel
    # filter's edge, an emitter's side) does not count as either one's noise.
    ref = os.path.join(tmp, "mitsuba_ref.exr")
    mi.Bitmap(render(scene, spp * ref_factor, 99)).write(ref)
    return out, ref, spp, wall, cpu


def main():
    binary, seconds, size, ref_passes, ref_factor = arguments()
    mitsuba_fastest_variant(mi)
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        scene_file, common, ref = diffuse_box(binary, tmp, size, ref_passes)
        for sampler in ("sobol", "independent"):
            img = os.path.join(tmp, "clppm_%s.exr" % sampler)
            wall, cpu, passes = clppm_timed(common + ["--sampler", sampler, "--time", str(seconds), "-o", img],
                                            os.path.join(tmp, "stats.json"))
            rows.append(("clppm pt, %s" % sampler, passes, wall, cpu, compare(binary, img, ref)))

        # Every Mitsuba image against one reference of its own: the first sampler's (independent
        # numbers) at REF_FACTOR times its spp.
        mi_ref = None
        for sampler in os.environ.get("MI_SAMPLERS", "independent,ldsampler,multijitter").split(","):
            d = make_references.mitsuba_scene(scene_file, tmp, size=size, max_depth=17)
            d["sensor"]["sampler"] = {"type": sampler}
            scene = mi.load_dict(d)
            out, new_ref, spp, wall, cpu = timed_render(scene, seconds, tmp, 0 if mi_ref else ref_factor,
                                                        "mitsuba_" + sampler)
            mi_ref = mi_ref or new_ref
            rows.append(("Mitsuba %s path, %s (%s)" % (mi.__version__, sampler, mi.variant()), spp, wall, cpu,
                         compare(binary, out, mi_ref)))
        cross = compare(binary, mi_ref, ref)

    title = ("Diffuse Cornell box, %dx%d, about %g s each; references: clppm pt, %d independent passes, and Mitsuba, "
             "%d times its spp; %d cores" % (size, size, seconds, ref_passes, ref_factor, os.cpu_count()))
    print_report(title, cross, rows)


if __name__ == "__main__":
    main()
