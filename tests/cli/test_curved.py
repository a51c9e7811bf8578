"""Curved (second-order) meshes as a user gives them: read from Gmsh .msh (2.2 and 4.1, ASCII and
binary), VTK .vtk/.vtu, Exodus II, CGNS and Medit, measured by `quality` (validity certified over
each cell), written by `convert` to .msh, .vtu (Lagrange cells, which VTK reads), .vtk, .exo,
.cgns and .mesh (triangles and tetrahedra) with their group facets at second order, and smoothed,
every node moving, to a mesh whose cells are certified valid. Gmsh meshes are made by the gmsh
program (skipped without it), Mesquite's quadratic meshes come from ../shared/corpus (skipped
without it). Run with NEOMESH=path/to/neomesh."""
import glob
import json
import os
import shutil
import subprocess

import numpy as np
import pytest

from conftest import CORPUS, expect_one_error_line, needs_corpus, neomesh, read_mesh

needs_gmsh = pytest.mark.skipif(shutil.which("gmsh") is None, reason="the gmsh program is missing")

RING = """SetFactory("OpenCASCADE");
Disk(1) = {0, 0, 0, 2, 2};
Disk(2) = {0, 0, 0, 1, 1};
BooleanDifference{ Surface{1}; Delete; }{ Surface{2}; Delete; }
Mesh.MeshSizeMax = 0.5;
Physical Surface("ring", 7) = {1};
Physical Curve("boundary", 8) = {1, 2};
"""
CYLINDER = """SetFactory("OpenCASCADE");
Disk(1) = {0, 0, 0, 1, 1};
Mesh.MeshSizeMax = 0.6;
Extrude {0, 0, 1} { Surface{1}; Layers{2}; Recombine; }
Physical Volume("solid", 3) = {1};
Physical Surface("wall", 4) = {2};
"""
BALL = """SetFactory("OpenCASCADE");
Sphere(1) = {0, 0, 0, 1};
Mesh.MeshSizeMax = 0.6;
Physical Volume("ball", 5) = {1};
Physical Surface("sphere", 6) = {1};
"""

# name: (geometry, dimension, Gmsh options, the cell type neomesh reports)
GMSH_CASES = {
    "tri6": (RING, 2, [], "triangle6"),
    "quad8": (RING, 2, ["-setnumber", "Mesh.RecombineAll", "1", "-setnumber",
                        "Mesh.SecondOrderIncomplete", "1"], "quadrilateral8"),
    "quad9": (RING, 2, ["-setnumber", "Mesh.RecombineAll", "1"], "quadrilateral9"),
    "tet10": (BALL, 3, [], "tetrahedron10"),
    "hex20": (CYLINDER, 3, ["-setnumber", "Mesh.RecombineAll", "1", "-setnumber",
                            "Mesh.SecondOrderIncomplete", "1"], "hexahedron20"),
    "hex27": (CYLINDER, 3, ["-setnumber", "Mesh.RecombineAll", "1"], "hexahedron27"),
    # (Without Mesh.RecombineAll the cylinder's disc has triangles: its layers are prisms.)
    "wedge15": (CYLINDER, 3, ["-setnumber", "Mesh.SecondOrderIncomplete", "1"], "wedge15"),
    "wedge18": (CYLINDER, 3, [], "wedge18"),
}


def gmsh_mesh(tmp, case, fmt="msh41", binary=False):
    geometry, dim, options, _ = GMSH_CASES[case]
    geo = os.path.join(tmp, case + ".geo")
    open(geo, "w").write(geometry)
    out = os.path.join(tmp, f"{case}-{fmt}{'-bin' if binary else ''}.msh")
    subprocess.run(["gmsh", f"-{dim}", "-order", "2", *options, *(["-bin"] if binary else []),
                    geo, "-format", fmt, "-o", out], check=True, capture_output=True)
    return out


def medit(case):
    """Whether Medit has the case's cells: its P2 triangles and tetrahedra."""
    return case in ("tri6", "tet10")


def curved_quality(tmp, path):
    out = os.path.join(tmp, "q.json")
    neomesh("quality", path, "--json", out)
    return json.load(open(out))["curved"]


