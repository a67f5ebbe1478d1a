#!/usr/bin/env bash
# How a pass's cost grows to 10x the largest sizes of throughput_bench (bench/RESULTS.md, "How
# the cost grows at 10x"): SPPM seconds per pass against triangles (to a 1.0M-triangle blob made
# by scripts/make_scenes.py --large, not shipped), pixels (to 3840x2160) and photons per pass (to
# 10M), each with the other two held, and the peak memory of each run. Writes a Markdown table on
# stdout and the runs' stats into $OUT (default /tmp/clppm_scaling).
#
#   bench/scaling_10x.sh            # PASSES=8 by default; CLPPM=build/clppm
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
CLPPM=${CLPPM:-build/clppm}
OUT=${OUT:-/tmp/clppm_scaling}
PASSES=${PASSES:-8}
mkdir -p "$OUT"
[ -f "$OUT/bunny_1m.gltf" ] || python3 scripts/make_scenes.py --large "$OUT" >&2

# run NAME SCENE WIDTH HEIGHT PHOTONS: one render of $PASSES passes, a row of the table: wall
# seconds per pass (render time / passes, the first pass's allocations included), device seconds
# per pass (the phases' sum), the BVH build, device memory and the process's peak RSS.
run() {
    local name=$1 scene=$2 w=$3 h=$4 photons=$5
    /usr/bin/time -f "%M" -o "$OUT/$name.rss" "$CLPPM" "$scene" --integrator sppm --width "$w" --height "$h" \
        --photons "$photons" --passes "$PASSES" --quiet --no-png -o "$OUT/$name.exr" --stats-json "$OUT/$name.json"
    python3 - "$OUT/$name.json" "$OUT/$name.rss" "$name" <<'PY'
import json, sys
j = json.load(open(sys.argv[1]))
rss_mib = int(open(sys.argv[2]).read().split()[-1]) / 1024
passes = j["passes"]
wall = j["render_seconds"] / passes
device = sum(j["phase_seconds"].values()) / passes
print(f"| {sys.argv[3]} | {j['bvh']['triangles']} | {j['width']}x{j['height']} | {j['photons_per_pass']} | "
      f"{wall:.3f} | {device:.3f} | {j['bvh']['build_seconds']:.2f} | "
      f"{j['device_memory_bytes']['total'] / 2**20:.0f} | {rss_mib:.0f} |")
PY
}

echo "| run | triangles | pixels | photons/pass | s/pass | device s/pass | BVH build s | device MiB | peak RSS MiB |"
echo "|---|---|---|---|---|---|---|---|---|"
run tris_100k scenes/bunny_100k.gltf 128 128 100000
run tris_1m "$OUT/bunny_1m.gltf" 128 128 100000
run pixels_1k scenes/cornell_box.gltf 1024 1024 100000
run pixels_4k scenes/cornell_box.gltf 3840 2160 100000
run photons_1m scenes/cornell_box.gltf 128 128 1000000
run photons_10m scenes/cornell_box.gltf 128 128 10000000
