"""Surface meshes (triangles and quadrilaterals whose vertices are not coplanar) smoothed end to
end: Mesquite's 7 surface meshes (../shared/corpus/mesquite, skipped without it) and a poor
sphere made by Gmsh (skipped without gmsh). Every vertex slides on the input's own cells, so it
stays within their sagitta of the exact sphere; the points, their numbering and the cells are
kept; the quality before and after is the surface cells'. What surfaces do not support is refused
in one line. The figures print with pytest -s. Run with NEOMESH=path/to/neomesh."""
import json
import os
import shutil
import time

import numpy as np
import pytest

from conftest import CORPUS, expect_one_error_line, needs_corpus, needs_mpi, neomesh, read_mesh, run

# Mesquite's surface meshes, with the sphere each lies on (centre, radius), or None.
MESQUITE = {
    "2D/vtk/tris/untangled/Mesquite_geo_10242": ((0, 0, 0), 1.0),
    "2D/vtk/quads/untangled/quads_on_sphere_529": ((2, 2, 0), 3.0),
    "2D/vtk/quads/untangled/bias-sphere-quads": ((0, 0, 0), 10.0),
    "3D/vtk/hexes/untangled/sph-10-zsquare": ((0, 0, 0), 10.0),
    "3D/vtk/to-do/quad_sphere": ((0, 0, 0), 5.0),
    "3D/vtk/to-do/quad_sphere_ref": ((0, 0, 0), 5.0),
    "2D/vtk/quads/untangled/paraboloid": None,
}
# How much a run may lower the mean scaled Jacobian (QualityGuardResult::kMeanSlack).
MEAN_SLACK = 0.005

SPHERE_GEO = """SetFactory("OpenCASCADE");
Sphere(1) = {0, 0, 0, 1};
Mesh.Algorithm = 1;
Mesh.MeshSizeMin = 0.25;
Mesh.MeshSizeMax = 0.25;
Mesh.Smoothing = 0;
Physical Surface("sphere") = {1};
"""


def triangles(mesh):
    """The cells as triangles, each quadrilateral split along both of its diagonals (the
    discrete surface splits it along one)."""
    out = []
    for block in mesh.cells:
        for c in block.data:
            if block.type == "triangle":
                out.append(c)
            elif block.type == "quad":
                out += [c[[0, 1, 2]], c[[0, 2, 3]], c[[0, 1, 3]], c[[1, 2, 3]]]
    return np.array(out)


def sphere_bounds(mesh, centre):
    """Between which distances from `centre` every point of the mesh's cells lies: the least
    distance of a cell's plane (a point of a flat cell is no nearer) and the largest of a vertex
    (nor farther)."""
    p = mesh.points - centre
    t = triangles(mesh)
    normal = np.cross(p[t[:, 1]] - p[t[:, 0]], p[t[:, 2]] - p[t[:, 0]])
    normal /= np.linalg.norm(normal, axis=1)[:, None]
    plane = np.abs(np.einsum("ij,ij->i", normal, p[t[:, 0]]))
    return plane.min(), np.linalg.norm(p, axis=1).max()


def cells_of(mesh):
    return sorted((c.type, tuple(cell)) for c in mesh.cells if c.type in ("triangle", "quad")
                  for cell in c.data.tolist())


def smooth(tmp, path, *options):
    """Smooths `path` into a .vtu with the defaults; returns the output, the report (with the
    run's wall-clock seconds as "seconds")."""
    out = os.path.join(tmp, os.path.splitext(os.path.basename(path))[0] + "-out.vtu")
    report = out + ".json"
    start = time.monotonic()
    neomesh("smooth", path, "-o", out, "--quiet", "--report", report, *options)
    seconds = time.monotonic() - start
    with open(report) as f:
        r = json.load(f)
    r["seconds"] = seconds
    return out, r


def quality(r, when):
    m = r[when]["metrics"]["scaled_jacobian"]
    return m["min"], m["mean"]


