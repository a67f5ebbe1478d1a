"""Where clppm comes from, and a render through it with progress and cancel.

Found, in order: the add-on's preference (a clppm command, or a folder holding the clppm Python
package), the CLPPM environment variable (the same), the clppm Python module importable as it is,
a clppm command on PATH. Through the module, passes run in this process (the GIL released) and
the image is read after any pass; through the command, clppm runs as a child process with
--progressive-output and the image is read from its EXR as it is rewritten.
"""
import importlib
import os
import re
import shutil
import signal
import subprocess
import sys
import threading
import time


class NotFound(RuntimeError):
    pass


def _module_from(folder):
    if folder not in sys.path:
        sys.path.insert(0, folder)
    import clppm  # noqa: F401 (import by name: the folder now comes first)
    return importlib.import_module("clppm")


def locate(preference=""):
    """('module', clppm) or ('command', path); raises NotFound naming what was tried."""
    tried = []
    for origin, value in (("the add-on's preferences", preference), ("CLPPM", os.environ.get("CLPPM", ""))):
        if not value:
            continue
        if os.path.isdir(value):
            try:
                return "module", _module_from(value)
            except ImportError as e:
                tried.append("%s: %s has no clppm package (%s)" % (origin, value, e))
        elif os.path.isfile(value) and os.access(value, os.X_OK):
            return "command", value
        else:
            tried.append("%s: %s is neither a clppm command nor a folder" % (origin, value))
    try:
        return "module", importlib.import_module("clppm")
    except ImportError:
        tried.append("no clppm Python module")
    found = shutil.which("clppm")
    if found:
        return "command", found
    tried.append("no clppm on PATH")
    raise NotFound("clppm not found: " + "; ".join(tried) +
                   " (set its path in the add-on's preferences, or pip install clppm's repository)")


class ModuleRender:
    """A render through the Python module in a worker thread, so that the caller can poll for
    cancel and show the image as it converges. Only the worker touches the renderer (one thread
    at a time may); the caller asks for a copy of the image and takes the last one made."""

    def __init__(self, clppm, scene, options):
        self.clppm = clppm
        self.renderer = clppm.Renderer(scene, quiet=True, **options)
        self.error = None
        self.interrupted = False
        self.done = threading.Event()
        self._want = threading.Event()
        self._cancelled = threading.Event()
        self._latest = None, {}
        self.thread = threading.Thread(target=self._run, daemon=True)
        self.thread.start()

    def _snapshot(self):
        r = self.renderer
        e = r.error_estimate()
        photons = r.stats().get("photons_emitted")
        self._latest = r.image(), {"pass": r.passes, "pass_limit": r.settings["pass_limit"],
                                   "photons": format_count(photons) if photons else None,
                                   "error": e["estimated"] if e else None, "integrator": r.settings["integrator"]}

    def _run(self):
        # A launch at a time (the path tracer's short passes run several to a launch); a module
        # older than batches() steps a pass at a time.
        steps = self.renderer.batches() if hasattr(self.renderer, "batches") else self.renderer
        try:
            for _ in steps:
                if self._cancelled.is_set():  # a cancel between two steps (or before the first)
                    self.interrupted = True
                    break
                if self._want.is_set():
                    self._want.clear()
                    self._snapshot()
        except self.clppm.Interrupted:
            self.interrupted = True
        except Exception as e:  # reported by the engine
            self.error = e
        try:
            self._snapshot()
        except Exception as e:
            self.error = self.error or e
        self.done.set()

    def cancel(self):
        self._cancelled.set()
        self.renderer.cancel()  # the pass in flight stops at its next photon batch

    def request(self):
        """Asks for a copy of the image after the next pass."""
        self._want.set()

    def latest(self):
        """(image, status) as of the last copy made: status has pass, pass_limit, error, integrator."""
        return self._latest

    def close(self):
        self.thread.join()
        self.renderer.close()


