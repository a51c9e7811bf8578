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
import subprocess
import sys
import tempfile

import meshio

NEOMESH = os.path.abspath(os.environ["NEOMESH"]) if "NEOMESH" in os.environ else "neomesh"
SOURCE = os.environ.get("NEOMESH_SOURCE",
                        os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
MPIEXEC = os.environ.get("NEOMESH_MPIEXEC")
EXAMPLES = os.path.join(SOURCE, "examples")
DATA = os.path.join(SOURCE, "tests", "data")

HOLES = [(1.0, 1.0, 0.4), (2.4, 0.7, 0.3), (3.2, 1.4, 0.35)]  # examples/plate_with_holes.geo
HOLES_LEVEL_SET = "levelset:min(min({}, {}), {})".format(
    *(f"sqrt((x-{cx})^2+(y-{cy})^2)-{r}" for cx, cy, r in HOLES))
failures = []


def check(condition, message):
    print(("ok   " if condition else "FAIL ") + message)
    if not condition:
        failures.append(message)


def run(args, cwd, expect_ok=True):
    proc = subprocess.run(args, cwd=cwd, capture_output=True, text=True, timeout=300)
    if expect_ok and proc.returncode != 0:
        sys.exit(f"{' '.join(args)}: exit {proc.returncode}\n{proc.stdout}\n{proc.stderr}")
    return proc


def read_msh(path):
    """Vertex coordinates by position (neomesh writes the input's vertices in input order)."""
    return dict(enumerate(tuple(float(v) for v in p) for p in meshio.read(path).points))


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


def plate(tmp, quads):
    kind = "quads" if quads else "triangles"
    mesh = os.path.join(tmp, f"plate-{kind}.msh")
    run(["gmsh", "-2", os.path.join(EXAMPLES, "plate_with_holes.geo"), "-setnumber", "quads",
         str(int(quads)), "-format", "msh41", "-o", mesh], tmp)
    fixed = smooth(tmp, mesh, f"fixed-{kind}.msh", "--boundary", "fixed")
    slide = smooth(tmp, mesh, f"slide-{kind}.msh", "--boundary", "slide")
    shape = smooth(tmp, mesh, f"shape-{kind}.msh", "--boundary", "slide", "--shape",
                   "holes=" + HOLES_LEVEL_SET)
    print(f"plate {kind}: min scaled Jacobian input {fixed['quality_before']['metrics']['scaled_jacobian']['min']:.3f}, "
          f"fixed {min_sj(fixed):.3f} ({fixed['seconds']:.2f} s), slide {min_sj(slide):.3f} "
          f"({slide['seconds']:.2f} s), slide on the circles {min_sj(shape):.3f} "
          f"({shape['seconds']:.2f} s); volume change {slide['boundary_change']['relative_volume_change']:+.2e} "
          f"/ {shape['boundary_change']['relative_volume_change']:+.2e}")
    # The worst quads sit on the holes; the worst triangle of Gmsh's frontal mesh does not.
    margin = 0.03 if quads else 0.0
    check(min_sj(slide) >= min_sj(fixed) + margin,
          f"plate {kind}: sliding ends above the fixed boundary ({min_sj(slide):.3f} vs "
          f"{min_sj(fixed):.3f})")
    # `quality --reference` measures what the run reported: on the input's facets, volume +.
    run([NEOMESH, "quality", f"slide-{kind}.msh", "--reference", mesh, "--json", "q.json"], tmp)
    with open(os.path.join(tmp, "q.json")) as f:
        change = json.load(f)["boundary_change"]
    check(change["max_distance_from_reference_boundary"] <= 1e-12 and
          abs(change["relative_volume_change"] -
              slide["boundary_change"]["relative_volume_change"]) <= 1e-12,
          f"plate {kind}: quality --reference agrees with the run's report ({change})")
    before = read_msh(mesh)
    box = [(0, 0, 0), (4, 0, 0), (4, 2, 0), (0, 2, 0)]
    h = 0.1  # edge length on the holes (h/2 of the .geo's 0.2)
    sagitta = max(r * (1 - math.cos(math.asin(min(1.0, 1.5 * h / (2 * r))))) for *_, r in HOLES)
    on_holes = hole_vertices(before, HOLES, 2)
    check(len(on_holes) > 50, f"plate {kind}: {len(on_holes)} vertices on the holes")
    for name, out, tolerance in ((f"slide-{kind}.msh", "polygon", sagitta),
                                 (f"shape-{kind}.msh", "circles", 1e-10)):
        after = read_msh(os.path.join(tmp, name))
        check(corners_kept(before, after, box), f"plate {kind} ({out}): the box corners stay")
        worst = max(abs(math.dist(after[t][:2], c) - r) for t, c, r in on_holes)
        check(worst <= tolerance,
              f"plate {kind}: hole vertices within {worst:.1e} of their circles (<= {tolerance:.1e}, on the {out})")


def box_with_hole(tmp):
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
    check(min_sj(slide) >= min_sj(fixed) + 0.05,
          f"box with hole: sliding ends clearly above the fixed boundary ({min_sj(slide):.3f} vs {min_sj(fixed):.3f})")
    before = read_msh(mesh)
    corners = [(x, y, z) for x in (0, 1) for y in (0, 1) for z in (0, 1)]
    on_sphere = hole_vertices(before, [(0.5, 0.5, 0.5, 0.25)], 3)
    check(len(on_sphere) > 50, f"box with hole: {len(on_sphere)} vertices on the sphere")
    for name, tolerance in (("box-slide.msh", 0.25 * (1 - math.cos(0.6 / 2))),
                            ("box-shape.msh", 1e-10)):
        after = read_msh(os.path.join(tmp, name))
        check(corners_kept(before, after, corners), f"box with hole ({name}): the corners stay")
        worst = max(abs(math.dist(after[t], c) - r) for t, c, r in on_sphere)
        check(worst <= tolerance, f"box with hole ({name}): sphere vertices within {worst:.1e} of it")


def feat_charts(tmp):
    out = os.path.join(tmp, "ring.msh")
    report = smooth(tmp, os.path.join(DATA, "feat_ring_quad.xml"), out, "--boundary", "slide")
    after = read_msh(out)
    radii = [math.hypot(*x[:2]) for x in after.values()]
    on = [r for r in radii if abs(r - 0.5) < 1e-3 or abs(r - 1.0) < 1e-3]
    worst = max(min(abs(r - 0.5), abs(r - 1.0)) for r in on)
    print(f"FEAT3 ring with circle charts: {len(on)} boundary vertices, min scaled Jacobian "
          f"{report['quality_before']['metrics']['scaled_jacobian']['min']:.3f} -> {min_sj(report):.3f}")
    check(len(on) == 32 and worst <= 1e-12, f"FEAT3 ring: vertices on the charts to {worst:.1e}")


def mpi_matches_serial(tmp):
    if not MPIEXEC:
        print("NEOMESH_MPIEXEC is not set: no MPI comparison")
        return
    mesh = os.path.join(tmp, "plate-quads.msh")  # made by plate()
    options = ["--boundary", "slide", "--shape", "holes=" + HOLES_LEVEL_SET, "--no-practical",
               "--tol", "1e-11"]
    results = []
    for ranks in (1, 2):
        out = os.path.join(tmp, f"mpi-{ranks}.msh")
        launcher = [] if ranks == 1 else [MPIEXEC, "--allow-run-as-root", "--oversubscribe",
                                          "-n", "2"]
        run([*launcher, NEOMESH, "smooth", mesh, "-o", out, "--quiet", *options], tmp)
        results.append(read_msh(out))
    worst = max(abs(a - b) for t in results[0] for a, b in zip(results[0][t], results[1][t]))
    check(worst <= 1e-8, f"plate quads sliding on the holes: 2 ranks within {worst:.1e} of serial")


def bad_inputs(tmp):
    good = os.path.join(DATA, "feat_ring_quad.xml")
    with open(os.path.join(tmp, "bad_chart.xml"), "w") as f:
        with open(good) as g:
            f.write(g.read().replace('chart="inner"', 'chart="nosuchchart"'))
    cases = [
        ("unknown part", ["--boundary", "slide", "--shape", "hole=circle:0,0,0.5"], good,
         ["hole", "bnd:inner"]),
        ("shape off the part's vertices",
         ["--boundary", "slide", "--shape", "bnd:inner=circle:0,0,0.45"], good,
         ["bnd:inner", "from it"]),
        ("malformed shape", ["--boundary", "slide", "--shape", "bnd:inner=circle:0,0"], good,
         ["circle:cx,cy,r"]),
        ("shape without =", ["--boundary", "slide", "--shape", "circle:0,0,1"], good,
         ["PART=SHAPE"]),
        ("shape with fixed boundary", ["--boundary", "fixed", "--shape", "bnd:inner=circle:0,0,0.5"],
         good, ["--boundary slide"]),
        ("feature angle out of range", ["--boundary", "slide", "--feature-angle", "200"], good,
         ["--feature-angle"]),
        ("part on an unknown chart", ["--boundary", "slide"], os.path.join(tmp, "bad_chart.xml"),
         ["nosuchchart"]),
    ]
    for name, options, mesh, words in cases:
        out = os.path.join(tmp, "bad-out.msh")
        proc = run([NEOMESH, "smooth", mesh, "-o", out, *options], tmp, expect_ok=False)
        lines = proc.stderr.strip().splitlines()
        ok = (proc.returncode == 1 and len(lines) == 1 and lines[0].startswith("neomesh: error:")
              and all(w in lines[0] for w in words) and not os.path.exists(out))
        check(ok, f"bad input ({name}): {lines[0] if lines else proc.returncode}")


def main():
    with tempfile.TemporaryDirectory() as tmp:
        plate(tmp, quads=True)
        plate(tmp, quads=False)
        box_with_hole(tmp)
        feat_charts(tmp)
        mpi_matches_serial(tmp)
        bad_inputs(tmp)
    if failures:
        sys.exit(f"{len(failures)} checks failed")


if __name__ == "__main__":
    main()
