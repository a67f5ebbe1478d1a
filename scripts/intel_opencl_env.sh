#!/usr/bin/env bash
# Sourced: installs Intel's CPU OpenCL runtime from PyPI into BUILD_DIR/intel-opencl (kept between
# runs) and exports OCL_ICD_VENDORS and LD_LIBRARY_PATH so that the OpenCL loader lists it beside
# the system's implementations (PoCL). Returns 77, saying why, where PyPI cannot be reached or the
# runtime lists no device on this CPU; 1 on other failures.
#   source scripts/intel_opencl_env.sh BUILD_DIR || exit $?
intel_opencl_env() {
  local build venv vendors devices f
  build=$(cd "$1" && pwd) || return 1
  venv=$build/intel-opencl
  # Pinned: a new runtime is a new compiler, and gets a run of the implementations test first.
  local packages=(intel-opencl-rt==2026.2.0 intel-cmplr-lib-rt==2026.2.0)
  if [[ ! -f $venv/lib/libintelocl.so ]]; then
    python3 -m venv "$venv" || { echo "intel_opencl_env: cannot create $venv" >&2; return 1; }
    if ! "$venv/bin/pip" install -q --disable-pip-version-check "${packages[@]}"; then
      echo "intel_opencl_env: Intel's CPU runtime could not be installed from PyPI" >&2
      return 77
    fi
  fi
  [[ -f $venv/lib/libintelocl.so ]] || { echo "intel_opencl_env: $venv/lib/libintelocl.so missing" >&2; return 1; }
  # An ICD folder that names both implementations: the system's and Intel's.
  vendors=$venv/vendors
  mkdir -p "$vendors"
  rm -f "$vendors"/*.icd
  for f in /etc/OpenCL/vendors/*.icd; do [[ -e $f ]] && cp "$f" "$vendors/"; done
  echo "$venv/lib/libintelocl.so" >"$vendors/intel-cpu-runtime.icd"
  export OCL_ICD_VENDORS=$vendors
  export LD_LIBRARY_PATH=$venv/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}
  devices=$("$build/clppm" --list-devices 2>&1)
  if ! grep -q "platform: Intel(R) OpenCL" <<<"$devices"; then
    echo "intel_opencl_env: Intel's CPU runtime lists no device on this CPU:" >&2
    echo "$devices" >&2
    return 77
  fi
}
intel_opencl_env "$@"
