"""Exodus II files (.exo, .e, .ex2) as users bring them: written by meshio (an independent
writer, through netCDF4) they read as the mesh meshio wrote, neomesh's .e and .ex2 read back
unchanged (read -> write -> read: the same coordinates, cells, cell groups and facet groups),
meshio reads it, and a run on an .exo changes nothing but the coordinates (the round trips
with the other formats: test_formats.py). Run with
NEOMESH=path/to/neomesh."""
import json
import os

import numpy as np
import pytest

from conftest import (DATA, RANKS, expect_nothing_else_changed, expect_one_error_line, neomesh,
                      read_mesh)
from test_formats import TOP, CASES, convert, expect_same, facet_groups, generated

meshio = pytest.importorskip("meshio", reason="python3-meshio is not installed")
netCDF4 = pytest.importorskip("netCDF4", reason="python3-netcdf4 is not installed")


@pytest.mark.parametrize("case, level", CASES)
def test_an_exodus_file_written_by_meshio_reads_as_meshio_wrote_it(tmp, case, level):
    mesh = generated(tmp, case, level)
    exo = os.path.join(tmp, "in.exo")
    meshio.write(exo, mesh, file_format="exodus")
    expect_same(read_mesh(convert(tmp, exo, "out.msh")), mesh, groups=False)


def test_blocks_of_lines_are_skipped(tmp):
    """A 2D mesh with its boundary edges in a BAR2 block, as Cubit writes it: the triangles."""
    mesh = generated(tmp, "box-tri", "2")
    edges = [(a, b) for t in mesh.cells[0].data.tolist() for a, b in ((t[0], t[1]), (t[1], t[2]))]
    exo = os.path.join(tmp, "in.exo")
    meshio.write(exo, meshio.Mesh(mesh.points, [mesh.cells[0], ("line", np.array(edges[:5]))]),
                 file_format="exodus")
    expect_same(read_mesh(convert(tmp, exo, "out.msh")), mesh, groups=False)


# Exodus' sides (the manual's tables, 0-based nodes), to write side sets as Cubit does.
SIDES = {"tetra": [(0, 1, 3), (1, 2, 3), (0, 3, 2), (0, 2, 1)],
         "hexahedron": [(0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6), (0, 4, 7, 3), (0, 3, 2, 1),
                        (4, 5, 6, 7)],
         "wedge": [(0, 1, 4, 3), (1, 2, 5, 4), (0, 3, 5, 2), (0, 2, 1), (3, 4, 5)]}


def add_names_and_a_side_set(exo, block_name, set_id, set_name, elements, sides):
    """Names the first element block and adds one side set, in the netCDF variables the Exodus
    library reads (what Cubit writes and meshio does not)."""
    with netCDF4.Dataset(exo, "a") as f:
        if "len_name" not in f.dimensions:
            f.createDimension("len_name", 33)
        names = f.createVariable("eb_names", "S1", ("num_el_blk", "len_name"))
        names[0] = netCDF4.stringtochar(np.array([block_name], "S33"))
        f.createDimension("num_side_sets", 1)
        f.createDimension("num_side_ss1", len(elements))
        f.createVariable("ss_status", "i4", ("num_side_sets",))[:] = [1]
        ids = f.createVariable("ss_prop1", "i4", ("num_side_sets",))
        ids.setncattr("name", "ID")
        ids[:] = [set_id]
        names = f.createVariable("ss_names", "S1", ("num_side_sets", "len_name"))
        names[0] = netCDF4.stringtochar(np.array([set_name], "S33"))
        f.createVariable("elem_ss1", "i4", ("num_side_ss1",))[:] = elements
        f.createVariable("side_ss1", "i4", ("num_side_ss1",))[:] = sides


@pytest.mark.parametrize("case, type", [("box-tet", "tetra"), ("box-hex", "hexahedron"),
                                        ("box-wedge", "wedge")])
def test_side_sets_and_names_written_by_another_program_read_as_groups(tmp, case, type):
    """The sides of the box's floor (its lowest z), found with the manual's side table, come
    out as the facet group of the side set, under its name; the block's name names the cell
    group."""
    mesh = generated(tmp, case, "1")
    exo = os.path.join(tmp, "in.exo")
    meshio.write(exo, mesh, file_format="exodus")
    elements, sides, floor = [], [], []
    for e, nodes in enumerate(mesh.cells[0].data):
        for s, side in enumerate(SIDES[type]):
            if all(mesh.points[nodes[list(side)], 2] == mesh.points[:, 2].min()):
                elements.append(e + 1)
                sides.append(s + 1)
                floor.append((7, tuple(sorted(nodes[list(side)].tolist()))))
    assert floor
    add_names_and_a_side_set(exo, "solid", 7, "floor", elements, sides)
    out = read_mesh(convert(tmp, exo, "out.msh"))
    expect_same(out, mesh, groups=False)
    assert facet_groups(out) == sorted(floor)
    assert {"solid", "floor"} <= out.field_data.keys()
    assert out.field_data["floor"].tolist() == [7, 2]


