#!/usr/bin/env python3
"""Issue 57's targets against Mitsuba 3's `volpath`, in one run, at equal wall time:
- the diffuse Cornell box (bench/cornell_diffuse.py) filled with fog (extras.clppm_medium: density
  0.3, 0.4, 0.5 per scene unit, albedo 0.9, 0.85, 0.8, g 0.3; the box is open towards the camera,
  so the fog fills the world around it too);
- the volumetric caustic: the Cornell box (scenes/cornell_box.gltf) with its glass and mirror
  spheres in fog (density 0.25, albedo 0.95, g 0.5), the glass focusing the ceiling light into it
  (bench/media_scenes.py's fog_caustic).
Each image is compared (`clppm compare --box 4`) with one reference per scene that is not clppm's:
Mitsuba's volpath at REF_FACTOR (20) times its spp. Since the error falls as 1/time, MSE x CPU s
compares the renderers at equal error; the last column is clppm's CPU time to its error as a
fraction of Mitsuba's (the targets: at most 0.5 in the fog box for the best of clppm, at most 0.1
for the default on the caustic). clppm's CPU time includes loading and kernel compilation;
Mitsuba's is its render's alone, compiled beforehand (peers_diffuse_box.py). Every integrator
that renders media runs (INTEGRATORS, default auto,sppm,sppm@10000:beams,pppm,pt; NAME@M: --photons M,
NAME:beams: --volume-gather beams; in media the photon integrators take 10000 a pass unless given).
SCENES=caustic runs that scene alone.

    DRJIT_LIBLLVM_PATH=/usr/lib/x86_64-linux-gnu/libLLVM-19.so /tmp/mi/bin/python \\
        bench/peers_media.py [BUILD_DIR] [SECONDS] [SIZE]

The scenes reach Mitsuba through tests/references/make_references.py: the same triangles, twosided
diffuse surfaces, the world's medium as Mitsuba's homogeneous medium on the sensor and outside
the glass (unbounded, as clppm's), max_depth 17 (clppm's 16 bounces)."""
import json
import os
import subprocess
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

def fog_scenes(tmp):
    """[(name, path)]: the fogged diffuse box and the volumetric caustic, written into tmp by
    bench/media_scenes.py."""
    subprocess.run([sys.executable, os.path.join(HERE, "media_scenes.py"), tmp], check=True)
    return [("diffuse Cornell box in fog", os.path.join(tmp, "fog_box.gltf")),
            ("volumetric caustic (glass sphere, area light)", os.path.join(tmp, "fog_caustic.gltf"))]


def main():
    build = sys.argv[1] if len(sys.argv) > 1 else os.path.join(ROOT, "build")
    seconds = float(sys.argv[2]) if len(sys.argv) > 2 else 15
    size = int(sys.argv[3]) if len(sys.argv) > 3 else 128
    ref_factor = int(os.environ.get("REF_FACTOR", "20"))
    integrators = os.environ.get("INTEGRATORS", "auto,sppm,sppm@10000:beams,pppm,pt").split(",")
    binary = os.path.join(build, "clppm")
    mitsuba_fastest_variant(mi)
    print("| scene | renderer | spp or passes | render wall s | CPU s | mean ratio | box-4 relative MSE | MSE x CPU s | "
          "clppm / Mitsuba |")
    print("|---|---|---:|---:|---:|---:|---:|---:|---:|")
    with tempfile.TemporaryDirectory() as tmp:
        only = os.environ.get("SCENES")  # a substring of the scenes' names to run alone
        for name, path in fog_scenes(tmp):
            if only and only not in name:
                continue
            scene = mi.load_dict(make_references.mitsuba_scene(path, tmp, size=size, max_depth=17,
                                                               vertex_normals=True))
            mi_img, ref, spp, wall, cpu = timed_render(scene, seconds, tmp, ref_factor, "mitsuba")
            c = compare(binary, mi_img, ref)
            mi_cost = c["box_rel_mse"] * cpu
            print("| %s | Mitsuba %s volpath (%s) | %d | %.1f | %.1f | %.4f | %.3e | %.2e | |"
                  % (name, mi.__version__, mi.variant(), spp, wall, cpu, c["mean_ratio"], c["box_rel_mse"], mi_cost))
            for entry in integrators:
                entry, _, gather = entry.partition(":")
                integrator, _, photons = entry.partition("@")
                out = os.path.join(tmp, "clppm.exr")
                stats = os.path.join(tmp, "stats.json")
                w, cpu, passes = clppm_timed([binary, path, "--width", str(size), "--height", str(size), "--quiet",
                                              "--no-png", "--time", str(seconds), "--integrator", integrator, "-o",
                                              out] + (["--photons", photons] if photons else []) +
                                             (["--volume-gather", gather] if gather else []), stats)
                label = integrator if integrator != "auto" else "default (%s)" % json.load(open(stats))["integrator"]
                if photons:
                    label += ", %s photons per pass" % photons
                if gather:
                    label += ", --volume-gather %s" % gather
                c = compare(binary, out, ref)
                cost = c["box_rel_mse"] * cpu
                print("| %s | clppm %s | %d | %.1f | %.1f | %.4f | %.3e | %.2e | **%.2f** |"
                      % (name, label, passes, w, cpu, c["mean_ratio"], c["box_rel_mse"], cost, cost / mi_cost))
                sys.stdout.flush()


if __name__ == "__main__":
    main()
