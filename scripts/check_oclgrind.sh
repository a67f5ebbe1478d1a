#!/usr/bin/env bash
# Every kernel under oclgrind (issue 58): Debian's OpenCL simulator reports invalid memory
# accesses, reads of uninitialised values (--uninitialized) and data races between work items
# (--data-races). Small renders by every integrator (PPM, SPPM, PPPM, the path tracer, VCM, BPT),
# error estimation, visual importance (photon chains), an environment map, dispersion, the sun and
# sky, the world's medium and a scattering mesh (the path tracer's and the photons'), and the
# generic kernels (every feature compiled in) on glass and in fog. The check passes when oclgrind
# says nothing at all: any line of its output fails it.
#
# Three things make oclgrind 21.10 usable here, none of which changes an image:
#   - -cl-opt-disable: its optimiser turns the kernels' bit tricks into llvm.bitreverse and
#     llvm.ctpop, which its interpreter lacks ("Undefined external function"); unoptimised, the
#     kernels call the OpenCL builtins it implements;
#   - CLPPM_OCLGRIND=1: buffers handled as its shadow memory needs (src/device/kernel_launch.h):
#     without it, VCM's light vertices and the photon chains' tables read as uninitialised where
#     a buffer took the slot of a smaller one released before;
#   - kernels/scene.cl builds triangle_uv's float4 element by element: --uninitialized crashed on
#     the (float2, float2) form in the generic kernels.
# Usage: check_oclgrind.sh CLPPM_BINARY
set -uo pipefail
clppm=$1
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
if ! command -v oclgrind >/dev/null 2>&1; then
  echo "check_oclgrind: skipped: oclgrind is not installed (Debian's package oclgrind)" >&2
  exit 77
fi
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
export CLPPM_NO_CACHE=1 CLPPM_OCLGRIND=1
small=(--width 8 --height 8 --passes 2 --photons 2000 --quiet --no-png)
cases=(
  "ppm|--integrator ppm"
  "sppm|--integrator sppm"
  "pppm|--integrator pppm"
  "pt|--integrator pt"
  "vcm|--integrator vcm"
  "bpt|--integrator bpt"
  "visual-importance|--integrator sppm --visual-importance"
  "sppm-error|--integrator sppm --target-error 0.01 --passes 5"
  "pt-error|--integrator pt --target-error 0.01 --passes 5"
  "studio-pt|--integrator pt --env studio"
  "studio-sppm|--integrator sppm --env studio"
  "dispersion|$here/scenes/dispersion_box.gltf --integrator sppm"
  "skylight|$here/scenes/skylight.gltf --integrator pt"
  "generic-pt|$here/scenes/caustic.gltf --integrator pt --generic-kernels"
  "generic-vcm|$here/scenes/caustic.gltf --integrator vcm --generic-kernels"
  "fog-pt|$here/tests/data/fog_room.gltf --integrator pt"
  "fog-generic|$here/tests/data/fog_room.gltf --integrator pt --generic-kernels"
  "wax-pt|$here/tests/data/wax_block.gltf --integrator pt"
  "fog-sppm|$here/tests/data/fog_room.gltf --integrator sppm"
  "wax-pppm|$here/tests/data/wax_block.gltf --integrator pppm"
  "wax-sppm|$here/tests/data/wax_block.gltf --integrator sppm --direct photons"
  "fog-beams|$here/tests/data/fog_room.gltf --integrator pppm --volume-gather beams"
  "fog-ppm|$here/tests/data/fog_room.gltf --integrator ppm --spp 2 --target-error 0.01"
  "fog-cube-sppm|$here/tests/data/fog_cube_room.gltf --integrator sppm"
)
status=0
for c in "${cases[@]}"; do
  name=${c%%|*}
  read -r -a args <<<"${c#*|}"
  log=$out/$name.log
  start=$SECONDS
  oclgrind --uninitialized --data-races --build-options "-cl-opt-disable" \
    "$clppm" "${args[@]}" "${small[@]}" -o "$out/$name.exr" >"$log" 2>&1
  rc=$?
  # oclgrind's reports (invalid accesses, uninitialised values, races, divergence, fatal errors):
  # every line but clppm's own; each report names its kernel on a "Kernel:" line.
  lines=$(grep -cv -e '^$' -e '^clppm: ' "$log")
  reports=$(grep -c 'Kernel: ' "$log")
  echo "check_oclgrind: $name: exit $rc, $reports reports ($lines lines), $((SECONDS - start)) s"
  if [[ $rc -ne 0 || $lines -ne 0 ]]; then
    status=1
    head -40 "$log"
  fi
done

# The check can fail: VCM's light vertices with one field left unwritten (d_vc) must be reported
# where the grid copies them, through everything CLPPM_OCLGRIND changes.
broken=$out/kernels
cp -r "$here/kernels" "$broken"
sed -i '/v->d_vc = m.d_vc;/d' "$broken/vcm.cl"
if cmp -s "$here/kernels/vcm.cl" "$broken/vcm.cl"; then
  echo "check_oclgrind: the canary's line (v->d_vc = m.d_vc;) is no longer in kernels/vcm.cl" >&2
  exit 1
fi
CLPPM_KERNEL_DIR=$broken oclgrind --uninitialized --build-options "-cl-opt-disable" \
  "$clppm" --integrator vcm "${small[@]}" -o "$out/canary.exr" >"$out/canary.log" 2>&1
canary=$(grep -c 'Kernel: ' "$out/canary.log")
echo "check_oclgrind: canary (a field of the light vertices unwritten): $canary reports"
[[ $canary -gt 0 ]] || status=1
exit $status
