#!/usr/bin/env python3
"""clppm against LuxCore on the diffuse Cornell box, side by side at equal wall time (issue 36):
LuxCore's PATHCPU (its path tracer, Sobol' sampler by default) and BIDIRCPU, each image against
one reference, by `clppm compare --box 4`, with the wall and CPU time each took. LuxCore comes
from PyPI (pyluxcore; CPython 3.11 wheels), run offline in a virtual environment:

    python3 -m venv /tmp/mi && /tmp/mi/bin/pip install pyluxcore mitsuba numpy
    /tmp/mi/bin/python bench/peers_luxcore.py [BUILD_DIR] [SECONDS] [SIZE] [REF_PASSES]

The scene reaches LuxCore as it reaches Mitsuba, as the same triangles written to PLY files
(tests/references/gltf_subset.py). Surfaces are matte of the glTF base colours, which LuxCore
reflects on both sides as clppm does. The emitter is one-sided, of radiance emissiveFactor times
emissiveStrength (emission gain 1, power and efficacy 0: the radiance as given). Then the glTF
camera, a box pixel filter of one pixel, 17 path vertices (clppm's 16 bounces), and every other
setting at LuxCore's default. The references are clppm's path tracer with independent numbers and
another seed (REF_PASSES passes; PEERS_REF=FILE reuses one), and LuxCore's own of REF_FACTOR (20)
times the time of its PATHCPU run (LUX_REF=FILE reuses one), so that what differs between the
renderers' models does not count as noise; the two references against each other say whether the
renderers agree. Wall time is the renderers' (clppm's passes, --stats-json render_seconds;
LuxCore's session from start to stop); CPU time is the process's, loading and compilation included.
MSE x CPU s compares renderers at equal error (lower is better)."""
import base64
import json
import math
import os
import sys
import tempfile
import time

# pyluxcore looks for OpenCL devices when a session starts, and PoCL's libraries abort in its
# process (their LLVM against its own): LuxCore sees no OpenCL platform (its CPU engines need none),
# while clppm, a child process, gets the environment as it was.
CLPPM_ENV = dict(os.environ)
os.environ["OCL_ICD_VENDORS"] = tempfile.mkdtemp(prefix="no-icd-")
import pyluxcore  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.join(ROOT, "tests", "references"))
import gltf_subset  # noqa: E402
from peer_runs import arguments, clppm_timed, compare, diffuse_box, print_report  # noqa: E402


def quiet(message):
    """LuxCore's log handler: its messages are not the benchmark's."""


def luxcore_scene(gltf, tmp, size):
    """LuxCore scene properties for a glTF file of translated meshes, diffuse or emissive
    surfaces and a perspective camera (as the Cornell box scenes are), for a square image of
    `size` pixels. LuxCore 2.11 puts its image one pixel row lower than clppm and Mitsuba do (the
    diffuse box's light on rows 16 to 20 of 128, theirs on 15 to 19; relative MSE 18.5 between
    them, 0.0014 after the shift): its screen window moves up by one pixel (2 / size of its
    height of 2)."""
    doc = json.load(open(gltf))
    uri = doc["buffers"][0]["uri"]
    blob = base64.b64decode(uri[uri.index(",") + 1:])
    props = []
    for n, node in enumerate(doc["nodes"][i] for i in doc["scenes"][doc.get("scene", 0)]["nodes"]):
        t = node.get("translation", [0, 0, 0])
        if "camera" in node:
            q = node.get("rotation", [0, 0, 0, 1])
            fwd, up = gltf_subset.quat_rotate(q, (0, 0, -1)), gltf_subset.quat_rotate(q, (0, 1, 0))
            yfov = doc["cameras"][node["camera"]]["perspective"]["yfov"]
            props += ['scene.camera.type = "perspective"',
                      "scene.camera.lookat.orig = %r %r %r" % tuple(t),
                      "scene.camera.lookat.target = %r %r %r" % tuple(t[i] + fwd[i] for i in range(3)),
                      "scene.camera.up = %r %r %r" % tuple(up),
                      "scene.camera.fieldofview = %r" % math.degrees(yfov),
                      "scene.camera.screenwindow = -1 1 %r %r" % (-1 - 2 / size, 1 - 2 / size)]
            continue
        if "mesh" not in node:
            continue
        assert "rotation" not in node and "scale" not in node, "mesh nodes are translated only"
        for k, prim in enumerate(doc["meshes"][node["mesh"]]["primitives"]):
            pos = gltf_subset.read_accessor(doc, blob, prim["attributes"]["POSITION"])
            idx = gltf_subset.read_accessor(doc, blob, prim["indices"])
            tris = [tuple(tuple(pos[idx[i + j]][c] + t[c] for c in range(3)) for j in range(3))
                    for i in range(0, len(idx), 3)]
            name = "n%d_%d" % (n, k)
            path = os.path.join(tmp, name + ".ply")
            gltf_subset.write_ply(path, tris)
            m = doc["materials"][prim["material"]]
            ext = m.get("extensions", {})
            pbr = m["pbrMetallicRoughness"]
            diffuse = "KHR_materials_transmission" not in ext and pbr.get("metallicFactor", 1) == 0
            assert diffuse, "diffuse surfaces only"
            kd = pbr.get("baseColorFactor", [1, 1, 1, 1])[:3]
            props += ['scene.materials.%s.type = "matte"' % name, "scene.materials.%s.kd = %r %r %r" % (name, *kd)]
            if "emissiveFactor" in m:
                s = ext.get("KHR_materials_emissive_strength", {}).get("emissiveStrength", 1.0)
                props += ["scene.materials.%s.emission = %r %r %r" % (name, *[e * s for e in m["emissiveFactor"]]),
                          "scene.materials.%s.emission.gain = 1 1 1" % name,
                          "scene.materials.%s.emission.power = 0" % name,
                          "scene.materials.%s.emission.efficency = 0" % name]
            props += ['scene.objects.%s.ply = "%s"' % (name, path), 'scene.objects.%s.material = "%s"' % (name, name)]
    return pyluxcore.Properties().SetFromString("\n".join(props))


