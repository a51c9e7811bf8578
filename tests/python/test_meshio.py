"""Meshes in and out as arrays and meshio objects: mixed cell types, groups (cell sets),
lower-dimensional cells, point and cell data all come back unchanged; only coordinates move."""
import os

import meshio
import numpy as np
import pytest

import neomesh
from conftest import DATA


def mixed_plate():
    """[0,2]×[0,1]: 2 quads on the left, 4 triangles on the right, boundary lines, data."""
    points = np.array([[0, 0, 0], [1, 0, 0], [2, 0, 0], [0, 0.5, 0], [1.1, 0.45, 0],
                       [2, 0.5, 0], [0, 1, 0], [1, 1, 0], [2, 1, 0]], dtype=float)
    quads = np.array([[0, 1, 4, 3], [3, 4, 7, 6]])
    triangles = np.array([[1, 2, 5], [1, 5, 4], [4, 5, 8], [4, 8, 7]])
    lines = np.array([[0, 1], [1, 2], [6, 7], [7, 8]])
    return meshio.Mesh(
        points, [("quad", quads), ("line", lines), ("triangle", triangles)],
        point_data={"temperature": np.arange(9.0), "velocity": np.ones((9, 2))},
        cell_data={"material": [np.array([1, 2]), np.array([7, 7, 8, 8]),
                                np.array([3, 4, 5, 6])]},
        cell_sets={"left": [np.array([0, 1]), np.array([], dtype=int), np.array([], dtype=int)],
                   "bottom": [np.array([], dtype=int), np.array([0, 1]), np.array([], dtype=int)]},
        field_data={"bottom": np.array([1, 1])})


def assert_same_except_points(a, b):
    assert [c.type for c in a.cells] == [c.type for c in b.cells]
    for x, y in zip(a.cells, b.cells):
        np.testing.assert_array_equal(x.data, y.data)
    assert set(a.point_data) == set(b.point_data)
    for k in a.point_data:
        np.testing.assert_array_equal(a.point_data[k], b.point_data[k])
    assert set(a.cell_data) == set(b.cell_data)
    for k in a.cell_data:
        for x, y in zip(a.cell_data[k], b.cell_data[k]):
            np.testing.assert_array_equal(x, y)
    assert set(a.cell_sets) == set(b.cell_sets)
    for k in a.cell_sets:
        for x, y in zip(a.cell_sets[k], b.cell_sets[k]):
            np.testing.assert_array_equal(x, y)
    assert set(a.field_data) == set(b.field_data)


def test_a_mixed_mesh_with_groups_and_data_round_trips_and_only_its_points_move(tmp_path):
    m = mixed_plate()
    mesh = neomesh.Mesh.from_meshio(m)
    assert (mesh.dim, mesh.num_cells, mesh.num_vertices) == (2, 6, 9)
    back = mesh.to_meshio()
    np.testing.assert_array_equal(back.points, m.points)
    assert_same_except_points(back, m)
    assert [t for t, _ in mesh.cells] == ["quad", "triangle"]

    neomesh.smooth(mesh, boundary="fixed", targets="ideal", sizes="uniform")
    moved = mesh.to_meshio()
    assert moved.points.shape == (9, 3) and np.all(moved.points[:, 2] == 0)
    assert np.abs(moved.points[4] - m.points[4]).max() > 1e-3  # the interior vertex moved
    np.testing.assert_array_equal(np.delete(moved.points, 4, axis=0),
                                  np.delete(m.points, 4, axis=0))
    assert_same_except_points(moved, m)
    moved.write(tmp_path / "moved.vtu")  # what meshio writes, it reads back
    again = meshio.read(tmp_path / "moved.vtu")
    np.testing.assert_allclose(again.points, moved.points, rtol=0, atol=1e-15)


@pytest.mark.parametrize("cells", [
    {"quad": [[0, 1, 4, 3], [3, 4, 7, 6]], "triangle": [[1, 2, 5], [1, 5, 4], [4, 5, 8], [4, 8, 7]]},
    [("quad", [[0, 1, 4, 3], [3, 4, 7, 6]]), ("triangle", [[1, 2, 5], [1, 5, 4], [4, 5, 8],
                                                          [4, 8, 7]])],
])
def test_from_arrays_takes_a_dict_or_a_list(cells):
    points = mixed_plate().points[:, :2]
    mesh = neomesh.Mesh.from_arrays(points, cells)
    np.testing.assert_array_equal(mesh.points, points)
    blocks = mesh.cells
    assert [t for t, _ in blocks] == ["quad", "triangle"]
    np.testing.assert_array_equal(blocks[1][1][0], [1, 2, 5])
    q = mesh.quality()
    assert q["volume"].sum() == pytest.approx(2.0, rel=1e-14)


def test_a_3d_mixed_file_reads_the_same_through_meshio_and_neomesh():
    path = os.path.join(DATA, "vtu_mixed_3d_ascii.vtu")
    m = meshio.read(path)
    ours = neomesh.Mesh.from_meshio(m)
    theirs = neomesh.Mesh.read(path)
    # (neomesh's reader drops the points of the vertex and line cells; meshio keeps them)
    assert [t for t, _ in ours.cells] == [t for t, _ in theirs.cells] == [
        "hexahedron", "wedge", "pyramid", "tetra"]
    for (_, a), (_, b) in zip(ours.cells, theirs.cells):
        np.testing.assert_array_equal(ours.points[a], theirs.points[b])
    np.testing.assert_allclose(ours.quality()["volume"], theirs.quality()["volume"], rtol=1e-14)
    assert ours.quality()["inverted"].sum() == 0


