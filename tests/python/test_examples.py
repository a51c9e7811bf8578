"""The scripts of examples/python run as documented and make what they say they make."""
import importlib.util
import os
import re
import sys

import pytest

from conftest import SOURCE, mpiexec, needs_mpi, run

EXAMPLES = os.path.join(SOURCE, "examples", "python")


def example(name, tmp_path, ranks=1):
    launcher = mpiexec(ranks, str(tmp_path)) if ranks > 1 else []
    return run([*launcher, sys.executable, os.path.join(EXAMPLES, name)], cwd=tmp_path).stdout


# Not imported here: importing gmsh sets SIGINT to its default action for the whole process,
# and Ctrl-C would then end the test run instead of raising KeyboardInterrupt.
@pytest.mark.skipif(importlib.util.find_spec("gmsh") is None, reason="no gmsh module")
def test_gmsh_smooth_plot(tmp_path):
    out = example("gmsh_smooth_plot.py", tmp_path)
    before, after = map(float, re.search(r"min scaled Jacobian ([\d.]+) -> ([\d.]+)", out).groups())
    assert after > before
    assert (tmp_path / "plate-python.png").stat().st_size > 10_000


def test_moving_level_set(tmp_path):
    out = example("moving_level_set.py", tmp_path)
    steps = [int(n) for n in re.findall(r"step \d+, t = [\d.]+: (\d+) iterations", out)]
    assert len(steps) == 6 and max(steps[1:]) < steps[0]  # warm steps are shorter
    pvd = (tmp_path / "moving.pvd").read_text()
    assert pvd.count("<DataSet") == 6
    assert all((tmp_path / f"moving-{i:04d}.vtu").exists() for i in range(6))


@pytest.mark.parametrize("ranks", [1, pytest.param(2, marks=needs_mpi)])
def test_dmplex_roundtrip(tmp_path, ranks):
    out = example("dmplex_roundtrip.py", tmp_path, ranks)
    assert f"on {ranks} process(es): scaled Jacobian min 0.783 -> 1.000" in out