@pytest.mark.parametrize("ext", [".e", ".ex2"])
def test_every_exodus_extension_is_read_and_written(tmp, ext):
    """(.exo: test_formats.py, with the other formats.)"""
    source = os.path.join(DATA, "cube_tet_v41.msh")
    direct = read_mesh(convert(tmp, source, "direct.msh"))
    again = read_mesh(convert(tmp, convert(tmp, source, "middle" + ext), "again.msh"))
    expect_same(again, direct)
    assert facet_groups(again) == facet_groups(direct)


@pytest.mark.parametrize("case, level", CASES)
def test_meshio_reads_what_neomesh_writes(tmp, case, level):
    """Every cell type, in the order and with the coordinates of the .msh; a 2D mesh has
    num_dim 2."""
    source = os.path.join(tmp, "box.msh")
    neomesh("generate", case, "--level", level, "--jitter", "0.2", "-o", source)
    exo = convert(tmp, source, "box.exo")
    ours = read_mesh(source)
    with netCDF4.Dataset(exo) as f:
        assert f.dimensions["num_dim"].size == max(TOP.get(b.type, 0) for b in ours.cells)
    expect_same(read_mesh(exo), ours, groups=False)


@pytest.mark.parametrize("ranks", RANKS)
@pytest.mark.parametrize("case", ["box-tri", "box-hex"])
def test_smoothing_an_exodus_file_changes_only_coordinates(tmp, case, ranks):
    source = os.path.join(tmp, "box.msh")
    neomesh("generate", case, "--level", "1", "--jitter", "0.2", "-o", source)
    exo, out = convert(tmp, source, "in.exo"), os.path.join(tmp, "out.exo")
    neomesh("smooth", exo, "-o", out, "--quiet", ranks=ranks)
    expect_nothing_else_changed(exo, out)
    before = read_mesh(convert(tmp, exo, "before.msh"))
    after = read_mesh(convert(tmp, out, "after.msh"))
    assert facet_groups(after) == facet_groups(before) != []
    assert not np.array_equal(after.points, before.points)


def test_what_cannot_be_read_is_refused_in_one_line(tmp):
    second_order = os.path.join(tmp, "p2.exo")
    points = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1], [.5, 0, 0], [.5, .5, 0],
                       [0, .5, 0], [0, 0, .5], [.5, 0, .5], [0, .5, .5]], float)
    meshio.write(second_order, meshio.Mesh(points, [("tetra10", [list(range(10))])]),
                 file_format="exodus")
    garbage = os.path.join(tmp, "garbage.e")
    open(garbage, "w").write("not an Exodus file\n")
    out = os.path.join(tmp, "o.exo")
    for command, path, more, words in [
            ("adapt", second_order, ["--sphere", "0.3,0.3,0.3,0.1"],
             ["p2.exo", "second-order (curved) cells", "adapt does not take"]),
            ("smooth", garbage, [], ["garbage.e", "Exodus"])]:
        expect_one_error_line(neomesh(command, path, "-o", out, *more, expect=1), words, [out])


def test_meshios_tetra10_is_read_with_its_nodes_on_their_edges(tmp):
    # meshio writes the nodes as given, here each on the edge Exodus numbers it: the curved cell
    # is the straight one, measured alike (a wrong order would bend it).
    second_order = os.path.join(tmp, "p2.exo")
    points = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1], [.5, 0, 0], [.5, .5, 0],
                       [0, .5, 0], [0, 0, .5], [.5, 0, .5], [0, .5, .5]], float)
    meshio.write(second_order, meshio.Mesh(points, [("tetra10", [list(range(10))])]),
                 file_format="exodus")
    report = os.path.join(tmp, "q.json")
    neomesh("quality", second_order, "--json", report)
    q = json.load(open(report))
    assert q["curved"]["cells"] == {"tetrahedron10": 1}
    assert q["curved"]["not_certified_valid"] == 0
    assert q["curved"]["scaled_jacobian"]["min"] == pytest.approx(2 ** -0.5)
