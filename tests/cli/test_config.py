"""--config FILE: options of a subcommand in its [section], top-level options at the top,
command-line values win; a misspelled key is an error (see test_bad_inputs.py)."""
import json
import os
import subprocess
import sys
import tempfile

NEOMESH = os.path.abspath(os.environ["NEOMESH"]) if "NEOMESH" in os.environ else "neomesh"
SOURCE = os.environ.get("NEOMESH_SOURCE",
                        os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
MESH = os.path.join(SOURCE, "tests", "data", "square_tri_v41.msh")

CONFIG = """# neomesh options; command-line values win
quiet = true

[smooth]
lambda = 2
kmin = 3
linear-solver = "jacobi"
no-table = true
"""


def smooth(tmp, *extra):
    report = os.path.join(tmp, "report.json")
    proc = subprocess.run([NEOMESH, "--config", os.path.join(tmp, "run.toml"), "smooth", MESH,
                           "-o", os.path.join(tmp, "out.msh"), "--report", report, *extra],
                          capture_output=True, text=True, timeout=60)
    if proc.returncode != 0:
        sys.exit(f"smooth with --config failed:\n{proc.stdout}\n{proc.stderr}")
    with open(report) as f:
        return proc.stdout, json.load(f)


def check(condition, message):
    if not condition:
        sys.exit(message)


def main():
    with tempfile.TemporaryDirectory() as tmp:
        with open(os.path.join(tmp, "run.toml"), "w") as f:
            f.write(CONFIG)
        out, report = smooth(tmp)
        check(report["energy_options"]["lambda"] == 2.0, f"lambda from config: {report}")
        check(report["solver_options"]["kmin"] == 3, f"kmin from config: {report}")
        check(report["solver_options"]["linear_solver"] == "jacobi", f"solver: {report}")
        # quiet = true at the top level: only the final summary.
        check("reading" not in out and "stopped after" in out, f"quiet from config: {out}")

        out, report = smooth(tmp, "--kmin", "4", "--linear-solver", "amg")
        check(report["solver_options"]["kmin"] == 4, f"command line must win: {report}")
        check(report["solver_options"]["linear_solver"] == "amg", f"command line: {report}")
        check(report["energy_options"]["lambda"] == 2.0, f"config still applies: {report}")
        # Defaults that --thesis changes back: the Riesz tolerance (1e-3 vs the thesis' 1e-8)
        # unless given; the δ̃ solve preconditioned by L's hierarchy unless --hess-pc hessian.
        check(report["solver_options"]["riesz_rtol"] == 1e-3, f"Riesz default: {report}")
        check(report["solver_options"]["hessian_pc"] == "laplacian", f"hess-pc: {report}")
        _, report = smooth(tmp, "--linear-solver", "amg", "--thesis", "--hess-pc", "hessian")
        check(report["solver_options"]["riesz_rtol"] == 1e-8, f"--thesis Riesz: {report}")
        check(report["solver_options"]["hessian_pc"] == "hessian", f"--hess-pc: {report}")
        _, report = smooth(tmp, "--thesis", "--riesz-rtol", "1e-5")
        check(report["solver_options"]["riesz_rtol"] == 1e-5, f"--riesz-rtol wins: {report}")
    print("config file OK")


if __name__ == "__main__":
    main()