@needs_gmsh
@pytest.mark.parametrize("case", sorted(GMSH_CASES))
def test_a_gmsh_curved_mesh_is_measured_alike_in_every_format(tmp, case):
    # 2.2, 4.1 ASCII and binary, and what convert writes: the same curved cells.
    inputs = [gmsh_mesh(tmp, case), gmsh_mesh(tmp, case, "msh22"),
              gmsh_mesh(tmp, case, binary=True)]
    for ext in ("msh", "vtu", "vtk", "exo", "cgns") + (("mesh",) if medit(case) else ()):
        inputs.append(os.path.join(tmp, f"converted.{ext}"))
        neomesh("convert", inputs[0], "-o", inputs[-1])
    reference = curved_quality(tmp, inputs[0])
    assert list(reference["cells"]) == [GMSH_CASES[case][3]]
    # Gmsh's meshes of these round shapes are valid everywhere.
    assert reference["not_certified_valid"] == 0
    assert reference["scaled_jacobian"]["min"] > 0
    # (Gmsh's ASCII files round the coordinates of its binary ones.)
    for path in inputs[1:]:
        q = curved_quality(tmp, path)
        assert (q["cells"], q["not_certified_valid"]) == (reference["cells"], 0), path
        for key in ("min", "mean", "max"):
            assert q["scaled_jacobian"][key] == pytest.approx(reference["scaled_jacobian"][key],
                                                              rel=1e-9), path


@needs_gmsh
@pytest.mark.parametrize("case, lagrange", [("tri6", 69), ("quad9", 70), ("tet10", 71),
                                            ("hex27", 72), ("hex20", 25), ("wedge18", 73)])
def test_vtk_reads_the_vtu_with_lagrange_cells_at_the_same_nodes(tmp, case, lagrange):
    vtk = pytest.importorskip("vtk")
    import meshio
    msh = gmsh_mesh(tmp, case)
    vtu = os.path.join(tmp, "out.vtu")
    neomesh("convert", msh, "-o", vtu)
    reader = vtk.vtkXMLUnstructuredGridReader()
    reader.SetFileName(vtu)
    reader.Update()
    grid = reader.GetOutput()
    points = np.array([grid.GetPoint(i) for i in range(grid.GetNumberOfPoints())])
    types, ours = set(), []
    for i in range(grid.GetNumberOfCells()):
        cell = grid.GetCell(i)  # (VTK reuses the object: read it at once)
        if cell.GetCellDimension() != GMSH_CASES[case][1]:
            continue
        types.add(cell.GetCellType())
        ids = [cell.GetPointId(k) for k in range(cell.GetNumberOfPoints())]
        ours.append(tuple(sorted(map(tuple, np.round(points[ids], 9)))))
    assert types == {lagrange}
    # Each cell's nodes are where Gmsh put them: the cells' point sets agree.
    ours.sort()
    m = meshio.read(msh)
    block = next(b for b in m.cells if b.dim == GMSH_CASES[case][1])
    theirs = sorted(tuple(sorted(map(tuple, np.round(m.points[cell], 9)))) for cell in block.data)
    assert ours == theirs


@needs_gmsh
def test_convert_keeps_the_groups_of_a_curved_mesh(tmp):
    import meshio
    out = os.path.join(tmp, "out.msh")
    neomesh("convert", gmsh_mesh(tmp, "tri6"), "-o", out)
    m = meshio.read(out)
    assert set(m.field_data) == {"ring", "boundary"}
    assert {b.type for b in m.cells} == {"triangle6", "line3"}


SQUARE = """SetFactory("OpenCASCADE");
Rectangle(1) = {0, 0, 0, 1, 1};
Mesh.MeshSizeMax = 0.25;
Physical Surface("square", 1) = {1};
Physical Curve("boundary", 2) = {1, 2, 3, 4};
"""


def jittered_square(tmp, case, amount=0.025, seed=1):
    """The unit square meshed by Gmsh with cells of `case`, every interior node (corners and
    higher-order nodes) moved at random by up to `amount` of the mesh size per coordinate."""
    gmsh = pytest.importorskip("gmsh")
    _, _, options, _ = GMSH_CASES[case]
    geo = os.path.join(tmp, "square.geo")
    open(geo, "w").write(SQUARE)
    msh = os.path.join(tmp, f"square-{case}.msh")
    subprocess.run(["gmsh", "-2", "-order", "2", *options, geo, "-o", msh], check=True,
                   capture_output=True)
    rng = np.random.default_rng(seed)
    gmsh.initialize()
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.open(msh)
        inner = set(gmsh.model.mesh.getNodes(2, 1)[0])
        tags, coords, _ = gmsh.model.mesh.getNodes()
        for i, tag in enumerate(tags):
            if tag in inner:
                x = coords[3 * i:3 * i + 3].copy()
                x[:2] += rng.uniform(-1, 1, 2) * amount * 0.25
                gmsh.model.mesh.setNode(tag, x, [])
        gmsh.write(msh)
    finally:
        gmsh.finalize()
    return msh


