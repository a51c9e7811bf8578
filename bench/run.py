#!/usr/bin/env python3
"""Whole-program benchmarks of neomesh (issue 6): generates the meshes, runs
`neomesh smooth|adapt --report r.json` on each and prints one markdown table with cells,
dofs, iterations, Krylov iterations, time per phase and peak memory, all taken from the
program's own JSON report.

    bench/run.py --quick                 # small sizes, < 2 minutes
    bench/run.py --full -o table.md      # up to 2048² quads and 64³ hexes
    bench/run.py --only square-midpoint-1024 --ranks 2

Environment: NEOMESH (the binary, default build-perf/neomesh next to this script, then
`neomesh` on PATH), NEOMESH_MPIEXEC (mpiexec, for --ranks > 1). Stdlib only.
"""
import argparse
import json
import os
import shutil
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))

# Interior vertices of the jittered meshes move by up to this many cell widths per
# coordinate: about ±h/4 in 2D as in the Mesquite comparison (the generators need < 1/4);
# less in 3D, where 0.24 inverts some tetrahedra (box-tet --cells 26).
JITTER = {2: 0.24, 3: 0.12}


class Case:
    """One benchmark: how to generate its mesh and how to run neomesh on it. Smoothing keeps
    the boundary vertices fixed, as the peers' runs and the thesis do (smooth's default slides
    them)."""

    def __init__(self, name, generate, command="smooth", args=(), sizes=("quick", "full")):
        self.name, self.generate, self.command = name, generate, command
        self.args, self.sizes = list(args), sizes
        if command == "smooth":
            self.args += ["--boundary", "fixed"]


def cases():
    out = []
    # The thesis' levels: t = 3 … 10 is 16² … 2048² quads (docs/cases.md); uniform desired
    # volumes (the thesis' problem, optimum = uniform grid), practical stopping criterion.
    for t in range(3, 11):
        n = 2 ** (t + 1)
        out.append(Case(f"square-midpoint-{n}", ["square-midpoint", "--level", str(t)],
                        args=["--sizes", "uniform"],
                        sizes=("quick", "full") if n <= 256 else ("full",)))
    for t in range(3, 6):
        n = 2 ** (t + 1)
        out.append(Case(f"cube-midpoint-{n}", ["cube-midpoint", "--level", str(t)],
                        args=["--sizes", "uniform"],
                        sizes=("quick", "full") if n <= 16 else ("full",)))
    # Jittered meshes: Mesquite's sizes (300² quads, 2·300² triangles), then ~100k and ~1M.
    jittered = [("quad", "square-random", 2, [100, 300, 316, 1000]),
                ("tri", "box-tri", 2, [70, 300, 224, 708]),
                ("tet", "box-tet", 3, [12, 26, 55]),
                ("hex", "box-hex", 3, [16, 47, 100])]
    for kind, generator, dim, sizes in jittered:
        for i, n in enumerate(sizes):
            noise = ["--amplitude" if generator == "square-random" else "--jitter",
                     str(JITTER[dim])]
            out.append(Case(f"jitter-{kind}-{n}", [generator, "--cells", str(n), *noise],
                            args=["--sizes", "uniform"],
                            sizes=("quick", "full") if i == 0 else ("full",)))
    out.append(Case("adapt-circle-64", ["box-quad", "--level", "6"], command="adapt",
                    args=["--circle", "0,0,0.7"]))
    out.append(Case("adapt-circle-256", ["box-quad", "--level", "8"], command="adapt",
                    args=["--circle", "0,0,0.7"], sizes=("full",)))
    out.append(Case("adapt-sphere-16", ["box-hex", "--level", "4"], command="adapt",
                    args=["--sphere", "0,0,0,0.7"]))
    out.append(Case("adapt-sphere-64", ["box-hex", "--level", "6"], command="adapt",
                    args=["--sphere", "0,0,0,0.7"], sizes=("full",)))
    return out


def find_neomesh():
    if os.environ.get("NEOMESH"):
        return os.environ["NEOMESH"]
    local = os.path.join(HERE, "..", "build-perf", "neomesh")
    return local if os.path.exists(local) else shutil.which("neomesh") or "neomesh"


def run(cmd, log):
    with open(log, "w") as f:
        proc = subprocess.run(cmd, stdout=f, stderr=subprocess.STDOUT)
    if proc.returncode != 0:
        with open(log) as f:
            tail = f.read()[-2000:]
        sys.exit(f"{' '.join(cmd)} failed (exit {proc.returncode}):\n{tail}")


