"""--boundary slide on real geometry, run as a user would (docs/boundary.md):
- the plate with three holes (quads and triangles, Gmsh) and the box with a spherical hole
  (tets): the minimum scaled Jacobian ends clearly above the fixed-boundary run's, the outer
  box's corners do not move, hole vertices stay on the input's polygon (within its sagitta of
  the circle) or, with the hole given as a shape, on the circle/sphere to 1e-10;
- a FEAT3 mesh with circle charts: its boundary vertices end on the charts to 1e-12;
- 2 MPI ranks give the serial result (coordinates within 1e-8) with sliding on;
- bad shapes and charts: one `neomesh: error:` line, exit 1, no output.
Prints the figures. Needs gmsh (scripts/setup.sh installs it)."""
import json
import math
import os

import pytest

from conftest import DATA, EXAMPLES, NEOMESH, expect_one_error_line, mpiexec, needs_mpi, \
    read_mesh, run

HOLES = [(1.0, 1.0, 0.4), (2.4, 0.7, 0.3), (3.2, 1.4, 0.35)]  # examples/plate_with_holes.geo
HOLES_LEVEL_SET = "levelset:min(min({}, {}), {})".format(
    *(f"sqrt((x-{cx})^2+(y-{cy})^2)-{r}" for cx, cy, r in HOLES))


def read_msh(path):
    """Vertex coordinates by position (neomesh writes the input's vertices in input order)."""
    return dict(enumerate(tuple(float(v) for v in p) for p in read_mesh(path).points))


def smooth(cwd, mesh, out, *options):
    report = out + ".json"
    run([NEOMESH, "smooth", mesh, "-o", out, "--report", report, "--quiet", *options], cwd)
    with open(os.path.join(cwd, report)) as f:
        return json.load(f)


def min_sj(report):
    return report["quality_after"]["metrics"]["scaled_jacobian"]["min"]


def corners_kept(before, after, corners):
    """Every input vertex at one of `corners` is still exactly there."""
    for tag, x in before.items():
        if any(all(abs(a - b) < 1e-12 for a, b in zip(x, c)) for c in corners):
            if after[tag] != x:
                return False
    return True


def hole_vertices(nodes, holes, dim):
    """(tag, centre, radius) of the vertices within 1e-9 of a hole's circle/sphere."""
    out = []
    for tag, x in nodes.items():
        for *centre, r in holes:
            if abs(math.dist(x[:dim], centre) - r) < 1e-9:
                out.append((tag, centre, r))
    return out


def plate_mesh(tmp, kind):
    """Gmsh's mesh of examples/plate_with_holes.geo in quads or triangles, in `tmp`."""
    mesh = os.path.join(tmp, f"plate-{kind}.msh")
    run(["gmsh", "-2", os.path.join(EXAMPLES, "plate_with_holes.geo"), "-setnumber", "quads",
         str(int(kind == "quads")), "-format", "msh41", "-o", mesh], tmp)
    return mesh