def luxcore_render(scene_props, engine, size, seconds, out, seed=1):
    """Renders for `seconds` of wall time with `engine`; writes the linear radiance to `out`:
    (samples per pixel, wall s, CPU s)."""
    cfg = pyluxcore.Properties().SetFromString("\n".join([
        'renderengine.type = "%s"' % engine,
        "renderengine.seed = %d" % seed,
        "native.threads.count = %d" % os.cpu_count(),
        "film.width = %d" % size, "film.height = %d" % size,
        'film.filter.type = "BOX"', "film.filter.width = 0.5",
        'film.outputs.0.type = "RGB"', 'film.outputs.0.filename = "%s"' % out,
        "path.pathdepth.total = 17", "path.pathdepth.diffuse = 17", "path.pathdepth.glossy = 17",
        "path.pathdepth.specular = 17",
        "light.maxdepth = 17", "path.maxdepth = 17",
        "batch.halttime = %g" % seconds,
    ]))
    scene = pyluxcore.Scene()
    scene.Parse(scene_props)
    session = pyluxcore.RenderSession(pyluxcore.RenderConfig(cfg, scene))
    c0, t0 = time.process_time(), time.time()
    session.Start()
    while not session.HasDone():
        time.sleep(0.05)
        session.UpdateStats()
    session.Stop()
    wall, cpu = time.time() - t0, time.process_time() - c0
    stats = session.GetStats()
    spp = stats.Get("stats.renderengine.pass").GetInt()
    session.GetFilm().SaveOutputs()
    return spp, wall, cpu


def main():
    binary, seconds, size, ref_passes, ref_factor = arguments()
    engines = os.environ.get("LUX_ENGINES", "PATHCPU,BIDIRCPU").split(",")
    pyluxcore.Init(quiet)
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        scene_file, common, ref = diffuse_box(binary, tmp, size, ref_passes, CLPPM_ENV)
        img = os.path.join(tmp, "clppm.exr")
        wall, cpu, passes = clppm_timed(common + ["--time", str(seconds), "-o", img],
                                        os.path.join(tmp, "stats.json"), CLPPM_ENV)
        rows.append(("clppm pt (sobol)", passes, wall, cpu, compare(binary, img, ref, CLPPM_ENV)))
        props = luxcore_scene(scene_file, tmp, size)
        lux_ref = os.environ.get("LUX_REF", "")
        if not os.path.isfile(lux_ref):
            lux_ref = os.path.join(tmp, "lux_ref.exr")
            luxcore_render(props, "PATHCPU", size, seconds * ref_factor, lux_ref, seed=99)
        for engine in engines:
            out = os.path.join(tmp, "lux_%s.exr" % engine)
            spp, wall, cpu = luxcore_render(props, engine, size, seconds, out)
            rows.append(("LuxCore %s %s" % (pyluxcore.Version(), engine), spp, wall, cpu,
                         compare(binary, out, lux_ref, CLPPM_ENV)))
        cross = compare(binary, lux_ref, ref, CLPPM_ENV)

    title = ("Diffuse Cornell box, %dx%d, about %g s each; references: clppm pt, %d independent passes, and LuxCore "
             "PATHCPU, %d times the time; %d cores" % (size, size, seconds, ref_passes, ref_factor, os.cpu_count()))
    print_report(title, cross, rows)


if __name__ == "__main__":
    main()
