#!/usr/bin/python3
"""Second-order boundary-layer meshes: Gmsh's `-order 2` (plain), Gmsh's high-order optimizer
(`-optimize_ho`) and `neomesh curve` side by side, on the mesh around a cylinder (2D: quads in
the layer, triangles outside) and around a sphere (3D: the prisms of Gmsh's extruded layer,
raised to wedge18; tetrahedra outside), the first layer `--first` of the radius thick. Each result is measured by `neomesh quality --json`
(the Bézier certificate: cells not certified valid, least curved scaled Jacobian) and by the
largest distance of the nodes of the cylinder's (sphere's) facets from the exact circle
(sphere); each step is timed (seconds, wall). One Markdown table per case.

    bench/curve_boundary_layer.py                    # both cases
    bench/curve_boundary_layer.py --case sphere --around 16 --first 1e-3
    bench/curve_boundary_layer.py --case sphere --first 1e-2 --skip-optimize-ho

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
BOX = 4.0  # the 2D domain is [-BOX, BOX]² minus the disc
BOX3 = 2.0  # the 3D one [-BOX3, BOX3]³ minus the ball


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


def sphere_model(around, first, layers):
    """The linear boundary-layer mesh around the sphere: its eight octant patches (Gmsh's
    built-in kernel, exact spherical patches) extruded along their normals in `layers` thin
    layers of prisms, tetrahedra from there to the box [-BOX3, BOX3]³; the sphere in the physical group "sphere", the box in
    "outer", the volume in "fluid"."""
    gmsh.model.add("sphere")
    geo = gmsh.model.geo
    h = 2 * math.pi * RADIUS / around
    centre = geo.addPoint(0, 0, 0, h)
    poles = [geo.addPoint(*(RADIUS * np.eye(3)[i] * sign), h) for sign in (1, -1)
             for i in range(3)]
    arcs = {}

    def arc(a, b):
        if (b, a) in arcs:
            return -arcs[(b, a)]
        arcs.setdefault((a, b), geo.addCircleArc(poles[a], centre, poles[b]))
        return arcs[(a, b)]

    x, y, z, mx, my, mz = range(6)
    patches = []
    for a, b, c in [(x, y, z), (y, mx, z), (mx, my, z), (my, x, z), (y, x, mz), (mx, y, mz),
                    (my, mx, mz), (x, my, mz)]:
        loop = geo.addCurveLoop([arc(a, b), arc(b, c), arc(c, a)])
        patches.append(geo.addSurfaceFilling([loop], -1, centre))
    heights = [first * RADIUS * (1.3 ** (k + 1) - 1) / 0.3 for k in range(layers)]
    extruded = geo.extrudeBoundaryLayer([(2, s) for s in patches], [1] * layers, heights, True)
    # Per patch: the top surface, the volume, the sides.
    tops = [extruded[i - 1][1] for i, (d, _) in enumerate(extruded) if d == 3]
    layer_volumes = [t for d, t in extruded if d == 3]
    corners = {}
    for i in (-1, 1):
        for j in (-1, 1):
            for k in (-1, 1):
                corners[i, j, k] = geo.addPoint(i * BOX3, j * BOX3, k * BOX3, 8 * h)
    lines = {}

    def line(a, b):
        if (b, a) in lines:
            return -lines[(b, a)]
        lines.setdefault((a, b), geo.addLine(corners[a], corners[b]))
        return lines[(a, b)]

    faces = []
    for axis in range(3):
        for side in (-1, 1):
            square = []
            for u, v in [(-1, -1), (1, -1), (1, 1), (-1, 1)]:
                point = [0, 0, 0]
                point[axis], point[(axis + 1) % 3], point[(axis + 2) % 3] = side, u, v
                square.append(tuple(point))
            loop = geo.addCurveLoop([line(square[i], square[(i + 1) % 4]) for i in range(4)])
            faces.append(geo.addPlaneSurface([loop]))
    outside = geo.addVolume([geo.addSurfaceLoop(faces), geo.addSurfaceLoop(tops)])
    geo.synchronize()
    gmsh.model.addPhysicalGroup(2, patches, 1)
    gmsh.model.setPhysicalName(2, 1, "sphere")
    gmsh.model.addPhysicalGroup(2, faces, 2)
    gmsh.model.setPhysicalName(2, 2, "outer")
    gmsh.model.addPhysicalGroup(3, layer_volumes + [outside], 3)
    gmsh.model.setPhysicalName(3, 3, "fluid")
    gmsh.model.mesh.generate(3)


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


def shape_distance(path, group, dim):
    """The largest | |x| − R | over the nodes of `group`'s facets (x: the first `dim`
    coordinates)."""
    mesh = read_mesh(path)
    nodes = set()
    for kind, index in mesh.cell_sets_dict[group].items():
        data = np.concatenate([b.data for b in mesh.cells if b.type == kind])  # as meshio counts
        nodes.update(data[index].ravel().tolist())
    r = np.linalg.norm(mesh.points[sorted(nodes), :dim], axis=1)
    return float(np.max(np.abs(r - RADIUS)))


def timed(f):
    start = time.perf_counter()
    result = f()
    return result, time.perf_counter() - start


# Per case: the model, its dimension, the group on the shape, the shape as `curve` takes it.
CASES = {
    "cylinder": (cylinder_model, 2, "cylinder", f"circle:0,0,{RADIUS}"),
    "sphere": (sphere_model, 3, "sphere", f"sphere:0,0,0,{RADIUS}"),
}


def run_case(case, args, tmp):
    model, dim, group, shape = CASES[case]
    linear = os.path.join(tmp, f"{case}-linear.msh")
    rows = []
    gmsh.initialize()
    gmsh.option.setNumber("General.Terminal", 0)
    try:
        model(args.around, args.first, args.layers)
        write(linear)
        plain = os.path.join(tmp, f"{case}-gmsh-order2.msh")
        _, seconds = timed(lambda: gmsh.model.mesh.setOrder(2))
        write(plain)
        rows.append(("Gmsh -order 2", plain, seconds))
        if args.skip_optimize_ho:
            raise StopIteration
        gmsh.model.remove()
        model(args.around, args.first, args.layers)
        optimized = os.path.join(tmp, f"{case}-gmsh-optimize-ho.msh")
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
    except StopIteration:  # --skip-optimize-ho
        pass
    finally:
        gmsh.finalize()
    curved = os.path.join(tmp, f"{case}-neomesh-curve.msh")
    proc, seconds = timed(lambda: subprocess.run(
        [neomesh_binary(), "curve", linear, "-o", curved, "--order", "2", "--shape",
         f"{group}={shape}"], capture_output=True, text=True))
    rows.append(("neomesh curve", curved if proc.returncode == 0 else None, seconds,
                 proc.stderr.strip()))

    counts = read_mesh(linear)
    by_type = {}
    for b in counts.cells:
        if b.type in ("quad", "triangle", "tetra", "wedge") and b.data.shape[1] > dim:
            by_type[b.type] = by_type.get(b.type, 0) + len(b.data)
    cells = ", ".join(f"{n} {t}" for t, n in by_type.items())
    print(f"\n{case} of radius {RADIUS}, {args.around} edges around, first layer "
          f"{args.first:g} R, {args.layers} layers: {cells}\n")
    print(f"| method | cells not certified valid | min curved scaled Jacobian | "
          f"max distance of {group} nodes from it | seconds |")
    print("|---|---|---|---|---|")
    for name, path, seconds, *error in rows:
        if path is None:
            print(f"| {name} | (refused: {error[0].removeprefix('neomesh: error: ')}) | | | "
                  f"{seconds:.2f} |")
            continue
        q = quality(path, tmp)["curved"]
        print(f"| {name} | {q['not_certified_valid']} | {q['scaled_jacobian']['min']:.4g} | "
              f"{shape_distance(path, group, dim):.2g} | {seconds:.2f} |")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--case", choices=[*CASES, "all"], default="all")
    parser.add_argument("--around", type=int, default=24,
                        help="edges around the cylinder or the sphere's equator")
    parser.add_argument("--first", type=float, default=1e-3,
                        help="first layer's thickness over the radius")
    parser.add_argument("--layers", type=int, default=10, help="layers in the boundary layer")
    parser.add_argument("--skip-optimize-ho", action="store_true",
                        help="leave out Gmsh's high-order optimizer (minutes on the sphere)")
    args = parser.parse_args()
    tmp = tempfile.mkdtemp(prefix="curve-bl-")
    for case in CASES if args.case == "all" else [args.case]:
        run_case(case, args, tmp)
    return 0


if __name__ == "__main__":
    sys.exit(main())
