"""Under mpirun the module renders as the command line's processes do: every rank holds the image
of one process, bit for bit, and rank 0 alone writes the output."""
import os
import shutil
import subprocess
import sys
import textwrap

import numpy as np
import pytest

import clppm
from conftest import cli_args

SCRIPT = textwrap.dedent(
    """
    import sys, numpy as np, clppm
    integrator, out = sys.argv[1], sys.argv[2]
    image = clppm.render(width=48, height=32, photons=12000, passes=4, seed=7, quiet=True,
                         integrator=integrator, output=out + ".exr", no_png=True)
    np.save(f"{out}.{clppm.mpi_rank}.npy", image)
    with open(f"{out}.{clppm.mpi_rank}.txt", "w") as f:  # the ranks' stdout interleaves
        f.write(f"rank {clppm.mpi_rank} of {clppm.mpi_size}")
    """
)


@pytest.mark.parametrize("integrator", ["sppm", "pt", "vcm"])
def test_two_ranks_give_one_processs_image(integrator, tmp_path, cli_image):
    if not shutil.which("mpirun"):
        pytest.skip("mpirun is not installed (openmpi-bin)")
    out = str(tmp_path / "mpi")
    p = subprocess.run(["mpirun", "--allow-run-as-root", "--oversubscribe", "-np", "2", sys.executable, "-c", SCRIPT,
                        integrator, out], capture_output=True, text=True, timeout=300)
    said = [open(f"{out}.{r}.txt").read() if os.path.exists(f"{out}.{r}.txt") else "" for r in (0, 1)]
    if "rank 0 of 1" in said:
        pytest.skip("this clppm module was built without MPI: each process rendered alone")
    assert p.returncode == 0, p.stderr
    assert said == ["rank 0 of 2", "rank 1 of 2"], said
    one = cli_image(width=48, height=32, photons=12000, passes=4, seed=7, quiet=True, integrator=integrator)
    assert np.array_equal(clppm.read_exr(out + ".exr"), one)
    for rank in (0, 1):
        assert np.array_equal(np.load(f"{out}.{rank}.npy"), one)