@pytest.mark.parametrize("quads", [True, False], ids=["quads", "triangles"])
def test_plate(tmp, quads):
    kind = "quads" if quads else "triangles"
    mesh = plate_mesh(tmp, kind)
    fixed = smooth(tmp, mesh, f"fixed-{kind}.msh", "--boundary", "fixed")
    slide = smooth(tmp, mesh, f"slide-{kind}.msh", "--boundary", "slide")
    shape = smooth(tmp, mesh, f"shape-{kind}.msh", "--boundary", "slide", "--shape",
                   "holes=" + HOLES_LEVEL_SET)
    print(f"plate {kind}: min scaled Jacobian input {fixed['quality_before']['metrics']['scaled_jacobian']['min']:.3f}, "
          f"fixed {min_sj(fixed):.3f} ({fixed['seconds']:.2f} s), slide {min_sj(slide):.3f} "
          f"({slide['seconds']:.2f} s), slide on the circles {min_sj(shape):.3f} "
          f"({shape['seconds']:.2f} s); volume change {slide['boundary_change']['relative_volume_change']:+.2e} "
          f"/ {shape['boundary_change']['relative_volume_change']:+.2e}")
    # The worst quads sit on the holes; the worst triangle of Gmsh's frontal mesh does not, so
    # the worst-cell repair lifts it as far with either boundary (0.678651 fixed, 0.678650
    # sliding: the repair's short steps end one step apart). (It lifts the fixed boundary's
    # worst quads too: 0.694 against 0.706.)
    margin = 0.01 if quads else -1e-4
    assert min_sj(slide) >= min_sj(fixed) + margin, \
        (f"plate {kind}: sliding ends above the fixed boundary ({min_sj(slide):.3f} vs "
         f"{min_sj(fixed):.3f})")
    # `quality --reference` measures what the run reported: on the input's facets, volume +.
    run([NEOMESH, "quality", f"slide-{kind}.msh", "--reference", mesh, "--json", "q.json"], tmp)
    with open(os.path.join(tmp, "q.json")) as f:
        change = json.load(f)["boundary_change"]
    assert change["max_distance_from_reference_boundary"] <= 1e-12 and \
        abs(change["relative_volume_change"] -
            slide["boundary_change"]["relative_volume_change"]) <= 1e-12, \
        f"plate {kind}: quality --reference agrees with the run's report ({change})"
    before = read_msh(mesh)
    box = [(0, 0, 0), (4, 0, 0), (4, 2, 0), (0, 2, 0)]
    h = 0.1  # edge length on the holes (h/2 of the .geo's 0.2)
    sagitta = max(r * (1 - math.cos(math.asin(min(1.0, 1.5 * h / (2 * r))))) for *_, r in HOLES)
    on_holes = hole_vertices(before, HOLES, 2)
    assert len(on_holes) > 50, f"plate {kind}: {len(on_holes)} vertices on the holes"
    for name, out, tolerance in ((f"slide-{kind}.msh", "polygon", sagitta),
                                 (f"shape-{kind}.msh", "circles", 1e-10)):
        after = read_msh(os.path.join(tmp, name))
        assert corners_kept(before, after, box), f"plate {kind} ({out}): the box corners stay"
        worst = max(abs(math.dist(after[t][:2], c) - r) for t, c, r in on_holes)
        assert worst <= tolerance, \
            f"plate {kind}: hole vertices within {worst:.1e} of their circles (<= {tolerance:.1e}, on the {out})"


def test_box_with_hole(tmp):
    mesh = os.path.join(tmp, "box.msh")
    run(["gmsh", "-3", os.path.join(EXAMPLES, "box_with_hole.geo"), "-format", "msh41", "-o",
         mesh], tmp)
    fixed = smooth(tmp, mesh, "box-fixed.msh", "--boundary", "fixed")
    slide = smooth(tmp, mesh, "box-slide.msh", "--boundary", "slide")
    shape = smooth(tmp, mesh, "box-shape.msh", "--boundary", "slide", "--shape",
                   "sphere=sphere:0.5,0.5,0.5,0.25")
    print(f"box with hole: min scaled Jacobian input {fixed['quality_before']['metrics']['scaled_jacobian']['min']:.3f}, "
          f"fixed {min_sj(fixed):.3f} ({fixed['seconds']:.2f} s), slide {min_sj(slide):.3f} "
          f"({slide['seconds']:.2f} s), on the sphere {min_sj(shape):.3f} ({shape['seconds']:.2f} s)")
    assert min_sj(slide) >= min_sj(fixed) + 0.05, \
        f"box with hole: sliding ends clearly above the fixed boundary ({min_sj(slide):.3f} vs {min_sj(fixed):.3f})"
    before = read_msh(mesh)
    corners = [(x, y, z) for x in (0, 1) for y in (0, 1) for z in (0, 1)]
    on_sphere = hole_vertices(before, [(0.5, 0.5, 0.5, 0.25)], 3)
    assert len(on_sphere) > 50, f"box with hole: {len(on_sphere)} vertices on the sphere"
    for name, tolerance in (("box-slide.msh", 0.25 * (1 - math.cos(0.6 / 2))),
                            ("box-shape.msh", 1e-10)):
        after = read_msh(os.path.join(tmp, name))
        assert corners_kept(before, after, corners), f"box with hole ({name}): the corners stay"
        worst = max(abs(math.dist(after[t], c) - r) for t, c, r in on_sphere)
        assert worst <= tolerance, f"box with hole ({name}): sphere vertices within {worst:.1e} of it"


