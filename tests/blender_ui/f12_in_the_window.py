"""F12 and Esc in Blender's own window (run by scripts/check_blender_ui.sh under Xvfb): there the
render job runs the engine in a thread of its own, where operators fail, unlike the headless
bpy of tests/blender. Writes what happened, a JSON object per line, to the file named after "--",
and quits Blender.

Usage: blender --factory-startup --python-exit-code 1 --python f12_in_the_window.py -- LOG ADDON_DIR [MODULE_DIR]
"""
import json
import os
import sys
import threading
import time

import bpy

log_path, addon_dir = sys.argv[sys.argv.index("--") + 1:][:2]
sys.path[:0] = [addon_dir] + sys.argv[sys.argv.index("--") + 3:]
log = open(log_path, "w", buffering=1)


def say(**event):
    log.write(json.dumps(event) + "\n")


import clppm_blender  # noqa: E402
from clppm_blender import engine, export  # noqa: E402

# Watching the engine from outside: its functions are wrapped before the add-on registers.
_export, _one_line, _wait = export.export, engine.one_line, engine.runner.wait


def watched_export(*args, **kwargs):
    say(event="export", render_thread_is_main=threading.current_thread() is threading.main_thread())
    return _export(*args, **kwargs)


shown = []  # the images shown so far: Esc waits for three


def watched_wait(render, cancelled, show, every):
    def watched_show():
        image, status = render.latest()
        say(event="show", mean=None if image is None else float(image.mean()), status=status)
        if image is not None:
            shown.append(status.get("pass"))
        show()

    _wait(render, cancelled, watched_show, every)
    say(event="ended", error=None if render.error is None else str(render.error), interrupted=render.interrupted,
        at=time.monotonic())


engine.export.export = watched_export
engine.one_line = lambda e: (say(event="error", message=str(e)), _one_line(e))[1]
engine.runner.wait = watched_wait
clppm_blender.register()

scene = bpy.context.scene  # the factory scene: a cube, a 1000 W point light, a camera
scene.render.engine = "CLPPM"
scene.render.resolution_x, scene.render.resolution_y, scene.render.resolution_percentage = 64, 48, 100
scene.clppm.integrator, scene.clppm.time, scene.clppm.update_every = "sppm", 60.0, 0.5
bpy.ops.object.light_add(type="AREA", location=(0.0, 0.0, 4.0))
bpy.context.object.data.energy = 200.0


def f12():
    with bpy.context.temp_override(window=bpy.context.window_manager.windows[0]):
        say(event="f12", result=sorted(bpy.ops.render.render("INVOKE_DEFAULT")))


def esc():
    """Esc in the render window (the image editor's render.view_cancel, as the key does), once
    three images have been shown (on a loaded machine the kernels take longer to build), or after
    two minutes whatever happened (the check then says what is missing)."""
    if len(shown) < 3 and time.monotonic() - started < 120:
        return 0.1
    wm = bpy.context.window_manager
    say(event="job_running_before_esc", running=bpy.app.is_job_running("RENDER"))
    editors = [(w, a) for w in wm.windows for a in w.screen.areas if a.type == "IMAGE_EDITOR"]
    if not editors:
        say(event="no_image_editor")
        return quit_blender()
    window, area = editors[-1]
    region = [r for r in area.regions if r.type == "WINDOW"][0]
    pressed = time.monotonic()
    with bpy.context.temp_override(window=window, area=area, region=region):
        bpy.ops.render.view_cancel()
    say(event="esc", at=pressed)

    def until_ended():
        if bpy.app.is_job_running("RENDER") and time.monotonic() - pressed < 20:
            return 0.05
        say(event="job_ended", running=bpy.app.is_job_running("RENDER"), seconds=time.monotonic() - pressed)
        quit_blender()

    bpy.app.timers.register(until_ended, first_interval=0.05)


def quit_blender():
    log.close()
    bpy.ops.wm.quit_blender()


started = time.monotonic()
bpy.app.timers.register(f12, first_interval=2.0)
bpy.app.timers.register(esc, first_interval=3.0)
bpy.app.timers.register(quit_blender, first_interval=200.0)  # whatever happens
