"""The practical criterion's Newton half (docs/method.md §6): a run stops after a full Newton
step that moved no vertex more than --newton-move-rtol (default 1e-2) of its cell size, since
the step after it would move them by about the square of that. On a jittered box of 16³
hexahedra the last full Newton step moves 1.8e-3 of a cell: the default stops there, one
iteration before 1e-3 does, at the same mesh quality."""
import json

from conftest import neomesh


def smooth(tmp, mesh, name, *options):
    report = tmp / f"{name}.json"
    neomesh("smooth", mesh, "-o", tmp / f"{name}.msh", "--boundary", "fixed", "--quiet",
            "--report", report, *options)
    return json.loads(report.read_text())


def test_the_default_newton_half_skips_the_step_of_the_square(tmp_path):
    mesh = tmp_path / "box.msh"
    neomesh("generate", "box-hex", "--cells", "16", "--jitter", "0.12", "-o", mesh)
    default = smooth(tmp_path, mesh, "default")
    tighter = smooth(tmp_path, mesh, "tighter", "--newton-move-rtol", "1e-3")
    last = default["result"]["history"][-1]
    assert default["result"]["stop_reason"].startswith("practical criterion")
    assert 1e-3 < last["max_move"] < 1e-2 and last["alpha"] == 1 and last["armijo_steps"] == 0
    assert default["result"]["iterations"] + 1 == tighter["result"]["iterations"]
    for metric in ("inverse_mean_ratio", "scaled_jacobian"):
        for stat in ("min", "mean"):
            a = default["quality_after"]["metrics"][metric][stat]
            b = tighter["quality_after"]["metrics"][metric][stat]
            assert abs(a - b) <= 1e-6 * abs(b), f"{metric} {stat}: {a} against {b}"
