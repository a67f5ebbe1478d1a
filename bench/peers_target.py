#!/usr/bin/env python3
"""Issue 36's target, scene by scene, in one run: clppm's default against Mitsuba 3's `path` (each
sampler in MI_SAMPLERS; the best is the peer) at equal wall time, on the issue's kinds of scene:

    cornell_diffuse  the Cornell box without its spheres (bench/cornell_diffuse.py): a diffuse room
    cornell_box      the Cornell box with its glass and mirror spheres (scenes/): a caustic scene
                     whose light is an area light, so that a path tracer can reach its caustics
    asset_env        bunny_100k's blob on a floor under the default white world (bench/asset_scenes.py)
    asset_sun        the same under two directional lights
    doorway          a room lit through a doorway (scenes/)
    skylight         a room lit by the sun through a skylight (scenes/)

    DRJIT_LIBLLVM_PATH=/usr/lib/x86_64-linux-gnu/libLLVM-19.so /tmp/mi/bin/python \\
        bench/peers_target.py [BUILD_DIR] [SECONDS] [SIZE]

Environment: SCENES (names above), REF_DIR (NAME-ref.exr there is reused, else rendered there),
REF_SECONDS (300), MI_SAMPLERS (independent,multijitter), MI_REF_FACTOR (4).

Every image is compared (`clppm compare --box 4`) with one reference per scene: clppm's path
tracer with independent numbers and another seed, or for cornell_box, whose caustics the path
tracer finds slowly, VCM (consistent; it converges to the path tracer's mean: bench/RESULTS.md).
Mitsuba's own reference (MI_REF_FACTOR times its spp) against clppm's says whether the two
renderers agree (a difference between their models would count as Mitsuba's error otherwise).
Scenes reach Mitsuba through tests/references/make_references.py with the files' vertex normals and
max_depth 17 (clppm's 16 bounces). Since the error falls as 1/time, MSE x CPU s compares two
renderers at equal error; the last column is clppm's CPU time to its error as a fraction of the
best Mitsuba sampler's (issue 36's target: at most 0.5). clppm's CPU time includes loading and
kernel compilation; Mitsuba's is its render's alone, compiled beforehand (peers_diffuse_box.py)."""
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

ALL_SCENES = ("cornell_diffuse", "cornell_box", "asset_env", "asset_sun", "doorway", "skylight")
CAUSTIC_SCENES = ("cornell_box",)


def scene_files(tmp):
    """Every scene of ALL_SCENES as a glTF file (the generated ones written to tmp)."""
    subprocess.run([sys.executable, os.path.join(HERE, "cornell_diffuse.py"),
                    os.path.join(ROOT, "scenes", "cornell_box.gltf"), os.path.join(tmp, "cornell_diffuse.gltf")],
                   check=True)
    subprocess.run([sys.executable, os.path.join(HERE, "asset_scenes.py"),
                    os.path.join(ROOT, "scenes", "bunny_100k.gltf"), tmp], check=True)
    files = {n: os.path.join(tmp, n + ".gltf") for n in ("cornell_diffuse", "asset_env", "asset_sun")}
    files.update({n: os.path.join(ROOT, "scenes", n + ".gltf") for n in ("cornell_box", "doorway", "skylight")})
    return files


def reference(binary, name, scene_file, size, ref_dir, seconds):
    """REF_DIR/NAME-ref.exr, rendered there first when it is missing."""
    ref = os.path.join(ref_dir, name + "-ref.exr")
    if not os.path.isfile(ref):
        integ = ["--integrator", "vcm"] if name in CAUSTIC_SCENES else ["--integrator", "pt", "--sampler",
                                                                       "independent"]
        subprocess.run([binary, scene_file, "--width", str(size), "--height", str(size), "--quiet", "--no-png",
                        "--seed", "777", "--time", str(seconds), "-o", ref] + integ, check=True)
    return ref


