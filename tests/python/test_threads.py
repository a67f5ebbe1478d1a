"""The library from several threads at once (issue 61): renders in parallel give each the image it
gives alone, and a Renderer's cancel() stops its own pass in flight and nothing else: not another
Renderer's, not its own next one."""
import threading
import time

import numpy as np

import clppm
from conftest import SMALL

# Every integrator, some twice, as a batch of variants or a web service would run them.
JOBS = [("sppm", 1), ("pt", 2), ("vcm", 3), ("ppm", 4), ("bpt", 5), ("pppm", 6), ("pt", 7), ("sppm", 8)]


def render(integrator, seed):
    return clppm.render(integrator=integrator, **dict(SMALL, seed=seed, passes=3))


def test_eight_threads_give_the_images_each_gives_alone():
    alone = [render(i, s) for i, s in JOBS]
    together, errors = [None] * len(JOBS), []

    def work(k):
        try:
            together[k] = render(*JOBS[k])
        except BaseException as e:  # noqa: B902 - reported below with the job that raised it
            errors.append((JOBS[k], repr(e)))

    threads = [threading.Thread(target=work, args=(k,)) for k in range(len(JOBS))]
    for t in threads:
        t.start()
    for t in threads:
        t.join(timeout=600)
    assert not any(t.is_alive() for t in threads), "a render thread hung"
    assert not errors, errors
    for (integrator, seed), a, b in zip(JOBS, alone, together):
        assert a.mean() > 0, integrator
        assert np.array_equal(a, b), f"{integrator} (seed {seed}) differs when rendered beside the others"


def test_a_cancel_while_no_pass_runs_is_meant_for_nothing():
    r = clppm.Renderer(integrator="pt", passes=10, **SMALL)
    r.cancel()
    r.run_pass()  # not Interrupted: the cancel came before it
    assert r.passes == 1
    r.close()


def test_cancel_stops_one_renderer_and_not_the_other(monkeypatch):
    monkeypatch.setenv("CLPPM_PHOTON_BATCH", "1000")
    slow = dict(integrator="sppm", width=40, height=30, photons=200000, passes=100000, quiet=True)
    a, b = clppm.Renderer(**slow), clppm.Renderer(**slow)
    outcome = {}

    def iterate(name, r, stop_after):
        start = time.monotonic()
        try:
            for _ in r:
                if time.monotonic() - start > stop_after:
                    break
            outcome[name] = ("ran", r.passes)
        except clppm.Interrupted as e:
            outcome[name] = ("interrupted", e.passes)

    ta = threading.Thread(target=iterate, args=("a", a, 60))
    tb = threading.Thread(target=iterate, args=("b", b, 3))
    ta.start()
    tb.start()
    time.sleep(1.5)
    a.cancel()
    ta.join(timeout=120)
    tb.join(timeout=120)
    assert outcome["a"][0] == "interrupted", outcome
    assert outcome["b"][0] == "ran" and outcome["b"][1] >= 1, outcome
    a.close()
    b.close()
