#!/usr/bin/env bash
# The Blender add-on's tests (tests/blender), headless, in Blender as a Python module: PyPI's bpy
# in a virtual environment kept between runs (WORK_DIR/bpy-venv, with pytest), the add-on
# (blender/) and the clppm module of this build on the path. Exits 77 (ctest: skipped), saying
# so, when bpy is not installed and the package index cannot be reached.
# Usage: test_blender.sh PYTHON WORK_DIR MODULE_DIR CLPPM
set -euo pipefail
python=$1 dir=$2 module=$3 clppm=$4
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
venv=$dir/bpy-venv
if ! "$venv/bin/python" -c "import bpy, pytest" >/dev/null 2>&1; then
  rm -rf "$venv"
  "$python" -m venv "$venv"
  # Skipped only when the package index cannot be reached; any other failure to install fails.
  if ! "$venv/bin/python" -m pip index versions --disable-pip-version-check --retries 1 --timeout 20 bpy >/dev/null 2>&1; then
    echo "test_blender: skipped: the package index (for PyPI's bpy) cannot be reached"
    rm -rf "$venv"
    exit 77
  fi
  # bpy is built for one Python (3.11 for Blender 4.2 to 5.0: Debian 12's); pip picks the newest
  # release built for this one.
  "$venv/bin/python" -m pip install --quiet --disable-pip-version-check "bpy>=4.2" pytest
  if ! err=$("$venv/bin/python" -c "import bpy, pytest" 2>&1); then
    echo "test_blender: bpy is installed but does not import (scripts/install-deps.sh installs the libraries it links): $(tail -1 <<<"$err")"
    exit 1
  fi
fi
echo "test_blender: Blender $("$venv/bin/python" -c 'import bpy; print(bpy.app.version_string)' 2>/dev/null | tail -1)"
cd "$root"
PYTHONPATH="$module" CLPPM_BINARY="$clppm" exec "$venv/bin/python" -m pytest -q -p no:cacheprovider -s tests/blender
