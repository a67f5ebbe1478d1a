"""The add-on's tests run in Blender as a Python module (PyPI's bpy) with the add-on and the clppm
module on the path (scripts/test_blender.sh sets it up)."""
import os
import sys

import pytest

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.join(HERE, "..", "..", "blender"))

import bpy  # noqa: E402

import clppm_blender  # noqa: E402


@pytest.fixture(scope="session", autouse=True)
def addon():
    clppm_blender.register()
    yield clppm_blender
    clppm_blender.unregister()
