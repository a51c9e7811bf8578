"""Target cells (`--targets`, docs/method.md §9): the default keeps what the mesh's author meant
— boundary layers, graded CAD meshes — and still repairs the rest; `ideal` is the thesis'
model, which fights that design. Run with NEOMESH=path/to/neomesh."""
import json
import os

import numpy as np
import pytest

import boundary_layers
from conftest import (CORPUS, expect_nothing_else_changed, needs_corpus, needs_mpi, neomesh,
                      read_mesh)


def smooth(tmp, mesh, *options, name="out"):
    out = os.path.join(tmp, name + ".vtu")
    report = os.path.join(tmp, name + ".json")
    neomesh("smooth", mesh, "-o", out, "--quiet", "--report", report, *options)
    with open(report) as f:
        return out, json.load(f)


@pytest.fixture(scope="module")
def channel(module_tmp):
    return boundary_layers.channel(module_tmp)


@pytest.fixture(scope="module")
def sphere(module_tmp):
    return boundary_layers.sphere(module_tmp)


def test_the_default_keeps_a_2d_boundary_layer_and_repairs_the_rest(tmp, channel):
    out, report = smooth(tmp, channel)
    change = boundary_layers.layer_change_2d(channel, out)
    assert max(map(abs, change["first_height"])) < 0.01, change
    assert max(map(abs, change["thickness"])) < 0.01, change
    assert report["targets"]["mode"] == "smoothed"
    assert report["targets"]["cells_input"] == 320  # exactly the layer's quads
    # The triangles outside improve as much as with ideal targets (within 0.002 at the worst,
    # 0.001 in the mean).
    ideal, _ = smooth(tmp, channel, "--targets", "ideal", name="ideal")
    before = boundary_layers.rest_quality(smooth(tmp, channel, "--targets", "input",
                                                 name="input")[0])
    worst, mean = boundary_layers.rest_quality(out)
    ideal_worst, ideal_mean = boundary_layers.rest_quality(ideal)
    assert worst > before[0] + 0.06 and worst > ideal_worst - 0.002
    assert mean > ideal_mean - 0.001
    expect_nothing_else_changed(channel, out)


def test_ideal_targets_squash_the_layer(tmp, channel):
    """What the default prevents: the thesis' square target thins first layer cells by 10 % and
    thickens the layer by a third to a half."""
    out, _ = smooth(tmp, channel, "--targets", "ideal")
    change = boundary_layers.layer_change_2d(channel, out)
    assert change["first_height"][0] < -0.05 and change["thickness"][0] > 0.1, change


def test_input_targets_leave_a_valid_mesh_as_it_is(tmp, channel):
    out, report = smooth(tmp, channel, "--targets", "input")
    assert report["targets"]["cells_input"] == 3179
    # A quad's target is its Jacobian at its centre: a trapezoid is not quite its own minimum.
    change = boundary_layers.layer_change_2d(channel, out)
    assert max(map(abs, change["first_height"] + change["thickness"])) < 0.002, change


def test_the_default_keeps_a_3d_prism_layer_far_better_than_ideal_targets(tmp, sphere):
    """Within 1 % of the first height and of the thickness, where ideal targets change them by
    30 % and 70-180 % (the prisms' stiffness, docs/method.md §9, holds them)."""
    out, report = smooth(tmp, sphere)
    assert report["targets"]["cells_input"] == 2320  # exactly the prisms
    change = boundary_layers.layer_change_3d(sphere, out)
    assert max(map(abs, change["first_height"])) < 0.01, change
    assert max(map(abs, change["thickness"])) < 0.01, change
    ideal, _ = smooth(tmp, sphere, "--targets", "ideal", name="ideal")
    change = boundary_layers.layer_change_3d(sphere, ideal)
    assert change["thickness"][0] > 0.5, change


