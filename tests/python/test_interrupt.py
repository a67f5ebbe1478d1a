"""Ctrl-C (SIGINT) while Python renders: the pass in flight stops at its next photon batch, the
last complete pass is kept and raised with clppm.Interrupted (a KeyboardInterrupt), the files the
options name are written as the command line writes them, and the Renderer renders on afterwards."""
import os
import signal
import subprocess
import sys
import textwrap
import time

import clppm

SCRIPT = textwrap.dedent(
    """
    import sys, clppm
    mode, out = sys.argv[1], sys.argv[2]
    # Batches of 1000 photons: a stop request is answered within one.
    r = clppm.Renderer(integrator="sppm", width=40, height=30, photons=200000, passes=100000, quiet=True, output=out,
                       no_png=True)
    print("ready", flush=True)
    try:
        if mode == "render":
            r.render()
        else:
            for p in r:
                print("pass", p, flush=True)
    except clppm.Interrupted as e:
        assert isinstance(e, KeyboardInterrupt)
        print("interrupted", e.passes, e.image.shape, r.passes, flush=True)
        if mode == "iterate":
            r.run_pass()  # it renders on
            print("continued", r.passes, flush=True)
        r.close()
        sys.exit(3)
    """
)


def interrupt(mode, tmp_path):
    out = tmp_path / "i.exr"
    env = dict(os.environ, CLPPM_PHOTON_BATCH="1000")
    p = subprocess.Popen([sys.executable, "-c", SCRIPT, mode, str(out)], stdout=subprocess.PIPE,
                         stderr=subprocess.PIPE, text=True, env=env)
    assert p.stdout.readline().strip() == "ready"
    time.sleep(3)  # a few passes
    sent = time.monotonic()
    p.send_signal(signal.SIGINT)
    stdout, stderr = p.communicate(timeout=120)
    return p.returncode, time.monotonic() - sent, stdout, stderr, out


def test_interrupting_iteration_keeps_the_last_pass_and_goes_on(tmp_path):
    status, seconds, stdout, stderr, out = interrupt("iterate", tmp_path)
    assert status == 3, stderr
    lines = stdout.splitlines()
    done = [l for l in lines if l.startswith("interrupted")]
    assert done, stdout
    passes = int(done[0].split()[1])
    assert passes >= 1 and f"pass {passes}" in lines
    assert "(30, 40, 3)" in done[0]
    assert f"continued {passes + 1}" in lines
    assert seconds < 30  # a batch of 1000 photons, then one more pass


def test_interrupting_render_writes_the_last_pass(tmp_path):
    status, seconds, stdout, stderr, out = interrupt("render", tmp_path)
    assert status == 3, stderr
    assert seconds < 10, seconds  # within a batch (the pass is abandoned)
    passes = int(stdout.split("interrupted")[1].split()[0])
    assert passes >= 1
    assert os.path.exists(out)
    assert "interrupted after pass" in stderr
    assert clppm.read_exr(out).shape == (30, 40, 3)


def test_cancel_from_another_thread_stops_the_pass_and_keeps_the_last_one(monkeypatch):
    """What a GUI's Cancel button does: the Renderer iterates in one thread, cancel() comes from another."""
    import threading
    monkeypatch.setenv("CLPPM_PHOTON_BATCH", "1000")
    r = clppm.Renderer(integrator="sppm", width=40, height=30, photons=200000, passes=100000, quiet=True)
    timer = threading.Timer(1.5, r.cancel)
    timer.start()
    passes, raised = 0, None
    try:
        for passes in r:
            sent = time.monotonic()
    except clppm.Interrupted as e:
        raised, seconds = e, time.monotonic() - sent
    timer.join()
    assert raised is not None, "iteration went on although cancel() was called"
    assert seconds < 5, seconds  # within a batch of the pass in flight
    assert raised.passes == passes >= 1 and raised.image.shape == (30, 40, 3)
    assert raised.image.mean() > 0
    # The request is spent: the Renderer renders on.
    r.run_pass()
    assert r.passes == passes + 1
    r.close()