def expect_smoothed_on_the_surface(path, out, r, sphere):
    """What every surface run keeps and gives; returns the figures to print."""
    a, b = read_mesh(path), read_mesh(out)
    # The points, their numbering and the cells are kept; the .vtu is a surface in space.
    assert len(a.points) == len(b.points)
    assert cells_of(a) == cells_of(b)
    assert b.points.shape[1] == 3
    centre = b.points.mean(0)
    assert np.linalg.svd(b.points - centre, compute_uv=False)[-1] > 0
    # The worst cell no worse, the mean no lower than the promise allows.
    (min_before, mean_before), (min_after, mean_after) = quality(r, "quality_before"), quality(
        r, "quality_after")
    assert r["quality_after"]["inverted"] == 0
    assert min_after >= min_before
    assert mean_after >= mean_before - MEAN_SLACK
    # Every vertex on the input's cells.
    assert r["boundary_change"]["max_distance_from_input_boundary"] < 1e-12 * np.abs(a.points).max()
    far = None
    if sphere is not None:
        c, radius = np.array(sphere[0], float), sphere[1]
        near, outer = sphere_bounds(a, c)
        r_out = np.linalg.norm(b.points - c, axis=1)
        assert r_out.min() >= near - 1e-12 * radius and r_out.max() <= outer + 1e-12 * radius
        far = np.abs(r_out - radius).max()
        sagitta = radius - near
        assert far <= sagitta + np.abs(np.linalg.norm(a.points - c, axis=1) - radius).max()
        far = f"{far:.3g} (sagitta {sagitta:.3g})"
    return min_before, mean_before, min_after, mean_after, far


@needs_corpus
@pytest.mark.parametrize("name", list(MESQUITE))
def test_mesquites_surface_meshes_smooth_on_their_input_surface(tmp, name):
    path = os.path.join(CORPUS, "mesquite", name + ".vtk")
    out, r = smooth(tmp, path)
    figures = expect_smoothed_on_the_surface(path, out, r, MESQUITE[name])
    print(f"{os.path.basename(name)}: min/mean scaled Jacobian {figures[0]:.4f}/{figures[1]:.4f} "
          f"-> {figures[2]:.4f}/{figures[3]:.4f}, farthest from the sphere {figures[4]}, "
          f"{r['seconds']:.2f} s")


@needs_corpus
@pytest.mark.parametrize("name, lifted_to", [("2D/vtk/quads/untangled/paraboloid", 0.84),
                                             ("2D/vtk/quads/untangled/quads_on_sphere_529", 0.86)])
def test_the_worst_cells_repair_lifts_surface_cells_too(tmp, name, lifted_to):
    # The optimum leaves both worst cells where they were (0.750 and 0.785); the repair, its trial
    # points put back onto the input's cells and each cell judged along its normal at the
    # repair's start (so that a fold counts as one), lifts them.
    path = os.path.join(CORPUS, "mesquite", name + ".vtk")
    out, r = smooth(tmp, path)
    expect_smoothed_on_the_surface(path, out, r, MESQUITE[name])
    repair = r["worst_cell_repair"]
    assert repair["vertices_moved"] > 0
    assert r["quality_after"]["metrics"]["scaled_jacobian"]["min"] > lifted_to


@pytest.fixture(scope="module")
def poor_sphere(module_tmp):
    """A unit sphere of triangles made by Gmsh with its worst settings for quality (MeshAdapt,
    no smoothing, no optimization)."""
    gmsh = shutil.which("gmsh")
    if gmsh is None:
        pytest.skip("gmsh is not on PATH")
    geo, msh = os.path.join(module_tmp, "sphere.geo"), os.path.join(module_tmp, "sphere.msh")
    with open(geo, "w") as f:
        f.write(SPHERE_GEO)
    run([gmsh, "-2", geo, "-optimize", "0", "-format", "msh41", "-o", msh])
    return msh


def test_a_poor_gmsh_sphere_gets_better_and_stays_within_its_sagitta(tmp, poor_sphere):
    out, r = smooth(tmp, poor_sphere)
    figures = expect_smoothed_on_the_surface(poor_sphere, out, r, ((0, 0, 0), 1.0))
    assert figures[2] > figures[0] + 0.1 and figures[3] > figures[1]
    print(f"Gmsh sphere: min/mean scaled Jacobian {figures[0]:.4f}/{figures[1]:.4f} -> "
          f"{figures[2]:.4f}/{figures[3]:.4f}, farthest from the sphere {figures[4]}, "
          f"{r['seconds']:.2f} s")
    # Written back as Gmsh, the group and the points' numbering are kept too.
    msh = os.path.join(tmp, "out.msh")
    neomesh("smooth", poor_sphere, "-o", msh, "--quiet")
    a, b = read_mesh(poor_sphere), read_mesh(msh)
    assert cells_of(a) == cells_of(b)
    assert np.allclose(b.points, read_mesh(out).points, atol=1e-14)


def test_a_sphere_given_as_a_shape_keeps_every_vertex_on_it(tmp, poor_sphere):
    out, r = smooth(tmp, poor_sphere, "--shape", "sphere=sphere:0,0,0,1")
    b = read_mesh(out)
    assert np.abs(np.linalg.norm(b.points, axis=1) - 1).max() < 1e-12
    (min_before, mean_before), (min_after, mean_after) = quality(r, "quality_before"), quality(
        r, "quality_after")
    assert min_after > min_before + 0.1 and mean_after > mean_before
    assert r["result"]["stop_reason"] != "maximum number of iterations reached"
    print(f"Gmsh sphere, --shape: {min_before:.4f}/{mean_before:.4f} -> {min_after:.4f}/"
          f"{mean_after:.4f}, {r['result']['iterations']} iterations, {r['seconds']:.2f} s")


