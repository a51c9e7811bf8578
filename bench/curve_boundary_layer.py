#!/usr/bin/python3
"""Second-order boundary-layer meshes: Gmsh's `-order 2` (plain), Gmsh's high-order optimizer
(`-optimize_ho`) and `neomesh curve` side by side, on the mesh around a cylinder (2D: quads in
the layer, triangles outside, the first layer `--first` of the radius thick). Each result is
measured by `neomesh quality --json` (the Bézier certificate: cells not certified valid, least
curved scaled Jacobian) and by the largest distance of the cylinder's nodes (vertices and edge
nodes) from the exact circle; each step is timed (seconds, wall). One Markdown table.

    bench/curve_boundary_layer.py                    # the default mesh
    bench/curve_boundary_layer.py --around 24 --first 1e-3

Needs python3-gmsh and meshio. Environment: NEOMESH (default build/neomesh). Timings on a
loaded machine are provisional.
"""
import argparse
import contextlib
import io
import json
import math
import os
import subprocess
import sys
import tempfile
import time

import gmsh
import meshio
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
RADIUS = 0.5
BOX = 4.0  # the domain is [-BOX, BOX]² minus the disc


def neomesh_binary():
    return os.environ.get("NEOMESH") or os.path.join(HERE, "..", "build", "neomesh")


