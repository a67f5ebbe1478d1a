#!/usr/bin/env python3
"""clppm's integrators against Mitsuba 3's `path` on a glTF scene, side by side in one run at equal
wall time (issue 36: the skylit room of scenes/skylight.gltf, where light reaches what the camera
sees through a gap). Each image is compared with `clppm compare --box 4` against one reference;
wall and CPU time beside. Run offline with Mitsuba 3 from PyPI (as bench/peers_diffuse_box.py):

    DRJIT_LIBLLVM_PATH=/usr/lib/x86_64-linux-gnu/libLLVM-19.so /tmp/mi/bin/python \\
        bench/peers_scene.py [BUILD_DIR] [SCENE] [SECONDS] [SIZE] [METHODS]

METHODS: clppm's, comma-separated (default sppm+vi,sppm,pt; +vi adds --visual-importance). The
scene reaches Mitsuba through tests/references/make_references.py (the same triangles, twosided
diffuse surfaces, a directional light of the same irradiance, the same camera and box pixel
filter), max_depth 17 (clppm's 16 bounces). The reference is PEERS_REF (a clppm image of the same
size), or else Mitsuba's own of REF_FACTOR (20) times its spp; Mitsuba is also measured against
its own reference, and the two references against each other say whether the renderers agree.
Mitsuba 3 has no photon mapper: its `path` is the peer (pbrt-v4's SPPM is neither in Debian nor on
PyPI)."""
import os
import sys
import tempfile

import mitsuba as mi

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.join(ROOT, "tests", "references"))
import make_references  # noqa: E402
from peer_runs import clppm_timed, compare, mitsuba_fastest_variant  # noqa: E402
from peers_diffuse_box import timed_render  # noqa: E402


def main():
    build = sys.argv[1] if len(sys.argv) > 1 else os.path.join(ROOT, "build")
    scene_file = sys.argv[2] if len(sys.argv) > 2 else os.path.join(ROOT, "scenes", "skylight.gltf")
    seconds = float(sys.argv[3]) if len(sys.argv) > 3 else 30
    size = int(sys.argv[4]) if len(sys.argv) > 4 else 128
    methods = (sys.argv[5] if len(sys.argv) > 5 else "sppm+vi,sppm,pt").split(",")
    ref_factor = int(os.environ.get("REF_FACTOR", "20"))
    binary = os.path.join(build, "clppm")
    mitsuba_fastest_variant(mi)
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        scene = mi.load_dict(make_references.mitsuba_scene(scene_file, tmp, size=size, max_depth=17))
        mi_img, mi_ref, spp, wall, cpu = timed_render(scene, seconds, tmp, ref_factor, "mitsuba")
        ref = os.environ.get("PEERS_REF", "") or mi_ref
        rows.append(("Mitsuba %s path (%s, %d spp)" % (mi.__version__, mi.variant(), spp), wall, cpu,
                     compare(binary, mi_img, ref)))
        if ref != mi_ref:
            rows.append(("Mitsuba path against its own reference", wall, cpu, compare(binary, mi_img, mi_ref)))
        cross = compare(binary, mi_ref, ref) if ref != mi_ref else None

        for m in methods:
            args = ["--integrator", m.split("+")[0]] + (["--visual-importance"] if m.endswith("+vi") else [])
            out = os.path.join(tmp, "clppm.exr")
            wall, cpu, _ = clppm_timed([binary, scene_file, "--width", str(size), "--height", str(size), "--quiet",
                                     "--no-png", "--time", str(seconds), "-o", out] + args,
                                    os.path.join(tmp, "stats.json"))
            rows.append(("clppm " + " ".join(args[1:]), wall, cpu, compare(binary, out, ref)))

    print("%s, %dx%d, about %g s each; reference: %s; %d cores" % (
        os.path.basename(scene_file), size, size, seconds,
        "PEERS_REF" if cross else "Mitsuba, %d times its spp" % ref_factor, os.cpu_count()))
    if cross:
        print("Mitsuba's reference against PEERS_REF: mean ratio %.4f, box-4 relative MSE %.2e, p90 %.4f"
              % (cross["mean_ratio"], cross["box_rel_mse"], cross["p90_rel_error"]))
    print()
    print("| renderer | render wall s | CPU s | mean ratio | box-4 relative MSE | p90 relative error | MSE x CPU s |")
    print("|---|---:|---:|---:|---:|---:|---:|")
    for name, wall, cpu, c in rows:
        print("| %s | %.1f | %.1f | %.4f | %.3e | %.4f | %.2e |" % (name, wall, cpu, c["mean_ratio"], c["box_rel_mse"],
                                                                   c["p90_rel_error"], c["box_rel_mse"] * cpu))


if __name__ == "__main__":
    main()
