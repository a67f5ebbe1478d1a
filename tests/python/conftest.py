"""Shared fixtures of the Python module's tests: the clppm command beside the module (CLPPM_BINARY,
set by ctest), and small renders of the built-in Cornell box that both front ends make."""
import os
import subprocess

import pytest

import clppm

# Small and quick: 40 x 30 pixels, a few passes, few photons.
SMALL = dict(width=40, height=30, photons=5000, seed=3, quiet=True)


def cli_args(options):
    """The command line's spelling of keyword options."""
    args = []
    for key, value in options.items():
        name = "--" + key.replace("_", "-")
        if value is True:
            args.append(name)
        else:
            args += [name, str(value)]
    return args


@pytest.fixture(scope="session")
def clppm_binary():
    path = os.environ.get("CLPPM_BINARY")
    if not path or not os.path.exists(path):
        pytest.fail("CLPPM_BINARY must name the clppm command of the same build (ctest sets it)")
    return path


@pytest.fixture
def run_cli(clppm_binary):
    """Runs the clppm command; returns (exit status, stderr)."""

    def run(*args, **kwargs):
        p = subprocess.run([clppm_binary, *map(str, args)], capture_output=True, text=True, timeout=600, **kwargs)
        return p.returncode, p.stderr

    return run


@pytest.fixture
def cli_image(run_cli, tmp_path):
    """Renders with the command line and returns its EXR as read back."""

    def render(scene=None, **options):
        out = tmp_path / "cli.exr"
        status, err = run_cli(*([scene] if scene else []), *cli_args(options), "--no-png", "-o", out)
        assert status == 0, err
        return clppm.read_exr(out)

    return render