def cylinder_model(around, first, layers):
    """The linear boundary-layer mesh around the cylinder in the current Gmsh model; its circle
    in the physical group "cylinder", the box in "outer", the fluid in "fluid"."""
    gmsh.model.add("cylinder")
    occ = gmsh.model.occ
    box = occ.addRectangle(-BOX, -BOX, 0, 2 * BOX, 2 * BOX)
    disc = occ.addDisk(0, 0, 0, RADIUS, RADIUS)
    occ.cut([(2, box)], [(2, disc)])
    occ.synchronize()
    circle = [c for _, c in gmsh.model.getEntities(1)
              if max(abs(v) for v in gmsh.model.getBoundingBox(1, c)[:2]) < BOX / 2]
    outer = [c for _, c in gmsh.model.getEntities(1) if c not in circle]
    gmsh.model.addPhysicalGroup(1, circle, 1)
    gmsh.model.setPhysicalName(1, 1, "cylinder")
    gmsh.model.addPhysicalGroup(1, outer, 2)
    gmsh.model.setPhysicalName(1, 2, "outer")
    surfaces = [s for _, s in gmsh.model.getEntities(2)]
    gmsh.model.addPhysicalGroup(2, surfaces, 3)
    gmsh.model.setPhysicalName(2, 3, "fluid")
    gmsh.option.setNumber("Mesh.MeshSizeMax", 0.5)
    gmsh.option.setNumber("Mesh.MeshSizeFromCurvature", 0)
    for c in circle:  # `around` edges in all
        gmsh.model.mesh.setTransfiniteCurve(c, around // len(circle) + 1)
    layer = gmsh.model.mesh.field.add("BoundaryLayer")
    gmsh.model.mesh.field.setNumbers(layer, "CurvesList", circle)
    gmsh.model.mesh.field.setNumber(layer, "Size", first * RADIUS)
    gmsh.model.mesh.field.setNumber(layer, "Ratio", 1.3)
    gmsh.model.mesh.field.setNumber(layer, "Thickness",
                                    first * RADIUS * (1.3 ** layers - 1) / 0.3)
    gmsh.model.mesh.field.setNumber(layer, "Quads", 1)
    gmsh.model.mesh.field.setAsBoundaryLayer(layer)
    gmsh.model.mesh.generate(2)


def write(path):
    gmsh.option.setNumber("Mesh.MshFileVersion", 4.1)
    gmsh.write(path)


def quality(path, tmp):
    report = os.path.join(tmp, "quality.json")
    subprocess.run([neomesh_binary(), "quality", path, "--json", report], check=True,
                   stdout=subprocess.DEVNULL)
    with open(report) as f:
        return json.load(f)


def read_mesh(path):
    with contextlib.redirect_stdout(io.StringIO()):  # meshio's progress
        return meshio.read(path)


def circle_distance(path):
    """The largest | |x| − R | over the nodes of the "cylinder" group's edges."""
    mesh = read_mesh(path)
    nodes = set()
    for kind, index in mesh.cell_sets_dict["cylinder"].items():
        data = [b.data for b in mesh.cells if b.type == kind][0]
        nodes.update(data[index].ravel().tolist())
    r = np.linalg.norm(mesh.points[sorted(nodes), :2], axis=1)
    return float(np.max(np.abs(r - RADIUS)))


def timed(f):
    start = time.perf_counter()
    result = f()
    return result, time.perf_counter() - start


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--around", type=int, default=24, help="edges around the cylinder")
    parser.add_argument("--first", type=float, default=1e-3,
                        help="first layer's thickness over the radius")
    parser.add_argument("--layers", type=int, default=10, help="layers of quads")
    args = parser.parse_args()
    tmp = tempfile.mkdtemp(prefix="curve-bl-")
    linear = os.path.join(tmp, "linear.msh")
    gmsh.initialize()
    gmsh.option.setNumber("General.Terminal", 0)
    rows = []
    try:
        cylinder_model(args.around, args.first, args.layers)
        write(linear)
        plain = os.path.join(tmp, "gmsh-order2.msh")
        _, seconds = timed(lambda: gmsh.model.mesh.setOrder(2))
        write(plain)
        rows.append(("Gmsh -order 2", plain, seconds))
        gmsh.model.remove()
        cylinder_model(args.around, args.first, args.layers)
        optimized = os.path.join(tmp, "gmsh-optimize-ho.msh")
        gmsh.option.setNumber("Mesh.HighOrderOptimize", 2)  # elastic, then optimization

        def optimize():
            gmsh.model.mesh.setOrder(2)
            try:
                gmsh.model.mesh.optimize("HighOrder")
            except Exception as e:  # Gmsh reports not reaching its target, keeps the mesh
                return str(e)
            return ""

        note, seconds = timed(optimize)
        write(optimized)
        rows.append(("Gmsh -order 2 -optimize_ho" + (f" ({note})" if note else ""), optimized,
                     seconds))
    finally:
        gmsh.finalize()
    curved = os.path.join(tmp, "neomesh-curve.msh")
    proc, seconds = timed(lambda: subprocess.run(
        [neomesh_binary(), "curve", linear, "-o", curved, "--order", "2", "--shape",
         f"cylinder=circle:0,0,{RADIUS}"], capture_output=True, text=True))
    rows.append(("neomesh curve", curved if proc.returncode == 0 else None, seconds,
                 proc.stderr.strip()))

    counts = read_mesh(linear)
    cells = {b.type: len(b.data) for b in counts.cells if b.type in ("quad", "triangle")}
    print(f"cylinder of radius {RADIUS} in [-{BOX},{BOX}]², {args.around} edges around, first "
          f"layer {args.first:g} R, {args.layers} layers: {cells.get('quad', 0)} quads, "
          f"{cells.get('triangle', 0)} triangles\n")
    print("| method | cells not certified valid | min curved scaled Jacobian | "
          "max distance of cylinder nodes from the circle | seconds |")
    print("|---|---|---|---|---|")
    for name, path, seconds, *error in rows:
        if path is None:
            print(f"| {name} | (refused: {error[0].removeprefix('neomesh: error: ')}) | | | "
                  f"{seconds:.2f} |")
            continue
        q = quality(path, tmp)["curved"]
        print(f"| {name} | {q['not_certified_valid']} | {q['scaled_jacobian']['min']:.4g} | "
              f"{circle_distance(path):.2g} | {seconds:.2f} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
