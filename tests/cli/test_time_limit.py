"""--time-limit SECONDS: a run that would take longer ends with the best mesh so far (every
iterate is valid) and says so; a tangled mesh not untangled by then is an error, with no output.
Run with NEOMESH=path/to/neomesh."""
import json
import os

from conftest import expect_nothing_else_changed, expect_one_error_line, neomesh


def test_the_limit_ends_the_run_with_the_mesh_so_far(tmp):
    mesh = os.path.join(tmp, "in.msh")
    neomesh("generate", "box-hex", "--cells", 12, "--jitter", 0.2, "-o", mesh)
    out, report = os.path.join(tmp, "out.msh"), os.path.join(tmp, "r.json")
    proc = neomesh("smooth", mesh, "-o", out, "--report", report, "--time-limit", 1e-6)
    assert "time limit reached: the mesh is the best one so far" in proc.stdout
    with open(report) as f:
        r = json.load(f)
    assert r["result"]["iterations"] <= 1  # the limit is checked before each step
    assert r["result"]["stop_reason"].startswith("time limit reached")
    assert r["quality_after"]["inverted"] == 0
    expect_nothing_else_changed(mesh, out)
    neomesh("smooth", mesh, "-o", out, "--force", "--quiet", "--report", report)
    with open(report) as f:
        assert json.load(f)["result"]["iterations"] > 1


def test_a_tangled_mesh_not_untangled_in_time_is_an_error(tmp):
    mesh = os.path.join(tmp, "tangled.msh")
    neomesh("generate", "box-quad", "--cells", 30, "--jitter", 0.45, "-o", mesh)
    out = os.path.join(tmp, "out.msh")
    proc = neomesh("smooth", mesh, "-o", out, "--time-limit", 1e-6, expect=1)
    expect_one_error_line(proc, ["time limit ran out while untangling", "--time-limit"],
                          unwritten=[out])
