"""How many OpenMP threads `smooth` runs on (the report's "threads"; src/app/optimization.cpp,
share_cores): OMP_NUM_THREADS when the user sets it; otherwise one for a mesh too small for a
second thread to pay, one per core above that, whatever else the machine runs: the thread count
changes the last bits of the result (neomesh's sums over cells and OpenBLAS's vector reductions
run per thread), and the same command must give the same mesh."""
import json
import os
import subprocess

from conftest import NEOMESH, neomesh


def threads_of(tmp, cells, env_threads=None):
    mesh, report = tmp / f"box{cells}.msh", tmp / "report.json"
    if not mesh.exists():
        neomesh("generate", "box-quad", "--cells", str(cells), "--jitter", "0.2", "-o", mesh)
    env = dict(os.environ)
    env.pop("OMP_NUM_THREADS", None)
    if env_threads is not None:
        env["OMP_NUM_THREADS"] = str(env_threads)
    subprocess.run([NEOMESH, "smooth", mesh, "-o", tmp / "out.msh", "--boundary", "fixed",
                    "--quiet", "--report", report], env=env, check=True, capture_output=True)
    return json.loads(report.read_text())["threads"]


def test_a_small_mesh_runs_on_one_thread(tmp_path):
    assert threads_of(tmp_path, 20) == 1


def test_the_users_thread_count_wins(tmp_path):
    assert threads_of(tmp_path, 20, env_threads=3) == 3


def test_busy_cores_do_not_change_the_result(tmp_path):
    # 151² vertices × 2² is above the work that a second thread needs to pay off.
    out = tmp_path / "out.msh"
    quiet_threads = threads_of(tmp_path, 150)
    quiet = out.read_bytes()
    busy = [subprocess.Popen(["sh", "-c", "while :; do :; done"])
            for _ in range(os.cpu_count() or 1)]
    try:
        assert threads_of(tmp_path, 150) == quiet_threads
    finally:
        for process in busy:
            process.kill()
            process.wait()
    assert out.read_bytes() == quiet
