#!/usr/bin/python3
"""`adapt --fit` and a geometry that moves, as benchmarks with the issue's criteria.

  fit:     a box of quads/triangles (circle r = 0.35) or hexahedra (sphere r = 0.6) adapted
           and fitted: the facet group `interface` of the .msh output is a closed chain/surface,
           every vertex of it within 1e-10 of the zero set (analytic distance), min scaled
           Jacobian >= 0.3, no inverted cell.
  bubble:  a circle/sphere of radius 0.2 rising from y = -0.6 to 0.6 through [-1,1]^d, adapted
           and fitted at every step: no inverted cell, every interface vertex within 1e-10 of
           that step's zero set, cells within 0.05 of the interface <= 1/4 the mean volume of
           cells farther than 0.5, every step after the first at most half the iterations of
           the first (cold) one; meshio reads every member of the .pvd.

    bench/adapt_moving.py fit --cell quad --cells 64
    bench/adapt_moving.py bubble --cell hex --cells 32 --steps 10

Prints one line of figures per case (and per step), exits 1 if a criterion fails; each
failure is (criterion, message), so that tests can tell which one.
tests/cli/test_fit.py runs the same checks at small sizes. Environment: NEOMESH.
"""
import argparse
import json
import os
import subprocess
import sys
import time
import xml.etree.ElementTree as ElementTree

import meshio
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
FIT_RADIUS = {2: 0.35, 3: 0.6}
BUBBLE_RADIUS, BUBBLE_FROM, BUBBLE_TO = 0.2, -0.6, 0.6
DIM = {"quad": 2, "tri": 2, "hex": 3}


def neomesh_binary():
    return os.environ.get("NEOMESH") or os.path.join(HERE, "..", "build", "neomesh")


def bubble_level_set(dim):
    rise = f"({BUBBLE_FROM}+{BUBBLE_TO - BUBBLE_FROM}*t)"
    z = "+z^2" if dim == 3 else ""
    return f"sqrt(x^2+(y-{rise})^2{z})-{BUBBLE_RADIUS}"


def bubble_centre(dim, t):
    c = np.zeros(dim)
    c[1] = BUBBLE_FROM + (BUBBLE_TO - BUBBLE_FROM) * t
    return c


def generate(neomesh, cell, cells, path):
    if not os.path.exists(path):
        subprocess.run([neomesh, "generate", f"box-{cell}", "--cells", str(cells), "-o", path],
                       check=True, stdout=subprocess.DEVNULL)


def closed_and_connected(facets, dim):
    """A chain (2D: every vertex in two edges) or surface (3D: every edge in two faces) in
    one piece."""
    count = {}
    for f in facets:
        n = len(f)
        ridges = [(v,) for v in f] if dim == 2 else [tuple(sorted((f[k], f[(k + 1) % n])))
                                                     for k in range(n)]
        for r in ridges:
            count[r] = count.get(r, 0) + 1
    closed = all(c == 2 for c in count.values())
    of_vertex = {}
    for i, f in enumerate(facets):
        for v in f:
            of_vertex.setdefault(v, []).append(i)
    seen, todo = {0}, [0]
    while todo:
        for v in facets[todo.pop()]:
            for g in of_vertex[v]:
                if g not in seen:
                    seen.add(g)
                    todo.append(g)
    return closed, len(seen) == len(facets)


def interface_facets(mesh):
    """The facets of the physical group `interface` of a .msh read by meshio."""
    tag, dim = mesh.field_data["interface"]
    out = []
    for block, physical in zip(mesh.cells, mesh.cell_data["gmsh:physical"]):
        if block.dim == dim:
            out += [list(f) for f, p in zip(block.data, physical) if p == tag]
    return out


def distances(points, centre, radius):
    return np.abs(np.linalg.norm(points[:, :len(centre)] - centre, axis=1) - radius)


