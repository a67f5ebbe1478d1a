#!/usr/bin/env bash
# `pip install .` as the README gives it: a fresh virtual environment, the package built from this
# repository by its CMake (pyproject.toml: scikit-build-core and pybind11 from PyPI), then a render
# through the installed module that must equal the clppm command's image bit for bit, and the
# clppm command the wheel installs. Exits 77 (ctest: skipped) when the package index cannot be
# reached. Usage: check_pip_install.sh PYTHON WORK_DIR CLPPM
set -euo pipefail
python=$1 dir=$2 clppm=$3
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
mkdir -p "$dir"
rm -rf "$dir/venv" "$dir/probe"
"$python" -m venv "$dir/venv"
pip=("$dir/venv/bin/python" -m pip --disable-pip-version-check)
if ! "${pip[@]}" download --quiet --no-deps --dest "$dir/probe" scikit-build-core >/dev/null 2>&1; then
  echo "check_pip_install: skipped: the package index cannot be reached (pip download scikit-build-core failed)"
  exit 77
fi
# The build folder is kept, so that a second run rebuilds only what changed.
"${pip[@]}" install --quiet --config-settings=build-dir="$dir/build" "$root"
cd "$dir"
"$clppm" --width 24 --height 16 --passes 2 --photons 3000 --seed 5 --quiet --no-png -o cli.exr
"$dir/venv/bin/clppm" --version
"$dir/venv/bin/python" - <<'PY'
import numpy as np, clppm
image = clppm.render(width=24, height=16, passes=2, photons=3000, seed=5, quiet=True)
assert clppm.__file__.startswith(__import__("sys").prefix), clppm.__file__  # the installed package
assert np.array_equal(image, clppm.read_exr("cli.exr")), "the installed module's image differs from the command line's"
print("check_pip_install: pip install . gave", clppm.__file__, "and the command line's image bit for bit")
PY
