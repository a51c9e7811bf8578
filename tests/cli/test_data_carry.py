"""The input's point and cell data, written by another program (meshio), come out of
`neomesh smooth` and `neomesh convert` unchanged: the same names, components and values per
vertex and cell of the input's numbering, while the coordinates move. Run with
NEOMESH=path/to/neomesh (and NEOMESH_MPIEXEC for the 2-rank runs)."""
import os

import numpy as np
import pytest

from conftest import DATA, RANKS, neomesh, read_mesh

meshio = pytest.importorskip("meshio", reason="python3-meshio is not installed")

TOP = {"triangle": 2, "quad": 2, "tetra": 3, "hexahedron": 3, "wedge": 3, "pyramid": 3}


def with_data(tmp, case, level):
    """A generated, jittered mesh (its cells only) with point data "temperature" (float64),
    "velocity" (float32, 3 components) and cell data "material" (int32)."""
    msh = os.path.join(tmp, case + ".msh")
    neomesh("generate", case, "--level", level, "--jitter", "0.2", "-o", msh)
    m = read_mesh(msh)
    dim = max(TOP.get(b.type, 0) for b in m.cells)
    blocks = [(b.type, b.data) for b in m.cells if TOP.get(b.type, 0) == dim]
    p = m.points
    point_data = {"temperature": p[:, 0] + 2 * p[:, 1] + 3 * p[:, 2],
                  "velocity": np.stack([p[:, 1], -p[:, 0], p[:, 2] + 1], axis=1).astype(np.float32)}
    material = []
    first = 0
    for _, data in blocks:
        material.append((first + np.arange(len(data)) * 7 % 5).astype(np.int32))
        first += len(data)
    return meshio.Mesh(p, blocks, point_data=point_data, cell_data={"material": material})


def cell_values(mesh, name):
    """The cell data `name` of the cells (elements of the highest dimension), in order."""
    dim = max(TOP.get(b.type, 0) for b in mesh.cells)
    return np.concatenate([mesh.cell_data[name][k] for k, b in enumerate(mesh.cells)
                           if TOP.get(b.type, 0) == dim])


def expect_same_data(out, mesh):
    assert set(mesh.point_data) <= set(out.point_data), out.point_data.keys()
    for name, values in mesh.point_data.items():
        got = out.point_data[name]
        assert got.shape == values.shape, name
        assert np.array_equal(got, values), name
    for name in mesh.cell_data:
        assert np.array_equal(cell_values(out, name), cell_values(mesh, name)), name


@pytest.mark.parametrize("ranks", RANKS)
@pytest.mark.parametrize("case, level", [("box-tri", "2"), ("box-quad", "2"), ("box-tet", "1")])
@pytest.mark.parametrize("source, target", [(".vtu", ".vtu"), (".vtk", ".vtk"),
                                            (".vtu", ".vtk"), (".vtk", ".vtu")])
def test_smoothing_keeps_the_data_meshio_wrote(tmp, case, level, source, target, ranks):
    mesh = with_data(tmp, case, level)
    path = os.path.join(tmp, "in" + source)
    meshio.write(path, mesh, binary=False)
    out = os.path.join(tmp, "out" + target)
    neomesh("smooth", path, "-o", out, "--quiet", ranks=ranks)
    got = read_mesh(out)
    assert not np.allclose(got.points, mesh.points)  # the vertices moved, their data did not
    expect_same_data(got, read_mesh(path))  # as the file holds them (ASCII: 12 digits)
    # The types are kept (the legacy reader of meshio reads FIELD data as it is typed).
    assert got.point_data["velocity"].dtype == np.float32
    assert cell_values(got, "material").dtype == np.int32
    # neomesh's own fields come too.
    if target == ".vtu":
        assert "scaled_jacobian" in got.cell_data


@pytest.mark.parametrize("ranks", RANKS)
def test_exodus_keeps_the_data_as_variables(tmp, ranks):
    """.vtu -> .exo -> .vtu: the variables come back as the arrays (vectors joined again)."""
    mesh = with_data(tmp, "box-hex", "1")
    path = os.path.join(tmp, "in.vtu")
    meshio.write(path, mesh)
    exo = os.path.join(tmp, "mid.exo")
    neomesh("smooth", path, "-o", exo, "--quiet", ranks=ranks)
    again = os.path.join(tmp, "again.vtu")
    neomesh("convert", exo, "-o", again)
    got = read_mesh(again)
    for name, values in mesh.point_data.items():
        assert np.array_equal(got.point_data[name], values.astype(np.float64)), name
    assert np.array_equal(cell_values(got, "material"), cell_values(mesh, "material"))


@pytest.mark.parametrize("ranks", RANKS)
def test_exodus_keeps_every_time_step_and_the_global_variables(tmp, ranks):
    """An .exo of two time steps (times 0.5 and 1.5) and a global variable "energy", as
    meshio writes one step and netCDF4 adds the rest: smoothed to .exo, every step comes back
    with its time, nodal values and global values. (meshio stores a netCDF variable per nodal
    variable without saying so, where the Exodus library looks for one of them all.)"""
    netCDF4 = pytest.importorskip("netCDF4", reason="python3-netcdf4 is not installed")
    mesh = with_data(tmp, "box-hex", "1")
    t = mesh.point_data["temperature"]
    path = os.path.join(tmp, "in.exo")
    meshio.write(path, meshio.Mesh(mesh.points, mesh.cells, point_data={"temperature": t}))
    with netCDF4.Dataset(path, "a") as nc:
        nc["time_whole"][:2] = [0.5, 1.5]
        nc["vals_nod_var1"][1, :] = 2 * t
        nc.createDimension("num_glo_var", 1)
        name = nc.createVariable("name_glo_var", "S1", ("num_glo_var", "len_string"))
        name[0, :] = netCDF4.stringtochar(np.array(["energy"], f"S{len(nc.dimensions['len_string'])}"))
        nc.createVariable("vals_glo_var", "f8", ("time_step", "num_glo_var"))[:, 0] = [10, 20]
    out = os.path.join(tmp, "out.exo")
    neomesh("smooth", path, "-o", out, "--quiet", ranks=ranks)
    with netCDF4.Dataset(out) as nc:
        assert nc["time_whole"][:].tolist() == [0.5, 1.5]
        assert nc["vals_glo_var"][:].tolist() == [[10], [20]]
        assert np.array_equal(nc["vals_nod_var1"][0, :], t)
        assert np.array_equal(nc["vals_nod_var1"][1, :], 2 * t)
        assert not np.allclose(np.stack([nc["coordx"][:], nc["coordy"][:], nc["coordz"][:]], 1),
                               mesh.points)


