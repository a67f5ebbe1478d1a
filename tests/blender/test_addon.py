"""The CLPPM render engine against Cycles (the Blender it runs in), headless: scenes built by script
render within 5% in mean and a box-4 relative MSE of 0.02 of Cycles at 96x96; the engine can be
cancelled; a missing clppm is reported in one line; the command-line route gives the module's
image."""
import math
import os
import subprocess
import sys
import textwrap
import time

import bpy
import numpy as np
import pytest

import scenes
from clppm_blender import engine, export, properties, runner


def compare(name, tmp_path, clppm_seconds=10.0, samples=2048):
    cycles = scenes.render("CYCLES", str(tmp_path / (name + "_cycles.exr")), samples=samples)
    clppm = scenes.render("CLPPM", str(tmp_path / (name + "_clppm.exr")), time=clppm_seconds)
    ratio = float(clppm.mean() / cycles.mean())
    box = scenes.box_rel_mse(clppm, cycles)
    print("%s: mean ratio %.4f, box-4 relative MSE %.5f" % (name, ratio, box))
    return clppm, cycles, ratio, box


def test_diffuse_objects_an_area_light_and_a_grey_world_match_cycles(tmp_path):
    scenes.diffuse_room()
    _, _, ratio, box = compare("diffuse_room", tmp_path)
    assert abs(ratio - 1) < 0.05
    assert box < 0.02


def test_point_spot_and_sun_lights_match_cycles(tmp_path):
    scenes.punctual_lights()
    _, _, ratio, box = compare("punctual_lights", tmp_path, clppm_seconds=6.0, samples=1024)
    assert abs(ratio - 1) < 0.03
    assert box < 0.01


def test_a_world_volume_matches_cycles(tmp_path):
    """The world's Volume Scatter and Volume Absorption as clppm's world medium (world.py), lit by a
    point and an area light: the mean within 3% of Cycles' (issue 57's Blender target)."""
    scenes.fog_room()
    warnings = []
    options = export.medium_options(bpy.context.scene.world, warnings.append)
    assert warnings == []
    assert options["medium_density"] == pytest.approx((0.123, 0.111, 0.099))
    assert options["medium_albedo"] == pytest.approx((0.108 / 0.123, 0.096 / 0.111, 0.084 / 0.099))
    assert options["medium_anisotropy"] == pytest.approx(0.3)
    _, _, ratio, box = compare("fog_room", tmp_path, clppm_seconds=8.0, samples=512)
    assert abs(ratio - 1) < 0.03
    assert box < 0.02


def test_a_spots_soft_edge_keeps_its_power():
    # Cycles' smoothstep over w = (1 - c0) blend in cos has the integral w/2; glTF's squared ramp
    # from c0 to c1 has (c1 - c0)/3: equal for c1 = c0 + 3w/4.
    size, blend = math.radians(70), 0.3
    c0 = math.cos(size / 2)
    c1 = math.cos(export.spot_inner_cone(size, blend))
    w = (1 - c0) * blend
    s = np.linspace(0, 1, 200001)
    cycles = np.trapz(s * s * (3 - 2 * s), dx=1 / 200000) * w + (1 - c0 - w)
    gltf = (c1 - c0) / 3 + (1 - c1)
    assert gltf == pytest.approx(cycles, rel=1e-6)
    assert export.spot_inner_cone(size, 0.0) == pytest.approx(size / 2)
    assert export.spot_inner_cone(size, 1.0) < size / 2


def test_a_glass_spheres_caustic_under_an_area_light_matches_cycles(tmp_path):
    scenes.glass_on_floor()
    clppm, cycles, ratio, box = compare("glass_on_floor", tmp_path, clppm_seconds=15.0, samples=4096)
    # Away from the caustic (which Cycles resolves with noise): the floor but for the sphere's
    # shadow, where the caustic is (rows 44-66, columns 28-68 of 96, top row first).
    away = np.zeros(clppm.shape[:2], bool)
    away[30:] = True
    away[44:66, 28:68] = False
    r = clppm[away].mean() / cycles[away].mean()
    assert abs(r - 1) < 0.05, r
    # The shadow with its caustic: the caustic is there in both, to Cycles' noise.
    shadow = (slice(48, 62), slice(32, 64))
    r = clppm[shadow].mean() / cycles[shadow].mean()
    assert abs(r - 1) < 0.15, r
    assert abs(ratio - 1) < 0.05
    assert box < 0.02


