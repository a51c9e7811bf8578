"""neomesh generate + quality as a user runs them: the thesis' Table 5.1 mesh, every case
at a small level, and the errors for inconsistent size options."""
import concurrent.futures
import json
import os
import subprocess
import sys
import tempfile

NEOMESH = os.environ.get("NEOMESH", "neomesh")


def run(*args, expect=0):
    proc = subprocess.run([NEOMESH, *args], capture_output=True, text=True, timeout=120)
    if proc.returncode != expect:
        sys.exit(f"neomesh {' '.join(args)}: exit {proc.returncode}, expected {expect}\n"
                 f"stdout:\n{proc.stdout}\nstderr:\n{proc.stderr}")
    return proc.stdout + proc.stderr


def check(condition, message):
    if not condition:
        sys.exit(message)


def main():
    with tempfile.TemporaryDirectory() as tmp:
        square = os.path.join(tmp, "square.msh")
        out = run("generate", "square-midpoint", "--level", "3", "-o", square)
        check("256 quadrilaterals, 289 vertices" in out, f"generate reported: {out}")

        report = os.path.join(tmp, "quality.json")
        out = run("quality", square, "--json", report)
        check("256 quadrilaterals" in out, f"quality reported: {out}")
        check("inverted cells: 0," in out, f"quality reported: {out}")
        with open(report) as f:
            summary = json.load(f)
        check(summary["cells"]["total"] == 256, f"json: {summary}")
        check(summary["cells"]["quadrilateral"] == 256, f"json: {summary}")
        check(summary["inverted"] == 0 and summary["degenerate"] == 0, f"json: {summary}")
        check(abs(summary["metrics"]["volume"]["mean"] - 1 / 256) < 1e-12, f"json: {summary}")

        # Two processes print the same summary as one (the mesh is distributed, the
        # statistics reduced over the ranks).
        mpiexec = os.environ.get("NEOMESH_MPIEXEC")
        if mpiexec:
            proc = subprocess.run([mpiexec, "--allow-run-as-root", "--oversubscribe", "-n", "2",
                                   NEOMESH, "quality", square], capture_output=True, text=True,
                                  timeout=120)
            check(proc.returncode == 0, f"mpiexec -n 2 quality failed:\n{proc.stderr}")
            check(proc.stdout == out, f"2 ranks printed:\n{proc.stdout}\n1 rank:\n{out}")

        # Every case at a small level: expected cell count, nothing inverted.
        cases = {
            "square-midpoint": (1, "16 quadrilaterals"),
            "cube-midpoint": (1, "64 hexahedra"),
            "square-random": (3, "64 quadrilaterals"),
            "transition": (2, "80 quadrilaterals"),
            "circle-quad": (2, "80 quadrilaterals"),
            "triangle-equilateral": (3, "64 triangles"),
            "triangle-curved": (2, "128 triangles"),
            "box-quad": (2, "16 quadrilaterals"),
            "box-tri": (2, "32 triangles"),
            "box-hex": (2, "64 hexahedra"),
            "box-tet": (2, "384 tetrahedra"),
        }
        def generate_and_check(name):
            level, cells = cases[name]
            path = os.path.join(tmp, f"{name}.msh")
            out = run("generate", name, "--level", str(level), "--rotate", "27", "-o", path)
            check(cells in out, f"generate {name}: {out}")
            out = run("quality", path)
            check(cells in out and "inverted cells: 0," in out, f"quality of {name}: {out}")

        # Each run mostly waits for MPI start-up: run the cases side by side.
        with concurrent.futures.ThreadPoolExecutor(max_workers=4) as pool:
            list(pool.map(generate_and_check, cases))

        out = run("generate", "transition", "--cells", "4", "-o", square, expect=1)
        check("--level" in out, f"transition --cells: {out}")
        run("generate", "box-quad", "-o", square, expect=1)
        run("generate", "no-such-case", "--level", "1", "-o", square, expect=1)


if __name__ == "__main__":
    main()
