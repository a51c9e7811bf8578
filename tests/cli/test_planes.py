"""A 2D mesh is optimized in the plane it lies in and written back there: a plane at z = 5, a
plane tilted out of xy, Mesquite's planes off z = 0; a mesh of 2D cells that is not planar is a
surface mesh, smoothed on its own cells (test_surfaces.py). Every output is checked for what must not change
(conftest.expect_nothing_else_changed). Run with NEOMESH=path/to/neomesh."""
import json
import os

import numpy as np
import pytest

from conftest import (CORPUS, expect_nothing_else_changed, needs_corpus,
                      needs_mpi, neomesh, read_mesh, vtk_to_msh)


def placed(tmp, name, transform, cell="box-quad"):
    """A jittered 12×12 mesh of the unit square, its points moved by `transform`, as Gmsh 2.2."""
    import meshio
    flat = os.path.join(tmp, name + "-flat.msh")
    neomesh("generate", cell, "--cells", 12, "--jitter", 0.2, "-o", flat)
    m = read_mesh(flat)
    m.points = transform(m.points)
    path = os.path.join(tmp, name + ".msh")
    meshio.write(path, m, file_format="gmsh22", binary=False)
    return path


def smooth(tmp, path, *options, output=".msh"):
    out = path.replace(".msh", "-out" + output)
    report = path.replace(".msh", ".json")
    # Without the worst-cell repair, a max-min search whose choices round-off can flip (docs/
    # method.md, "Worst cells"): the plane's handling is what must agree to 1e-6.
    neomesh("smooth", path, "-o", out, "--quiet", "--report", report, "--no-repair", *options)
    with open(report) as f:
        r = json.load(f)
    sj = lambda q: q["metrics"]["scaled_jacobian"]["min"]
    return out, sj(r["quality_before"]), sj(r["quality_after"])


def lift(z):
    return lambda p: np.column_stack([p[:, 0], p[:, 1], np.full(len(p), z)])


def tilt(p):
    """Rotated 30° about x, then 20° about z, and moved: a plane no axis is normal to."""
    a, b = np.radians(30), np.radians(20)
    rx = np.array([[1, 0, 0], [0, np.cos(a), -np.sin(a)], [0, np.sin(a), np.cos(a)]])
    rz = np.array([[np.cos(b), -np.sin(b), 0], [np.sin(b), np.cos(b), 0], [0, 0, 1]])
    q = np.column_stack([p[:, 0], p[:, 1], np.zeros(len(p))])
    return q @ (rz @ rx).T + [1.5, -2.0, 3.0]


@pytest.mark.parametrize("boundary", ["slide", "fixed"])
@pytest.mark.parametrize("output", [".msh", ".vtu"])
@pytest.mark.parametrize("name, transform, cell", [("z5", lift(5.0), "box-quad"),
                                                    ("tilted", tilt, "box-tri")])
def test_a_plane_off_xy_is_optimized_in_it(tmp, name, transform, cell, output, boundary):
    path = placed(tmp, name, transform, cell)
    out, before, after = smooth(tmp, path, "--boundary", boundary, output=output)
    assert after > before + 0.05, f"min scaled Jacobian {before} -> {after}"
    expect_nothing_else_changed(path, out, fixed_boundary=boundary == "fixed")
    if name == "z5":
        assert np.all(read_mesh(out).points[:, 2] == 5.0)


def test_the_same_mesh_in_xy_and_in_a_tilted_plane_smooths_alike(tmp):
    a = smooth(tmp, placed(tmp, "flat", lift(0.0), "box-tri"))
    b = smooth(tmp, placed(tmp, "tilted", tilt, "box-tri"))
    assert a[1:] == pytest.approx(b[1:], rel=1e-6)


def test_a_surface_mesh_is_smoothed_on_its_own_cells(tmp):
    # 2D cells off one plane are a surface mesh (test_surfaces.py): smoothed, not refused.
    bowl = placed(tmp, "bowl", lambda p: np.column_stack([p[:, 0], p[:, 1], p[:, 0] ** 2 + p[:, 1] ** 2]))
    out, report = os.path.join(tmp, "out.msh"), os.path.join(tmp, "out.json")
    neomesh("smooth", bowl, "-o", out, "--quiet", "--report", report)
    with open(report) as f:
        r = json.load(f)
    assert r["boundary_change"]["max_distance_from_input_boundary"] < 1e-12
    assert len(read_mesh(out).points) == len(read_mesh(bowl).points)
    neomesh("quality", bowl)


MESQUITE_PLANES = ["tris/untangled/tri_5_not_xy", "tris/untangled/tri_5_xz",
                   "quads/untangled/quad_2_not_xy"]


@needs_corpus
@pytest.mark.parametrize("name", MESQUITE_PLANES)
def test_mesquites_planes_off_xy_stay_in_place(tmp, name):
    path = os.path.join(tmp, os.path.basename(name) + ".msh")
    vtk_to_msh(os.path.join(CORPUS, "mesquite", "2D", "vtk", name + ".vtk"), path)
    out, before, after = smooth(tmp, path)
    assert after >= before
    expect_nothing_else_changed(path, out)


@needs_mpi
def test_a_tilted_plane_on_two_ranks_is_written_back_in_it(tmp):
    path = placed(tmp, "tilted", tilt, "box-tri")
    outputs = []
    for ranks in (1, 2):
        out = path.replace(".msh", f"-{ranks}.msh")
        neomesh("smooth", path, "-o", out, "--quiet", "--boundary", "fixed", "--no-repair",
                ranks=ranks)
        expect_nothing_else_changed(path, out, fixed_boundary=True)
        outputs.append(read_mesh(out).points)
    assert np.abs(outputs[0] - outputs[1]).max() < 1e-6