def smooth_report(tmp, path, out, *options):
    report = os.path.join(tmp, "smooth.json")
    neomesh("smooth", path, "-o", out, "--report", report, *options)
    return json.load(open(report))


def expect_the_optimum_repaired(report, after):
    """The optimum of a smoothing that kept it, its worst cells repaired after it (docs/method.md
    §12): never worse, and what the repair reports is what the output `after` measures."""
    repair = report["worst_cell_repair"]
    assert not report["curved"]["input_returned"]
    assert repair["min_scaled_jacobian_before"] == pytest.approx(
        report["curved"]["min_scaled_jacobian_optimum"])
    assert repair["min_scaled_jacobian_after"] >= repair["min_scaled_jacobian_before"]
    assert repair["min_scaled_jacobian_after"] == pytest.approx(after["scaled_jacobian"]["min"])


@needs_gmsh
@pytest.mark.parametrize("case", ["tri6", "quad9", "quad8"])
@pytest.mark.parametrize("boundary", ["fixed", "slide"])
def test_smooth_moves_every_node_of_a_curved_mesh_to_a_better_valid_one(tmp, case, boundary):
    msh = jittered_square(tmp, case)
    before = curved_quality(tmp, msh)
    assert before["not_certified_valid"] == 0
    out = os.path.join(tmp, "out.msh")
    report = smooth_report(tmp, msh, out, "--boundary", boundary)
    after = curved_quality(tmp, out)
    assert after["not_certified_valid"] == 0
    assert after["scaled_jacobian"]["min"] > before["scaled_jacobian"]["min"] + 0.2
    assert after["scaled_jacobian"]["mean"] > before["scaled_jacobian"]["mean"]
    curved = report["curved"]
    assert not curved["input_returned"] and curved["not_valid_optimum"] == 0
    expect_the_optimum_repaired(report, after)
    # The square stays the square: boundary nodes on its sides, corners where they were.
    m = read_mesh(out)
    assert np.allclose(m.points[:, :2].min(axis=0), 0) and np.allclose(m.points[:, :2].max(axis=0), 1)
    assert report["boundary_change"]["max_distance_from_input_boundary"] < 1e-12
    # Every node moved, not only the corners: the mid-edge nodes leave the straight edges' midpoints.
    assert report["free_dofs"] > 2 * report["vertices"]


@needs_gmsh
def test_a_uniform_straight_grid_given_as_order_two_is_at_rest(tmp):
    # Every cell the optimal square (docs/method.md §12): the stress vanishes, so the mid-edge
    # and centre nodes are stationary too, and nothing moves.
    geo = os.path.join(tmp, "grid.geo")
    open(geo, "w").write(SQUARE.replace("Mesh.MeshSizeMax = 0.25;",
                                        "Transfinite Surface{1}; Transfinite Curve{:} = 5;"))
    msh, out = os.path.join(tmp, "grid.msh"), os.path.join(tmp, "out.msh")
    subprocess.run(["gmsh", "-2", "-order", "2", "-setnumber", "Mesh.RecombineAll", "1", geo,
                    "-o", msh], check=True, capture_output=True)
    neomesh("smooth", msh, "-o", out, "--boundary", "fixed", "--sizes", "uniform")
    # The same points (neomesh lists the corners first, then the other nodes).
    points = [np.round(read_mesh(path).points, 9) for path in (msh, out)]
    assert sorted(map(tuple, points[0])) == sorted(map(tuple, points[1]))


@needs_gmsh
def test_adapt_refuses_a_curved_mesh_in_one_line_and_writes_nothing(tmp):
    msh = gmsh_mesh(tmp, "quad9")
    proc = neomesh("adapt", msh, "-o", "out.msh", "--circle", "0,0,1.5", cwd=tmp, expect=1)
    expect_one_error_line(proc, ["second-order (curved) cells", "adapt does not take"],
                          unwritten=[os.path.join(tmp, "out.msh")])


