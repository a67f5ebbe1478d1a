#!/usr/bin/env bash
# Every kernel under oclgrind (issue 58): Debian's OpenCL simulator reports invalid memory
# accesses, reads of uninitialised values (--uninitialized) and data races between work items
# (--data-races). Small renders of PPM, SPPM, PPPM and the path tracer, error estimation, textures
# and an environment map, dispersion and the sun and sky (the cases below; what is not yet clean is
# listed after). The check passes when oclgrind reports nothing at all.
#
# Two things make oclgrind 21.10 usable here, neither of which changes an image:
#   - -cl-opt-disable: its optimiser turns the kernels' bit tricks into llvm.bitreverse and
#     llvm.ctpop, which its interpreter lacks ("Undefined external function"); unoptimised, the
#     kernels call the OpenCL builtins it implements;
#   - CLPPM_FILL_BY_WRITE=1: what clEnqueueFillBuffer writes is not marked initialised there, so
#     filled buffers are written from the host instead (src/device/kernel_launch.h, fill_buffer).
# Not yet clean, and so not run here (issue 58 stays open on them):
#   - vcm and bpt: 332 and 342 reports at 8x8, all from the light vertices. oclgrind flags every
#     field of a vertex that vcm_light reads back right after writing it (its pos, prim, d_vc), while
#     the values written are initialised by its own account and printf shows them right in
#     grid_count; a 20-line kernel with the same atomic-slot stores is clean, so this is not yet
#     pinned on the kernel or on oclgrind;
#   - --visual-importance: over 1000 reports (the photon chains);
#   - --generic-kernels: oclgrind itself segfaults building the all-features program.
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
export CLPPM_NO_CACHE=1 CLPPM_FILL_BY_WRITE=1
small=(--width 8 --height 8 --passes 2 --photons 2000 --quiet --no-png)
cases=(
  "ppm|--integrator ppm"
  "sppm|--integrator sppm"
  "pppm|--integrator pppm"
  "pt|--integrator pt"
  "sppm-error|--integrator sppm --target-error 0.01 --passes 5"
  "pt-error|--integrator pt --target-error 0.01 --passes 5"
  "studio-pt|--integrator pt --env studio"
  "studio-sppm|--integrator sppm --env studio"
  "dispersion|$here/scenes/dispersion_box.gltf --integrator sppm"
  "skylight|$here/scenes/skylight.gltf --integrator pt"
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
  # oclgrind's reports: invalid accesses, uninitialised values, races, divergence, fatal errors.
  reports=$(grep -cE '^(Invalid|Uninitialized|Read-write|Write-write|Work-group divergence|Work-item|OCLGRIND)' "$log")
  echo "check_oclgrind: $name: exit $rc, $reports reports, $((SECONDS - start)) s"
  if [[ $rc -ne 0 || $reports -ne 0 ]]; then
    status=1
    head -40 "$log"
  fi
done
exit $status
