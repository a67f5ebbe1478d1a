"""Every bad input raises clppm.Error with the command line's one-line message."""
import os

import pytest

import clppm
from conftest import SMALL, cli_args


@pytest.mark.parametrize(
    "options",
    [
        dict(alpha=1.5),
        dict(width=0),
        dict(radius=0),
        dict(passes=0),
        dict(integrator="mlt"),
        dict(photons=0),
        dict(env_color="1,2"),
        dict(filter="tent", integrator="vcm"),
        dict(error_bound=True),
        dict(radius=1e6),
        dict(aperture=1e30, integrator="vcm"),
        dict(device="no-such-device"),
        dict(env="/nonexistent/sky.hdr"),
        dict(variant="Red"),  # the built-in scene has none
    ],
)
def test_the_command_lines_message(options, run_cli):
    options = dict(SMALL, passes=1, **options) if "passes" not in options else dict(SMALL, **options)
    with pytest.raises(clppm.Error) as python:
        clppm.render(**options)
    status, err = run_cli(*cli_args(options), "-o", "/tmp/never-written.exr")
    assert status == 1
    assert err.strip().splitlines()[-1] == "clppm: error: " + str(python.value)


def test_a_missing_scene_names_the_file():
    with pytest.raises(clppm.Error, match="/no/such/scene.gltf"):
        clppm.render("/no/such/scene.gltf")
    with pytest.raises(clppm.Error, match="must be a .gltf or .glb file"):
        clppm.render("scene.obj")


def test_python_side_checks():
    with pytest.raises(clppm.Error, match=r"unknown option pases \(did you mean passes\?\)"):
        clppm.render(pases=3)
    with pytest.raises(clppm.Error, match="--no-png 'yes': must be True or False"):
        clppm.render(no_png="yes")
    with pytest.raises(clppm.Error, match="--passes True: must be an integer"):
        clppm.render(passes=True)
    with pytest.raises(clppm.Error, match="--progressive-output: needs an output image"):
        clppm.render(progressive_output=2)


def test_a_finished_renderer_says_so():
    r = clppm.Renderer(**dict(SMALL, passes=1))
    r.render()
    with pytest.raises(clppm.Error, match="has finished its render"):
        r.run_pass()
    r.close()