def run_case(case, neomesh, launcher, workdir, extra):
    mesh = os.path.join(workdir, f"{case.name}.msh")
    if not os.path.exists(mesh):  # meshes are kept between runs: generating is not timed
        run([neomesh, "generate", *case.generate, "-o", mesh + ".tmp.msh"],
            os.path.join(workdir, f"{case.name}.generate.log"))
        os.replace(mesh + ".tmp.msh", mesh)
    name = f"{case.name}-np{launcher[-1]}" if launcher else case.name  # launcher ends with P
    report = os.path.join(workdir, f"{name}.json")
    out = os.path.join(workdir, f"{name}.out.msh")
    start = time.monotonic()
    run([*launcher, neomesh, case.command, mesh, "-o", out, "--force", "--no-table", "--report",
         report, *case.args, *extra], os.path.join(workdir, f"{name}.log"))
    wall = time.monotonic() - start
    with open(report) as f:
        return json.load(f), wall


def row(case, r, wall):
    history = r["result"]["history"]
    t = r["result"]["times"]
    app = r["times"]
    cells = [
        case.name,
        f"{r['cells']:,}",
        f"{r['free_dofs']:,}",
        str(r["processes"]),
        str(len(history)),
        str(sum(h["krylov_delta"] for h in history)),
        str(sum(h["krylov_s"] for h in history)),
        f"{r['result']['final_defect']:.1e}",
    ]
    phases = [app["read"], app["prepare"] + t["setup"], t["gradient"], t["hessian_assembly"],
              t["hessian_setup"], t["hessian_solve"], t["riesz_setup"], t["riesz_solve"],
              t["line_search"], app["write"], r["seconds"], wall]
    cells += [f"{x:.2f}" for x in phases]
    cells.append(f"{r['peak_rss_mib']:,.0f}")
    cells.append(f"{r['quality_after']['metrics']['scaled_jacobian']['min']:.3f}")
    return cells


HEADER = ["case", "cells", "free dofs", "ranks", "Newton its", "Krylov δ", "Krylov s",
          "final defect", "read", "setup", "gradient", "H assembly", "H AMG setup",
          "δ solve", "L setup", "s solve", "line search", "write", "total", "wall",
          "peak RSS MiB", "min scaled Jacobian"]


def markdown(rows):
    lines = ["| " + " | ".join(HEADER) + " |",
             "|" + "|".join("---" if i == 0 else "---:" for i in range(len(HEADER))) + "|"]
    lines += ["| " + " | ".join(r) + " |" for r in rows]
    return "\n".join(lines) + "\n"


def main():
    p = argparse.ArgumentParser(description=__doc__,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    size = p.add_mutually_exclusive_group()
    size.add_argument("--quick", action="store_true", help="small sizes (default), < 2 minutes")
    size.add_argument("--full", action="store_true", help="every size, up to 2048² and 64³")
    p.add_argument("--only", action="append", default=[],
                   help="run only cases whose name starts with this (repeatable)")
    p.add_argument("--ranks", type=int, default=1, help="MPI processes per run")
    p.add_argument("--workdir", default=os.path.join(HERE, "..", "build-perf", "bench"),
                   help="meshes, reports and logs (meshes are reused)")
    p.add_argument("-o", "--output", help="also write the table to this file")
    p.add_argument("--list", action="store_true", help="list the cases and exit")
    p.add_argument("extra", nargs="*", help="more options for neomesh (after --)")
    a = p.parse_args()

    level = "full" if a.full else "quick"
    selected = [c for c in cases()
                if (any(c.name.startswith(o) for o in a.only) if a.only else level in c.sizes)]
    if a.list or not selected:
        print("\n".join(c.name for c in cases()))
        return 0 if a.list else 1
    neomesh = find_neomesh()
    launcher = []
    if a.ranks > 1:
        mpiexec = os.environ.get("NEOMESH_MPIEXEC", "mpiexec")
        launcher = [mpiexec, "--allow-run-as-root", "-n", str(a.ranks)]
    os.makedirs(a.workdir, exist_ok=True)

    rows = []
    for case in selected:
        report, wall = run_case(case, neomesh, launcher, a.workdir, a.extra)
        rows.append(row(case, report, wall))
        print(f"{case.name}: {report['seconds']:.2f} s", file=sys.stderr, flush=True)
    table = markdown(rows)
    sys.stdout.write(table)
    if a.output:
        with open(a.output, "w") as f:
            f.write(table)
    return 0


if __name__ == "__main__":
    sys.exit(main())
