#!/usr/bin/env python3
"""One table row of a timed clppm run, for the equal-time benchmark scripts (bench/sampler.sh,
bench/visual_importance.sh): reads OUT/run.json (--stats-json), OUT/time (/usr/bin/time -f "%U %S")
and compares OUT/run.exr with REF by `clppm compare --box 4`.

    run_row.py OUT NAME LABEL SEED BINARY REF [--wall]

prints | NAME | LABEL | SEED | [wall s |] CPU s | passes | mean ratio | box-4 relative MSE | p90 | relative MSE |"""
import json
import subprocess
import sys

out, name, label, seed, binary, ref = sys.argv[1:7]
wall = "--wall" in sys.argv[7:]
st = json.load(open(out + "/run.json"))
cpu = sum(float(x) for x in open(out + "/time").read().split()[-2:])
c = json.loads(subprocess.run([binary, "compare", out + "/run.exr", ref, "--box", "4"],
                              capture_output=True, text=True, check=True).stdout)
cols = [name, label, seed] + (["%.1f" % st["render_seconds"]] if wall else []) + [
    "%.1f" % cpu, "%d" % st["passes"], "%.4f" % c["mean_ratio"], "%.3e" % c["box_rel_mse"], "%.4f" % c["p90_rel_error"], "%.3e" % c["rel_mse"]]
print("| " + " | ".join(cols) + " |")
