#!/usr/bin/env bash
# The kernels on a second OpenCL implementation (issue 58): installs Intel's CPU runtime from PyPI
# into a virtual environment under the build (kept between runs), lists it beside PoCL through an
# ICD folder of its own, and runs on it
#   - implementations_test: every integrator's image on Intel's runtime against PoCL's;
#   - the kernel-level tests (each kernel against its host reference) with CLPPM_TEST_DEVICE set
#     to Intel's device.
# Exits 77 (ctest: skipped), saying why, where PyPI cannot be reached or the runtime lists no
# device on this CPU.
# Usage: check_implementations.sh BUILD_DIR
set -uo pipefail
build=$(cd "$1" && pwd)
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
venv=$build/intel-opencl
# Pinned: a new runtime is a new compiler, and gets a run of this check before the pin moves.
packages=(intel-opencl-rt==2026.2.0 intel-cmplr-lib-rt==2026.2.0)

if [[ ! -f $venv/lib/libintelocl.so ]]; then
  python3 -m venv "$venv" || { echo "check_implementations: cannot create $venv" >&2; exit 1; }
  if ! "$venv/bin/pip" install -q --disable-pip-version-check "${packages[@]}"; then
    echo "check_implementations: skipped: Intel's CPU runtime could not be installed from PyPI" >&2
    exit 77
  fi
fi
[[ -f $venv/lib/libintelocl.so ]] || { echo "check_implementations: $venv/lib/libintelocl.so missing after install" >&2; exit 1; }

# An ICD folder that names both implementations: the system's (PoCL) and Intel's.
vendors=$venv/vendors
mkdir -p "$vendors"
rm -f "$vendors"/*.icd
for f in /etc/OpenCL/vendors/*.icd; do [[ -e $f ]] && cp "$f" "$vendors/"; done
echo "$venv/lib/libintelocl.so" >"$vendors/intel-cpu-runtime.icd"
export OCL_ICD_VENDORS=$vendors
export LD_LIBRARY_PATH=$venv/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}

devices=$("$build/clppm" --list-devices 2>&1)
if ! grep -q "platform: Intel(R) OpenCL" <<<"$devices"; then
  echo "check_implementations: skipped: Intel's CPU runtime lists no device on this CPU:" >&2
  echo "$devices" >&2
  exit 77
fi
echo "$devices"

status=0
"$build/tests/implementations_test" || status=1
# Each kernel against its host reference, on Intel's runtime (the render-level tests of these
# binaries run on PoCL in the main suite; the integrators' images are compared above).
export CLPPM_TEST_DEVICE="Intel(R) OpenCL"
for t in rng_test sobol_test sampling_test bvh_test ggx_test bsdf_test light_emission_test vcm_mis_test \
  gather_test ppm_update_test shared_types_test; do
  filter='-Sobol.PathTracerKeepsTheMeanAndLowersTheError' # renders: 6 minutes there, covered above
  echo "== $t on Intel's CPU runtime"
  "$build/tests/$t" --gtest_brief=1 --gtest_filter="$filter" || status=1
done
exit $status