def test_feat_charts(tmp):
    out = os.path.join(tmp, "ring.msh")
    report = smooth(tmp, os.path.join(DATA, "feat_ring_quad.xml"), out, "--boundary", "slide")
    after = read_msh(out)
    radii = [math.hypot(*x[:2]) for x in after.values()]
    on = [r for r in radii if abs(r - 0.5) < 1e-3 or abs(r - 1.0) < 1e-3]
    worst = max(min(abs(r - 0.5), abs(r - 1.0)) for r in on)
    print(f"FEAT3 ring with circle charts: {len(on)} boundary vertices, min scaled Jacobian "
          f"{report['quality_before']['metrics']['scaled_jacobian']['min']:.3f} -> {min_sj(report):.3f}")
    assert len(on) == 32 and worst <= 1e-12, f"FEAT3 ring: vertices on the charts to {worst:.1e}"


@needs_mpi
def test_mpi_matches_serial(tmp):
    mesh = plate_mesh(tmp, "quads")
    options = ["--boundary", "slide", "--shape", "holes=" + HOLES_LEVEL_SET, "--no-practical",
               "--tol", "1e-11"]
    results = []
    for ranks in (1, 2):
        out = os.path.join(tmp, f"mpi-{ranks}.msh")
        run([*mpiexec(ranks), NEOMESH, "smooth", mesh, "-o", out, "--quiet", *options], tmp)
        results.append(read_msh(out))
    worst = max(abs(a - b) for t in results[0] for a, b in zip(results[0][t], results[1][t]))
    assert worst <= 1e-8, f"plate quads sliding on the holes: 2 ranks within {worst:.1e} of serial"


GOOD = os.path.join(DATA, "feat_ring_quad.xml")


@pytest.mark.parametrize("options, mesh, words", [
    pytest.param(["--boundary", "slide", "--shape", "hole=circle:0,0,0.5"], GOOD,
                 ["hole", "bnd:inner"], id="unknown part"),
    pytest.param(["--boundary", "slide", "--shape", "bnd:inner=circle:0,0,0.45"], GOOD,
                 ["bnd:inner", "from it"], id="shape off the part's vertices"),
    pytest.param(["--boundary", "slide", "--shape", "bnd:inner=circle:0,0"], GOOD,
                 ["circle:cx,cy,r"], id="malformed shape"),
    pytest.param(["--boundary", "slide", "--shape", "circle:0,0,1"], GOOD, ["PART=SHAPE"],
                 id="shape without ="),
    pytest.param(["--boundary", "fixed", "--shape", "bnd:inner=circle:0,0,0.5"], GOOD,
                 ["--boundary slide"], id="shape with fixed boundary"),
    pytest.param(["--boundary", "slide", "--feature-angle", "200"], GOOD, ["--feature-angle"],
                 id="feature angle out of range"),
])
def test_bad_input(tmp, options, mesh, words):
    out = os.path.join(tmp, "bad-out.msh")
    proc = run([NEOMESH, "smooth", mesh.format(tmp=tmp), "-o", out, *options], tmp, expect=None)
    expect_one_error_line(proc, words, unwritten=[out])