def second_order_elements(path):
    """Per element of a file (as meshio reads it), the coordinates of its nodes: cells as they
    are listed, facets (lines, triangles, quadrilaterals of 3, 6, 8 or 9 nodes) as their
    corners, each edge's corners with its node, and their centre, whichever corner comes first."""
    import meshio
    m = meshio.read(path)
    dim = max(b.dim for b in m.cells)
    out = {}
    for block in m.cells:
        for cell in block.data:
            x = [tuple(np.round(m.points[n], 9)) for n in cell]
            if block.dim == dim:
                out[frozenset(x)] = (block.type, tuple(x))
                continue
            corners = {3: 2, 6: 3, 8: 4, 9: 4}.get(len(x), len(x))
            edges = frozenset((frozenset((x[i], x[(i + 1) % corners])), x[corners + i])
                              for i in range(1 if corners == 2 else corners)
                              if corners + i < len(x))
            out[frozenset(x)] = (block.type, frozenset(x[:corners]), edges, tuple(x[2 * corners:]))
    return out


@needs_gmsh
@pytest.mark.parametrize("case", sorted(set(GMSH_CASES) - {"wedge15"}))  # (meshio has no wedge15)
def test_a_round_trip_through_every_format_keeps_every_node_and_group(tmp, case):
    # Gmsh -> X -> Gmsh: the cells keep their nodes in order, the group facets (second-order
    # elements in Gmsh's file) their mid-edge and face nodes, the groups their elements.
    import meshio
    msh = gmsh_mesh(tmp, case)
    original = second_order_elements(msh)
    assert len({e[0] for e in original.values()}) == 2, "the case has group facets"
    exts = ["msh", "vtu", "vtk", "exo", "cgns"] + (["mesh"] if medit(case) else [])
    for ext in exts:
        there, back = os.path.join(tmp, f"there.{ext}"), os.path.join(tmp, f"back-{ext}.msh")
        neomesh("convert", msh, "-o", there)
        neomesh("convert", there, "-o", back)
        assert second_order_elements(back) == original, ext
        if ext != "mesh":  # (Medit has no group names)
            assert set(meshio.read(back).field_data) == set(meshio.read(msh).field_data), ext
    # meshio's names of the cell types of the Exodus file (it reads no second-order wedges:
    # their block's type as netCDF reads it).
    cells = {"tri6": "triangle6", "quad8": "quad8", "quad9": "quad9", "tet10": "tetra10",
             "hex20": "hexahedron20", "hex27": "hexahedron27"}
    exo = os.path.join(tmp, "there.exo")
    if case.startswith("wedge"):
        netcdf = pytest.importorskip("netCDF4")
        with netcdf.Dataset(exo) as f:
            assert f.variables["connect1"].elem_type == case.upper()
    else:
        assert {b.type for b in meshio.read(exo).cells} == {cells[case]}


@needs_gmsh
@pytest.mark.parametrize("case", ["tri6", "tet10"])
def test_gmsh_reads_the_medit_p2_file_with_each_node_where_it_was(tmp, case):
    # Gmsh's own reader of TrianglesP2, TetrahedraP2 and EdgesP2: an order neomesh did not write.
    gmsh = pytest.importorskip("gmsh")
    msh = gmsh_mesh(tmp, case)
    out = os.path.join(tmp, "out.mesh")
    neomesh("convert", msh, "-o", out)
    dim = GMSH_CASES[case][1]

    def elements(path):
        gmsh.initialize()
        try:
            gmsh.option.setNumber("General.Terminal", 0)
            gmsh.open(path)
            tags, xyz, _ = gmsh.model.mesh.getNodes()
            at = dict(zip(tags, map(tuple, np.round(xyz.reshape(-1, 3), 9))))
            found = {}
            for d in (dim, dim - 1):
                types, _, nodes = gmsh.model.mesh.getElements(d)
                for t, listed in zip(types, nodes):
                    n = gmsh.model.mesh.getElementProperties(t)[3]
                    for e in np.array(listed).reshape(-1, n):
                        x = tuple(at[k] for k in e)
                        # (a facet, line3 or triangle6, by its edges' corners and nodes)
                        c = {3: 2, 6: 3}.get(n, n)
                        found[frozenset(x)] = (t, x if d == dim else frozenset(
                            (frozenset((x[i], x[(i + 1) % c])), x[c + i])
                            for i in range(1 if c == 2 else c)))
            return found
        finally:
            gmsh.finalize()
    assert elements(out) == elements(msh)


@pytest.mark.skipif(shutil.which("cgnscheck") is None, reason="cgnscheck is missing")
@needs_gmsh
@pytest.mark.parametrize("case", sorted(GMSH_CASES))
def test_cgnscheck_finds_no_error_in_a_curved_cgns_file(tmp, case):
    out = os.path.join(tmp, "out.cgns")
    neomesh("convert", gmsh_mesh(tmp, case), "-o", out)
    check = subprocess.run(["cgnscheck", out], capture_output=True, text=True)
    assert check.returncode == 0 and "ERROR" not in check.stdout.upper(), check.stdout