@pytest.mark.parametrize("degrees", [0, 60])
def test_the_worlds_environment_texture_and_its_rotation_match_cycles(tmp_path, degrees):
    sky = scenes.sky_map(str(tmp_path / "sky.hdr"))
    scenes.under_the_sky(sky, math.radians(degrees))
    _, _, ratio, box = compare("sky_%d" % degrees, tmp_path)
    assert abs(ratio - 1) < 0.05
    assert box < 0.02


def test_the_export_carries_area_lights_world_depth_of_field_and_resolution(tmp_path):
    scene = scenes.diffuse_room()
    scene.render.resolution_x, scene.render.resolution_y, scene.render.resolution_percentage = 200, 100, 50
    cam = scene.camera.data
    cam.dof.use_dof, cam.dof.aperture_fstop, cam.dof.focus_distance, cam.lens = True, 2.0, 5.0, 50.0
    said = []
    path, options = export.export(bpy.context.evaluated_depsgraph_get(), str(tmp_path), said.append)
    assert options["width"] == 100 and options["height"] == 50
    assert options["aperture"] == pytest.approx(0.05 / 4.0)
    assert options["focus_distance"] == pytest.approx(5.0)
    assert options["env_color"] == pytest.approx((0.2, 0.2, 0.2)) and options["env_strength"] == 1.0
    import json
    gltf = json.load(open(path))
    lamp = [m for m in gltf["materials"] if m["name"].endswith("(area light)")]
    assert len(lamp) == 1
    # 300 W from a 1 x 0.5 m rectangle: L = P / (pi A).
    assert lamp[0]["extensions"]["KHR_materials_emissive_strength"]["emissiveStrength"] == pytest.approx(
        300.0 / (math.pi * 0.5))
    assert said == []


def test_an_area_lights_spread_is_exported(tmp_path):
    scenes.diffuse_room()
    bpy.data.lights[0].spread = math.radians(60)
    said = []
    path, _ = export.export(bpy.context.evaluated_depsgraph_get(), str(tmp_path), said.append)
    import json
    lamp = [m for m in json.load(open(path))["materials"] if m["name"].endswith("(area light)")][0]
    assert lamp["extras"]["clppm_area_light_spread"] == pytest.approx(60.0, rel=1e-5)
    assert said == []


def test_an_area_lights_spread_matches_cycles(tmp_path):
    # Cycles' soft box: radiance times max(tan h - tan a, 0) / (tan h - h), the power kept.
    scenes.diffuse_room()
    bpy.data.lights[0].spread = math.radians(60)
    _, _, ratio, box = compare("spread_60", tmp_path, clppm_seconds=6.0, samples=1024)
    assert abs(ratio - 1) < 0.05
    assert box < 0.02


def test_esc_stops_the_render_promptly_and_keeps_the_image(tmp_path, monkeypatch):
    # Esc pressed three seconds into the render: the engine asks cancelled(), which asks Blender's
    # test_break() (never true headless).
    pressed = []

    def cancelled(self):
        if not pressed and time.monotonic() - started > 3.0:
            pressed.append(time.monotonic())
        return bool(pressed)

    monkeypatch.setattr(engine.ClppmRenderEngine, "cancelled", cancelled)
    scenes.diffuse_room()
    scene = bpy.context.scene
    scene.render.engine = "CLPPM"
    scene.clppm.integrator, scene.clppm.passes, scene.clppm.time = "sppm", 100000, 0.0
    scene.render.image_settings.file_format = "OPEN_EXR"
    scene.render.filepath = str(tmp_path / "cancelled.exr")
    started = time.monotonic()
    bpy.ops.render.render(write_still=True)
    assert pressed, "the render ended before Esc"
    # Stopped (within a photon batch), the image shown and written, in less time than the render
    # had run before Esc: a ratio of two intervals on the same machine, not a wall-clock bound (0.02 s
    # after 2 s on the idle machine; a loaded CI run once took 1.2 s).
    seconds, before = time.monotonic() - pressed[0], pressed[0] - started
    assert seconds < before, (seconds, before)
    image = bpy.data.images.load(str(tmp_path / "cancelled.exr"))
    px = np.empty(image.size[0] * image.size[1] * 4, dtype=np.float32)
    image.pixels.foreach_get(px)
    assert px.reshape(-1, 4)[:, :3].mean() > 0.05  # the last complete pass, not black