def test_the_groups_of_a_msh_survive_vtu_written_by_meshio(tmp):
    """meshio converts a .msh's boundary groups to lines with "gmsh:physical"; neomesh reads
    them as facet groups, and writes them back (with their names, which meshio drops)."""
    source = os.path.join(tmp, "square.msh")
    neomesh("generate", "square-midpoint", "--level", "2", "-o", source)
    m = read_mesh(source)
    vtu = os.path.join(tmp, "meshio.vtu")
    meshio.write(vtu, meshio.Mesh(m.points, m.cells,
                                  cell_data={"gmsh:physical": m.cell_data["gmsh:physical"]}))
    again = os.path.join(tmp, "again.msh")
    neomesh("convert", vtu, "-o", again)
    direct = os.path.join(tmp, "direct.msh")
    neomesh("convert", source, "-o", direct)

    def facets(path):
        mesh = read_mesh(path)
        tags = mesh.cell_data["gmsh:physical"]
        return sorted((int(t), tuple(sorted(f))) for k, b in enumerate(mesh.cells)
                      if b.type == "line" for f, t in zip(b.data.tolist(), tags[k]))

    assert facets(again) == facets(direct) != []
    # neomesh's own .vtu keeps the names too.
    ours = os.path.join(tmp, "ours.vtu")
    neomesh("convert", source, "-o", ours)
    named = os.path.join(tmp, "named.msh")
    neomesh("convert", ours, "-o", named)
    assert facets(named) == facets(direct)
    assert read_mesh(named).field_data.keys() == read_mesh(direct).field_data.keys()


def test_data_of_unused_points_and_facets_are_dropped_with_them(tmp):
    """A point no cell uses and the lines of a 2D mesh are not written back, nor their data."""
    points = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [9, 9, 0]], dtype=float)
    mesh = meshio.Mesh(points, [("triangle", np.array([[0, 1, 2], [0, 2, 3]])),
                                ("line", np.array([[0, 1]]))],
                       point_data={"id": np.arange(5, dtype=np.int64)},
                       cell_data={"c": [np.array([1.5, 2.5]), np.array([9.5])]})
    path = os.path.join(tmp, "in.vtu")
    meshio.write(path, mesh)
    out = os.path.join(tmp, "out.vtu")
    neomesh("convert", path, "-o", out)
    got = read_mesh(out)
    assert got.point_data["id"].tolist() == [0, 1, 2, 3]
    assert got.point_data["id"].dtype == np.int64
    assert [b.type for b in got.cells] == ["triangle"]
    assert got.cell_data["c"][0].tolist() == [1.5, 2.5]


@pytest.mark.parametrize("ranks", RANKS)
@pytest.mark.parametrize("target", [".msh", ".vtu"])
@pytest.mark.parametrize("version,binary", [("gmsh22", False), ("gmsh22", True), ("gmsh", True)])
def test_gmsh_node_and_element_data_are_kept(tmp, target, ranks, version, binary):
    """meshio writes point and cell data to .msh as $NodeData and $ElementData, in ASCII and in
    binary files (2.2 and 4.1)."""
    mesh = with_data(tmp, "box-quad", "2")
    mesh.cell_data["gmsh:physical"] = [np.full(len(b.data), 1, dtype=np.int32) for b in mesh.cells]
    mesh.cell_data["gmsh:geometrical"] = mesh.cell_data["gmsh:physical"]
    path = os.path.join(tmp, "in.msh")
    meshio.write(path, mesh, file_format=version, binary=binary)
    out = os.path.join(tmp, "out" + target)
    neomesh("smooth", path, "-o", out, "--quiet", ranks=ranks)
    got, expected = read_mesh(out), read_mesh(path)
    assert not np.allclose(got.points, expected.points)
    for name in ("temperature", "velocity"):
        assert np.array_equal(got.point_data[name].reshape(expected.point_data[name].shape),
                              expected.point_data[name]), name
    assert np.array_equal(cell_values(got, "material").ravel(),
                          cell_values(expected, "material").ravel())


def test_medit_vertex_references_are_kept(tmp):
    """meshio writes the point data "medit:ref" as Medit's vertex references; a .mesh -> .vtu ->
    .mesh conversion keeps them."""
    mesh = with_data(tmp, "box-tri", "2")
    refs = (np.arange(len(mesh.points)) % 4).astype(np.int32)
    path = os.path.join(tmp, "in.mesh")
    meshio.write(path, meshio.Mesh(mesh.points, mesh.cells, point_data={"medit:ref": refs}))
    mid = os.path.join(tmp, "mid.vtu")
    neomesh("convert", path, "-o", mid)
    assert np.array_equal(read_mesh(mid).point_data["medit:ref"], refs)
    again = os.path.join(tmp, "again.mesh")
    neomesh("convert", mid, "-o", again)
    assert np.array_equal(read_mesh(again).point_data["medit:ref"], refs)