@needs_gmsh
@pytest.mark.parametrize("case", ["quad9", "hex20", "wedge18"])
def test_medit_refuses_curved_cells_other_than_triangles_and_tetrahedra_in_one_line(tmp, case):
    out = os.path.join(tmp, "out.mesh")
    expect_one_error_line(neomesh("convert", gmsh_mesh(tmp, case), "-o", out, expect=1),
                          ["TrianglesP2 and TetrahedraP2", GMSH_CASES[case][3]],
                          unwritten=[out])


@needs_corpus
def test_every_quadratic_mesquite_mesh_is_read_and_certified(tmp):
    files = sorted(glob.glob(os.path.join(CORPUS, "mesquite", "*", "vtk", "quadratic", "*.vtk")))
    assert len(files) == 19
    for path in files:
        q = curved_quality(tmp, path)
        cells = sum(q["cells"].values())
        assert 0 <= q["not_certified_valid"] <= cells, path
        # A cell not certified valid has a sampled scaled Jacobian ≤ 0, a valid one > 0.
        assert (q["scaled_jacobian"]["min"] <= 0) == (q["not_certified_valid"] > 0), path
    # Mesquite's tangled twin of a valid mesh: only the twin has cells that fold.
    name = os.path.join(CORPUS, "mesquite", "3D", "vtk", "quadratic", "sphereCylinder_22492")
    assert curved_quality(tmp, name + ".vtk")["not_certified_valid"] == 0
    assert curved_quality(tmp, name + "_inv.vtk")["not_certified_valid"] > 0


# Gmsh element type and VTK's types for it in .vtu (Lagrange where VTK has one) and .vtk.
ORDERS = {"triangle6": (9, 69, 22), "quadrilateral8": (16, 23, 23),
          "quadrilateral9": (10, 70, 28), "tetrahedron10": (11, 71, 24),
          "hexahedron20": (17, 25, 25), "hexahedron27": (12, 72, 29),
          "wedge15": (18, 26, 26), "wedge18": (13, 73, 32)}


@pytest.mark.parametrize("name", sorted(ORDERS))
def test_vtk_finds_each_node_where_gmsh_numbers_it(tmp, name):
    # One cell whose nodes sit at Gmsh's reference positions of their numbers, written by
    # convert: VTK must find each of its points at its own reference position for that point.
    gmsh = pytest.importorskip("gmsh")
    vtk = pytest.importorskip("vtk")
    gmsh_type, vtu_type, vtk_type = ORDERS[name]
    gmsh.initialize()
    try:
        _, dim, _, nodes, reference, _ = gmsh.model.mesh.getElementProperties(gmsh_type)
    finally:
        gmsh.finalize()
    reference = np.reshape(reference, (nodes, dim))
    msh = os.path.join(tmp, "cell.msh")
    with open(msh, "w") as f:
        f.write(f"$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n{nodes}\n")
        for i, x in enumerate(reference):
            f.write(f"{i + 1} {' '.join(map(str, x))}{' 0' * (3 - dim)}\n")
        f.write(f"$EndNodes\n$Elements\n1\n1 {gmsh_type} 2 1 1 "
                f"{' '.join(str(i + 1) for i in range(nodes))}\n$EndElements\n")
    tensor = name.startswith(("quadrilateral", "hexahedron"))
    wedge = name.startswith("wedge")
    for ext, reader, expected_type in (("vtu", vtk.vtkXMLUnstructuredGridReader, vtu_type),
                                       ("vtk", vtk.vtkUnstructuredGridReader, vtk_type)):
        out = os.path.join(tmp, "cell." + ext)
        neomesh("convert", msh, "-o", out)
        r = reader()
        r.SetFileName(out)
        r.Update()
        cell = r.GetOutput().GetCell(0)
        assert cell.GetCellType() == expected_type
        pcoords = cell.GetParametricCoords()
        for k in range(nodes):
            where = np.array(cell.GetPoints().GetPoint(k))[:dim]
            t = np.array([pcoords[3 * k + j] for j in range(dim)])
            if wedge:
                # Its axis from 0 to 1; VTK's quadratic wedges list the triangles the other way
                # round (as its linear one): their points hold Gmsh's with r and s swapped.
                lagrange = cell.GetCellType() == 73
                t = np.array([t[0 if lagrange else 1], t[1 if lagrange else 0], 2 * t[2] - 1])
            assert np.allclose(where, 2 * t - 1 if tensor else t), (ext, k)


