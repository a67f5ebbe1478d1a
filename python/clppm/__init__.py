"""clppm: progressive photon mapping on OpenCL, from Python.

The same render loop as the ``clppm`` command, with the same options under their command-line
names with underscores (``--target-error`` is ``target_error``), the same defaults and checks, and
the same image bit for bit for the same scene, options, seed and device::

    import clppm
    image = clppm.render("scene.gltf", passes=32, width=256, height=256)   # float32 (H, W, 3)

    with clppm.Renderer("scene.gltf", integrator="sppm", target_error=0.05) as r:
        for p in r:                        # one pass a step, until passes, time or target error stop it
            print(p, r.error_estimate()["estimated"])
        r.save("scene.exr")                # EXR and PNG, as the command line writes them

Images are linear radiance (RGB), top row first. Every bad input raises :class:`Error` with the
command line's one-line message. Ctrl-C stops a render within a photon batch and raises
:class:`Interrupted` (a ``KeyboardInterrupt``) holding the last complete pass; a Renderer stays
usable afterwards. Passes run with the GIL released. Under ``mpirun -np N python script.py`` every
process renders its share of each pass, as the command line's processes do: every process must
make the same calls, and only rank 0 writes files.
"""

import difflib
import numbers
import os

from . import _clppm
from ._clppm import Error, devices

__all__ = ["render", "Renderer", "Error", "Interrupted", "devices", "read_exr", "options", "integrators", "__version__"]
__version__ = _clppm.__version__
mpi_rank = _clppm.mpi_rank
mpi_size = _clppm.mpi_size


class Interrupted(KeyboardInterrupt):
    """Ctrl-C (SIGINT) stopped a render; ``image`` is its last complete pass (``passes`` of them)."""

    def __init__(self, image, passes):
        super().__init__(f"clppm: interrupted after pass {passes}")
        self.image = image
        self.passes = passes


def read_exr(path):
    """The R, G, B of an OpenEXR file as float32 (height, width, 3), as clppm writes them."""
    return _clppm.read_exr(os.fspath(path))


def _python_name(option):
    return option[2:].replace("-", "_")


_OPTIONS = {_python_name(o["name"]): o for o in _clppm.option_table()}


def options():
    """The render options: {python name: {name, flag, range, default, help, group, role}}; role is "image"
    (shapes the image), "run" (when the render stops, what it estimates) or "local" (outputs, devices)."""
    return {k: dict(v) for k, v in _OPTIONS.items()}


def integrators():
    """The integrators --integrator takes: [{name, alias, summary}], "auto" first (the rule it follows)."""
    return _clppm.integrators()


def _scalar(value):
    if isinstance(value, os.PathLike):
        return os.fspath(value)
    if isinstance(value, str):
        return value
    if isinstance(value, numbers.Integral):
        return str(int(value))
    if isinstance(value, numbers.Real):
        return float.__repr__(float(value))  # shortest text that reads back to the same double
    return str(value)


def _arguments(kwargs):
    """Keyword arguments as the command line's ("--name", "value") pairs, in the order given."""
    args = []
    for key, value in kwargs.items():
        spec = _OPTIONS.get(key)
        if spec is None:
            near = difflib.get_close_matches(key, _OPTIONS, n=1)
            hint = f" (did you mean {near[0]}?)" if near else ""
            raise Error(f"unknown option {key}{hint}")
        name = spec["name"]
        if value is None:
            continue
        if spec["flag"]:
            if value is True:
                args.append((name, ""))
            elif value is not False:
                raise Error(f"{name} {value!r}: must be True or False")
            continue
        if isinstance(value, bool):
            raise Error(f"{name} {value}: must be {spec['range']}")
        if isinstance(value, (list, tuple)):
            if key == "device":  # repeatable: every device, in order
                args.extend((name, _scalar(v)) for v in value)
            else:  # env_color=(r, g, b)
                args.append((name, ",".join(_scalar(v) for v in value)))
            continue
        args.append((name, _scalar(value)))
    return args


def _scene_path(scene):
    return None if scene is None else os.fspath(scene)


