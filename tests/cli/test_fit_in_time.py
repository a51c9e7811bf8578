"""`adapt --fit --time`: a circle of radius 0.2 rising through 16x16 quads and triangles in 6
steps, with the checks of bench/adapt_moving.py (the full sizes): at every step no inverted
cell, every interface vertex within 1e-10 of that step's zero set, cells at the interface at
most 1/4 the mean volume of cells farther than 0.5, meshio reads every member of the .pvd, and
every step after the first needs at most half the iterations of the first (cold) one. The quads
also on 2 processes."""
import os
import sys

import pytest

from conftest import NEOMESH, SOURCE, mpiexec, needs_mpi

sys.path.insert(0, os.path.join(SOURCE, "bench"))
import adapt_moving  # noqa: E402


@pytest.mark.parametrize("cell", ["quad", "tri"])
def test_bubble(tmp, cell):
    rows, failures = adapt_moving.run_bubble(NEOMESH, cell, 16, 6, tmp)
    for r in rows:
        print(f"bubble {cell} 16: {r}")
    adapt_moving.report(failures)  # exits on a failure


@needs_mpi
def test_bubble_on_two_processes(tmp):
    rows, failures = adapt_moving.run_bubble(NEOMESH, "quad", 16, 6, tmp, launcher=mpiexec(2))
    for r in rows:
        print(f"bubble quad 16 on 2: {r}")
    adapt_moving.report(failures)
