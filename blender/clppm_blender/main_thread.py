"""Running a function on Blender's main thread from the render thread.

F12 in Blender's window renders in a thread of its own (a render job), where operators fail: the
glTF exporter, an operator, raises "'Context' object has no attribute 'active_object'" there
(seen in Blender 3.4 under Xvfb, the interface locked or not). A timer runs on the main thread
while the job renders, so the render thread hands the call to one and waits for it. Headless
(`blender -b`, the bpy module) the engine renders on the main thread, and the call is made
directly.
"""
import threading


class Cancelled(RuntimeError):
    pass


def _blender_scheduler(call):
    import bpy

    def on_timer():
        windows = bpy.context.window_manager.windows
        if len(windows):
            with bpy.context.temp_override(window=windows[0]):  # the context an operator needs
                call()
        else:
            call()
        return None  # once

    bpy.app.timers.register(on_timer, first_interval=0.0)


def call(fn, cancelled=lambda: False, schedule=None):
    """fn() on the main thread; its value, or its exception raised here. From another thread the
    call waits for the main thread, raising Cancelled if cancelled() says so first (the timer
    then still runs, and its result is dropped)."""
    if threading.current_thread() is threading.main_thread():
        return fn()
    done = threading.Event()
    box = {}

    def run():
        try:
            box["value"] = fn()
        except BaseException as e:  # raised in the render thread
            box["error"] = e
        done.set()

    (schedule or _blender_scheduler)(run)
    while not done.wait(0.05):
        if cancelled():
            raise Cancelled("cancelled while waiting for Blender's main thread")
    if "error" in box:
        raise box["error"]
    return box["value"]