@needs_gmsh
@pytest.mark.parametrize("case", ["tri6", "quad8", "hex27", "tet10"])
def test_a_mirrored_curved_mesh_is_measured_as_its_mirror_image(tmp, case):
    # Every cell listed the other way round (a coordinate negated): neomesh reorients it, its
    # other nodes with its corners, and finds the cells valid and as good as before.
    gmsh = pytest.importorskip("gmsh")
    msh, mirrored = gmsh_mesh(tmp, case), os.path.join(tmp, "mirrored.msh")
    axis = GMSH_CASES[case][1] - 1
    gmsh.initialize()
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.open(msh)
        tags, coords, _ = gmsh.model.mesh.getNodes()
        for i, tag in enumerate(tags):
            x = list(coords[3 * i:3 * i + 3])
            x[axis] = -x[axis]
            gmsh.model.mesh.setNode(tag, x, [])
        gmsh.write(mirrored)
    finally:
        gmsh.finalize()
    original, image = curved_quality(tmp, msh), curved_quality(tmp, mirrored)
    assert image["not_certified_valid"] == 0
    for key in ("min", "mean", "max"):
        assert image["scaled_jacobian"][key] == pytest.approx(original["scaled_jacobian"][key],
                                                              rel=1e-9)
    out = os.path.join(tmp, "mirrored.vtu")
    neomesh("convert", mirrored, "-o", out)
    assert curved_quality(tmp, out) == image


# Exodus II's nodes after the corners, by the corners they sit between (SEACAS Ioss' element
# topologies, 0-based): a tetrahedron10's edges, a hexahedron27's edges, centre and faces.
EXODUS_NODES = {
    "tet10": [(0, 1), (1, 2), (2, 0), (0, 3), (1, 3), (2, 3)],
    "hex27": [(0, 1), (1, 2), (2, 3), (3, 0), (0, 4), (1, 5), (2, 6), (3, 7), (4, 5), (5, 6),
              (6, 7), (7, 4), tuple(range(8)), (0, 3, 2, 1), (4, 5, 6, 7), (0, 4, 7, 3),
              (1, 2, 6, 5), (0, 1, 5, 4), (2, 3, 7, 6)],
    "wedge18": [(0, 1), (1, 2), (2, 0), (0, 3), (1, 4), (2, 5), (3, 4), (4, 5), (5, 3),
                (0, 1, 4, 3), (1, 2, 5, 4), (0, 3, 5, 2)],
}


@needs_gmsh
@pytest.mark.parametrize("case", sorted(EXODUS_NODES))
def test_each_exodus_node_sits_where_the_exodus_manual_numbers_it(tmp, case):
    # Read with netCDF, not by neomesh: each node after the corners is nearer to the centre of
    # the corners Ioss gives its number than to that of any other edge, face or the cell.
    netcdf = pytest.importorskip("netCDF4")
    out = os.path.join(tmp, "out.exo")
    neomesh("convert", gmsh_mesh(tmp, case), "-o", out)
    with netcdf.Dataset(out) as f:
        x = np.stack([f.variables[c][:] for c in ("coordx", "coordy", "coordz")], axis=1)
        cells = f.variables["connect1"][:] - 1
    places = EXODUS_NODES[case]
    corners = cells.shape[1] - len(places)
    for cell in cells:
        centres = np.array([x[cell[list(p)]].mean(axis=0) for p in places])
        for k, node in enumerate(cell[corners:]):
            assert np.argmin(np.linalg.norm(centres - x[node], axis=1)) == k


# CGNS' nodes after the corners (SIDS, "Unstructured Grid Element Numbering Conventions",
# 0-based): a TETRA_10's edges, a HEXA_27's edges, faces and centre.
CGNS_NODES = {
    "tet10": (11, [(0, 1), (1, 2), (2, 0), (0, 3), (1, 3), (2, 3)]),
    "hex27": (19, [(0, 1), (1, 2), (2, 3), (3, 0), (0, 4), (1, 5), (2, 6), (3, 7), (4, 5),
                   (5, 6), (6, 7), (7, 4), (0, 1, 2, 3), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6),
                   (0, 4, 7, 3), (4, 5, 6, 7), tuple(range(8))]),
    "wedge18": (16, [(0, 1), (1, 2), (2, 0), (0, 3), (1, 4), (2, 5), (3, 4), (4, 5), (5, 3),
                     (0, 1, 4, 3), (1, 2, 5, 4), (2, 0, 3, 5)]),
}


