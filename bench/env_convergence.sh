#!/bin/bash
# Error against time under the default environment (issue 15): tests/data/env_outdoor.gltf (a
# floor, a box and a rough metal sphere, no lights, so the uniform white world of radiance 1
# lights it), 128x128, each integrator for 5, 10 and 20 s against a 120-s path-traced reference;
# box-4 relative MSE and mean ratio from `clppm compare --box 4`, passes per second from the
# stats. Usage: bench/env_convergence.sh [BUILD_DIR] (default build).
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
bin=${1:-$here/build}/clppm
scene=$here/tests/data/env_outdoor.gltf
out=$(mktemp -d)
common="--width 128 --height 128 --quiet --no-png"
"$bin" "$scene" $common --integrator pt --time 120 -o "$out/ref.exr"
echo "| integrator | seconds | passes/s | mean ratio | box-4 relative MSE |"
echo "|---|---|---|---|---|"
for integ in pt sppm pppm ppm; do
  for t in 5 10 20; do
    "$bin" "$scene" $common --integrator "$integ" --time "$t" -o "$out/$integ$t.exr" --stats-json "$out/$integ$t.json"
    python3 - "$out/$integ$t.json" "$integ" "$t" <<PY
import json, subprocess, sys
st = json.load(open(sys.argv[1]))
c = json.loads(subprocess.run(["$bin", "compare", "$out/$integ$t.exr", "$out/ref.exr", "--box", "4"],
                              capture_output=True, text=True, check=True).stdout)
print("| %s | %s | %.1f | %.4f | %.2e |" % (sys.argv[2], sys.argv[3], st["passes_per_second"], c["mean_ratio"], c["box_rel_mse"]))
PY
  done
done
rm -rf "$out"
