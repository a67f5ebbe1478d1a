#!/usr/bin/env bash
# Installs the Debian 12 packages that clppm's build and tests need. Idempotent: when everything is
# already installed it only queries dpkg and exits; `apt-get update` runs only if something
# is missing. Works as root, or through sudo otherwise.
set -euo pipefail

required=(
  pocl-opencl-icd ocl-icd-opencl-dev opencl-headers opencl-clhpp-headers clinfo
  libglm-dev libopenexr-dev libtinygltf-dev nlohmann-json3-dev libstb-dev libdraco-dev libwebp-dev
  libgtest-dev googletest libcli11-dev libcpp-httplib-dev cmake g++ make pkg-config python3
  clang-format clang-15 cppcheck openmpi-bin libopenmpi-dev
  pybind11-dev python3-dev python3-venv python3-numpy python3-pytest # the Python module and its tests
  libx11-6 libxrender1 libxfixes3 libxi6 libxext6 libxkbcommon0 libsm6 libgl1 # what PyPI's bpy links (the Blender add-on's tests)
)
# Optional: Embree (the CPU traversal yardstick) and gnuplot (plots) for the benchmarks; tests that
# need the others skip, saying so, without them.
optional=(libembree-dev gnuplot-nox chromium python3-matplotlib blender xvfb xauth oclgrind) # chromium: the live
# view's browser test; matplotlib: examples/alpha_sweep.py and volumetric_caustic.py; blender,
# xvfb: the add-on's check in Blender's own window (scripts/check_blender_ui.sh); oclgrind: the
# kernels' memory and race check (scripts/check_oclgrind.sh)

# Prints the packages of "$@" that are not fully installed (one dpkg-query for all of them).
missing_of() {
  local installed pkg
  installed=$(dpkg-query -W -f='${Package} ${Status}\n' "$@" 2>/dev/null | awk '$4 == "installed" { print $1 }' || true)
  for pkg in "$@"; do
    grep -Fqx -- "$pkg" <<<"$installed" || echo "$pkg"
  done
}

as_root() {
  if [[ $(id -u) -eq 0 ]]; then
    "$@"
  elif command -v sudo >/dev/null 2>&1; then
    sudo "$@"
  else
    echo "install-deps.sh: need root or sudo to run: $*" >&2
    exit 1
  fi
}

mapfile -t missing < <(missing_of "${required[@]}")
mapfile -t missing_optional < <(missing_of "${optional[@]}")
if [[ ${#missing[@]} -eq 0 && ${#missing_optional[@]} -eq 0 ]]; then
  exit 0
fi

export DEBIAN_FRONTEND=noninteractive
# sudo drops the environment, so the variable is passed through env explicitly.
apt_install() { as_root env DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends "$@"; }

if [[ ${#missing[@]} -gt 0 ]]; then
  echo "install-deps.sh: installing ${missing[*]}" >&2
  as_root apt-get update -q
  apt_install "${missing[@]}"
fi

# Optional packages are tried only if the package lists know them: refreshing the lists just for
# an optional package would make every run slow where it is not in the archive.
if [[ ${#missing_optional[@]} -gt 0 ]]; then
  if apt-cache show "${missing_optional[@]}" >/dev/null 2>&1; then
    apt_install "${missing_optional[@]}" ||
      echo "install-deps.sh: optional ${missing_optional[*]} could not be installed (continuing)" >&2
  else
    echo "install-deps.sh: optional ${missing_optional[*]} not available (continuing)" >&2
  fi
fi