class CommandRender:
    """A render through the clppm command, as a child process writing its EXR every few passes."""

    def __init__(self, command, scene, options, directory, load_exr):
        self.output = os.path.join(directory, "render.exr")
        self.load_exr = load_exr
        args = [command, scene, "-o", self.output, "--no-png", "--progressive-output", "1"]
        for key, value in options.items():
            name = "--" + key.replace("_", "-")
            if value is True:  # a flag
                args.append(name)
                continue
            if isinstance(value, (tuple, list)):
                value = ",".join(repr(float(v)) for v in value)
            args += [name, str(value)]
        self.log = open(os.path.join(directory, "clppm.log"), "w+")
        self.process = subprocess.Popen(args, stdout=self.log, stderr=subprocess.STDOUT)
        self.error = None
        self.interrupted = False
        self.done = threading.Event()
        threading.Thread(target=self._wait, daemon=True).start()

    def _wait(self):
        status = self.process.wait()
        if status in (128 + signal.SIGINT, -signal.SIGINT):
            self.interrupted = True
        elif status != 0:
            self.log.seek(0)
            lines = [l for l in self.log.read().splitlines() if "error" in l]
            self.error = RuntimeError(lines[-1] if lines else "clppm exited with status %d" % status)
        self.done.set()

    def cancel(self):
        self.process.send_signal(signal.SIGINT)  # clppm writes its last complete pass

    def request(self):
        pass

    def latest(self):
        image = self.load_exr(self.output) if os.path.exists(self.output) else None
        with open(self.log.name) as log:  # what the child has written (it writes the file itself)
            return image, parse_progress(log.read())

    def close(self):
        self.process.wait()
        self.log.close()


def format_count(n):
    """1234567 as "1.23M", as clppm's progress line writes counts."""
    for suffix in ("", "k", "M", "G", "T"):
        if n < 999.5:
            return "%d" % n if suffix == "" else "%.3g%s" % (n, suffix)
        n /= 1000.0
    return "%.3gP" % n


_INTEGRATOR = re.compile(r"^clppm: integrator (\w+)", re.M)
_PASS = re.compile(r"\bpass (\d+)(?:/(\d+))?")
_PHOTONS = re.compile(r"\s(\S+) photons\b")
_ERROR = re.compile(r"\berr ([0-9.eE+-]+)")


def parse_progress(log):
    """The status of a clppm command's log (its progress lines): pass, pass_limit, photons, error,
    integrator; None for what it has not said yet."""
    status = {"pass": None, "pass_limit": None, "photons": None, "error": None, "integrator": None}
    found = _INTEGRATOR.search(log)
    if found:
        status["integrator"] = found.group(1)
    for line in reversed(log.replace("\r", "\n").splitlines()):
        m = _PASS.search(line)
        if m and not line.startswith("clppm:"):
            status["pass"] = int(m.group(1))
            status["pass_limit"] = int(m.group(2)) if m.group(2) else None
            photons, error = _PHOTONS.search(line), _ERROR.search(line)
            status["photons"] = photons.group(1) if photons else None
            status["error"] = float(error.group(1)) if error else None
            break
    return status


def status_text(status):
    """The render header's line: "clppm sppm | pass 12/100 | 2.4M photons | error 0.031"."""
    if status.get("pass") is None:
        return "clppm: preparing"
    text = " ".join(filter(None, ("clppm", status.get("integrator")))) + " | pass %d" % status["pass"]
    if status.get("pass_limit"):
        text += "/%d" % status["pass_limit"]
    if status.get("photons"):
        text += " | %s photons" % status["photons"]
    if status.get("error") is not None:
        text += " | error %.3g" % status["error"]
    return text


def wait(render, cancelled, show, every):
    """Until `render` ends: cancel it when cancelled() says so (it stops within a photon batch),
    and call show() every `every` seconds."""
    last = time.monotonic()
    while not render.done.wait(0.05):
        if cancelled():
            render.cancel()
            render.done.wait()
            break
        if time.monotonic() - last >= every:
            show()
            render.request()
            last = time.monotonic()
