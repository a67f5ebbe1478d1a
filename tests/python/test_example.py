"""The examples run as a user would run them, at a tiny size, and write their plots."""
import os
import subprocess
import sys

import pytest

EXAMPLE = os.path.join(os.path.dirname(__file__), "..", "..", "examples", "alpha_sweep.py")


def test_alpha_sweep_writes_its_plot(tmp_path):
    pytest.importorskip("matplotlib")
    out = tmp_path / "sweep.png"
    p = subprocess.run([sys.executable, EXAMPLE, "--alphas", "0.5,0.9", "--seconds", "1", "--size", "24",
                        "--photons", "5000", "--reference-passes", "20", "--out", str(out)],
                       capture_output=True, text=True, timeout=300)
    assert p.returncode == 0, p.stderr
    assert "alpha 0.5:" in p.stdout and "alpha 0.9:" in p.stdout
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_volumetric_caustic_writes_its_plot(tmp_path):
    """examples/volumetric_caustic.py: the fogged Cornell box by every integrator that renders media."""
    pytest.importorskip("matplotlib")
    out = tmp_path / "caustic.png"
    example = os.path.join(os.path.dirname(EXAMPLE), "volumetric_caustic.py")
    p = subprocess.run([sys.executable, example, "--seconds", "1", "--size", "24", "--photons", "5000",
                        "--reference-passes", "10", "--out", str(out)], capture_output=True, text=True, timeout=300)
    assert p.returncode == 0, p.stderr
    for integrator in ("sppm", "pppm", "ppm", "pt"):
        assert integrator + ":" in p.stdout, p.stdout
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