class Renderer:
    """A render set up and stepped from Python.

    ``Renderer(scene=None, **options)`` loads the scene (None: the built-in Cornell box), picks
    the devices and the integrator, checks the memory and builds the kernels, all as the command
    line does. Then:

    - ``run_pass()`` renders one pass (whatever the stop options say); ``passes`` counts them;
    - iterating renders passes until ``passes``, ``time`` or ``target_error`` stops them, yielding
      the pass count, then writes what the options ask for (``output``, ``stats_json``, ...);
    - ``batches()`` iterates the same way a launch at a time: the path tracer runs short passes
      several to a launch (about 20 ms of work), so the count may rise by more than one a step;
      the image is the same;
    - ``render()`` does all of that and returns the image;
    - ``image()`` is the image after the last pass, ``error_estimate()`` its estimated error (with
      ``target_error`` or ``error_output``), ``stats()`` the ``--stats-json`` content, ``save(path)``
      writes the EXR and PNG.
    """

    def __init__(self, scene=None, **options):
        self._native = _clppm.Renderer(_scene_path(scene), _arguments(options))

    def _checked(self, ran):
        if not ran and self._native.interrupted():
            self._native.clear_interrupt()
            raise Interrupted(self._native.image(), self._native.passes)
        return ran

    def run_pass(self):
        """Renders one pass; raises Interrupted on Ctrl-C (the last complete pass is kept)."""
        self._native.begin()
        self._checked(self._native.run_pass())
        return self._native.passes

    def __iter__(self):
        self._native.begin()
        return self

    def __next__(self):
        if self._checked(self._native.step()):
            return self._native.passes
        self._native.finish()
        raise StopIteration

    def batches(self):
        """Iterates as the Renderer itself does, a launch at a time: each step renders as many
        passes as the integrator runs in one launch (the path tracer's short passes, several to a
        launch), never past ``passes`` or a pass ``progressive_output`` or ``checkpoint_every``
        counts, and yields the pass count. Fewer launches cost less time on short passes; the
        image is the same bit for bit."""
        self._native.begin()
        while self._checked(self._native.step_batch()):
            yield self._native.passes
        self._native.finish()

    def render(self):
        """Renders until the stop options say, writes the outputs, and returns the image."""
        self._native.begin()
        if not self._native.render() and self._native.interrupted():
            self._native.clear_interrupt()
            raise Interrupted(self._native.image(), self._native.passes)
        return self._native.image()

    def cancel(self):
        """From another thread (a GUI's Cancel): the pass in flight stops at its next photon batch
        and the call running it raises Interrupted, as on Ctrl-C; between two steps of an iteration
        (or ``render()``), the next step does. This Renderer's alone: others in the process render
        on. A cancel while the Renderer is not rendering is meant for nothing and is dropped when
        the next ``run_pass()``, iteration or ``render()`` begins."""
        self._native.cancel()

    def image(self):
        """The image after the last pass: float32 (height, width, 3), linear RGB, top row first."""
        return self._native.image()

    def error_estimate(self):
        """With target_error or error_output: {estimated, bound, target, reached, passes, relative}
        (the 90th percentile of the per-pixel relative error and its per-pixel image), else None."""
        return self._native.error_estimate()

    def stats(self):
        """The statistics --stats-json writes, as a dict."""
        return self._native.stats()

    def save(self, path):
        """Writes the image to path (.exr) and, unless no_png, a PNG beside it, as the command line."""
        self._native.save(os.fspath(path))

    @property
    def passes(self):
        """Passes rendered so far (a resumed render counts the checkpoint's)."""
        return self._native.passes

    @property
    def warnings(self):
        """The warnings the render gave (also printed to stderr)."""
        return self._native.warnings

    @property
    def settings(self):
        """What is rendered: every option that shapes the image or says when the render stops, by keyword
        (the integrator the scene got for "auto"), and scene, output, pass_limit and time_limit."""
        return {_python_name(k) if k.startswith("--") else k: v for k, v in self._native.settings.items()}

    def close(self):
        """Ends the render (writing what the options ask for, if not yet) and frees the device."""
        self._native.close()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()
        return False


def render(scene=None, **options):
    """Renders ``scene`` (a .gltf or .glb path; None: the built-in Cornell box) and returns the
    image as float32 (height, width, 3), linear RGB. Options are the command line's, with
    underscores; ``output`` also writes the files. Raises Error for bad input and Interrupted on
    Ctrl-C."""
    with Renderer(scene, **options) as r:
        return r.render()


def _options_doc():
    lines = ["", "Options (the command line's, with underscores; clppm --help says more):", ""]
    for key, spec in _OPTIONS.items():
        kind = "True" if spec["flag"] else spec["metavar"]
        default = f" Default: {spec['default']}." if spec["default"] else ""
        lines.append(f"    {key}={kind}: {spec['help']}.{default}")
    return "\n".join(lines)


render.__doc__ += _options_doc()
Renderer.__doc__ += _options_doc()
