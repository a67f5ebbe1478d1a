#!/usr/bin/env python3
"""What rendering on several processes costs and gains (issue 18), from measured numbers.

1. The reduction each pass: its size (hit points x 32 bytes, + 8 with error estimation) and its
   time between two ranks of this machine, at WIDTHxHEIGHT, from clppm's stats ("mpi").
2. The pass's parts on one process at that size (phase_seconds): what every rank repeats (eye
   pass, per-hit-point update) and what splits between ranks (photon tracing, grid, gather), for
   the model of 8, 64 and 512 ranks on a network of BANDWIDTH Gbit/s (ring allreduce: each rank
   sends and receives 2 (p-1)/p of the buffer, plus 2 (p-1) latencies).
3. Balance: two ranks of different speed (PoCL with 2 threads and with 1 on the two cores), the
   photons each was given in the last pass and the seconds each spent waiting in collectives.

    bench/mpi_scaling.py [BUILD_DIR] [--width 1920 --height 1080 --passes 4 --bandwidth 10]
"""
import argparse, json, os, subprocess, sys, tempfile

here = os.path.dirname(os.path.abspath(__file__))


def run(cmd, env=None):
    r = subprocess.run(cmd, env=env, capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit("failed: %s\n%s" % (" ".join(cmd), r.stdout + r.stderr))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("build", nargs="?", default=os.path.join(here, "..", "build"))
    ap.add_argument("--width", type=int, default=1920)
    ap.add_argument("--height", type=int, default=1080)
    ap.add_argument("--passes", type=int, default=4)
    ap.add_argument("--photons", type=int, default=200000)
    ap.add_argument("--bandwidth", type=float, default=10.0, help="Gbit/s")
    ap.add_argument("--latency-us", type=float, default=50.0)
    a = ap.parse_args()
    clppm = os.path.join(a.build, "clppm")
    tmp = tempfile.mkdtemp(prefix="mpi_bench")
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    common = ["--integrator", "sppm", "--width", str(a.width), "--height", str(a.height), "--passes", str(a.passes),
              "--photons", str(a.photons), "--quiet", "--no-png"]
    run([clppm] + common + ["-o", tmp + "/one.exr", "--stats-json", tmp + "/one.json"])
    one = json.load(open(tmp + "/one.json"))
    run(["mpirun", "--oversubscribe", "-np", "2", clppm] + common + ["-o", tmp + "/two.exr", "--stats-json",
                                                                     tmp + "/two.json"], env)
    two = json.load(open(tmp + "/two.json"))
    same = open(tmp + "/one.exr", "rb").read() == open(tmp + "/two.exr", "rb").read()
    print("%d cores, %dx%d SPPM, %d photons per pass, %d passes" % (os.cpu_count(), a.width, a.height, a.photons,
                                                                   a.passes))
    print()
    n = one["hitpoints"]
    size = two["mpi"]["bytes_per_pass"]
    comm = two["mpi"]["communication_seconds"]
    print("Hit points: %d; reduction per pass: %.1f MB (measured bytes per pass: %.1f MB); two ranks' image "
          "equals one process's: %s" % (n, n * 32 / 1e6, size / 1e6, "yes, byte for byte" if same else "NO"))
    print("Two ranks on this machine: %.2f pass/s against %.2f for one process; communication (waiting "
          "included) %.3f and %.3f s per pass" % (two["passes_per_second"], one["passes_per_second"],
                                                 comm[0] / a.passes, comm[1] / a.passes))
    print()
    ph = one["phase_seconds"]
    split_phases = ("photon_trace", "grid_build", "gather")
    split_s = sum(v for k, v in ph.items() if k in split_phases) / a.passes
    fixed_s = sum(v for k, v in ph.items() if k not in split_phases) / a.passes
    wall = one["render_seconds"] / a.passes
    host_s = max(0.0, wall - split_s - fixed_s)  # readbacks, host work
    print("One process, per pass: %.3f s wall; device time %.3f s split between ranks (%s), %.3f s repeated "
          "by every rank (%s), %.3f s host" % (wall, split_s, ", ".join(split_phases), fixed_s,
                                               ", ".join(k for k in ph if k not in split_phases), host_s))
    print()
    bw = a.bandwidth * 1e9 / 8
    S = n * 32
    print("Model, %g Gbit/s and %g us a message: the same %d photons per pass shared by p ranks (strong), "
          "and %d photons per rank (weak: --photons %d x p)" % (a.bandwidth, a.latency_us, a.photons, a.photons,
                                                                a.photons))
    print()
    print("| ranks | reduction s | strong: pass s | strong: speed-up | weak: pass s | weak: photons/s | weak: "
          "efficiency |")
    print("|---:|---:|---:|---:|---:|---:|---:|")
    base_rate = a.photons / wall
    for p in (1, 8, 64, 512):
        red = 0.0 if p == 1 else 2 * (p - 1) / p * S / bw + 2 * (p - 1) * a.latency_us * 1e-6
        t = fixed_s + host_s + split_s / p + red
        tw = fixed_s + host_s + split_s + red
        rate = p * a.photons / tw
        print("| %d | %.3f | %.3f | %.2fx | %.3f | %.3g | %.0f%% |" % (p, red, t, wall / t, tw, rate,
                                                                    100 * rate / (p * base_rate)))
    print()
    # Balance between ranks of different speed.
    small = ["--integrator", "sppm", "--width", "320", "--height", "180", "--passes", "24", "--photons",
             str(a.photons), "--quiet", "--no-png"]
    for threads in ((2, 1), (1, 1)):
        cmd = ["mpirun", "--oversubscribe", "--bind-to", "none", "-np", "1", "-x",
               "POCL_MAX_PTHREAD_COUNT=%d" % threads[0], clppm] + \
              small + ["-o", tmp + "/b.exr", "--stats-json", tmp + "/b.json", ":", "-np", "1", "-x",
                       "POCL_MAX_PTHREAD_COUNT=%d" % threads[1], clppm] + small + ["-o", tmp + "/b.exr"]
        run(cmd, env)
        b = json.load(open(tmp + "/b.json"))
        m = b["mpi"]
        print("Two ranks, PoCL with %d and %d threads on the two cores, 320x180, 24 passes of %d photons: "
              "%.2f pass/s; the last pass's photons %s; seconds each spent in collectives, waiting for the "
              "other included, %s" % (threads[0], threads[1], a.photons, b["passes_per_second"],
                                       m["last_pass_share"], [round(x, 2) for x in m["communication_seconds"]]))


if __name__ == "__main__":
    main()