def cgns_cells(path, element_type):
    """The coordinates and the cells of the section of `element_type` of a CGNS file's first
    zone, read through the CGNS library itself (ctypes: no h5py needed)."""
    import ctypes
    lib = ctypes.CDLL("libcgns.so.3.4")
    size = ctypes.c_int32 if "CG_BUILD_64BIT  0" in open("/usr/include/cgnstypes.h").read() \
        else ctypes.c_int64
    fn = ctypes.c_int()
    assert lib.cg_open(path.encode(), 0, ctypes.byref(fn)) == 0
    try:
        zone = (size * 9)()
        assert lib.cg_zone_read(fn, 1, 1, ctypes.create_string_buffer(33), zone) == 0
        x = []
        for name in (b"CoordinateX", b"CoordinateY", b"CoordinateZ"):
            c = (ctypes.c_double * zone[0])()
            assert lib.cg_coord_read(fn, 1, 1, name, 4, ctypes.byref(size(1)),
                                     ctypes.byref(size(zone[0])), c) == 0
            x.append(list(c))
        sections = ctypes.c_int()
        lib.cg_nsections(fn, 1, 1, ctypes.byref(sections))
        for s in range(1, sections.value + 1):
            kind, start, end = ctypes.c_int(), size(), size()
            lib.cg_section_read(fn, 1, 1, s, ctypes.create_string_buffer(33), ctypes.byref(kind),
                                ctypes.byref(start), ctypes.byref(end),
                                ctypes.byref(ctypes.c_int()), ctypes.byref(ctypes.c_int()))
            if kind.value != element_type:
                continue
            n = ctypes.c_int()
            lib.cg_npe(kind, ctypes.byref(n))
            data = (size * ((end.value - start.value + 1) * n.value))()
            assert lib.cg_elements_read(fn, 1, 1, s, data, None) == 0
            return np.array(x).T, np.array(list(data)).reshape(-1, n.value) - 1
    finally:
        lib.cg_close(fn)
    raise AssertionError(f"{path} has no section of type {element_type}")


@needs_gmsh
@pytest.mark.skipif(not os.path.exists("/usr/include/cgnstypes.h"), reason="no CGNS headers")
@pytest.mark.parametrize("case", sorted(CGNS_NODES))
def test_each_cgns_node_sits_where_the_sids_number_it(tmp, case):
    out = os.path.join(tmp, "out.cgns")
    neomesh("convert", gmsh_mesh(tmp, case), "-o", out)
    element_type, places = CGNS_NODES[case]
    x, cells = cgns_cells(out, element_type)
    corners = cells.shape[1] - len(places)
    for cell in cells:
        centres = np.array([x[cell[list(p)]].mean(axis=0) for p in places])
        for k, node in enumerate(cell[corners:]):
            assert np.argmin(np.linalg.norm(centres - x[node], axis=1)) == k


@needs_corpus
@pytest.mark.parametrize("name", ["2D/vtk/quadratic/homogeneousPart", "2D/vtk/quadratic/quadPart",
                                  "3D/vtk/quadratic/6x6x6-hex20", "3D/vtk/quadratic/cutCube",
                                  "3D/vtk/quadratic/hex3Dpart"])
def test_mesquites_curved_meshes_measure_alike_through_exodus_cgns_and_medit(tmp, name):
    # Cells that fold (cutCube, hex3Dpart) included: the same figures to the digit.
    vtk = os.path.join(CORPUS, "mesquite", name + ".vtk")
    reference = curved_quality(tmp, vtk)
    medit_too = "quadPart" not in name and "hex" not in name
    for ext in ("exo", "cgns") + (("mesh",) if medit_too else ()):
        out = os.path.join(tmp, "out." + ext)
        neomesh("convert", vtk, "-o", out)
        assert curved_quality(tmp, out) == reference, ext

MESQUITE_2D = os.path.join(CORPUS, "mesquite", "2D", "vtk", "quadratic")


@needs_corpus
def test_mesquites_folded_2d_quadratic_meshes_are_untangled_to_certified_valid_ones(tmp):
    # Each has 1 to 3 cells that a mid-edge node folds: untangled, then smoothed.
    files = sorted(glob.glob(os.path.join(MESQUITE_2D, "*.vtk")))
    assert len(files) == 11
    out = os.path.join(tmp, "out.vtk")
    for path in files:
        assert curved_quality(tmp, path)["not_certified_valid"] > 0, path
        report = smooth_report(tmp, path, out)
        after = curved_quality(tmp, out)
        assert after["not_certified_valid"] == 0, path
        assert after["scaled_jacobian"]["min"] > 0.02, path
        expect_the_optimum_repaired(report, after)


