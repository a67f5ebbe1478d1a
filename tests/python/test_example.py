"""examples/alpha_sweep.py runs as a user would run it, at a tiny size, and writes its plot."""
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