@needs_mpi
def test_two_ranks_keep_the_same_cells_as_one(tmp, channel):
    out, report = smooth(tmp, channel)
    out2 = os.path.join(tmp, "two.vtu")
    report2 = os.path.join(tmp, "two.json")
    neomesh("smooth", channel, "-o", out2, "--quiet", "--report", report2, ranks=2)
    with open(report2) as f:
        assert json.load(f)["targets"] == report["targets"]
    # The same minimizer to the stopping tolerance: the layer kept as well.
    change = boundary_layers.layer_change_2d(channel, out2)
    assert max(map(abs, change["first_height"] + change["thickness"])) < 0.01, change


@needs_corpus
def test_a_graded_cad_mesh_ends_fast_and_no_worse(tmp):
    """Mesquite's cub_fru (10,752 hexes, edge ratios up to 531): ideal targets did not end in
    900 s; kept, it ends in ≤ 15 iterations with a better worst cell."""
    mesh = os.path.join(CORPUS, "mesquite", "3D", "vtk", "hexes", "untangled", "cub_fru.vtk")
    out, report = smooth(tmp, mesh)
    assert len(report["result"]["history"]) <= 15
    before = report["quality_before"]["metrics"]["scaled_jacobian"]["min"]
    after = report["quality_after"]["metrics"]["scaled_jacobian"]["min"]
    assert after >= before and report["quality_after"]["inverted"] == 0


@needs_corpus
def test_an_optimized_graded_mesh_is_not_made_worse(tmp):
    """Mesquite's shashkov_opt (8,192 graded triangles, already optimized): ideal targets took
    its min scaled Jacobian from 0.086 to 0.069 and its mean from 0.330 to 0.259."""
    mesh = os.path.join(CORPUS, "mesquite", "2D", "vtk", "tris", "untangled", "shashkov_opt.vtk")
    out, report = smooth(tmp, mesh)
    sj = lambda q: q["metrics"]["scaled_jacobian"]
    before, after = sj(report["quality_before"]), sj(report["quality_after"])
    assert after["min"] >= before["min"] and after["mean"] >= before["mean"]


@needs_corpus
def test_an_optimum_with_a_lower_mean_returns_the_input(tmp):
    """shashkov_opt with ideal targets: the optimum lowers the mean scaled Jacobian, so the
    input comes back (its worst cells repaired) and the run says so."""
    mesh = os.path.join(CORPUS, "mesquite", "2D", "vtk", "tris", "untangled", "shashkov_opt.vtk")
    out, report = smooth(tmp, mesh, "--targets", "ideal")
    guard = report["quality_guard"]
    assert guard["input_returned"] is True, guard
    assert guard["mean_scaled_jacobian_optimum"] < guard["input_mean_scaled_jacobian"] - 0.005
    sj = lambda q: q["metrics"]["scaled_jacobian"]  # noqa: E731
    before, after = sj(report["quality_before"]), sj(report["quality_after"])
    assert after["min"] >= before["min"] and after["mean"] >= before["mean"] - 0.005


def test_a_tangled_input_gets_ideal_targets(tmp):
    """A tangled mesh's cells around the inverted ones are no design to keep."""
    mesh = os.path.join(tmp, "box.msh")
    neomesh("generate", "box-quad", "--cells", 6, "--jitter", 0.2, "-o", mesh)
    m = read_mesh(mesh)
    inner = np.where((m.points[:, 0] > 0.3) & (m.points[:, 0] < 0.7) &
                     (m.points[:, 1] > 0.3) & (m.points[:, 1] < 0.7))[0]
    m.points[inner[0], 0] += 0.4  # folds its cells over their neighbours
    import meshio
    meshio.write(mesh, m, file_format="gmsh22", binary=False)
    out, report = smooth(tmp, mesh)
    assert report["targets"]["mode"] == "ideal"
    assert report["targets"]["ideal_because_tangled"] is True
    assert report["quality_after"]["inverted"] == 0


