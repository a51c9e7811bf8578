"""--config FILE: options of a subcommand in its [section], top-level options at the top,
command-line values win; a misspelled key is an error (see test_bad_inputs.py)."""
import json
import os

import pytest

from conftest import DATA, neomesh

MESH = os.path.join(DATA, "square_tri_v41.msh")

CONFIG = """# neomesh options; command-line values win
quiet = true

[smooth]
lambda = 2
kmin = 3
linear-solver = "jacobi"
no-table = true
"""


@pytest.fixture
def smooth(tmp):
    """`neomesh --config run.toml smooth MESH ... EXTRA`: (stdout, report)."""
    with open(os.path.join(tmp, "run.toml"), "w") as f:
        f.write(CONFIG)

    def run(*extra):
        report = os.path.join(tmp, "report.json")
        proc = neomesh("--config", os.path.join(tmp, "run.toml"), "smooth", MESH,
                       "-o", os.path.join(tmp, "out.msh"), "--report", report, *extra,
                       timeout=60)
        with open(report) as f:
            return proc.stdout, json.load(f)
    return run


def test_options_from_the_config_file(smooth):
    out, report = smooth()
    assert report["energy_options"]["lambda"] == 2.0, f"lambda from config: {report}"
    assert report["solver_options"]["kmin"] == 3, f"kmin from config: {report}"
    assert report["solver_options"]["linear_solver"] == "jacobi", f"solver: {report}"
    # quiet = true at the top level: only the final summary.
    assert "reading" not in out and "stopped after" in out, f"quiet from config: {out}"


def test_the_command_line_wins(smooth):
    _, report = smooth("--kmin", "4", "--linear-solver", "amg")
    assert report["solver_options"]["kmin"] == 4, f"command line must win: {report}"
    assert report["solver_options"]["linear_solver"] == "amg", f"command line: {report}"
    assert report["energy_options"]["lambda"] == 2.0, f"config still applies: {report}"
    # Defaults that --thesis changes back: the Riesz tolerance (1e-3 vs the thesis' 1e-8)
    # unless given; the δ̃ solve preconditioned by L's hierarchy unless --hess-pc hessian.
    assert report["solver_options"]["riesz_rtol"] == 1e-3, f"Riesz default: {report}"
    assert report["solver_options"]["hessian_forcing_max"] == 1e-2, f"forcing: {report}"
    assert report["solver_options"]["max_trial_move"] == 64, f"trial move: {report}"
    assert report["solver_options"]["lazy_riesz"] is True, f"lazy Riesz: {report}"
    assert report["solver_options"]["hessian_pc"] == "laplacian", f"hess-pc: {report}"


def test_thesis_defaults_and_what_wins_over_them(smooth):
    _, report = smooth("--linear-solver", "amg", "--thesis", "--hess-pc", "hessian")
    assert report["solver_options"]["riesz_rtol"] == 1e-8, f"--thesis Riesz: {report}"
    assert report["solver_options"]["hessian_forcing_max"] == 0, f"--thesis forcing: {report}"
    assert report["solver_options"]["max_trial_move"] == 0, f"--thesis trial move: {report}"
    assert report["solver_options"]["lazy_riesz"] is False, f"--thesis lazy Riesz: {report}"
    assert report["solver_options"]["hessian_pc"] == "hessian", f"--hess-pc: {report}"
    _, report = smooth("--thesis", "--riesz-rtol", "1e-5")
    assert report["solver_options"]["riesz_rtol"] == 1e-5, f"--riesz-rtol wins: {report}"
    _, report = smooth("--thesis", "--hess-forcing-max", "0.05")
    assert report["solver_options"]["hessian_forcing_max"] == 0.05, f"forcing wins: {report}"
    _, report = smooth("--thesis", "--max-trial-move", "8")
    assert report["solver_options"]["max_trial_move"] == 8, f"trial move wins: {report}"
    # Every option given explicitly wins over --thesis, not only those above.
    _, report = smooth("--thesis", "--gauss", "2", "--sizes", "input")
    assert report["energy_options"]["gauss_points"] == 2, f"--gauss wins: {report}"
    assert report["smooth_options"]["sizes"] == "input", f"--sizes wins: {report}"
    assert report["boundary_options"]["mode"] == "fixed", f"--thesis boundary: {report}"


def test_riesz_solve_every_step_or_when_the_angle_test_needs_it(smooth):
    # Default (AMG): the quasi-Newton steps estimate η with one V-cycle and skip the solve.
    _, report = smooth("--linear-solver", "amg")
    history = report["result"]["history"]
    assert any(not h["s_solved"] and not h["used_s"] for h in history), f"lazy: {history}"
    assert all(h["s_solved"] for h in history if h["used_s"]), f"-s needs s: {history}"
    _, report = smooth("--linear-solver", "amg", "--riesz-every-step")
    assert report["solver_options"]["lazy_riesz"] is False, f"--riesz-every-step: {report}"
    assert all(h["s_solved"] for h in report["result"]["history"]), f"s every step: {report}"


def petsc_option_examples():
    """The `neomesh smooth in.msh -o out.msh -...` lines of the user guide's PETSc options."""
    with open(os.path.join(os.path.dirname(DATA), "..", "docs", "user-guide.md")) as f:
        text = f.read()
    section = text[text.index("**PETSc options.**"):]
    section = section[:section.index("\n\n", section.index("    neomesh"))]
    return [line.split("#")[0].split()[5:] for line in section.splitlines()
            if line.startswith("    neomesh smooth in.msh -o out.msh ")]


@pytest.mark.parametrize("options", petsc_option_examples(), ids=" ".join)
def test_the_user_guides_petsc_options_run(tmp, options):
    """Each documented example ends well: MINRES, for one, gives no unpreconditioned residual,
    which neomesh asks for unless told otherwise."""
    assert options, "the user guide lists no PETSc options"
    neomesh("smooth", MESH, "-o", "out.msh", "--quiet", *options, cwd=tmp, timeout=120)
    assert os.path.exists(os.path.join(tmp, "out.msh"))
