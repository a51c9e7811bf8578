#!/usr/bin/python3
"""Untangling (docs/untangling.md) as a benchmark: tangled meshes made from neomesh's boxes and
the example plate, smoothed by `neomesh smooth` (untangling first), one table row per case:
inverted cells before and after, the untangling phase's iterations, rounds of epsilon and
seconds, the Neo-Hookean phase's iterations, the output's minimum scaled Jacobian and the
whole program's wall time.

    bench/untangle.py                 # every case; prints a Markdown table
    bench/untangle.py --only bump     # the cases whose name contains "bump"

Tangled meshes: boxes jittered by `generate --jitter A` (A cell widths, 0.25 ≤ A < 1), boxes
whose bottom side was bulged into the cells (a boundary that moved through them), the plate
with holes (examples/plate_with_holes.geo, needs gmsh) with interior vertices jittered.
Environment: NEOMESH (default build/neomesh).
"""
import argparse
import collections
import contextlib
import io
import json
import os
import subprocess
import sys
import time

import meshio
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))


def neomesh_binary():
    return os.environ.get("NEOMESH") or os.path.join(HERE, "..", "build", "neomesh")


def run(cmd):
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)


def read_mesh(path):
    with contextlib.redirect_stdout(io.StringIO()):  # meshio prints empty lines
        return meshio.read(path)


def write_msh22(path, mesh):
    with contextlib.redirect_stdout(io.StringIO()):
        meshio.write(path, mesh, file_format="gmsh22", binary=False)


def generated(neomesh, path, case, cells, jitter=0.0):
    run([neomesh, "generate", case, "--cells", str(cells), "--jitter", str(jitter), "--seed",
         "1", "-o", path])
    return path


def bulged(neomesh, path, case, cells):
    """The box's bottom side (y = -1 in 2D, z = -1 in 3D) pushed up by 0.8 (1 - x²)(1 - y²)."""
    generated(neomesh, path, case, cells)
    m = read_mesh(path)
    p = m.points
    axis = 2 if case in ("box-hex", "box-tet") else 1
    bottom = np.isclose(p[:, axis], -1.0)
    bump = 1.0 - p[bottom, 0] ** 2
    if axis == 2:
        bump *= 1.0 - p[bottom, 1] ** 2
    p[bottom, axis] += 0.8 * bump
    write_msh22(path, m)
    return path


def jittered_plate(neomesh, path, amplitude):
    """The plate with holes in quadrilaterals, interior vertices moved by up to amplitude times
    the mean length of their edges, per coordinate."""
    geo = os.path.join(HERE, "..", "examples", "plate_with_holes.geo")
    run(["gmsh", "-2", geo, "-setnumber", "quads", "1", "-format", "msh41", "-o", path])
    m = read_mesh(path)
    cells = [c.data for c in m.cells if c.type == "quad"][0]
    edges = collections.Counter()
    lengths = collections.defaultdict(list)
    for cell in cells:
        for a, b in zip(cell, np.roll(cell, -1)):
            edges[tuple(sorted((a, b)))] += 1
            length = np.linalg.norm(m.points[a] - m.points[b])
            lengths[a].append(length)
            lengths[b].append(length)
    boundary = {v for e, k in edges.items() if k == 1 for v in e}
    rng = np.random.default_rng(7)
    for v, ls in lengths.items():
        if v not in boundary:
            m.points[v, :2] += amplitude * np.mean(ls) * rng.uniform(-1, 1, 2)
    write_msh22(path, m)
    return path


def cases(neomesh, work):
    at = lambda name: os.path.join(work, name + ".msh")
    yield "quads 100², jitter 0.5", lambda: generated(neomesh, at("q50"), "box-quad", 100, 0.5), []
    yield "quads 100², jitter 0.9", lambda: generated(neomesh, at("q90"), "box-quad", 100, 0.9), []
    yield "triangles 100², jitter 0.5", lambda: generated(neomesh, at("t50"), "box-tri", 100, 0.5), []
    yield "hexes 20³, jitter 0.4", lambda: generated(neomesh, at("h40"), "box-hex", 20, 0.4), []
    yield "hexes 20³, jitter 0.7", lambda: generated(neomesh, at("h70"), "box-hex", 20, 0.7), []
    yield "tets 16³, jitter 0.5", lambda: generated(neomesh, at("e50"), "box-tet", 16, 0.5), []
    yield "plate quads, jitter 0.7", lambda: jittered_plate(neomesh, at("p70"), 0.7), []
    yield "plate quads, jitter 0.99", lambda: jittered_plate(neomesh, at("p99"), 0.99), []
    for case, cells, label in (("box-quad", 32, "quads 32²"), ("box-hex", 12, "hexes 12³"),
                               ("box-tet", 12, "tets 12³")):
        make = lambda case=case, cells=cells: bulged(neomesh, at(f"bump-{case}"), case, cells)
        yield f"{label} bump, fixed boundary", make, ["--boundary", "fixed"]
        yield f"{label} bump, sliding boundary", make, []


def main():
    p = argparse.ArgumentParser(description=__doc__,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--only", default="", help="run the cases whose name contains this")
    p.add_argument("--workdir", default=os.path.join(HERE, "..", "build", "bench", "untangle"))
    a = p.parse_args()
    neomesh = neomesh_binary()
    os.makedirs(a.workdir, exist_ok=True)
    print("| mesh | inverted before → after | untangling: iterations, rounds, s "
          "| smoothing iterations | min scaled Jacobian | wall s |")
    print("|---|---|---|---|---|---|")
    failed = False
    for name, make, options in cases(neomesh, a.workdir):
        if a.only not in name:
            continue
        mesh = make()
        report = os.path.join(a.workdir, "report.json")
        start = time.monotonic()
        proc = subprocess.run([neomesh, "smooth", mesh, "-o", os.path.join(a.workdir, "out.msh"),
                               "--quiet", "--report", report, *options],
                              capture_output=True, text=True)
        wall = time.monotonic() - start
        if proc.returncode != 0:
            print(f"| {name} | failed: {proc.stderr.strip()} | | | | |")
            failed = True
            continue
        with open(report) as f:
            r = json.load(f)
        u = r["untangling"]
        worst = r["quality_after"]["metrics"]["scaled_jacobian"]["min"]
        print(f"| {name} | {u['inverted_before']} → {u['inverted_after']} | {u['iterations']}, "
              f"{u['rounds']}, {u['seconds']:.2f} | {r['result']['iterations']} | {worst:.3f} "
              f"| {wall:.2f} |")
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
