"""clppm.render and clppm.Renderer: the command line's image bit for bit, the same defaults, and
the Renderer's calls (passes, image, error estimate, stats, save, iteration)."""
import os
import threading
import time

import numpy as np
import pytest

import clppm
from conftest import SMALL

DATA = os.path.join(os.path.dirname(__file__), "..", "data")


@pytest.mark.parametrize("integrator", ["ppm", "sppm", "pppm", "pt", "vcm", "bpt"])
def test_render_is_the_command_lines_image_bit_for_bit(integrator, cli_image):
    options = dict(SMALL, integrator=integrator, passes=3)
    image = clppm.render(**options)
    assert image.dtype == np.float32 and image.shape == (30, 40, 3)
    assert np.isfinite(image).all() and (image >= 0).all() and image.mean() > 0.01
    assert np.array_equal(image, cli_image(**options))


def test_a_scene_file_and_environment_options(cli_image):
    scene = os.path.join(DATA, "lights.gltf")
    options = dict(SMALL, passes=2, env_color=(0.2, 0.3, 0.4), env_strength=0.5, alpha=0.55)
    image = clppm.render(scene, **dict(options, env_color=(0.2, 0.3, 0.4)))
    assert np.array_equal(image, cli_image(scene, **dict(options, env_color="0.2,0.3,0.4")))


def test_the_medium_by_keyword(cli_image):
    """The world's medium set, scaled and removed by keyword as on the command line; the
    integrators that cannot render it refuse it with the command line's message."""
    scene = os.path.join(DATA, "lights.gltf")
    options = dict(SMALL, passes=2, medium_density=(0.2, 0.3, 0.4), medium_albedo=0.8, medium_anisotropy=0.5)
    image = clppm.render(scene, **options)
    assert np.isfinite(image).all() and (image >= 0).all() and image.mean() > 0
    assert np.array_equal(image, cli_image(scene, **dict(options, medium_density="0.2,0.3,0.4")))
    clear = clppm.render(scene, **dict(SMALL, passes=2, integrator="pt"))
    assert not np.array_equal(image, clear)
    fog_room = os.path.join(DATA, "fog_room.gltf")
    assert np.array_equal(clppm.render(fog_room, **dict(SMALL, passes=2, integrator="pt", medium_scale=0)),
                          clppm.render(fog_room, **dict(SMALL, passes=2, integrator="pt", no_medium=True)))
    assert clppm.render(fog_room, **dict(SMALL, passes=1, integrator="sppm")).mean() > 0
    with pytest.raises(clppm.Error, match="--integrator vcm: the scene has a participating medium"):
        clppm.render(fog_room, **dict(SMALL, passes=1, integrator="vcm"))


def test_visual_importance_by_keyword(cli_image):
    """The command line's flag as a keyword: the same Markov chains, the same image."""
    scene = os.path.join(DATA, "..", "..", "scenes", "skylight.gltf")
    options = dict(SMALL, integrator="sppm", visual_importance=True, passes=2)
    image = clppm.render(scene, **options)
    assert np.isfinite(image).all() and image.mean() > 0.01
    assert np.array_equal(image, cli_image(scene, **options))


def test_the_defaults_are_the_command_lines():
    with clppm.Renderer(**SMALL) as r:
        s = r.settings
        assert s["integrator"] == "vcm"  # auto: the built-in scene's glass casts caustics of its lights
        assert s["pass_limit"] == 16 and s["photons"] == 5000 and s["alpha"] == 0.7
        assert s["output"] == ""  # nothing is written unless asked
    with clppm.Renderer(**dict(SMALL, integrator="pt")) as r:
        assert r.settings["pass_limit"] == 512
    with clppm.Renderer(**dict(SMALL, integrator="sppm")) as r:
        assert r.settings["pass_limit"] == 64
    with clppm.Renderer(**dict(SMALL, time=5)) as r:
        assert r.settings["pass_limit"] == 0  # unlimited: the time bounds it


