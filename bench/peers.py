#!/usr/bin/env python3
"""The meshes of the comparison with Mesquite and MFEM's TMOP, timed the way the peers' side of
that comparison was: whole program, `neomesh smooth IN -o OUT.vtu --quiet` with fixed boundary
vertices, median of several runs on a quiet machine. Prints a markdown table with the peers'
figures quoted from the issues that measured them on this machine: Mesquite 2.99 (feasible
Newton on the inverse mean ratio, skin fixed; optimisation alone and read + optimise + write of
VTK legacy; issue 30) and MFEM 4.5's TMOP (metric 2/303, Newton and MINRES-Jacobi; issue 15).

    bench/peers.py                  # every row, 3 runs each (a few minutes)
    bench/peers.py --runs 1 --only quads-300
    bench/peers.py -- --targets ideal   # more options for every neomesh run

Each run starts --pause seconds (default 3) after the one before, as a user's runs do: this VM
hands memory freed by a process back to its host within a second or two, and a run started at
once would reuse the last one's pages instead of the fresh memory a user's run gets
(docs/benchmarks.md, "Huge pages"). --pause 0 times runs back to back.

Environment: NEOMESH (the binary; default build/neomesh next to this script). Stdlib only.
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))

# name, generate arguments, Mesquite optimise s, Mesquite total s, Mesquite iterations, TMOP s,
# Mesquite's mean inverse mean ratio (issue 15, on its own meshes of the same kind)
ROWS = [
    ("quads-300", ["square-random", "--cells", "300", "--amplitude", "0.24"], 1.09, 1.19, 7, 17.9,
     1.00000),
    ("triangles-300", ["box-tri", "--cells", "300", "--jitter", "0.24"], 1.16, 1.33, 12, 34.4,
     1.15470),
    ("hexes-40", ["box-hex", "--cells", "40", "--jitter", "0.12"], 1.08, 1.33, 3, 19.1, 1.00000),
    ("tets-40", ["box-tet", "--cells", "40", "--jitter", "0.12"], 0.79, 2.50, 3, 16.6, 1.32283),
    ("quads-1024", ["square-random", "--cells", "1024", "--amplitude", "0.24"], 28.8, 29.8, 12,
     None, 1.00000),
    ("quads-100", ["square-random", "--cells", "100", "--amplitude", "0.24"], None, None, None,
     None, None),
    ("hexes-20", ["box-hex", "--cells", "20", "--jitter", "0.12"], None, None, None, None, None),
    ("square-midpoint-1024", ["square-midpoint", "--level", "9"], None, None, None, None, None),
    # The issues' quarter annuli (the peers' meshes are not in the repository: ours are
    # 1 <= r <= 2, 0 <= theta <= 90 deg, z in [0, 1], jittered like the boxes).
    ("annulus-quads", ["annulus-quad", "--cells", "100", "--jitter", "0.24"], 0.13, 0.14, 7, 1.16,
     None),
    ("annulus-triangles", ["annulus-tri", "--cells", "100", "--jitter", "0.24"], 0.10, 0.12, 7,
     1.82, None),
    ("annulus-hexes", ["annulus-hex", "--cells", "20", "--jitter", "0.12"], 0.08, 0.11, 3, 1.96,
     None),
    ("annulus-tets", ["annulus-tet", "--cells", "20", "--jitter", "0.12"], 0.08, 0.28, 3, 2.05,
     None),
]
# The thesis' problem (uniform desired volumes, optimum = the uniform grid), as bench/run.py.
EXTRA_ARGS = {"square-midpoint-1024": ["--sizes", "uniform"]}


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--runs", type=int, default=3)
    parser.add_argument("--only", action="append", help="row name (repeatable)")
    parser.add_argument("--pause", type=float, default=3.0,
                        help="seconds before each run (default 3; see above)")
    parser.add_argument("extra", nargs="*", help="more options for neomesh (after --)")
    args = parser.parse_args()
    neomesh = os.environ.get("NEOMESH", os.path.join(HERE, "..", "build", "neomesh"))
    print("| mesh | cells | neomesh s (solve part) | iterations | mean IMR after | Mesquite "
          "optimise / total s (iterations) | neomesh / Mesquite total | TMOP s | "
          "Mesquite's mean IMR |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|---:|")
    with tempfile.TemporaryDirectory() as work:
        for name, generate, optimise, total, its, tmop, mesquite_imr in ROWS:
            if args.only and name not in args.only:
                continue
            mesh = os.path.join(work, name + ".msh")
            subprocess.run([neomesh, "generate", *generate, "-o", mesh], check=True,
                           capture_output=True)
            walls, report = [], None
            for _ in range(args.runs):
                out, report_file = os.path.join(work, "out.vtu"), os.path.join(work, "r.json")
                time.sleep(args.pause)
                start = time.monotonic()
                subprocess.run([neomesh, "smooth", mesh, "-o", out, "--force", "--quiet",
                                "--boundary", "fixed", "--report", report_file,
                                *EXTRA_ARGS.get(name, []), *args.extra],
                               check=True, stdout=subprocess.DEVNULL)
                walls.append(time.monotonic() - start)
                with open(report_file) as f:
                    report = json.load(f)
            t = report["result"]["times"]
            solve = sum(t.values())
            imr = report["quality_after"]["metrics"]["inverse_mean_ratio"]["mean"]
            wall = statistics.median(walls)
            quote = lambda x, fmt: "—" if x is None else fmt.format(x)
            mesquite = "—" if total is None else f"{optimise:.2f} / {total:.2f} ({its})"
            ratio = "—" if total is None else f"{wall / total:.2f}"
            print(f"| {name} | {report['cells']:,} | {wall:.2f} ({solve:.2f}) "
                  f"| {report['result']['iterations']} | {imr:.5f} | {mesquite} | {ratio} "
                  f"| {quote(tmop, '{:.1f}')} | {quote(mesquite_imr, '{:.5f}')} |")
            sys.stdout.flush()


if __name__ == "__main__":
    main()