@needs_corpus
def test_a_folded_curved_mesh_is_refused_without_untangling_and_nothing_is_written(tmp):
    out = os.path.join(tmp, "out.vtk")
    proc = neomesh("smooth", os.path.join(MESQUITE_2D, "triPatch_0_0.vtk"), "-o", out,
                   "--no-untangle", expect=1)
    expect_one_error_line(proc, ["not certified valid", "untangling is switched off"],
                          unwritten=[out])


@needs_corpus
def test_mesquites_hexahedron20_grid_stays_valid_and_as_good(tmp):
    # Serendipity cells: the virtual face and centre vertices carry the topology only.
    path = os.path.join(CORPUS, "mesquite", "3D", "vtk", "quadratic", "6x6x6-hex20.vtk")
    out = os.path.join(tmp, "out.vtk")
    report = smooth_report(tmp, path, out)
    after = curved_quality(tmp, out)
    assert after["not_certified_valid"] == 0
    assert after["scaled_jacobian"]["min"] >= curved_quality(tmp, path)["scaled_jacobian"]["min"]
    assert report["curved"]["nodes"] == read_mesh(out).points.shape[0]


@needs_gmsh
def test_boundary_nodes_slide_on_a_given_circle_exactly(tmp):
    # Corners and mid-edge nodes alike: every node of the rim stays on the circle.
    geo, msh, out = (os.path.join(tmp, name) for name in ("disk.geo", "disk.msh", "out.vtu"))
    open(geo, "w").write('SetFactory("OpenCASCADE");\nDisk(1) = {0, 0, 0, 1, 1};\n'
                         'Mesh.MeshSizeMax = 0.3;\nPhysical Surface("disk", 7) = {1};\n'
                         'Physical Curve("rim", 8) = {1};\n')
    subprocess.run(["gmsh", "-2", "-order", "2", "-setnumber", "Mesh.RecombineAll", "1", geo,
                    "-o", msh], check=True, capture_output=True)
    report = smooth_report(tmp, msh, out, "--shape", "rim=circle:0,0,1")
    assert not report["curved"]["input_returned"]
    radius = np.hypot(*read_mesh(out).points[:, :2].T)
    on_rim = np.abs(radius - 1) < 1e-3
    assert on_rim.sum() == 48 and np.abs(radius[on_rim] - 1).max() < 1e-14
    assert radius.max() < 1 + 1e-14



def picture_pixels(path):
    """A PNG picture's mesh part (the left 70 %: not the colour bar): its pixels in colour (the
    viridis fill) and in red (cells drawn as invalid)."""
    image = pytest.importorskip("matplotlib.image").imread(path)[:, :, :3]
    image = image[:, :int(0.7 * image.shape[1])]
    coloured = image.max(axis=2) - image.min(axis=2) > 0.2
    red = (image[:, :, 0] > 0.75) & (image[:, :, 1] < 0.25) & (image[:, :, 2] < 0.25)
    return coloured.sum(), red.sum()


def test_render_draws_a_curved_mesh_with_its_edges_curved(tmp):
    # A quarter annulus raised onto its circles: its cells cover the annulus, the straight
    # mesh's only the polygon of its chords, whose outer ones cut off more than the inner add.
    straight, curved = os.path.join(tmp, "annulus.msh"), os.path.join(tmp, "curved.msh")
    neomesh("generate", "annulus-quad", "--level", "2", "-o", straight)
    neomesh("curve", straight, "-o", curved, "--shape", "inner=circle:0,0,1",
            "--shape", "outer=circle:0,0,2")
    pictures = [os.path.join(tmp, f"{name}.png") for name in ("straight", "curved")]
    for mesh, picture in zip((straight, curved), pictures):
        neomesh("render", mesh, "-o", picture, "--width", "600")
    (flat, _), (round_, red) = (picture_pixels(p) for p in pictures)
    assert round_ > 1.01 * flat and red == 0


@needs_corpus
def test_render_draws_the_cells_not_certified_valid_in_red(tmp):
    # triPatch_0_0: 6 triangle6, one folded by a mid-edge node between its valid corners.
    path = os.path.join(MESQUITE_2D, "triPatch_0_0.vtk")
    picture = os.path.join(tmp, "curved.png")
    neomesh("render", path, "-o", picture, "--width", "600")
    assert picture_pixels(picture)[1] > 500
