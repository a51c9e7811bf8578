"""What the Python package's tests (tests/python/test_*.py) share.

ctest runs each file as `/usr/bin/python3 -m pytest -q -p no:cacheprovider FILE`
(python/CMakeLists.txt) with
- PYTHONPATH: the build tree's package folder (build/python), so the package under test is the
  one just built, not an installed one,
- NEOMESH: the command line built with it (the tests compare the two),
- NEOMESH_SOURCE: the source tree,
- NEOMESH_MPIEXEC: Open MPI's mpiexec; without it the 2-rank tests are skipped.
By hand, from the source tree:
    PYTHONPATH=build/python NEOMESH=build/neomesh python3 -m pytest -q tests/python
"""
import os
import shutil
import subprocess

import pytest

NEOMESH = os.path.abspath(os.environ["NEOMESH"]) if "NEOMESH" in os.environ else "neomesh"
SOURCE = os.path.abspath(os.environ.get(
    "NEOMESH_SOURCE", os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")))
MPIEXEC = os.environ.get("NEOMESH_MPIEXEC") or shutil.which("mpiexec")
DATA = os.path.join(SOURCE, "tests", "data")

needs_mpi = pytest.mark.skipif(MPIEXEC is None, reason="no mpiexec (NEOMESH_MPIEXEC)")


def child_environment():
    """The environment this process started with: importing neomesh initialized MPI, which put
    variables of its own into the process's environment, and an mpiexec started with them fails
    without a word."""
    return dict(os.environ)


def run(args, cwd=None, timeout=300):
    """Runs `args`, failing the test with its output unless it exits with 0."""
    proc = subprocess.run([str(a) for a in args], cwd=cwd, capture_output=True, text=True,
                          timeout=timeout, env=child_environment())
    assert proc.returncode == 0, (f"{' '.join(map(str, args))}: exit {proc.returncode}\n"
                                  f"stdout:\n{proc.stdout[-3000:]}\nstderr:\n{proc.stderr[-3000:]}")
    return proc


def neomesh_cli(*args, cwd=None):
    return run([NEOMESH, *args], cwd=cwd)


def mpiexec(ranks, sessions):
    return [MPIEXEC, "--allow-run-as-root", "--oversubscribe", "--mca", "orte_tmpdir_base",
            sessions, "-n", str(ranks)]