def main():
    build = sys.argv[1] if len(sys.argv) > 1 else os.path.join(ROOT, "build")
    seconds = float(sys.argv[2]) if len(sys.argv) > 2 else 15
    size = int(sys.argv[3]) if len(sys.argv) > 3 else 128
    binary = os.path.join(build, "clppm")
    scenes = os.environ.get("SCENES", " ".join(ALL_SCENES)).split()
    samplers = os.environ.get("MI_SAMPLERS", "independent,multijitter").split(",")
    ref_factor = int(os.environ.get("MI_REF_FACTOR", "4"))
    ref_seconds = float(os.environ.get("REF_SECONDS", "300"))
    mitsuba_fastest_variant(mi)
    rows, agreement = [], []
    with tempfile.TemporaryDirectory() as tmp:
        ref_dir = os.environ.get("REF_DIR", "") or tmp
        files = scene_files(tmp)
        for name in scenes:
            ref = reference(binary, name, files[name], size, ref_dir, ref_seconds)
            out, stats = os.path.join(tmp, "clppm.exr"), os.path.join(tmp, "stats.json")
            wall, cpu, passes = clppm_timed([binary, files[name], "--width", str(size), "--height", str(size),
                                             "--quiet", "--no-png", "--time", str(seconds), "-o", out], stats)
            st = json.load(open(stats))
            picked = st.get("integrator", "?") + ("+vi" if "visual_importance" in st else "")
            scene_rows = [("clppm default (%s)" % picked, passes, wall, cpu, compare(binary, out, ref))]
            mi_ref = None
            for sampler in samplers:
                d = make_references.mitsuba_scene(files[name], tmp, size=size, max_depth=17, vertex_normals=True)
                d["sensor"]["sampler"] = {"type": sampler}
                img, new_ref, spp, wall, cpu = timed_render(mi.load_dict(d), seconds, tmp,
                                                            0 if mi_ref else ref_factor, "mitsuba_" + sampler)
                mi_ref = mi_ref or new_ref
                scene_rows.append(("Mitsuba %s path, %s" % (mi.__version__, sampler), spp, wall, cpu,
                                   compare(binary, img, ref)))
            agreement.append((name, compare(binary, mi_ref, ref)))
            rows.append((name, scene_rows))
            print_scene(name, scene_rows, agreement[-1][1], flush=True)

    print()
    print("Issue 36's target, %dx%d, about %g s each (Mitsuba %s, %s); references: clppm, %g s or REF_DIR; %d cores"
          % (size, size, seconds, mi.__version__, mi.variant(), ref_seconds, os.cpu_count()))
    print()
    print("| scene | renderer | spp or passes | render wall s | CPU s | mean ratio | box-4 relative MSE | "
          "p90 relative error | MSE x CPU s | CPU to the same error, clppm / best Mitsuba |")
    print("|---|---|---:|---:|---:|---:|---:|---:|---:|---:|")
    for name, scene_rows in rows:
        best = min(r[4]["box_rel_mse"] * r[3] for r in scene_rows[1:])
        for i, (label, n, wall, cpu, c) in enumerate(scene_rows):
            eff = c["box_rel_mse"] * cpu
            print("| %s | %s | %d | %.1f | %.1f | %.4f | %.3e | %.4f | %.2e | %s |"
                  % (name if i == 0 else "", label, n, wall, cpu, c["mean_ratio"], c["box_rel_mse"],
                     c["p90_rel_error"], eff, "%.2f" % (eff / best) if i == 0 else ""))
    print()
    print("Mitsuba's reference (independent, %d times its spp) against clppm's:" % ref_factor)
    print()
    print("| scene | mean ratio | box-4 relative MSE | p90 relative error |")
    print("|---|---:|---:|---:|")
    for name, c in agreement:
        print("| %s | %.4f | %.2e | %.4f |" % (name, c["mean_ratio"], c["box_rel_mse"], c["p90_rel_error"]))


def print_scene(name, scene_rows, cross, flush):
    """One scene's rows as they finish (the full table comes at the end)."""
    for label, n, wall, cpu, c in scene_rows:
        print("%s: %s: %d, %.1f s, %.1f CPU s, mean %.4f, box-4 %.3e, p90 %.4f" % (
            name, label, n, wall, cpu, c["mean_ratio"], c["box_rel_mse"], c["p90_rel_error"]), flush=flush)
    print("%s: Mitsuba's reference against clppm's: mean %.4f, box-4 %.2e" % (
        name, cross["mean_ratio"], cross["box_rel_mse"]), flush=flush)


if __name__ == "__main__":
    main()
