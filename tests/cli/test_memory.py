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
    env = dict(os.environ, NEOMESH_MEMORY_AVAILABLE_MIB="50")
    proc = subprocess.run([NEOMESH, "smooth", mesh, "-o", out], capture_output=True, text=True,
                          env=env)
    expect_one_error_line(proc, ["needs about", "GiB of memory", "available"], unwritten=[out])
    # 40,401 vertices of 2D: about 0.13 GiB, which 1 GiB holds.
    env["NEOMESH_MEMORY_AVAILABLE_MIB"] = "1024"
    assert subprocess.run([NEOMESH, "smooth", mesh, "-o", out, "--quiet"], env=env,
                          capture_output=True).returncode == 0
