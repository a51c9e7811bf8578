"""Meshes with boundary layers, and what a CFD user measures on them: the first-layer height at
every wall cell and the layer's thickness at every point of its outer edge, before and after.
Used by test_targets.py and bench/targets.py.

- 2D: examples/cylinder_channel_bl.geo (Gmsh's BoundaryLayer field: 320 quads on the cylinder,
  first height 5e-4, ratio 1.25, thickness 0.01; 2,859 triangles outside).
- 3D: a sphere of radius 0.1 in the box [-0.5, 0.5]^3 with 5 layers of prisms (first height
  2.2e-3, ratio 1.3, thickness 0.02; Gmsh meshes the tetrahedra outside radius 0.12, the prisms
  are extruded from its triangles on that sphere, inwards along the radius)."""
import contextlib
import io
import os
import subprocess

import numpy as np

REPO = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))

BOX_WITH_SPHERICAL_HOLE = """SetFactory("OpenCASCADE");
Box(1) = {-0.5, -0.5, -0.5, 1, 1, 1};
Sphere(2) = {0, 0, 0, R};
BooleanDifference(3) = {Volume{1}; Delete;}{Volume{2}; Delete;};
Mesh.MeshSizeFromCurvature = N;
Mesh.MeshSizeMax = H;
Mesh.Smoothing = 0;
"""


def gmsh(geo, out, *options):
    subprocess.run(["gmsh", geo, "-format", "msh41", "-o", out, *map(str, options)], check=True,
                   stdout=subprocess.DEVNULL)
    return out


def channel(directory):
    """The 2D channel with a boundary layer on the cylinder, as Gmsh 4.1."""
    geo = os.path.join(REPO, "examples", "cylinder_channel_bl.geo")
    return gmsh(geo, os.path.join(directory, "channel_bl.msh"), "-2")


def sphere(directory, h=0.1, per_circle=24, r_in=0.1, r_out=0.12, layers=5, ratio=1.3):
    """The 3D sphere in a box: prisms in the layer, tetrahedra outside, as Gmsh 2.2."""
    import meshio
    geo = os.path.join(directory, "box_hole.geo")
    with open(geo, "w") as f:
        f.write(BOX_WITH_SPHERICAL_HOLE.replace("R}", f"{r_out}}}").replace("= N", f"= {per_circle}")
                .replace("= H", f"= {h}"))
    m = _read(gmsh(geo, os.path.join(directory, "box_hole.msh"), "-3"))
    p = m.points
    tets = np.vstack([c.data for c in m.cells if c.type == "tetra"])
    on = np.abs(np.linalg.norm(p, axis=1) - r_out) < 1e-6 * r_out
    faces = {}
    for t in tets:
        for f in ((0, 1, 2), (0, 1, 3), (0, 2, 3), (1, 2, 3)):
            v = t[list(f)]
            if on[v].all():
                faces[tuple(sorted(v))] = v
    first = (r_out - r_in) * (ratio - 1) / (ratio ** layers - 1)
    radii = r_in + np.concatenate([[0.0], np.cumsum(first * ratio ** np.arange(layers))])
    radii[-1] = r_out
    on_sphere = np.where(on)[0]
    index = {v: [0] * layers + [v] for v in on_sphere}  # the vertex at each radius
    points = [p]
    n = len(p)
    for k in range(layers):
        points.append(p[on_sphere] * (radii[k] / r_out))
        for i, v in enumerate(on_sphere):
            index[v][k] = n + i
        n += len(on_sphere)
    points = np.vstack(points)
    prisms = []
    for t in faces.values():
        a, b, c = points[t]
        if np.dot(np.cross(b - a, c - a), a) < 0:
            t = t[[0, 2, 1]]  # the bottom triangle's normal points outwards, to the top one
        for k in range(layers):
            prisms.append([index[v][k] for v in t] + [index[v][k + 1] for v in t])
    out = os.path.join(directory, "sphere_bl.msh")
    with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(io.StringIO()):
        meshio.write(out, meshio.Mesh(points, [("tetra", tets), ("wedge", np.array(prisms))]),
                     file_format="gmsh22", binary=False)
    return out