def near_far(mesh, centre, radius):
    cells = mesh.cells[0].data
    volume = mesh.cell_data["volume"][0].ravel()
    d = distances(mesh.points[cells].mean(axis=1), centre, radius)
    return volume[d <= 0.05].mean() / volume[d > 0.5].mean()


def run_fit(neomesh, cell, cells, workdir, extra=(), launcher=()):
    """adapt --fit (under `launcher`, e.g. mpiexec -n 2); returns (figures, failures)."""
    dim = DIM[cell]
    stem = os.path.join(workdir, f"fit-{cell}-{cells}")
    generate(neomesh, cell, cells, stem + "-in.msh")
    shape = ["--circle", f"0,0,{FIT_RADIUS[2]}"] if dim == 2 else \
        ["--sphere", f"0,0,0,{FIT_RADIUS[3]}"]
    start = time.monotonic()
    proc = subprocess.run([*launcher, neomesh, "adapt", stem + "-in.msh", "-o", stem + ".msh", "--fit",
                           "--no-table", "--report", stem + ".json", *shape, *extra],
                          capture_output=True, text=True)
    wall = time.monotonic() - start
    if proc.returncode != 0:
        return {}, [("run", f"fit {cell} {cells}: {proc.stderr.strip()[-400:]}")]
    report = json.load(open(stem + ".json"))
    mesh = meshio.read(stem + ".msh")
    facets = interface_facets(mesh)
    closed, connected = closed_and_connected(facets, dim)
    vertices = sorted({v for f in facets for v in f})
    distance = distances(mesh.points[vertices], np.zeros(dim), FIT_RADIUS[dim]).max()
    metrics = report["quality_after"]["metrics"]
    figures = {"cells": report["cells"], "facets": len(facets), "closed": closed,
               "connected": connected, "max_distance": float(distance),
               "min_scaled_jacobian": metrics["scaled_jacobian"]["min"],
               "inverted": report["quality_after"]["inverted"],
               "iterations": len(report["result"]["history"]),
               "fit_iterations": report["fit"]["iterations"], "stages": report["fit"]["stages"],
               "undone": report["fit"]["undone"],
               "moved_across": report["fit"]["cells_moved_across"], "seconds": wall}
    failures = [(key, f"fit {cell} {cells}: {what}") for key, what, bad in [
        ("closed", "interface not closed", not closed),
        ("closed", "interface in pieces", not connected),
        ("distance", f"vertex {distance:.2e} from the zero set", distance > 1e-10),
        ("scaled_jacobian", f"min scaled Jacobian {figures['min_scaled_jacobian']:.3f} < 0.3",
         figures["min_scaled_jacobian"] < 0.3),
        ("inverted", "inverted cells", figures["inverted"] > 0)] if bad]
    return figures, failures