def test_quality_measures_a_surface_as_its_cells_lie(tmp, poor_sphere):
    proc = neomesh("quality", poor_sphere)
    assert "580 triangles" in proc.stdout and "inverted cells: 0" in proc.stdout


def cell_areas_and_centres(mesh):
    """Each cell's area (a quadrilateral's as the mean of its two splittings) and centroid."""
    areas, centres = [], []
    for block in mesh.cells:
        if block.type not in ("triangle", "quad"):
            continue
        p = mesh.points[block.data]
        if block.type == "triangle":
            a = 0.5 * np.linalg.norm(np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0]), axis=1)
        else:
            a = 0.5 * np.linalg.norm(np.cross(p[:, 2] - p[:, 0], p[:, 3] - p[:, 1]), axis=1)
        areas.append(a)
        centres.append(p.mean(1))
    return np.concatenate(areas), np.concatenate(centres)


def test_adapt_crowds_a_surfaces_cells_where_the_size_field_asks(tmp, poor_sphere):
    # Small cells near the circle where the sphere of radius 0.5 about the pole cuts the unit
    # sphere, every vertex kept on the input's cells.
    out, report = os.path.join(tmp, "out.vtu"), os.path.join(tmp, "r.json")
    neomesh("adapt", poor_sphere, "-o", out, "--sphere", "0,0,1,0.5", "--quiet", "--report",
            report)
    with open(report) as f:
        r = json.load(f)
    a, b = read_mesh(poor_sphere), read_mesh(out)
    assert len(a.points) == len(b.points) and cells_of(a) == cells_of(b)
    assert r["quality_after"]["inverted"] == 0
    assert r["boundary_change"]["max_distance_from_input_boundary"] < 1e-12
    near, outer = sphere_bounds(a, np.zeros(3))
    radius = np.linalg.norm(b.points, axis=1)
    assert radius.min() >= near - 1e-12 and radius.max() <= 1 + 1e-12

    def near_over_far(mesh):
        area, centre = cell_areas_and_centres(mesh)
        d = np.abs(np.linalg.norm(centre - [0, 0, 1], axis=1) - 0.5)
        return area[d < 0.1].mean() / area[d > 0.6].mean()

    before, after = near_over_far(a), near_over_far(b)
    assert after < 0.5 * before
    print(f"Gmsh sphere, adapt --sphere 0,0,1,0.5: mean area near the circle / far from it "
          f"{before:.3f} -> {after:.3f}, min scaled Jacobian "
          f"{r['quality_after']['metrics']['scaled_jacobian']['min']:.3f}")


def test_what_surfaces_do_not_support_is_refused_in_one_line(tmp, poor_sphere):
    out = os.path.join(tmp, "out.msh")
    proc = neomesh("adapt", poor_sphere, "-o", out, "--sphere", "0,0,1,0.5", "--fit", expect=1)
    expect_one_error_line(proc, ["a surface mesh", "without --fit"], unwritten=[out])
    proc = neomesh("adapt", poor_sphere, "-o", out, "--metric", "1;0;0;1;0;1", expect=1)
    expect_one_error_line(proc, ["a surface mesh", "not to a metric"], unwritten=[out])
    picture = os.path.join(tmp, "out.png")
    proc = neomesh("render", poor_sphere, "-o", picture, expect=1)
    expect_one_error_line(proc, ["a surface mesh"], unwritten=[picture])


