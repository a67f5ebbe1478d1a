#!/usr/bin/env bash
# Compiles every OpenCL program clppm builds as strict OpenCL C 1.2 for two targets other than
# PoCL's: SPIR (the portable intermediate, no vendor builtins) and NVIDIA's PTX
# (nvptx64-nvidia-nvcl, which has no 64-bit atomics, so the 32-bit fallback in fixed_point.cl is
# what compiles there). A kernel that used an x86 builtin, a PoCL-only function, an extension
# without its guard, or a construct clang rejects for either target fails here, on a machine
# without a GPU. It checks compilation only: what a GPU computes is for the device runs
# (bench/RESULTS.md, "Closer to the hardware").
#
#   scripts/check_kernel_portability.sh [CLANG]     (default: clang-15, the one PoCL uses)
#
# Each program is compiled generic (every feature in), with every feature out, with both eye-slot
# counts and the tent filter, and with CLPPM_NO_INT64_ATOMICS; warnings are errors.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/../kernels"
clang=${1:-clang-15}
command -v "$clang" >/dev/null || { echo "check_kernel_portability: $clang not found (Debian: clang-15)" >&2; exit 1; }

programs=(sppm_program.cl ppm_program.cl path_trace.cl vcm_program.cl trace_rays.cl)
targets=(spir64 nvptx64-nvidia-nvcl)
# Every feature flag kernel_features.h lists, switched off.
none=$(sed -n 's/^ *X(\(HAS_[A-Z_]*\),.*/-D\1=0/p' kernel_features.h | tr '\n' ' ')
[[ -n $none ]] || { echo "check_kernel_portability: no HAS_ flags found in kernel_features.h" >&2; exit 1; }
variants=(
  "-DEYE_SLOTS=1"
  "-DEYE_SLOTS=4 -DPIXEL_FILTER_TENT"
  "-DEYE_SLOTS=1 $none"
  "-DEYE_SLOTS=4 -DCLPPM_NO_INT64_ATOMICS"
  "-DEYE_SLOTS=1 -DPHOTON_VISUAL_IMPORTANCE -DPATH_SAMPLER_INDEPENDENT"
)
failed=0
n=0
for program in "${programs[@]}"; do
  for target in "${targets[@]}"; do
    for variant in "${variants[@]}"; do
      # shellcheck disable=SC2086 # variant is a list of options
      if ! out=$("$clang" -x cl -cl-std=CL1.2 -target "$target" -Xclang -finclude-default-header \
        -D__OPENCL_VERSION__=120 $variant -Wall -Werror -c -emit-llvm -o /dev/null "$program" 2>&1); then
        echo "check_kernel_portability: $program for $target ($variant) does not compile:" >&2
        echo "$out" | head -20 >&2
        failed=1
      fi
      n=$((n + 1))
    done
  done
done
[[ $failed -eq 0 ]] || exit 1
echo "check_kernel_portability: $n builds (${#programs[@]} programs, ${targets[*]}) compile as OpenCL C 1.2"
