#!/usr/bin/env python3
"""The live view's image transfer (issue 17): PNG encoded by the server, or half floats that the
page tone-maps itself, measured in headless Chromium on this machine.

For each image size: a render with --serve, the page's ?bench=N mode (N updates with each
transfer; medians of the page's time from request to drawn canvas, the server's encode time
from Server-Timing, and the bytes), read from the page's title through the DevTools endpoint.
Then what watching costs the render: passes in SECONDS with no viewer, with the page open on the
PNG, and on the half floats (a viewer that keeps the render publishing four times a second),
with CPU seconds beside wall seconds, since the page shares the two cores.

    bench/live_view_transport.py [BUILD_DIR] [--sizes 256,512,1024] [--n 10] [--seconds 20]
"""
import argparse, json, os, signal, socket, subprocess, sys, tempfile, time, urllib.request

here = os.path.dirname(os.path.abspath(__file__))


def free_port():
    s = socket.socket()
    s.bind(("127.0.0.1", 0))
    p = s.getsockname()[1]
    s.close()
    return p


def get(url, timeout=2):
    with urllib.request.urlopen(url, timeout=timeout) as r:
        return r.read()


def wait_for_image(port, seconds=120):
    t0 = time.time()
    while time.time() - t0 < seconds:
        try:
            if json.loads(get("http://127.0.0.1:%d/stats" % port))["version"] > 0:
                return
        except OSError:
            pass
        time.sleep(0.2)
    raise SystemExit("the render never published an image")


def chromium(url, tmp):
    devtools = free_port()
    return devtools, subprocess.Popen(
        ["chromium", "--headless", "--no-sandbox", "--disable-gpu", "--user-data-dir=" + tmp + "/profile%d" % devtools,
         "--remote-debugging-port=%d" % devtools, url],
        stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, start_new_session=True)


def page_title_json(devtools, seconds):
    t0 = time.time()
    while time.time() - t0 < seconds:
        time.sleep(0.5)
        try:
            for t in json.loads(get("http://127.0.0.1:%d/json/list" % devtools)):
                title = t.get("title", "").replace("&quot;", '"')
                if t.get("type") == "page" and title.startswith("{"):
                    return json.loads(title)
        except (OSError, ValueError):
            pass
    raise SystemExit("the page reported nothing in %d s" % seconds)


def kill(p):
    try:
        os.killpg(p.pid, signal.SIGTERM)
    except ProcessLookupError:
        pass
    p.wait()


def cpu_seconds(pid):
    with open("/proc/%d/stat" % pid) as f:
        fields = f.read().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def group_cpu_seconds(pgid):
    """CPU seconds of every process in the session `pgid` (chromium's renderer, GPU and browser)."""
    total = 0.0
    for pid in os.listdir("/proc"):
        if not pid.isdigit():
            continue
        try:
            with open("/proc/%s/stat" % pid) as f:
                fields = f.read().rsplit(")", 1)[1].split()
            if int(fields[2]) == pgid:  # the process group
                total += (int(fields[11]) + int(fields[12]) + int(fields[13]) + int(fields[14])) / os.sysconf("SC_CLK_TCK")
        except (OSError, IndexError, ValueError):
            pass
    return total


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("build", nargs="?", default=os.path.join(here, "..", "build"))
    ap.add_argument("--sizes", default="256,512,1024")
    ap.add_argument("--n", type=int, default=10)
    ap.add_argument("--seconds", type=float, default=20)
    ap.add_argument("--repeats", type=int, default=2, help="rounds of the no/png/f16 viewer runs, interleaved")
    a = ap.parse_args()
    binary = os.path.join(a.build, "clppm")
    tmp = tempfile.mkdtemp(prefix="live_bench")
    print("%d cores, %s, %s" % (os.cpu_count(), subprocess.run(["chromium", "--version"], capture_output=True,
                                                                text=True).stdout.strip(), time.strftime("%F")))
    print()
    print("| size | transfer | page ms (request to canvas) | server encode ms | bytes |")
    print("|---|---|---:|---:|---:|")
    for size in [int(s) for s in a.sizes.split(",") if s]:
        port = free_port()
        render = subprocess.Popen([binary, "--width", str(size), "--height", str(size), "--passes", "1000000",
                                   "--quiet", "--no-png", "-o", tmp + "/b.exr", "--serve", "127.0.0.1:%d" % port])
        try:
            wait_for_image(port)
            devtools, page = chromium("http://127.0.0.1:%d/?bench=%d" % (port, a.n), tmp)
            try:
                r = page_title_json(devtools, 300)
            finally:
                kill(page)
        finally:
            render.send_signal(signal.SIGINT)
            render.wait()
        if "error" in r:
            raise SystemExit("page: " + r["error"])
        for t in ("png", "f16"):
            print("| %d² | %s | %.1f | %.1f | %d |" % (size, t, r[t]["ms"], r[t]["encode_ms"], r[t]["bytes"]))
    print()
    size = 256
    print("What watching costs the render (%d², %g s each, SPPM defaults):" % (size, a.seconds))
    print()
    print("| viewer | passes | passes/s | clppm CPU s | chromium CPU s | requests served |")
    print("|---|---:|---:|---:|---:|---:|")
    for viewer in ("none", "png", "f16") * a.repeats:
        port = free_port()
        stats = tmp + "/stats-%s.json" % viewer
        render = subprocess.Popen([binary, "--width", str(size), "--height", str(size), "--time", str(a.seconds),
                                   "--quiet", "--no-png", "-o", tmp + "/w.exr", "--stats-json", stats,
                                   "--serve", "127.0.0.1:%d" % port])
        page = None
        if viewer != "none":
            _, page = chromium("http://127.0.0.1:%d/?transport=%s" % (port, viewer), tmp)
        cpu = page_cpu = 0.0
        while render.poll() is None:
            try:
                cpu = cpu_seconds(render.pid)
            except OSError:
                break
            if page:
                page_cpu = group_cpu_seconds(page.pid)
            time.sleep(0.2)
        if page:
            kill(page)
        st = json.load(open(stats))
        print("| %s | %d | %.2f | %.1f | %.1f | %d |" % (viewer, st["passes"], st["passes_per_second"], cpu, page_cpu,
                                                  st.get("live_view", {}).get("requests", 0)))


if __name__ == "__main__":
    main()
