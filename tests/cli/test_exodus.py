"""Exodus II files (.exo, .e, .ex2) as users bring them: written by meshio (an independent
writer, through netCDF4) they read as the mesh meshio wrote, neomesh's .e and .ex2 read back
unchanged (read -> write -> read: the same coordinates, cells, cell groups and facet groups),
meshio reads it, and a run on an .exo changes nothing but the coordinates (the round trips
with the other formats: test_formats.py). Run with
NEOMESH=path/to/neomesh."""
import os

import numpy as np
import pytest

from conftest import (DATA, RANKS, expect_nothing_else_changed, expect_one_error_line, neomesh,
                      read_mesh)
from test_formats import CASES, cells, convert, expect_same, facet_groups, generated

meshio = pytest.importorskip("meshio", reason="python3-meshio is not installed")
netCDF4 = pytest.importorskip("netCDF4", reason="python3-netcdf4 is not installed")


@pytest.mark.parametrize("case, level", CASES)
def test_an_exodus_file_written_by_meshio_reads_as_meshio_wrote_it(tmp, case, level):
    mesh = generated(tmp, case, level)
    exo = os.path.join(tmp, "in.exo")
    meshio.write(exo, mesh, file_format="exodus")
    expect_same(read_mesh(convert(tmp, exo, "out.msh")), mesh, groups=False)


@pytest.mark.parametrize("ext", [".e", ".ex2"])
def test_every_exodus_extension_is_read_and_written(tmp, ext):
    """(.exo: test_formats.py, with the other formats.)"""
    source = os.path.join(DATA, "cube_tet_v41.msh")
    direct = read_mesh(convert(tmp, source, "direct.msh"))
    again = read_mesh(convert(tmp, convert(tmp, source, "middle" + ext), "again.msh"))
    expect_same(again, direct)
    assert facet_groups(again) == facet_groups(direct)


def test_a_2d_mesh_is_written_with_two_coordinates_and_meshio_reads_it(tmp):
    source = os.path.join(tmp, "box.msh")
    neomesh("generate", "box-quad", "--level", "2", "--jitter", "0.2", "-o", source)
    exo = convert(tmp, source, "box.exo")
    with netCDF4.Dataset(exo) as f:
        assert f.dimensions["num_dim"].size == 2
    theirs, ours = read_mesh(exo), read_mesh(source)
    assert np.array_equal(theirs.points[:, :2], ours.points[:, :2])
    assert np.array_equal(cells(theirs)[0]["quad"], cells(ours)[0]["quad"])


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
    for path, words in [(second_order, ["p2.exo", "block 0", "TETRA10", "10 nodes"]),
                        (garbage, ["garbage.e", "Exodus"])]:
        expect_one_error_line(neomesh("smooth", path, "-o", out, expect=1), words, [out])