@needs_mpi
def test_two_processes_give_the_serial_surface(tmp, poor_sphere):
    # Given as a sphere, the problem is smooth and the run converges: the energy and the quality
    # are the serial ones, the vertices on the sphere; they may turn about it (a direction the
    # energy does not see, user guide "Parallel runs").
    tight = ("--shape", "sphere=sphere:0,0,0,1", "--no-repair", "--no-practical", "--tol", "1e-11")
    figures = []
    for ranks in (1, 2):
        out, report = os.path.join(tmp, f"out{ranks}.vtu"), os.path.join(tmp, f"r{ranks}.json")
        neomesh("smooth", poor_sphere, "-o", out, "--quiet", "--report", report, *tight,
                ranks=ranks)
        with open(report) as f:
            r = json.load(f)
        b = read_mesh(out)
        assert np.abs(np.linalg.norm(b.points, axis=1) - 1).max() < 1e-12
        assert r["result"]["stop_reason"] != "maximum number of iterations reached"
        figures.append((r["result"]["final_energy"], *quality(r, "quality_after")))
    serial, parallel = figures
    assert parallel[0] == pytest.approx(serial[0], rel=1e-10)
    assert parallel[1] == pytest.approx(serial[1], abs=1e-7)
    assert parallel[2] == pytest.approx(serial[2], abs=1e-7)
    # On the input's own cells, with the defaults (the iterations cut where the quality has
    # settled, user guide "Surface meshes"): on the input surface, valid, the quality within what
    # the repair's choices and the stopping rule leave apart.
    out, r = smooth(tmp, poor_sphere, "--max-iter", "40")
    out2 = os.path.join(tmp, "out-2.vtu")
    report2 = out2 + ".json"
    neomesh("smooth", poor_sphere, "-o", out2, "--quiet", "--report", report2, "--max-iter", "40",
            ranks=2)
    with open(report2) as f:
        r2 = json.load(f)
    expect_smoothed_on_the_surface(poor_sphere, out2, r2, ((0, 0, 0), 1.0))
    for a, b in zip(quality(r, "quality_after"), quality(r2, "quality_after")):
        assert abs(a - b) < 0.005


def total_area(mesh):
    return cell_areas_and_centres(mesh)[0].sum()


def farthest_from_sphere(mesh, sphere):
    c, radius = np.array(sphere[0], float), sphere[1]
    return np.abs(np.linalg.norm(mesh.points - c, axis=1) - radius).max()


def test_on_a_phong_tessellation_the_poor_sphere_stops_and_keeps_its_area(tmp, poor_sphere):
    # --surface-geometry phong: the vertices slide on a curved reconstruction through the input's
    # vertices. On the Gmsh sphere (edges turning by 14 degrees) the run stops by the practical
    # criterion (on the flat cells it creeps to --max-iter), the vertices stay far closer to the
    # sphere than the cells' sagitta, and the area is kept.
    out, r = smooth(tmp, poor_sphere, "--surface-geometry", "phong")
    a, b = read_mesh(poor_sphere), read_mesh(out)
    assert len(a.points) == len(b.points) and cells_of(a) == cells_of(b)
    assert r["boundary_options"]["surface_geometry"] == "phong"
    assert r["result"]["stop_reason"] != "maximum number of iterations reached"
    (min_before, mean_before), (min_after, mean_after) = quality(r, "quality_before"), quality(
        r, "quality_after")
    assert r["quality_after"]["inverted"] == 0
    assert min_after > min_before + 0.1 and mean_after > mean_before
    sagitta = 1 - sphere_bounds(a, np.zeros(3))[0]
    far = farthest_from_sphere(b, ((0, 0, 0), 1.0))
    assert far < sagitta / 20
    # Off the input's cells by at most their sagitta (the reconstruction bulges out of them).
    assert r["boundary_change"]["max_distance_from_input_boundary"] <= sagitta
    area = total_area(b) / total_area(a) - 1
    assert abs(area) < 1e-3
    print(f"Gmsh sphere, phong: {min_before:.4f}/{mean_before:.4f} -> {min_after:.4f}/"
          f"{mean_after:.4f}, farthest from the sphere {far:.3g} (sagitta {sagitta:.3g}), area "
          f"{100 * area:+.3f} %, {r['result']['iterations']} iterations, {r['seconds']:.2f} s")


@needs_corpus
@pytest.mark.parametrize("name", [n for n, s in MESQUITE.items() if s is not None])
def test_mesquites_spheres_on_a_phong_tessellation_stay_closer_to_the_sphere(tmp, name):
    path = os.path.join(CORPUS, "mesquite", name + ".vtk")
    figures = {}
    for geometry in ("cells", "phong"):
        out, r = smooth(tmp, path, "--surface-geometry", geometry)
        b = read_mesh(out)
        assert r["quality_after"]["inverted"] == 0
        assert quality(r, "quality_after")[0] >= quality(r, "quality_before")[0]
        figures[geometry] = (farthest_from_sphere(b, MESQUITE[name]),
                             total_area(b) / total_area(read_mesh(path)) - 1,
                             *quality(r, "quality_after"), r["result"]["iterations"], r["seconds"])
    assert figures["phong"][0] < figures["cells"][0] / 3
    for geometry, (far, area, worst, mean, iterations, seconds) in figures.items():
        print(f"{os.path.basename(name)}, {geometry}: farthest from the sphere {far:.3g}, area "
              f"{100 * area:+.3f} %, min/mean scaled Jacobian {worst:.4f}/{mean:.4f}, "
              f"{iterations} iterations, {seconds:.2f} s")