def test_a_deformed_mesh_is_repaired_not_kept(tmp):
    """The thesis' square-midpoint: a uniform grid deformed by moving its middle vertex, cells
    sheared smoothly and coherently (min scaled Jacobian 0.08). A shear is no design: the
    default repairs it as ideal targets do (when coherence alone decided, 539 of the 16,384
    cells kept their shear and 3,498 part of it, and the worst cell stayed at 0.086)."""
    mesh = os.path.join(tmp, "midpoint.msh")
    neomesh("generate", "square-midpoint", "--level", 6, "-o", mesh)
    out, report = smooth(tmp, mesh, "--boundary", "fixed", "--sizes", "uniform")
    sj = report["quality_after"]["metrics"]["scaled_jacobian"]
    assert report["quality_before"]["metrics"]["scaled_jacobian"]["min"] < 0.1
    assert sj["min"] > 0.8 and sj["mean"] > 0.99, sj
    assert report["targets"]["cells_input"] == 0


def test_a_kept_stretched_quad_aims_at_its_rectangle_not_its_skew(tmp):
    """A block of 10:1 quads whose columns lean by up to 14 degrees: coherently stretched, so
    the default keeps the cells' sizes and proportions, but a mesher designs no skew: the cells
    come back as rectangles (the input cells as targets kept the lean, min scaled Jacobian
    0.97)."""
    import meshio
    columns, rows = 20, 10
    x, y = np.meshgrid(np.arange(columns + 1, dtype=float), np.linspace(0, 1, rows + 1))
    x = x + 0.25 * y * np.sin(np.pi * x / columns)  # the ends stay straight
    points = np.stack([x.ravel(), y.ravel()], axis=1)
    index = lambda i, j: j * (columns + 1) + i  # noqa: E731
    quads = [[index(i, j), index(i + 1, j), index(i + 1, j + 1), index(i, j + 1)]
             for j in range(rows) for i in range(columns)]
    mesh = os.path.join(tmp, "leaning.msh")
    meshio.write(mesh, meshio.Mesh(points, [("quad", np.array(quads))]), file_format="gmsh22",
                 binary=False)
    out, report = smooth(tmp, mesh)
    sj = lambda q: q["metrics"]["scaled_jacobian"]  # noqa: E731
    assert sj(report["quality_before"])["min"] < 0.98
    assert report["targets"]["cells_input"] + report["targets"]["cells_blended"] > 100
    assert sj(report["quality_after"])["min"] > 0.995, sj(report["quality_after"])
    # The proportions stay: the cells keep their 10:1 (the domain's corners do not move).
    assert sj(report["quality_after"])["mean"] > 0.999


@needs_corpus
@pytest.mark.parametrize("name, least", [("feat3/heat-v77-tria.xml", None),
                                         ("mesquite/3D/vtk/tets/untangled/cube-clip-5.vtk", 0.25),
                                         ("mesquite/3D/vtk/tets/untangled/flat-tet-sphere.vtk",
                                          0.35)])
def test_the_worst_cell_repair_does_not_trade_the_mean_away(tmp, name, least):
    """FEAT3's heat-v77-tria: the optimum lowers the mean, so the input comes back; the repair's
    last sweep, which no longer lifted the worst cell, had moved 11 vertices and taken the mean
    from 0.735 to 0.719: it is undone. Mesquite's cube-clip-5 (a tetrahedron at 3e-4, mean 0.606)
    and flat-tet-sphere (0.054 / 0.586): lifting the worst cells without a floor took the mean to
    0.588 and 0.579; the repair spends no more than the promise's 0.005."""
    _, report = smooth(tmp, os.path.join(CORPUS, name))
    sj = lambda q: q["metrics"]["scaled_jacobian"]  # noqa: E731
    before, after = sj(report["quality_before"]), sj(report["quality_after"])
    assert after["min"] >= before["min"]
    assert after["mean"] >= before["mean"] - 0.005, (before, after)
    if least is None:
        assert report["quality_guard"]["input_returned"] is True
    else:
        assert after["min"] > least, after
