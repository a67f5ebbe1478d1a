#!/bin/sh
# Fuzzes the glTF loader: tests/fuzz/run.sh [seconds] [extra libFuzzer flags...]
# Default 60 s. Brings tests/fuzz/build.sh's target up to date first (BUILD_DIR, default
# build-fuzz in the repository root). The seed corpus is rebuilt every run from scenes/*.gltf|glb,
# tests/data/*.gltf|glb, tests/fuzz/hostile/*, tests/fuzz/regressions/* and .glb conversions of
# the .gltf seeds; inputs that find new coverage accumulate in $CORPUS (default
# $BUILD_DIR/corpus) across runs. Extra flags pass through, e.g. -max_len=16384 to keep the
# mutator on small inputs (the big scene seeds are then cut, and mostly only exercise JSON errors).
# Crashers, timeouts and OOMs go to tests/fuzz/crashes/ (crash-*, timeout-*, oom-*); minimise one
# with  $BUILD_DIR/gltf_fuzz -minimize_crash=1 -runs=10000 -exact_artifact_path=OUT crash-...
# Share the machine:  nice -n 10 tests/fuzz/run.sh 600
set -eu
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
seconds=${1:-60}
[ $# -gt 0 ] && shift
build=${BUILD_DIR:-$root/build-fuzz}
"$here/build.sh" "$build" >/dev/null

seeds=$build/seeds
rm -rf "$seeds"
corpus=${CORPUS:-$build/corpus}
mkdir -p "$seeds" "$corpus" "$here/crashes"
for f in "$root"/scenes/*.gltf "$root"/scenes/*.glb "$root"/tests/data/*.gltf "$root"/tests/data/*.glb \
         "$here"/hostile/* "$here"/regressions/*; do
    # Seeds over 256 KiB (a 2.4 MB .bin-backed .glb, say) only slow the mutator down.
    [ -f "$f" ] && [ "$(wc -c < "$f")" -le 262144 ] && cp "$f" "$seeds/"
done
python3 "$here/gltf_to_glb.py" "$seeds/glb" "$root"/scenes/*.gltf "$root"/tests/data/*.gltf
mv "$seeds"/glb/*.glb "$seeds/" 2>/dev/null || true
rmdir "$seeds/glb" 2>/dev/null || true

# Run from the build dir: libFuzzer writes fuzz-*.log there and a relative URI in an input never
# lands in the source tree.
cd "$build"
exec "$build/gltf_fuzz" "$corpus" "$seeds" \
    -dict="$here/gltf.dict" -max_total_time="$seconds" -rss_limit_mb=2048 -timeout=10 \
    -artifact_prefix="$here/crashes/" -print_final_stats=1 "$@"