def run_blender(script, env):
    """Runs a script in a fresh Python with bpy and the add-on (for what needs another environment)."""
    code = textwrap.dedent("""
        import sys
        sys.path[:0] = [%r, %r]
        import bpy, clppm_blender, scenes
        clppm_blender.register()
    """ % (os.path.dirname(__file__), os.path.join(os.path.dirname(__file__), "..", "..", "blender"))) + script
    return subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=600, env=env)


def test_a_missing_clppm_is_reported_in_one_line(tmp_path):
    env = dict(os.environ, PATH="/usr/bin:/bin", CLPPM="")
    env["PYTHONPATH"] = ":".join(p for p in env.get("PYTHONPATH", "").split(":") if "python" not in p)
    p = run_blender(textwrap.dedent("""
        scenes.diffuse_room()
        bpy.context.scene.render.engine = "CLPPM"
        try:
            bpy.ops.render.render()
        except RuntimeError as e:
            print("RuntimeError:", e)
    """), env)
    out = p.stdout + p.stderr
    assert "clppm not found" in out, out
    assert "no clppm Python module" in out and "no clppm on PATH" in out, out


# The module route steps the path tracer a launch at a time (several short passes to a launch),
# the command route a pass at a time (--progressive-output 1): the same image either way.
@pytest.mark.parametrize("settings", [dict(integrator="sppm", passes=4, photons=20000),
                                      dict(integrator="pt", passes=64)], ids=["sppm", "pt"])
def test_the_command_line_route_gives_the_modules_image(tmp_path, settings):
    binary = os.environ.get("CLPPM_BINARY")
    if not binary:
        pytest.skip("CLPPM_BINARY is not set")
    scenes.diffuse_room()
    module_image = scenes.render("CLPPM", str(tmp_path / "module.exr"), time=0.0, **settings)
    os.environ["CLPPM"] = binary  # the command before the module
    try:
        command_image = scenes.render("CLPPM", str(tmp_path / "command.exr"), time=0.0, **settings)
    finally:
        del os.environ["CLPPM"]
    assert np.array_equal(module_image, command_image)


def test_the_module_route_runs_short_passes_several_to_a_launch():
    import clppm
    scene = os.path.join(os.path.dirname(__file__), "..", "..", "scenes", "cornell_box.gltf")
    render = runner.ModuleRender(clppm, scene, dict(integrator="pt", passes=100, width=40, height=30))
    assert render.done.wait(120)
    assert render.error is None and not render.interrupted
    passes, launches = render.renderer.passes, render.renderer.stats()["pass_launches"]
    render.close()
    assert passes == 100 and launches < 50, (passes, launches)


def test_the_header_line_reads_a_commands_progress(tmp_path):
    binary = os.environ.get("CLPPM_BINARY")
    if not binary:
        pytest.skip("CLPPM_BINARY is not set")
    p = subprocess.run([binary, "--width", "32", "--height", "24", "--passes", "3", "--target-error", "0.9",
                        "-o", str(tmp_path / "p.exr"), "--no-png"], capture_output=True, text=True, timeout=300)
    assert p.returncode == 0, p.stderr
    status = runner.parse_progress(p.stdout + p.stderr)
    assert status["integrator"] == "vcm" and status["pass"] >= 1 and status["photons"].endswith("k"), status
    assert status["error"] is not None and 0 < status["error"] < 10, status
    text = runner.status_text(status)
    assert text.startswith("clppm vcm | pass ") and " photons | error " in text, text
    assert runner.status_text({"pass": None}) == "clppm: preparing"


