#!/usr/bin/env python3
"""The meshes of the comparison with Mesquite and MFEM's TMOP (issue 15), timed the way that
comparison timed neomesh: whole program, `neomesh smooth IN -o OUT.vtu --quiet` with fixed
boundary vertices, median of several runs on a quiet machine. Prints a markdown table with the
peers' figures quoted from the issue (measured on this machine with Mesquite 2.3 and MFEM 4.5).

    bench/peers.py                  # every row, 3 runs each (a few minutes)
    bench/peers.py --runs 1 --only quads-300

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

# name, generate arguments, Mesquite s, TMOP s, Mesquite's mean inverse mean ratio
ROWS = [
    ("quads-300", ["square-random", "--cells", "300", "--amplitude", "0.24"], 1.28, 17.9, 1.00000),
    ("triangles-300", ["box-tri", "--cells", "300", "--jitter", "0.24"], 1.48, 34.4, 1.15470),
    ("hexes-40", ["box-hex", "--cells", "40", "--jitter", "0.12"], 1.45, 19.1, 1.00000),
    ("tets-40", ["box-tet", "--cells", "40", "--jitter", "0.12"], 1.74, 16.6, 1.32283),
    ("quads-1024", ["square-random", "--cells", "1024", "--amplitude", "0.24"], 41.2, None,
     1.00000),
    ("quads-100", ["square-random", "--cells", "100", "--amplitude", "0.24"], None, None, None),
    ("hexes-20", ["box-hex", "--cells", "20", "--jitter", "0.12"], None, None, None),
    ("square-midpoint-1024", ["square-midpoint", "--level", "9"], None, None, None),
    # The issue's quarter annuli (its peers' meshes are not in the repository: ours are
    # 1 <= r <= 2, 0 <= theta <= 90 deg, z in [0, 1], jittered like the boxes).
    ("annulus-quads", ["annulus-quad", "--cells", "100", "--jitter", "0.24"], 0.15, 1.16, None),
    ("annulus-triangles", ["annulus-tri", "--cells", "100", "--jitter", "0.24"], 0.16, 1.82,
     None),
    ("annulus-hexes", ["annulus-hex", "--cells", "20", "--jitter", "0.12"], 0.15, 1.96, None),
    ("annulus-tets", ["annulus-tet", "--cells", "20", "--jitter", "0.12"], 0.21, 2.05, None),
]
# The thesis' problem (uniform desired volumes, optimum = the uniform grid), as bench/run.py.
EXTRA_ARGS = {"square-midpoint-1024": ["--sizes", "uniform"]}


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--runs", type=int, default=3)
    parser.add_argument("--only", action="append", help="row name (repeatable)")
    args = parser.parse_args()
    neomesh = os.environ.get("NEOMESH", os.path.join(HERE, "..", "build", "neomesh"))
    print("| mesh | cells | neomesh s (solve part) | iterations | mean IMR after | Mesquite s | "
          "TMOP s | Mesquite's mean IMR |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|")
    with tempfile.TemporaryDirectory() as work:
        for name, generate, mesquite, tmop, mesquite_imr in ROWS:
            if args.only and name not in args.only:
                continue
            mesh = os.path.join(work, name + ".msh")
            subprocess.run([neomesh, "generate", *generate, "-o", mesh], check=True,
                           capture_output=True)
            walls, report = [], None
            for _ in range(args.runs):
                out, report_file = os.path.join(work, "out.vtu"), os.path.join(work, "r.json")
                start = time.monotonic()
                subprocess.run([neomesh, "smooth", mesh, "-o", out, "--force", "--quiet",
                                "--boundary", "fixed", "--report", report_file, *EXTRA_ARGS.get(name, [])],
                               check=True, stdout=subprocess.DEVNULL)
                walls.append(time.monotonic() - start)
                with open(report_file) as f:
                    report = json.load(f)
            t = report["result"]["times"]
            solve = sum(t.values())
            imr = report["quality_after"]["metrics"]["inverse_mean_ratio"]["mean"]
            quote = lambda x, fmt: "—" if x is None else fmt.format(x)
            print(f"| {name} | {report['cells']:,} | {statistics.median(walls):.2f} ({solve:.2f}) "
                  f"| {report['result']['iterations']} | {imr:.5f} | {quote(mesquite, '{:.2f}')} "
                  f"| {quote(tmop, '{:.1f}')} | {quote(mesquite_imr, '{:.5f}')} |")
            sys.stdout.flush()


if __name__ == "__main__":
    main()
