"""A run that will not fit in memory is refused before it starts, in one line, instead of being
killed by the kernel without a word (src/api/memory_check.hpp). NEOMESH_MEMORY_AVAILABLE_MIB
stands in for a small machine. Run with NEOMESH=path/to/neomesh."""
import os
import subprocess

from conftest import NEOMESH, expect_one_error_line, neomesh


def test_a_run_larger_than_the_memory_is_refused_before_it_starts(tmp):
    mesh = os.path.join(tmp, "in.msh")
    neomesh("generate", "box-quad", "--cells", 200, "--jitter", 0.2, "-o", mesh)
    out = os.path.join(tmp, "out.msh")
    env = dict(os.environ, NEOMESH_MEMORY_AVAILABLE_MIB="20")
    proc = subprocess.run([NEOMESH, "smooth", mesh, "-o", out], capture_output=True, text=True,
                          env=env)
    expect_one_error_line(proc, ["needs about", "MiB of memory", "more than it holds", "available"],
                          unwritten=[out])
    # 40,401 vertices of 2D: about 113 MiB at the peak, which 1 GiB holds.
    env["NEOMESH_MEMORY_AVAILABLE_MIB"] = "1024"
    assert subprocess.run([NEOMESH, "smooth", mesh, "-o", out, "--quiet"], env=env,
                          capture_output=True).returncode == 0


def test_what_the_run_already_holds_is_not_counted_twice(tmp):
    """The estimate is the run's peak; the libraries and the mesh it has read are part of it and
    already in memory (square-midpoint 4096²: 4.3 of its 21 GiB, refused before with 18.6 GiB
    available, runs at a peak of 20.1 GiB)."""
    mesh = os.path.join(tmp, "in.msh")
    neomesh("generate", "box-quad", "--cells", 200, "--jitter", 0.2, "-o", mesh)
    out = os.path.join(tmp, "out.msh")
    # Less than the 113 MiB estimate, more than what the run still needs beyond the 60 MiB of
    # libraries and the mesh.
    env = dict(os.environ, NEOMESH_MEMORY_AVAILABLE_MIB="100")
    proc = subprocess.run([NEOMESH, "smooth", mesh, "-o", out, "--quiet"], env=env,
                          capture_output=True, text=True)
    assert proc.returncode == 0, proc.stderr
    assert os.path.exists(out)


def test_a_hierarchy_of_the_hessian_is_counted(tmp):
    """--hess-pc hessian builds an AMG hierarchy of H(α) too, about 2.35 times the memory beyond
    the libraries on quads: admitted with the default preconditioner, refused with that one."""
    mesh = os.path.join(tmp, "in.msh")
    neomesh("generate", "box-quad", "--cells", 200, "--jitter", 0.2, "-o", mesh)
    out = os.path.join(tmp, "out.msh")
    # The default run needs about 40 MiB more than it holds, the other about 110 MiB.
    env = dict(os.environ, NEOMESH_MEMORY_AVAILABLE_MIB="80")
    assert subprocess.run([NEOMESH, "smooth", mesh, "-o", out, "--quiet"], env=env,
                          capture_output=True).returncode == 0
    os.remove(out)
    proc = subprocess.run([NEOMESH, "smooth", mesh, "-o", out, "--hess-pc", "hessian"],
                          capture_output=True, text=True, env=env)
    expect_one_error_line(proc, ["needs about", "more than it holds", "available"],
                          unwritten=[out])
