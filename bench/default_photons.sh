#!/bin/bash
# Photons per pass for the default integrator at the default resolution (issue 16): the Cornell box
# at 512x512 (the default size), SPPM with 50k to 800k photons per pass for SECONDS of rendering
# each, against an SPPM reference of REF_SECONDS (1M photons per pass, another seed); metrics from
# `clppm compare --box 4`. CPU seconds beside wall seconds: the machine may be shared.
#   bench/default_photons.sh [BUILD_DIR]   (env: SECONDS_EACH=30, REF_SECONDS=300, SCENE=path or empty)
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
bin=${1:-$here/build}/clppm
t=${SECONDS_EACH:-30}
ref_seconds=${REF_SECONDS:-300}
scene=${SCENE:-}
out=$(mktemp -d)
"$bin" $scene --integrator sppm --photons 1000000 --time "$ref_seconds" --seed 1000 --quiet --no-png -o "$out/ref.exr"
echo "| photons per pass | seconds | CPU s | passes | mean ratio | box-4 relative MSE | p90 relative error |"
echo "|---:|---:|---:|---:|---:|---:|---:|"
for photons in 50000 100000 200000 400000 800000; do
  /usr/bin/time -f "%U %S" -o "$out/time" "$bin" $scene --integrator sppm --photons "$photons" --time "$t" --quiet \
    --no-png -o "$out/$photons.exr" --stats-json "$out/$photons.json"
  python3 - "$out" "$photons" "$t" "$bin" <<'PY'
import json, subprocess, sys
out, photons, t, binary = sys.argv[1:]
st = json.load(open("%s/%s.json" % (out, photons)))
cpu = sum(float(x) for x in open(out + "/time").read().split()[-2:])
c = json.loads(subprocess.run([binary, "compare", "%s/%s.exr" % (out, photons), out + "/ref.exr", "--box", "4"],
                              capture_output=True, text=True, check=True).stdout)
print("| %s | %s | %.0f | %d | %.4f | %.2e | %.4f |" % (photons, t, cpu, st["passes"], c["mean_ratio"],
                                                        c["box_rel_mse"], c["p90_rel_error"]))
PY
done
rm -rf "$out"
