#!/usr/bin/env python3
"""Surface smoothing side by side: `neomesh smooth` against CGAL's tangential_relaxation and
angle_and_area_smoothing (bench/cgal_surface_smoothing.cpp) on three triangle surfaces made by
Gmsh with its worst settings for quality (MeshAdapt, no smoothing, -optimize 0): the unit
sphere of tests/cli/test_surfaces.py, a torus (R = 1, r = 0.4) and a cylinder with caps
(r = 0.5, height 1). Every output is measured the same way: `neomesh quality --json
--reference INPUT` on it written with the input's cells (min and mean scaled Jacobian, mean
inverse mean ratio, largest distance from the input's triangles, area change) and the largest
distance of a vertex from the exact surface, computed here. Prints a markdown table.

    bench/surfaces.py                 # 3 runs each, the fastest kept
    bench/surfaces.py --runs 1 --iterations 20

Times: the whole command (read, smooth, write; wall clock of the process) and the smoothing
alone (neomesh's report: its "seconds" less reading and writing; the driver's own clock around
the CGAL call).

Environment: NEOMESH (default build/neomesh next to this script), CGAL_SMOOTHING (default
build/bench/cgal_surface_smoothing; built when CMake finds CGAL), gmsh on PATH. Needs numpy and
meshio.
"""
import argparse
import contextlib
import io
import json
import os
import subprocess
import sys
import tempfile
import time

import meshio
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
BUILD = os.path.join(HERE, "..", "build")

GMSH_POOR = """SetFactory("OpenCASCADE");
{shape}
Mesh.Algorithm = 1;
Mesh.MeshSizeMin = {size};
Mesh.MeshSizeMax = {size};
Mesh.Smoothing = 0;
{groups}
"""
TORUS_R, TORUS_r = 1.0, 0.4
CYLINDER_r, CYLINDER_h = 0.5, 1.0


def sphere_distance(p):
    return np.abs(np.linalg.norm(p, axis=1) - 1.0)


def torus_distance(p):
    rho = np.hypot(p[:, 0], p[:, 1])
    return np.abs(np.hypot(rho - TORUS_R, p[:, 2]) - TORUS_r)


def cylinder_distance(p):
    """Distance from the closed cylinder's surface: its side or a cap, whichever is nearer."""
    rho, z = np.hypot(p[:, 0], p[:, 1]), p[:, 2]
    beyond = np.maximum(0.0, np.maximum(-z, z - CYLINDER_h))
    side = np.hypot(rho - CYLINDER_r, beyond)
    outside = np.maximum(0.0, rho - CYLINDER_r)
    caps = np.minimum(np.hypot(z, outside), np.hypot(z - CYLINDER_h, outside))
    return np.minimum(side, caps)


# name, Gmsh shape, groups, mesh size, distance from the exact surface, neomesh's --shape options
MESHES = [
    ("sphere", "Sphere(1) = {0, 0, 0, 1};", 'Physical Surface("sphere") = {1};', 0.25,
     sphere_distance, ["--shape", "sphere=sphere:0,0,0,1"]),
    ("torus", f"Torus(1) = {{0, 0, 0, {TORUS_R}, {TORUS_r}}};", 'Physical Surface("torus") = {1};',
     0.2, torus_distance,
     ["--shape", f"torus=levelset:(sqrt(x^2+y^2)-{TORUS_R})^2+z^2-{TORUS_r ** 2}"]),
    ("cylinder with caps", f"Cylinder(1) = {{0, 0, 0, 0, 0, {CYLINDER_h}, {CYLINDER_r}}};",
     'Physical Surface("side") = {1};\nPhysical Surface("top") = {2};\n'
     'Physical Surface("bottom") = {3};', 0.15, cylinder_distance,
     ["--shape", f"side=cylinder:0,0,0,0,0,1,{CYLINDER_r}"]),
]


def run(cmd):
    start = time.monotonic()
    proc = subprocess.run(cmd, capture_output=True, text=True)
    seconds = time.monotonic() - start
    if proc.returncode != 0:
        sys.exit(f"{' '.join(cmd)} failed:\n{proc.stderr}")
    return proc, seconds


def make_mesh(tmp, name, shape, groups, size):
    stem = os.path.join(tmp, name.split()[0])
    with open(stem + ".geo", "w") as f:
        f.write(GMSH_POOR.format(shape=shape, size=size, groups=groups))
    run(["gmsh", "-2", stem + ".geo", "-optimize", "0", "-format", "msh41", "-o", stem + ".msh"])
    with contextlib.redirect_stdout(io.StringIO()):  # meshio's progress output
        mesh = meshio.read(stem + ".msh")
    triangles = np.vstack([c.data for c in mesh.cells if c.type == "triangle"])
    with open(stem + ".off", "w") as f:
        f.write(f"OFF\n{len(mesh.points)} {len(triangles)} 0\n")
        f.writelines("%.17g %.17g %.17g\n" % tuple(p) for p in mesh.points)
        f.writelines("3 %d %d %d\n" % tuple(t) for t in triangles)
    return stem, mesh.points, triangles


