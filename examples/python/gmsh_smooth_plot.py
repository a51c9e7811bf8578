"""Mesh a plate with three holes with Gmsh's Python API, smooth it with neomesh, and draw it
before and after with matplotlib, coloured by the scaled Jacobian (1 = ideal).

    python3 gmsh_smooth_plot.py            # writes plate-python.png
"""
import signal
import sys

import gmsh
import matplotlib

# Importing gmsh makes Ctrl-C kill the process at once; Python's own handler raises
# KeyboardInterrupt, which neomesh turns into a clean stop with the mesh as it was.
signal.signal(signal.SIGINT, signal.default_int_handler)

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.collections import PolyCollection  # noqa: E402

import neomesh  # noqa: E402

# Gmsh element types of the cells neomesh optimizes, and meshio's names for them.
GMSH_CELLS = {2: "triangle", 3: "quad"}


def plate_with_holes(h=0.2):
    """The plate of examples/plate_with_holes.geo, recombined into quadrilaterals by Gmsh, as
    points and meshio-style cells."""
    gmsh.initialize()
    gmsh.option.setNumber("General.Verbosity", 2)  # warnings and errors only
    gmsh.model.add("plate")
    occ = gmsh.model.occ
    plate = occ.addRectangle(0, 0, 0, 4, 2)
    holes = [occ.addDisk(cx, cy, 0, r, r) for cx, cy, r in
             [(1.0, 1.0, 0.4), (2.4, 0.7, 0.3), (3.2, 1.4, 0.35)]]
    occ.cut([(2, plate)], [(2, d) for d in holes])
    occ.synchronize()
    gmsh.option.setNumber("Mesh.MeshSizeMax", h)
    gmsh.option.setNumber("Mesh.Smoothing", 0)  # neomesh starts from the raw mesh
    gmsh.option.setNumber("Mesh.RecombineAll", 1)
    gmsh.model.mesh.generate(2)
    tags, coords, _ = gmsh.model.mesh.getNodes()
    index = np.zeros(int(tags.max()) + 1, dtype=np.int64)
    index[tags.astype(np.int64)] = np.arange(len(tags))
    cells = {}
    types, _, nodes = gmsh.model.mesh.getElements(dim=2)
    for t, n in zip(types, nodes):
        name = GMSH_CELLS[int(t)]
        vertices = 3 if name == "triangle" else 4
        cells[name] = index[n.astype(np.int64)].reshape(-1, vertices)
    gmsh.finalize()
    return coords.reshape(-1, 3)[:, :2], cells


def draw(ax, mesh, title):
    """The cells coloured by their scaled Jacobian."""
    points = mesh.points
    polygons = [points[c] for _, block in mesh.cells for c in block]
    sj = mesh.quality()["scaled_jacobian"]
    collection = PolyCollection(polygons, array=sj, cmap="viridis", edgecolors="k",
                                linewidths=0.3)
    collection.set_clim(0, 1)
    ax.add_collection(collection)
    ax.set_aspect("equal")
    ax.autoscale_view()
    ax.set_title(f"{title}: scaled Jacobian min {sj.min():.2f}, mean {sj.mean():.2f}")
    return collection


def main(output="plate-python.png"):
    points, cells = plate_with_holes()
    mesh = neomesh.Mesh.from_arrays(points, cells, name="plate from gmsh")
    print(mesh)
    fig, axes = plt.subplots(2, 1, figsize=(9, 9))
    draw(axes[0], mesh, "Gmsh")
    result = neomesh.smooth(mesh)  # boundary vertices slide along the plate and the holes
    print(result)
    colours = draw(axes[1], mesh, "neomesh smooth")
    fig.colorbar(colours, ax=axes, shrink=0.6, label="scaled Jacobian")
    fig.savefig(output, dpi=110)
    print(f"wrote {output}")


if __name__ == "__main__":
    main(*sys.argv[1:])