def test_renderer_steps_and_reports(tmp_path):
    with clppm.Renderer(**dict(SMALL, integrator="sppm", passes=3)) as r:
        assert r.passes == 0
        assert r.run_pass() == 1
        first = r.image()
        assert [p for p in r] == [2, 3]  # the stop policy: --passes 3
        assert r.passes == 3
        assert not np.array_equal(first, r.image())
        assert r.error_estimate() is None  # not asked for
        stats = r.stats()
        assert stats["passes"] == 3 and stats["integrator"] == "sppm" and stats["photons_emitted"] == 15000
        assert stats["width"] == 40 and stats["interrupted"] is False
        r.save(tmp_path / "r.exr")
        assert os.path.exists(tmp_path / "r.exr") and os.path.exists(tmp_path / "r.png")
        assert np.array_equal(clppm.read_exr(tmp_path / "r.exr"), r.image())
        with pytest.raises(clppm.Error, match="save x.png: must be a file name ending in .exr"):
            r.save("x.png")
    with pytest.raises(clppm.Error, match="closed"):
        r.image()


def test_batches_step_a_launch_at_a_time_to_the_same_image(tmp_path):
    # The path tracer's 40 x 30 passes are short: a launch takes several of them, never past the
    # pass limit or a pass that progressive_output counts, and the image is that of one pass a step.
    options = dict(SMALL, integrator="pt", passes=200)
    with clppm.Renderer(**options) as r:
        assert list(r)[-1] == 200
        single = r.image()
    with clppm.Renderer(**options) as r:
        counts = list(r.batches())
        assert counts[-1] == 200 and r.passes == 200
        assert counts == sorted(set(counts)) and len(counts) < 100
        assert r.stats()["pass_launches"] == len(counts)
        assert np.array_equal(r.image(), single)
    with clppm.Renderer(**dict(options, passes=60, progressive_output=25, output=tmp_path / "p.exr")) as r:
        counts = list(r.batches())
        assert 25 in counts and 50 in counts and counts[-1] == 60
    with clppm.Renderer(**dict(SMALL, integrator="sppm", passes=3)) as r:  # one pass a launch
        assert list(r.batches()) == [1, 2, 3]


def test_iteration_stops_at_the_target_error():
    with clppm.Renderer(**dict(SMALL, integrator="pt", target_error=0.5, passes=400)) as r:
        passes = list(r)
        e = r.error_estimate()
        assert e["reached"] and e["estimated"] <= 0.5 and e["target"] == 0.5
        assert e["relative"].shape == (30, 40)
        assert passes[-1] == r.passes < 400


def test_output_options_write_the_files_as_the_command_line(tmp_path):
    out, stats = tmp_path / "o.exr", tmp_path / "s.json"
    image = clppm.render(**dict(SMALL, passes=2, output=out, stats_json=stats))
    assert np.array_equal(clppm.read_exr(out), image)
    assert os.path.exists(tmp_path / "o.png") and os.path.getsize(stats) > 100


def test_the_gil_is_released_while_passes_run():
    ticks = []
    stop = threading.Event()

    def tick():
        while not stop.is_set():
            ticks.append(time.perf_counter())
            time.sleep(0.005)

    with clppm.Renderer(**dict(SMALL, integrator="sppm", photons=200000, passes=4)) as r:
        r.run_pass()  # the first pass builds what it needs
        t = threading.Thread(target=tick)
        t.start()
        start = time.perf_counter()
        r.run_pass()
        r.run_pass()
        elapsed = time.perf_counter() - start
        stop.set()
        t.join()
    during = [x for x in ticks if start <= x <= start + elapsed]
    # A thread that held the GIL for the passes would let the other tick only between them.
    assert len(during) >= 0.3 * elapsed / 0.005, (len(during), elapsed)


def test_devices_are_listed():
    devices = clppm.devices()
    assert devices and {"index", "name", "platform", "implementation", "type", "fp64"} <= set(devices[0])
    assert devices[0]["index"] == 0


def test_the_studio_world_by_keyword():
    """env="studio" is the command line's --env studio: the same image."""
    from conftest import SMALL
    image = clppm.render(env="studio", integrator="pt", **dict(SMALL, passes=2))
    assert image.shape[2] == 3 and image.mean() > 0