@pytest.mark.parametrize("generate, options, alpha0", [
    (["box-quad"], [], 1.0),  # its sides are axis-aligned: fixed normal coordinates
    (["annulus-quad"], [], 0.3),  # vertices slide on the arcs
    (["annulus-quad"], ["--boundary", "fixed"], 1.0),
    (["box-quad"], ["--thesis"], 0.3),
    (["box-quad"], ["--thesis", "--alpha0", "0.5"], 0.5),
])
def test_alpha0_is_1_unless_vertices_slide_on_a_curve(tmp, generate, options, alpha0):
    # docs/method.md: α₀ = 1 starts in the Newton regime; on curved sliding boundaries the
    # thesis' 0.3 took fewer iterations. The report gives the α₀ used, not "auto".
    run([NEOMESH, "generate", *generate, "--cells", "12", "--jitter", "0.2", "-o", "in.msh"], tmp)
    report = smooth(tmp, "in.msh", "out.msh", *options)
    assert report["solver_options"]["alpha0"] == alpha0
    assert report["result"]["history"][0]["alpha"] == alpha0


@pytest.mark.parametrize("generate, options, lazy", [
    (["box-quad"], [], True),  # axis-aligned sides: fixed normal coordinates, nothing slides
    (["annulus-quad"], ["--boundary", "fixed"], True),
    (["annulus-quad"], [], False),  # vertices slide on the arcs: L's hierarchy is its first one
])
def test_riesz_solve_skipped_only_where_nothing_slides_on_a_curve(tmp, generate, options, lazy):
    # docs/method.md §4, the angle test without s: the quasi-Newton steps estimate η with one
    # V-cycle of L's hierarchy, except where vertices slide on a curve (L follows their tangent
    # spaces, its hierarchy does not, and the estimate was off by up to 2x there).
    run([NEOMESH, "generate", *generate, "--cells", "12", "--jitter", "0.2", "-o", "in.msh"], tmp)
    history = smooth(tmp, "in.msh", "out.msh", *options)["result"]["history"]
    newton = [h for h in history if not h["used_s"]]
    assert newton, f"no quasi-Newton step: {history}"
    assert any(not h["s_solved"] for h in newton) == lazy, f"lazy {lazy}: {history}"
    assert all(h["s_solved"] for h in history if h["used_s"]), f"-s needs s: {history}"


@pytest.mark.parametrize("boundary", ["fixed", "slide"])
def test_nodes_of_no_cell_stay_where_they_are(tmp, boundary):
    """Gmsh's extrusion with rotation writes nodes that only its curves use, none of the volume's
    cells: they have no energy, and freed they left the linear solvers empty rows (with --boundary
    fixed hypre's eigenvalue estimate never returned). They stay; the run ends as any other."""
    geo = os.path.join(tmp, "twisted.geo")
    with open(geo, "w") as f:
        f.write("Point(1) = {0, 0, 0};\n"
                "Extrude {1, 0, 0} { Point{1}; Layers{4}; }\n"
                "Extrude {0, 1, 0} { Line{1}; Layers{4}; Recombine; }\n"
                "Extrude {{0, 0, 1}, {0, 0, 1}, {0.5, 0.5, 0}, Pi/3} "
                "{ Surface{5}; Layers{4}; Recombine; }\n")
    mesh, out = os.path.join(tmp, "twisted.msh"), os.path.join(tmp, "out.msh")
    run(["gmsh", "-3", geo, "-format", "msh41", "-o", mesh])
    given = read_mesh(mesh)
    hexes = next(c.data for c in given.cells if c.type == "hexahedron")
    unused = sorted(set(range(len(given.points))) - set(hexes.ravel().tolist()))
    assert unused, "the extrusion no longer writes nodes of no cell: the test needs another mesh"
    run([NEOMESH, "smooth", mesh, "-o", out, "--quiet", "--boundary", boundary], timeout=60)
    assert (read_mesh(out).points[unused] == given.points[unused]).all()