def read_off_points(path):
    with open(path) as f:
        words = f.read().split()
    assert words[0] == "OFF"
    n = int(words[1])
    return np.array(words[4:4 + 3 * n], float).reshape(n, 3)


def measure(neomesh, stem, label, points, triangles, distance):
    """The output's quality, as neomesh measures it, and its distance from the exact surface."""
    vtu, report = f"{stem}-{label}.vtu", f"{stem}-{label}.json"
    meshio.write(vtu, meshio.Mesh(points, [("triangle", triangles)]))
    run([neomesh, "quality", vtu, "--reference", stem + ".msh", "--json", report])
    with open(report) as f:
        q = json.load(f)
    m = q["metrics"]
    return {"min": m["scaled_jacobian"]["min"], "mean": m["scaled_jacobian"]["mean"],
            "imr": m["inverse_mean_ratio"]["mean"],
            "input_distance": q["boundary_change"]["max_distance_from_reference_boundary"],
            "area_change": q["boundary_change"]["relative_volume_change"],
            "exact_distance": distance(points).max()}


def best_of(runs, once):
    """The fastest of `runs` calls of once() -> (output points, whole s, smoothing s)."""
    results = [once() for _ in range(runs)]
    return min(results, key=lambda r: r[1])


def neomesh_run(neomesh, stem, label, options):
    out, report = f"{stem}-{label}-out.vtu", f"{stem}-{label}-out.json"

    def once():
        _, seconds = run([neomesh, "smooth", stem + ".msh", "-o", out, "--quiet", "--report",
                          report, *options])
        with open(report) as f:
            r = json.load(f)
        smoothing = r["seconds"] - r["times"]["read"] - r["times"]["write"]
        return meshio.read(out).points, seconds, smoothing

    return once


def cgal_run(driver, stem, method, iterations):
    out = f"{stem}-{method}.off"

    def once():
        proc, seconds = run([driver, stem + ".off", out, method, str(iterations)])
        r = json.loads(proc.stdout)
        return read_off_points(out), seconds, r["smoothing_seconds"]

    return once


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--runs", type=int, default=3, help="runs of each tool, fastest kept")
    parser.add_argument("--iterations", type=int, default=10, help="CGAL's iterations")
    args = parser.parse_args()
    neomesh = os.environ.get("NEOMESH", os.path.join(BUILD, "neomesh"))
    driver = os.environ.get("CGAL_SMOOTHING",
                            os.path.join(BUILD, "bench", "cgal_surface_smoothing"))
    print("| mesh | tool | min / mean scaled Jacobian | mean inverse mean ratio | farthest from "
          "the exact surface | from the input's cells | area change | s whole (smoothing) |")
    print("|---|---|---|---|---|---|---|---|")
    with tempfile.TemporaryDirectory() as tmp:
        for name, shape, groups, size, distance, shape_options in MESHES:
            stem, points, triangles = make_mesh(tmp, name, shape, groups, size)
            rows = [("input", "input", None),
                    ("neomesh", "neomesh", neomesh_run(neomesh, stem, "neomesh", [])),
                    ("neomesh, `--shape`", "shape",
                     neomesh_run(neomesh, stem, "shape", shape_options)),
                    (f"CGAL tangential_relaxation ×{args.iterations}", "relax",
                     cgal_run(driver, stem, "relax", args.iterations)),
                    (f"CGAL angle_and_area_smoothing ×{args.iterations}", "angle-area",
                     cgal_run(driver, stem, "angle-area", args.iterations))]
            label = f"{name} ({len(triangles)} triangles)"
            for tool, key, once in rows:
                out, whole, smoothing = (points, None, None) if once is None else best_of(
                    args.runs, once)
                m = measure(neomesh, stem, key, out, triangles, distance)
                time_cell = "" if whole is None else f"{whole:.2f} ({smoothing:.3f})"
                print(f"| {label} | {tool} | {m['min']:.3f} / {m['mean']:.3f} | {m['imr']:.4f} | "
                      f"{m['exact_distance']:.2g} | {m['input_distance']:.1g} | "
                      f"{100 * m['area_change']:+.2f}% | {time_cell} |", flush=True)
                label = ""


if __name__ == "__main__":
    main()
