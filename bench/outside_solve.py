#!/usr/bin/env python3
"""Where a whole `neomesh smooth IN -o OUT.vtu --quiet --boundary fixed` run spends what lies
outside the optimization (start-up, reading, quality tables, targets, worst cells, writing,
exit), on the meshes of bench/peers.py: the wall-clock median of --runs runs with the report's
times, and with --callgrind the instructions of each phase (valgrind's callgrind, one OpenMP
thread so that every instruction is counted in the phase that asked for it).

    bench/outside_solve.py                            # hexes 40³ and the quarter annuli, 5 runs
    bench/outside_solve.py --callgrind --runs 0       # instructions per phase (a few minutes)
    bench/outside_solve.py --only annulus-hexes --runs 9

Environment: NEOMESH (the launcher, default build/neomesh next to this script; callgrind runs
the neomesh-main beside it, with the launcher's settings). Stdlib only.
"""
import argparse
import json
import os
import re
import statistics
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from peers import ROWS  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
DEFAULT = ["hexes-40", "annulus-quads", "annulus-triangles", "annulus-hexes"]

# Phase name, and the function whose inclusive instructions it is (callgrind_annotate's name).
PHASES = [
    ("dynamic loading", r":_dl_start "),
    ("PetscInitialize (MPI_Init)", r":PetscInitialize "),
    ("read: file, DMPlex, MeshView", r"OptimizationRun::Impl::read\("),
    ("memory fault-in", r"neomesh::keep_and_fault_in\("),
    ("quality before", r"Optimizer::Impl::input_quality\("),
    ("boundary, functional", r"Optimizer::Impl::start\(neomesh::EnergyOptions"),
    ("set-up: the targets, the input's means", r"Optimizer::Impl::set_up_smoothing\("),
    ("  of which the targets", r"Optimizer::Impl::smoothing_targets\("),
    ("inversion check", r"Optimizer::Impl::untangle\("),
    ("minimize (the solve)", r"neomesh::minimize\("),
    ("corner phase", r"Optimizer::Impl::lift_corners\("),
    ("worst-cell repair", r"Optimizer::Impl::repair_worst\("),
    ("quality guard", r"Optimizer::Impl::guard_worst\("),
    ("mean guard (the input returned: its repair too)", r"Optimizer::Impl::guard_mean\("),
    ("quality after", r"Optimizer::Impl::finish\("),
    ("write", r"OptimizationRun::snapshot\("),
    ("  of which the cell fields (energy, det G, Q)", r"Functional::cell_fields\("),
    ("PetscFinalize", r":PetscFinalize "),
]
LAUNCHER_ENV = {"GLIBC_TUNABLES": "glibc.malloc.hugetlb=0", "OMP_WAIT_POLICY": "PASSIVE"}


def smooth_args(mesh, out, report):
    return ["smooth", mesh, "-o", out, "--force", "--quiet", "--boundary", "fixed", "--report",
            report]


def callgrind(neomesh, mesh, work):
    main = os.path.join(os.path.dirname(neomesh), "neomesh-main")
    out = os.path.join(work, "callgrind.out")
    env = dict(os.environ, OMP_NUM_THREADS="1", **LAUNCHER_ENV)
    subprocess.run(["valgrind", "--tool=callgrind", f"--callgrind-out-file={out}", main,
                    *smooth_args(mesh, os.path.join(work, "cg.vtu"), os.path.join(work, "cg.json"))],
                   check=True, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    text = subprocess.run(["callgrind_annotate", "--inclusive=yes", "--threshold=100", out],
                          check=True, capture_output=True, text=True).stdout
    counts = {}
    total = re.search(r"^\s*([\d,]+) \(100.0%\)\s+PROGRAM TOTALS", text, re.M)
    counts["total"] = int(total.group(1).replace(",", ""))
    for name, pattern in PHASES:
        line = re.search(r"^\s*([\d,]+) \(.*" + pattern, text, re.M)
        counts[name] = int(line.group(1).replace(",", "")) if line else 0
    return counts


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--runs", type=int, default=5, help="timed runs per mesh (median)")
    parser.add_argument("--pause", type=float, default=2.0, help="seconds before each run")
    parser.add_argument("--only", action="append", help="row name of bench/peers.py (repeatable)")
    parser.add_argument("--callgrind", action="store_true", help="instructions per phase")
    args = parser.parse_args()
    neomesh = os.environ.get("NEOMESH", os.path.join(HERE, "..", "build", "neomesh"))
    names = args.only or DEFAULT
    rows = {name: generate for name, generate, *_ in ROWS}
    with tempfile.TemporaryDirectory() as work:
        for name in names:
            mesh = os.path.join(work, name + ".msh")
            subprocess.run([neomesh, "generate", *rows[name], "-o", mesh], check=True,
                           capture_output=True)
            out, report = os.path.join(work, "out.vtu"), os.path.join(work, "r.json")
            walls, reports = [], []
            for _ in range(args.runs):
                time.sleep(args.pause)
                start = time.monotonic()
                subprocess.run([neomesh, *smooth_args(mesh, out, report)], check=True,
                               stdout=subprocess.DEVNULL)
                walls.append(time.monotonic() - start)
                with open(report) as f:
                    reports.append(json.load(f))
            if reports:
                wall = statistics.median(walls)
                solve = statistics.median(sum(r["result"]["times"].values()) for r in reports)
                app = {k: statistics.median(r["times"][k] for r in reports)
                       for k in ("read", "prepare", "write")}
                print(f"{name}: {reports[0]['cells']:,} cells, wall {wall:.3f} s (median of "
                      f"{len(walls)}), solve {solve:.3f} s, outside the solve {wall - solve:.3f} s "
                      f"({100 * (wall - solve) / wall:.0f} %); read {app['read']:.3f}, prepare "
                      f"{app['prepare']:.3f}, write {app['write']:.3f} s; load "
                      f"{os.getloadavg()[0]:.1f}")
            if args.callgrind:
                counts = callgrind(neomesh, mesh, work)
                print(f"{name}: instructions (millions, one thread)")
                for key, value in counts.items():
                    print(f"  {key:32s} {value / 1e6:10.1f}")
            sys.stdout.flush()


if __name__ == "__main__":
    main()