def _read(path):
    import meshio
    with contextlib.redirect_stdout(io.StringIO()):  # meshio's notes on Gmsh 2.2 tags
        return meshio.read(path)


def _relative(before, after):
    r = after / before - 1
    return float(r.min()), float(r.max())


def layer_change_2d(before, after, centre=(0.2, 0.2), radius=0.05):
    """Relative change (min, max) of the first-layer height of every wall quad (the distance of
    its two other vertices from the line of its wall edge) and of the layer's thickness at
    every vertex of its outer edge (the distance from the polygon of the wall edges)."""
    m0, m1 = _read(before), _read(after)
    quads = np.vstack([c.data for c in m0.cells if c.type == "quad"])
    triangles = np.vstack([c.data for c in m0.cells if c.type == "triangle"])
    wall = np.abs(np.linalg.norm(m0.points[:, :2] - centre, axis=1) - radius) < 1e-9
    first = [q for q in quads if wall[q].sum() == 2]
    outer = np.intersect1d(np.unique(quads), np.unique(triangles))

    def measure(p):
        p = p[:, :2]
        heights = []
        for q in first:
            a, b = p[q[wall[q]]]
            n = np.array([a[1] - b[1], b[0] - a[0]]) / np.linalg.norm(b - a)
            heights.append(np.mean([abs((p[v] - a) @ n) for v in q[~wall[q]]]))
        edges = np.array([q[wall[q]] for q in first])
        a, b = p[edges[:, 0]], p[edges[:, 1]]
        x = p[outer][:, None, :]
        t = np.clip(((x - a) * (b - a)).sum(-1) / ((b - a) ** 2).sum(-1), 0, 1)
        thickness = np.linalg.norm(x - (a + t[..., None] * (b - a)), axis=-1).min(1)
        return np.array(heights), thickness

    (h0, t0), (h1, t1) = measure(m0.points), measure(m1.points)
    return {"first_height": _relative(h0, h1), "thickness": _relative(t0, t1)}


def layer_change_3d(before, after):
    """The same for the prism layer: per column of prisms from a wall triangle, the distance of
    the first prism's top vertices and of the last prism's top vertices from the wall
    triangle's plane."""
    m0, m1 = _read(before), _read(after)
    prisms = np.vstack([c.data for c in m0.cells if c.type == "wedge"])
    by_bottom = {tuple(sorted(w[:3])): w for w in prisms}
    tops = {tuple(sorted(w[3:])) for w in prisms}
    columns = []
    for key, w in by_bottom.items():
        if key in tops:
            continue  # not on the wall
        column = [w]
        while tuple(sorted(column[-1][3:])) in by_bottom:
            column.append(by_bottom[tuple(sorted(column[-1][3:]))])
        columns.append(column)

    def measure(p):
        first, thickness = [], []
        for column in columns:
            a, b, c = p[column[0][:3]]
            n = np.cross(b - a, c - a)
            n /= np.linalg.norm(n)
            first.append(np.mean([abs((p[v] - a) @ n) for v in column[0][3:]]))
            thickness.append(np.mean([abs((p[v] - a) @ n) for v in column[-1][3:]]))
        return np.array(first), np.array(thickness)

    (h0, t0), (h1, t1) = measure(m0.points), measure(m1.points)
    return {"first_height": _relative(h0, h1), "thickness": _relative(t0, t1)}


def rest_quality(report):
    """Min and mean scaled Jacobian of the simplices (the cells outside the layer) in a run's
    .vtu output."""
    m = _read(report)
    sj = np.concatenate([np.asarray(m.cell_data["scaled_jacobian"][i]).ravel()
                         for i, c in enumerate(m.cells) if c.type in ("triangle", "tetra")])
    return float(sj.min()), float(sj.mean())