def test_what_neomesh_cannot_use_is_refused_in_one_line():
    points = np.zeros((4, 2))
    with pytest.raises(neomesh.Error, match="no cells neomesh optimizes .*; got triangle6"):
        neomesh.Mesh.from_arrays(points, {"triangle6": [[0, 1, 2, 3, 3, 3]]})
    with pytest.raises(neomesh.Error, match="does not optimize 'triangle6'"):
        neomesh.Mesh.from_arrays(points, {"quad": [[0, 1, 2, 3]], "triangle6": [[0, 1, 2, 3, 3, 3]]})
    with pytest.raises(neomesh.Error, match="need 3 vertices"):
        neomesh.Mesh.from_arrays(points, {"triangle": [[0, 1, 2, 3]]})
    with pytest.raises(neomesh.Error, match="lie in one plane: give 2 coordinates per vertex"):
        neomesh.Mesh.from_arrays([[0, 0, 0], [1, 0, 1], [0, 1, 0]], {"triangle": [[0, 1, 2]]})


def cubed_sphere(n):
    """The unit sphere as n × n quads on each face of the cube [-1, 1]³, pushed out onto it,
    counter-clockwise seen from outside: (points, quads)."""
    points, quads = [], []
    t = np.linspace(-1, 1, n + 1)
    for axis in range(3):
        for side in (-1.0, 1.0):
            first = len(points)
            for b in t:
                for a in t:
                    p = np.empty(3)
                    p[axis], p[(axis + 1) % 3], p[(axis + 2) % 3] = side, a, b
                    points.append(p / np.linalg.norm(p))
            for j in range(n):
                for i in range(n):
                    v = first + j * (n + 1) + i
                    q = [v, v + 1, v + n + 2, v + n + 1]
                    quads.append(q if side > 0 else q[::-1])
    return np.array(points), np.array(quads)


def test_a_surface_mesh_has_three_coordinates_per_point_and_moves_with_them():
    points, quads = cubed_sphere(4)
    mesh = neomesh.Mesh.from_arrays(points, {"quad": quads})
    assert (mesh.dim, mesh.coordinate_dim) == (2, 3)
    np.testing.assert_array_equal(mesh.points, points)
    assert mesh.local_points.shape == (mesh.num_vertices, 3)
    neomesh.smooth(mesh)
    smoothed = mesh.points
    assert np.linalg.norm(smoothed, axis=1).max() <= 1 + 1e-12  # on the input's cells
    # Assigned points that leave the surface move it: the sphere blown up to radius 2 is
    # smoothed on its own cells, not pulled back.
    mesh.points = 2 * smoothed
    neomesh.smooth(mesh)
    radius = np.linalg.norm(mesh.points, axis=1)
    assert radius.min() > 1.8 and radius.max() <= 2 + 1e-12
    np.testing.assert_array_equal(mesh.to_meshio().points, mesh.points)


def test_write_and_read_back(tmp_path):
    mesh = neomesh.Mesh.generate("box-tri", size=4)
    neomesh.smooth(mesh)
    mesh.write(str(tmp_path / "out.msh"))
    again = neomesh.Mesh.read(str(tmp_path / "out.msh"))
    np.testing.assert_allclose(again.points, mesh.points, rtol=0, atol=1e-15)
    s = mesh.quality_summary()
    assert s["cells"]["total"] == mesh.num_cells and s["inverted"] == 0


def test_a_feat3_mesh_reads_with_its_chart_file():
    mesh = neomesh.Mesh.read([os.path.join(DATA, "feat_chart_file_charts.xml"),
                              os.path.join(DATA, "feat_chart_file_mesh.xml")])
    assert mesh.num_cells > 0 and "feat_chart_file_mesh.xml" in mesh.name


def entities_by_group(m):
    """{group name: sorted vertex tuples of its cells/facets} from meshio's Gmsh tags."""
    out = {}
    for name, (tag, dim) in m.field_data.items():
        out[name] = sorted(tuple(sorted(c)) for block, tags in zip(m.cells, m.cell_data["gmsh:physical"])
                           if meshio._mesh.topological_dimension[block.type] == dim
                           for c in block.data[tags == tag])
    return out


def test_a_file_read_by_neomesh_comes_out_with_its_groups_and_data(tmp_path):
    path = os.path.join(DATA, "mixed_tri_quad_v41.msh")
    theirs = meshio.read(path)
    mesh = neomesh.Mesh.read(path)
    ours = mesh.to_meshio()
    groups = entities_by_group(theirs)
    assert len(groups) >= 3 and entities_by_group(ours) == groups
    assert set(ours.cell_sets) == set(groups)

    # point and cell data of a .vtu
    m = mixed_plate()
    data = meshio.Mesh(m.points, [("quad", m.cells[0].data), ("triangle", m.cells[2].data)],
                       point_data={"temperature": np.arange(9.0), "velocity": np.ones((9, 2))},
                       cell_data={"material": [np.array([1.0, 2.0]), np.array([3.0, 4, 5, 6])]})
    data.write(tmp_path / "data.vtu")
    mesh = neomesh.Mesh.read(str(tmp_path / "data.vtu"))
    neomesh.smooth(mesh, boundary="fixed")
    out = mesh.to_meshio()
    np.testing.assert_array_equal(out.point_data["temperature"], np.arange(9.0))
    np.testing.assert_array_equal(out.point_data["velocity"], np.ones((9, 2)))
    np.testing.assert_array_equal(np.concatenate(out.cell_data["material"][:2]), [1, 2, 3, 4, 5, 6])
    assert np.abs(out.points[4, :2] - m.points[4, :2]).max() > 1e-3
