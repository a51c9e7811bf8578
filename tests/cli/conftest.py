"""What the whole-program tests (tests/cli/test_*.py) share: the neomesh executable under test
and how to run it, the source tree's data, a fresh directory per test, meshio reading.

ctest runs each file as `/usr/bin/python3 -m pytest -q -p no:cacheprovider FILE`
(tests/CMakeLists.txt) with
- NEOMESH: the executable (default: `neomesh` on PATH),
- NEOMESH_SOURCE: the source tree (default: two folders up from here),
- NEOMESH_MPIEXEC: Open MPI's mpiexec; without it the 2-rank tests are skipped.
Debian's /usr/bin/python3 because the tests import meshio from python3-meshio, which another
python3 (a venv's, pyenv's) does not see. The test files import the helpers below
(`from conftest import ...`) and take the fixtures as arguments. The figures the tests print
show with pytest's -s, e.g. from the build directory:
    NEOMESH=$PWD/neomesh python3 -m pytest -s -p no:cacheprovider ../tests/cli/test_untangle.py
"""
import atexit
import contextlib
import io
import os
import shutil
import subprocess
import tempfile

import pytest

NEOMESH = os.path.abspath(os.environ["NEOMESH"]) if "NEOMESH" in os.environ else "neomesh"
SOURCE = os.path.abspath(os.environ.get(
    "NEOMESH_SOURCE", os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")))
MPIEXEC = os.environ.get("NEOMESH_MPIEXEC") or None
DATA = os.path.join(SOURCE, "tests", "data")
EXAMPLES = os.path.join(SOURCE, "examples")


# Open MPI's session directory for this process's launches. Under the default, /tmp/ompi.HOST.UID,
# two mpiexec that ctest -j starts at the same moment can both try to create it, and the loser
# aborts with "mkdir ... File exists" (Open MPI 4.1).
MPI_SESSIONS = tempfile.mkdtemp(prefix="neomesh-test-mpiexec-")
atexit.register(shutil.rmtree, MPI_SESSIONS, ignore_errors=True)


def mpiexec(ranks=2, *options):
    """The launcher of a run on `ranks` processes (as root and on 2 cores, as CI runs it);
    [] for one rank."""
    if ranks == 1:
        return []
    return [MPIEXEC, "--allow-run-as-root", "--oversubscribe", "--mca", "orte_tmpdir_base",
            MPI_SESSIONS, *options, "-n", str(ranks)]


# Marks a test that needs mpiexec (NEOMESH_MPIEXEC); skipped, and said so, without it.
needs_mpi = pytest.mark.skipif(MPIEXEC is None, reason="NEOMESH_MPIEXEC is not set")
# The rank counts to run a test with: 1, and 2 where NEOMESH_MPIEXEC is set.
RANKS = [1, pytest.param(2, marks=needs_mpi)]


def describe(proc):
    command = " ".join(a if len(a) < 100 else a[:20] + "..." for a in proc.args)
    return (f"{command}: exit {proc.returncode}\nstdout:\n{proc.stdout[-4000:]}\n"
            f"stderr:\n{proc.stderr[-4000:]}")


def run(args, cwd=None, expect=0, timeout=300):
    """Runs the command `args` (a list) and returns its CompletedProcess (text stdout and
    stderr); fails the test, showing both, unless it exits with `expect` (None: any code)."""
    proc = subprocess.run([str(a) for a in args], cwd=cwd, capture_output=True, text=True,
                          timeout=timeout)
    assert expect is None or proc.returncode == expect, \
        f"expected exit {expect}\n{describe(proc)}"
    return proc


def neomesh(*args, cwd=None, expect=0, ranks=1, timeout=300):
    """`neomesh ARGS...` (under mpiexec for ranks > 1), as run()."""
    return run([*mpiexec(ranks), NEOMESH, *args], cwd=cwd, expect=expect, timeout=timeout)


def expect_one_error_line(proc, words=(), unwritten=()):
    """The run failed as a user must see it: exit code 1, one line on stderr,
    `neomesh: error: ...`, holding every one of `words`, and none of the files `unwritten`
    exists. Returns that line."""
    lines = proc.stderr.strip().splitlines()
    assert proc.returncode == 1 and len(lines) == 1 and lines[0].startswith("neomesh: error:"), \
        f"not one error line and exit 1\n{describe(proc)}"
    missing = [w for w in words if w not in lines[0]]
    assert not missing, f"the message lacks {missing}: {lines[0]}"
    left = [f for f in unwritten if os.path.exists(f)]
    assert not left, f"written despite the error: {left}"
    return lines[0]


def read_mesh(path):
    """meshio's reading of `path`, its progress and warnings kept off the output."""
    import meshio  # only the tests that read meshes need it (python3-meshio)
    with contextlib.redirect_stdout(io.StringIO()):
        return meshio.read(path)


CORPUS = os.path.abspath(os.path.join(SOURCE, "..", "shared", "corpus"))
# Marks a test over the real meshes of ../shared/corpus; skipped, and said so, without them.
needs_corpus = pytest.mark.skipif(not os.path.isdir(CORPUS),
                                  reason=f"the real meshes are not at {CORPUS}")


def vtk_to_msh(vtk, msh):
    """A VTK legacy file as a Gmsh 2.2 file (every cell in physical group 1), through meshio."""
    import meshio
    import numpy as np
    m = read_mesh(vtk)
    cells = [(c.type, c.data) for c in m.cells if c.type != "vertex"]
    tags = {k: [np.ones(len(d), int) for _, d in cells] for k in ("gmsh:physical", "gmsh:geometrical")}
    with contextlib.redirect_stdout(io.StringIO()):
        meshio.write(msh, meshio.Mesh(m.points, cells, cell_data=tags), file_format="gmsh22",
                     binary=False)


def boundary_vertices(mesh):
    """The vertices of facets that belong to one cell only (meshio mesh of 2D or 3D cells)."""
    import collections
    faces = {"triangle": [(0, 1), (1, 2), (2, 0)], "quad": [(0, 1), (1, 2), (2, 3), (3, 0)],
             "tetra": [(0, 1, 2), (0, 1, 3), (1, 2, 3), (0, 2, 3)],
             "hexahedron": [(0, 1, 2, 3), (4, 5, 6, 7), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6),
                            (3, 0, 4, 7)],
             "wedge": [(0, 1, 2), (3, 4, 5), (0, 1, 4, 3), (1, 2, 5, 4), (2, 0, 3, 5)],
             "pyramid": [(0, 1, 2, 3), (0, 1, 4), (1, 2, 4), (2, 3, 4), (3, 0, 4)]}
    count = collections.Counter()
    for block in mesh.cells:
        for cell in block.data:
            for face in faces.get(block.type, []):
                count[frozenset(int(cell[i]) for i in face)] += 1
    return sorted({v for face, n in count.items() if n == 1 for v in face})


SOLIDS = ("tetra", "hexahedron", "wedge", "pyramid")


def expect_nothing_else_changed(before, after, fixed_boundary=False):
    """What a run must never change, for the output `after` of the input `before` (paths of files
    meshio reads): the points (count and numbering), the cells (each the same vertices, in input
    order), the physical groups of cells, the plane a 2D mesh lies in and, with
    `fixed_boundary`, every coordinate of a boundary vertex, bit for bit."""
    import numpy as np
    a, b = read_mesh(before), read_mesh(after)
    assert len(a.points) == len(b.points), "the number of points changed"
    solid = any(c.type in SOLIDS for c in a.cells)
    top = SOLIDS if solid else ("triangle", "quad")
    cells = lambda m: sorted((c.type, tuple(sorted(cell))) for c in m.cells if c.type in top
                             for cell in c.data.tolist())
    assert cells(a) == cells(b), "the cells changed"
    if "gmsh:physical" in a.cell_data and "gmsh:physical" in b.cell_data:
        groups = lambda m: sorted((c.type, int(t)) for c, d in
                                  zip(m.cells, m.cell_data["gmsh:physical"]) if c.type in top
                                  for t in d)
        assert groups(a) == groups(b), "the physical groups of the cells changed"
    if not solid:
        centre = a.points.mean(0)
        normal = np.linalg.svd(a.points - centre, full_matrices=False)[2][-1]
        scale = np.abs(a.points - centre).max()
        off_in = np.abs((a.points - centre) @ normal).max()
        off_out = np.abs((b.points - centre) @ normal).max()
        assert off_out <= max(off_in, 1e-12 * scale), \
            f"the mesh left its plane: {off_out:.3g} off it (input {off_in:.3g})"
    if fixed_boundary:
        fixed = boundary_vertices(a)
        moved = [v for v in fixed if not np.array_equal(a.points[v], b.points[v])]
        assert not moved, f"{len(moved)} fixed boundary vertices moved, e.g. {moved[:3]}"


def fresh_directory():
    """A new empty directory, and a function that removes it."""
    path = tempfile.mkdtemp(prefix="neomesh-cli-")
    return path, lambda: shutil.rmtree(path, ignore_errors=True)


@pytest.fixture
def tmp():
    """A fresh directory for one test (a str), removed afterwards."""
    path, remove = fresh_directory()
    yield path
    remove()


@pytest.fixture(scope="module")
def module_tmp():
    """A directory the tests of one file share (inputs made once), removed after them."""
    path, remove = fresh_directory()
    yield path
    remove()
