"""Curved (second-order) meshes as a user gives them: read from Gmsh .msh (2.2 and 4.1, ASCII and
binary) and VTK .vtk/.vtu, measured by `quality` (validity certified over each cell), written by
`convert` to .msh, .vtu (Lagrange cells, which VTK reads) and .vtk, and smoothed, every node
moving, to a mesh whose cells are certified valid. Gmsh meshes are made by the gmsh program (skipped without it), Mesquite's quadratic
meshes come from ../shared/corpus (skipped without it). Run with NEOMESH=path/to/neomesh."""
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
"""
BALL = """SetFactory("OpenCASCADE");
Sphere(1) = {0, 0, 0, 1};
Mesh.MeshSizeMax = 0.6;
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
}


def gmsh_mesh(tmp, case, fmt="msh41", binary=False):
    geometry, dim, options, _ = GMSH_CASES[case]
    geo = os.path.join(tmp, case + ".geo")
    open(geo, "w").write(geometry)
    out = os.path.join(tmp, f"{case}-{fmt}{'-bin' if binary else ''}.msh")
    subprocess.run(["gmsh", f"-{dim}", "-order", "2", *options, *(["-bin"] if binary else []),
                    geo, "-format", fmt, "-o", out], check=True, capture_output=True)
    return out


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
    for ext in ("msh", "vtu", "vtk"):
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
                                            ("hex27", 72), ("hex20", 25)])
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
    assert {b.type for b in m.cells} == {"triangle6", "line"}


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
    assert curved["min_scaled_jacobian_optimum"] == pytest.approx(after["scaled_jacobian"]["min"])
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


@needs_gmsh
def test_smooth_refuses_a_curved_mesh_on_several_processes(tmp):
    msh = gmsh_mesh(tmp, "tri6")
    proc = neomesh("smooth", msh, "-o", "out.msh", cwd=tmp, expect=1, ranks=2)
    expect_one_error_line(proc, ["second-order (curved) cells", "one process"],
                          unwritten=[os.path.join(tmp, "out.msh")])


@needs_gmsh
def test_a_curved_mesh_is_not_written_where_the_format_has_no_curved_cells(tmp):
    msh = gmsh_mesh(tmp, "tri6")
    for ext in ("mesh", "exo", "cgns"):
        out = os.path.join(tmp, "out." + ext)
        expect_one_error_line(neomesh("convert", msh, "-o", out, expect=1),
                              ["second-order (curved) cells", ".msh, .vtu or .vtk"],
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
          "hexahedron20": (17, 25, 25), "hexahedron27": (12, 72, 29)}


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
        assert report["curved"]["min_scaled_jacobian_optimum"] == pytest.approx(
            after["scaled_jacobian"]["min"])


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