@pytest.mark.parametrize("kind", ["extension", "legacy"])
def test_the_packages_install_and_register_the_engine(tmp_path, kind):
    root = os.path.join(os.path.dirname(__file__), "..", "..")
    subprocess.run([sys.executable, os.path.join(root, "scripts", "package_blender.py"), str(tmp_path)], check=True)
    version = [l.split('"')[1] for l in open(os.path.join(root, "blender", "clppm_blender", "blender_manifest.toml"))
               if l.startswith("version")][0]
    package = tmp_path / ("clppm_blender-%s%s.zip" % (version, "" if kind == "extension" else "-legacy"))
    script = textwrap.dedent("""
        import bpy, sys
        kind, path = sys.argv[1], sys.argv[2]
        if kind == "extension":
            bpy.ops.extensions.package_install_files(filepath=path, repo="user_default", enable_on_install=True)
            name = "bl_ext.user_default.clppm_blender"
        else:
            bpy.ops.preferences.addon_install(filepath=path)
            bpy.ops.preferences.addon_enable(module="clppm_blender")
            name = "clppm_blender"
        engines = [getattr(e, "bl_idname", "") for e in bpy.types.RenderEngine.__subclasses__()]
        print("enabled", name in bpy.context.preferences.addons, "CLPPM" in engines,
              bpy.context.preferences.addons[name].preferences.clppm_path == "")
        bpy.context.scene.render.engine = "CLPPM"
        print("engine", bpy.context.scene.render.engine, bpy.context.scene.clppm.integrator)
    """)
    # Installed into a user folder of the test's own, never the user's.
    env = dict(os.environ, BLENDER_USER_RESOURCES=str(tmp_path / "blender"))
    p = subprocess.run([sys.executable, "-c", script, kind, str(package)], capture_output=True, text=True,
                       timeout=300, env=env)
    assert "enabled True True True" in p.stdout, p.stdout + p.stderr
    assert "engine CLPPM auto" in p.stdout, p.stdout + p.stderr


def test_the_settings_have_the_librarys_defaults_and_integrators():
    import clppm
    table = clppm.options()
    settings = bpy.context.scene.clppm
    for name in ("alpha", "seed", "integrator"):
        value = settings.bl_rna.properties[name].default  # the panel's default (earlier tests changed the values)
        assert str(value) == table[name]["default"] or value == pytest.approx(float(table[name]["default"])), name
    # Photons: 0, the library's choice (its default, and fewer in participating media).
    assert settings.bl_rna.properties["photons"].default == 0
    names = {i[0] for i in properties.INTEGRATORS}
    assert table["integrator"]["range"] == "auto, ppm, sppm, pppm, pt, vcm or bpt"
    assert names == {"auto", "ppm", "sppm", "pppm", "pt", "vcm", "bpt"}
    # Where the library has no value (0 in the panel), the option is not passed.
    for name in ("passes", "time", "target_error", "device", "visual_importance", "photons"):
        settings.property_unset(name)
    assert set(settings.options()) == {"integrator", "alpha", "seed"}
    settings.photons = 20000
    assert settings.options()["photons"] == 20000
    settings.property_unset("photons")
    # A switch the library takes as a flag: passed only when on.
    assert not settings.bl_rna.properties["visual_importance"].default and table["visual_importance"]["flag"]
    settings.visual_importance = True
    assert settings.options()["visual_importance"] is True
    settings.property_unset("visual_importance")


def test_the_export_is_handed_to_the_main_thread_from_the_render_thread():
    """F12 in Blender's window renders in a thread where operators fail; the exporter runs on the
    main thread (a timer there), the render thread waiting. A queue stands for the timers here."""
    import queue
    import threading
    from clppm_blender import main_thread
    timers = queue.Queue()
    seen = {}

    def render_thread():
        try:
            seen["value"] = main_thread.call(lambda: threading.current_thread() is threading.main_thread(),
                                             schedule=timers.put)
            main_thread.call(lambda: 1 / 0, schedule=timers.put)
        except ZeroDivisionError:
            seen["error"] = True
        try:
            main_thread.call(lambda: None, cancelled=lambda: True, schedule=lambda fn: None)
        except main_thread.Cancelled:
            seen["cancelled"] = True

    t = threading.Thread(target=render_thread)
    t.start()
    for _ in range(2):
        timers.get(timeout=10)()  # the main thread's timers
    t.join(10)
    assert seen == {"value": True, "error": True, "cancelled": True}
    assert main_thread.call(lambda: 7) == 7  # on the main thread: directly


def test_an_operators_error_is_one_line():
    e = RuntimeError("Error: Python: Traceback (most recent call last):\n  File \"x.py\", line 1\n"
                     "AttributeError: 'Context' object has no attribute 'active_object'\n"
                     "Location: /usr/share/blender/scripts/modules/bpy/ops.py:113\n")
    assert engine.one_line(e) == "AttributeError: 'Context' object has no attribute 'active_object'"
