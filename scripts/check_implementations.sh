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
source "$here/scripts/intel_opencl_env.sh" "$build"
rc=$?
if [[ $rc -ne 0 ]]; then
  [[ $rc -eq 77 ]] && echo "check_implementations: skipped (above)" >&2
  exit $rc
fi
"$build/clppm" --list-devices

status=0
CLPPM_REQUIRE_IMPLEMENTATIONS=1 "$build/tests/implementations_test" || status=1
# Each kernel against its host reference, on Intel's runtime (the render-level tests of these
# binaries run on PoCL in the main suite; the integrators' images are compared above).
export CLPPM_TEST_DEVICE="Intel(R) OpenCL"
filter='-Sobol.PathTracerKeepsTheMeanAndLowersTheError' # renders: 6 minutes there, covered above
for t in rng_test sobol_test sampling_test bvh_test ggx_test bsdf_test bsdf_model_test extension_lobes_test \
  multiple_scattering_test light_emission_test vcm_mis_test gather_test ppm_update_test shared_types_test \
  disc_coverage_test medium_test; do
  echo "== $t on Intel's CPU runtime"
  "$build/tests/$t" --gtest_brief=1 --gtest_filter="$filter" || status=1
done
exit $status
