"""The CLPPM render engine: F12 renders the scene through clppm, showing the image as it
converges; Esc stops it within a photon batch and keeps the last complete pass."""
import os
import tempfile

import bpy
import numpy as np

from . import export, main_thread, runner

ADDON = __package__


def preference_path(context):
    addon = context.preferences.addons.get(ADDON)
    return addon.preferences.clppm_path if addon else ""


def load_exr(path):
    """An EXR as float32 (height, width, 3), top row first, through Blender's image loader."""
    image = bpy.data.images.load(path, check_existing=False)
    try:
        w, h = image.size
        pixels = np.empty(w * h * 4, dtype=np.float32)
        image.pixels.foreach_get(pixels)
        return pixels.reshape(h, w, 4)[::-1, :, :3].copy()
    finally:
        bpy.data.images.remove(image)


def one_line(error):
    """An error as one line for Blender's report: an operator's error carries a traceback, whose
    last line says what went wrong."""
    lines = [l.strip() for l in str(error).splitlines() if l.strip() and not l.strip().startswith("Location:")]
    return lines[-1] if lines else type(error).__name__


def write_result(result, image):
    """clppm's image (top row first, RGB) into a render result (bottom row first, RGBA)."""
    h, w = image.shape[:2]
    rgba = np.ones((h, w, 4), dtype=np.float32)
    rgba[:, :, :3] = image[::-1]
    result.layers[0].passes["Combined"].rect = rgba.reshape(h * w, 4)


class ClppmRenderEngine(bpy.types.RenderEngine):
    bl_idname = "CLPPM"
    bl_label = "clppm"
    bl_use_preview = False
    bl_use_eevee_viewport = True

    def cancelled(self):
        """Esc in the image editor (Blender's test_break), asked a few times a second."""
        return self.test_break()

    def render(self, depsgraph):
        scene = depsgraph.scene
        said = set()

        def warn(message):
            if message not in said:
                said.add(message)
                self.report({"WARNING"}, "clppm: " + message)

        try:
            kind, found = runner.locate(preference_path(bpy.context))
        except runner.NotFound as e:
            self.report({"ERROR"}, str(e))
            return
        with tempfile.TemporaryDirectory(prefix="clppm-blender-") as directory:
            try:
                scene_file, options = export.export(depsgraph, directory, warn, self.cancelled)
                options.update(scene.clppm.options())
                if kind == "module":
                    render = runner.ModuleRender(found, scene_file, options)
                    for w in render.renderer.warnings:
                        warn(w)
                else:
                    render = runner.CommandRender(found, scene_file, options, directory, load_exr)
            except main_thread.Cancelled:
                return
            except Exception as e:  # clppm.Error and the exporter's: one line, in Blender's report
                self.report({"ERROR"}, "clppm: " + one_line(e))
                return
            width, height = options["width"], options["height"]
            result = self.begin_result(0, 0, width, height)

            def show():
                image, status = render.latest()
                if image is not None and image.shape[:2] == (height, width):
                    write_result(result, image)
                    self.update_result(result)
                self.update_stats("", runner.status_text(status))
                if status.get("pass") is not None and status.get("pass_limit"):
                    self.update_progress(min(1.0, status["pass"] / status["pass_limit"]))

            failure = None
            try:
                runner.wait(render, self.cancelled, show, scene.clppm.update_every)
            except Exception as e:  # the add-on's own failure: clppm is stopped, its image kept
                failure = e
                render.cancel()
            finally:
                # The result is always ended (Blender crashes on one left open).
                render.close()
                try:
                    image, _ = render.latest()
                    if image is not None and image.shape[:2] == (height, width):
                        write_result(result, image)
                except Exception as e:
                    failure = failure or e
                self.end_result(result)
            for e in (render.error, failure):
                if e is not None:
                    self.report({"ERROR"}, "clppm: " + one_line(e))