def run_bubble(neomesh, cell, cells, steps, workdir, extra=(), launcher=()):
    """adapt --fit --time 0:1:STEPS (under `launcher`); returns (per-step figures, failures)."""
    dim = DIM[cell]
    stem = os.path.join(workdir, f"bubble-{cell}-{cells}")
    generate(neomesh, cell, cells, stem + "-in.msh")
    start = time.monotonic()
    proc = subprocess.run([*launcher, neomesh, "adapt", stem + "-in.msh", "-o", stem + ".pvd", "--fit",
                           "--levelset", bubble_level_set(dim), "--time", f"0:1:{steps}",
                           "--report", stem + ".json", *extra], capture_output=True, text=True)
    wall = time.monotonic() - start
    if proc.returncode != 0:
        return [], [("run", f"bubble {cell} {cells}: {proc.stderr.strip()[-400:]}")]
    report = json.load(open(stem + ".json"))
    members = [(float(d.get("timestep")), d.get("file"))
               for d in ElementTree.parse(stem + ".pvd").getroot().iter("DataSet")]
    rows, failures = [], []
    for (t, name), step in zip(members, report["steps"]):
        mesh = meshio.read(os.path.join(os.path.dirname(stem), name))
        centre = bubble_centre(dim, t)
        on = mesh.point_data["interface"].ravel() > 0.5
        distance = distances(mesh.points[on], centre, BUBBLE_RADIUS).max()
        row = {"t": t, "iterations": step["iterations"], "updates": step["updates"],
               "max_distance": float(distance), "interface_vertices": int(on.sum()),
               "near_far": float(near_far(mesh, centre, BUBBLE_RADIUS)),
               "min_scaled_jacobian": step["min_scaled_jacobian"], "inverted": step["inverted"],
               "min_volume": float(mesh.cell_data["volume"][0].min()),
               "stages": step["fit"]["stages"], "undone": step["fit"]["undone"],
               "seconds": step["seconds"]}
        rows.append(row)
        failures += [(key, f"bubble {cell} {cells} t = {t:.3g}: {what}") for key, what, bad in [
            ("distance", f"vertex {distance:.2e} from the zero set", distance > 1e-10),
            ("inverted", "inverted cells", row["inverted"] > 0 or row["min_volume"] <= 0),
            ("near_far", f"near/far {row['near_far']:.3f} > 1/4", row["near_far"] > 0.25)]
            if bad]
    if len(rows) != steps:
        failures.append(("run", f"bubble {cell} {cells}: {len(rows)} of {steps} steps written"))
    cold = rows[0]["iterations"] if rows else 0
    for row in rows[1:]:
        if 2 * row["iterations"] > cold:
            failures.append(("warm_iterations",
                             f"bubble {cell} {cells} t = {row['t']:.3g}: {row['iterations']} "
                             f"iterations, more than half the cold start's {cold}"))
    if rows:
        rows[0]["wall"] = wall
    return rows, failures


def report(failures, reported_only=lambda key: False):
    """Prints the failures (those `reported_only` accepts as such) and exits 1 if any other."""
    failed = [m for key, m in failures if not reported_only(key)]
    for key, m in failures:
        print(("reported: " if reported_only(key) else "FAIL ") + m)
    if failed:
        sys.exit(f"{len(failed)} checks failed")


def main():
    p = argparse.ArgumentParser(description=__doc__,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("case", choices=["fit", "bubble"])
    p.add_argument("--cell", choices=sorted(DIM), default="quad")
    p.add_argument("--cells", type=int, default=64, help="cells per direction")
    p.add_argument("--steps", type=int, default=20, help="time steps (bubble)")
    p.add_argument("--workdir", default=os.path.join(HERE, "..", "build", "bench"))
    p.add_argument("--ranks", type=int, default=1, help="MPI processes (mpiexec -n RANKS)")
    p.add_argument("extra", nargs="*", help="more options for neomesh adapt (after --)")
    a = p.parse_args()
    os.makedirs(a.workdir, exist_ok=True)
    neomesh = neomesh_binary()
    launcher = ["mpiexec", "--allow-run-as-root", "-n", str(a.ranks)] if a.ranks > 1 else []
    if a.case == "fit":
        figures, failures = run_fit(neomesh, a.cell, a.cells, a.workdir, a.extra, launcher)
        print(f"fit {a.cell} {a.cells}: " + ", ".join(f"{k} {v:.3g}" if isinstance(v, float)
                                                      else f"{k} {v}" for k, v in figures.items()))
    else:
        rows, failures = run_bubble(neomesh, a.cell, a.cells, a.steps, a.workdir, a.extra,
                                    launcher)
        for r in rows:
            print(f"bubble {a.cell} {a.cells} t = {r['t']:.3f}: {r['iterations']} iterations "
                  f"({r['stages']} stages, {r['undone']} undone), max distance "
                  f"{r['max_distance']:.1e}, near/far {r['near_far']:.3f}, min scaled Jacobian "
                  f"{r['min_scaled_jacobian']:.3f}, {r['seconds']:.1f} s")
    report(failures)


if __name__ == "__main__":
    main()
