"""The package on 2 ranks with mpi4py: the same calls on a communicator give the serial
run's mesh (to round-off) and a Result on every rank."""
import json
import os
import subprocess
import sys

import numpy as np

import neomesh
from conftest import NEOMESH, child_environment, mpiexec, needs_mpi, neomesh_cli, run

HERE = os.path.dirname(os.path.abspath(__file__))


@needs_mpi
def test_two_ranks_give_the_serial_result(tmp_path):
    source = tmp_path / "in.msh"
    neomesh_cli("generate", "box-quad", "--cells", "16", "--jitter", "0.2", "-o", source)
    out = subprocess.run([*mpiexec(2, str(tmp_path)), sys.executable,
                          os.path.join(HERE, "mpi_smooth.py"), str(source)],
                         capture_output=True, text=True, timeout=120,
                         env=child_environment())
    assert out.returncode == 0, out.stdout + out.stderr
    parallel = json.loads(out.stdout.strip().splitlines()[-1])
    assert parallel["ranks"] == 2 and parallel["processes"] == 2
    assert parallel["groups"] == sorted(neomesh.Mesh.read(str(source)).to_meshio().cell_sets)
    assert len(parallel["groups"]) >= 4  # box-quad's sides

    mesh = neomesh.Mesh.read(str(source))
    result = neomesh.smooth(mesh)
    smoothed = mesh.points
    adapted = neomesh.adapt(mesh, lambda p: np.hypot(p[:, 0], p[:, 1]) - 0.5, max_iter=10)
    assert parallel["iterations"] == result.iterations
    assert parallel["adapt_iterations"] == adapted.iterations
    # 2 ranks stop at the practical criterion a few 1e-8 away from 1 rank's mesh (the command
    # line's too: another partition sums in another order) ...
    smooth_difference = np.abs(np.array(parallel["smoothed"]) - smoothed).max()
    adapt_difference = np.abs(np.array(parallel["points"]) - mesh.points).max()
    print(f"2 ranks vs 1: smooth {smooth_difference:.2e}, adapt {adapt_difference:.2e}")
    assert smooth_difference < 1e-6 and adapt_difference < 1e-6
    # ... and exactly where the command line on 2 ranks stops
    run([*mpiexec(2, str(tmp_path)), NEOMESH, "smooth", source, "-o", tmp_path / "cli.msh"])
    cli = neomesh.Mesh.read(str(tmp_path / "cli.msh")).points
    assert np.abs(np.array(parallel["smoothed"]) - cli).max() <= 1e-12
