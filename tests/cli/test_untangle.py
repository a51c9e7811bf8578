"""neomesh smooth (and adapt) untangles a mesh with inverted cells before smoothing (adapting)
it (docs/untangling.md):
jittered boxes of quads and hexes, bumped boxes, and jittered Gmsh meshes of wedges, hexahedra,
pyramids and tets come out with no inverted cell, the table names the phases,
the report counts the inverted cells before and after; --no-untangle refuses such a mesh, and a
mesh whose boundary folds over ends with one error line naming the cells, and no output."""
import json
import os

import numpy
import pytest

from conftest import DATA, NEOMESH, read_mesh, run

def bumped_box(tmp, name, cells):
    """box-quad whose bottom side was pushed up by a bump of height 0.8 (a moving boundary):
    it runs through the cells above it, which must move far up, round after round."""
    mesh = os.path.join(tmp, name + ".msh")
    run([NEOMESH, "generate", "box-quad", "--cells", str(cells), "-o", mesh], timeout=120)
    m = read_mesh(mesh)
    bottom = numpy.isclose(m.points[:, 1], -1.0)
    m.points[bottom, 1] += 0.8 * (1.0 - m.points[bottom, 0] ** 2)
    m.write(mesh, file_format="gmsh22", binary=False)
    return mesh


# Faces of meshio's 3D cell types (local vertex numbers), to find the boundary vertices.
FACES = {"tetra": [(0, 1, 2), (0, 1, 3), (0, 2, 3), (1, 2, 3)],
         "hexahedron": [(0, 1, 2, 3), (4, 5, 6, 7), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6),
                        (3, 0, 4, 7)],
         "wedge": [(0, 1, 2), (3, 4, 5), (0, 1, 4, 3), (1, 2, 5, 4), (2, 0, 3, 5)],
         "pyramid": [(0, 1, 2, 3), (0, 1, 4), (1, 2, 4), (2, 3, 4), (3, 0, 4)]}


def tangled_gmsh_mesh(tmp, name, geo, amplitude):
    """A 3D mesh Gmsh makes from tests/data/geo/GEO, its interior vertices moved by up to
    `amplitude` times their shortest edge per coordinate (seeded)."""
    mesh = os.path.join(tmp, name + ".msh")
    run(["gmsh", "-3", os.path.join(DATA, "geo", geo), "-format", "msh41", "-o", mesh],
        timeout=120)
    m = read_mesh(mesh)
    faces, shortest = {}, numpy.full(len(m.points), numpy.inf)
    for block in m.cells:
        for cell in block.data if block.type in FACES else []:
            for face in FACES[block.type]:
                key = tuple(sorted(cell[list(face)]))
                faces[key] = faces.get(key, 0) + 1
            for a in cell:
                for b in cell:
                    if a != b:
                        shortest[a] = min(shortest[a], numpy.linalg.norm(m.points[a] - m.points[b]))
    boundary = {v for face, count in faces.items() if count == 1 for v in face}
    random = numpy.random.default_rng(5)
    for v in range(len(m.points)):
        if v not in boundary and numpy.isfinite(shortest[v]):
            m.points[v] += amplitude * shortest[v] * random.uniform(-1, 1, 3)
    m.write(mesh, file_format="gmsh22", binary=False)
    return mesh


def untangles(tmp, name, generate=None, mesh=None, options=(), inverted_before=100,
              command="smooth"):
    out, report = (os.path.join(tmp, name + ext) for ext in ("-out.vtu", ".json"))
    if generate:
        mesh = os.path.join(tmp, name + ".msh")
        run([NEOMESH, "generate", *generate, "-o", mesh], timeout=120)
    proc = run([NEOMESH, command, mesh, "-o", out, "--report", report, *options], timeout=120)
    with open(report) as f:
        r = json.load(f)
    u = r["untangling"]
    assert u["inverted_before"] >= inverted_before, \
        f"{name}: only {u['inverted_before']} cells were inverted"
    assert u["inverted_after"] == 0, f"{name}: {u['inverted_after']} cells still inverted"
    assert r["quality_before"]["inverted"] > 0 and r["quality_after"]["inverted"] == 0, \
        f"{name}: quality tables {r['quality_before']} / {r['quality_after']}"
    worst = r["quality_after"]["metrics"]["scaled_jacobian"]["min"]
    assert worst > 0.1, f"{name}: min scaled Jacobian after {worst}"
    assert all(row["untangling_round"] >= 1 for row in u["history"]), \
        f"{name}: untangling rows without a round"
    text = proc.stdout
    for line in (f"{u['inverted_before']} cells are inverted: untangling them first",
                 "untangling, round 1", "optimizing the Neo-Hookean energy:"):
        assert line in text, f"{name}: '{line}' not in the output:\n{text}"
    print(f"{name}: {u['inverted_before']} inverted -> 0 in {u['iterations']} iterations "
          f"({u['rounds']} rounds, {u['seconds']:.2f} s); then {r['result']['iterations']} "
          f"iterations; min scaled Jacobian {worst:.3f}")


# Two quads of [0,2]x[0,1] whose bottom middle vertex sits above the top edge: the boundary
# itself folds over, so no vertex placement on it makes either quad valid.
FOLDED = """$MeshFormat
2.2 0 8
$EndMeshFormat
$Nodes
6
1 0 0 0
2 1 1.5 0
3 2 0 0
4 0 1 0
5 1 1 0
6 2 1 0
$EndNodes
$Elements
2
1 3 2 1 1 1 2 5 4
2 3 2 1 1 2 3 6 5
$EndElements
"""


def refuses(tmp, args, mesh, expected, command="smooth"):
    out = os.path.join(tmp, "refused.msh")
    proc = run([NEOMESH, command, mesh, "-o", out, *args], expect=1, timeout=120)
    errors = [line for line in proc.stderr.splitlines() if line.strip()]
    assert len(errors) == 1 and errors[0].startswith("neomesh: error:"), \
        f"expected one error line, got:\n{proc.stderr}"
    assert expected in errors[0], f"'{expected}' not in: {errors[0]}"
    assert not os.path.exists(out), "an output file was left behind"


JITTERED_QUADS = ["box-quad", "--cells", "40", "--jitter", "0.6"]


@pytest.mark.parametrize("name, generate, options, inverted_before", [
    ("quads", JITTERED_QUADS, (), 100),
    ("hexes", ["box-hex", "--cells", "8", "--jitter", "0.6"], (), 100),
], ids=["quads", "hexes"])
def test_jittered_box_untangles(tmp, name, generate, options, inverted_before):
    untangles(tmp, name, generate, options=options, inverted_before=inverted_before)


@pytest.mark.parametrize("name, options", [("bump-fixed", ["--boundary", "fixed"]),
                                           ("bump-sliding", [])], ids=["fixed", "sliding"])
def test_bumped_box_untangles(tmp, name, options):
    untangles(tmp, name, mesh=bumped_box(tmp, "bump", 16), options=options, inverted_before=10)


# Wedges and hexahedra (an extruded triangle/quad mesh); hexahedra, pyramids and tets.
@pytest.mark.parametrize("name, geo", [("wedges-hexes", "extruded_prisms_hexes.geo"),
                                       ("hexes-pyramids-tets", "hex_tet_pyramids.geo")],
                         ids=["wedges-hexes", "hexes-pyramids-tets"])
def test_tangled_gmsh_mesh_untangles(tmp, name, geo):
    untangles(tmp, name, mesh=tangled_gmsh_mesh(tmp, name, geo, 0.9), inverted_before=20)


def test_no_untangle_refuses_a_tangled_mesh(tmp):
    tangled = os.path.join(tmp, "quads.msh")
    run([NEOMESH, "generate", *JITTERED_QUADS, "-o", tangled], timeout=120)
    refuses(tmp, ["--no-untangle"], tangled, "is inverted")


def test_adapt_untangles_then_adapts(tmp):
    """A geometry that moved through the mesh leaves it tangled: adapt untangles it towards the
    size field's volumes, then adapts."""
    untangles(tmp, "adapt-quads", JITTERED_QUADS, options=["--circle", "0,0,0.5"],
              command="adapt")


def test_adapt_no_untangle_refuses_a_tangled_mesh(tmp):
    tangled = os.path.join(tmp, "quads.msh")
    run([NEOMESH, "generate", *JITTERED_QUADS, "-o", tangled], timeout=120)
    refuses(tmp, ["--no-untangle", "--circle", "0,0,0.5"], tangled, "is inverted",
            command="adapt")


@pytest.mark.parametrize("boundary", ["slide", "fixed"])
def test_a_folded_boundary_cannot_be_untangled(tmp, boundary):
    folded = os.path.join(tmp, "folded.msh")
    with open(folded, "w") as f:
        f.write(FOLDED)
    refuses(tmp, ["--boundary", boundary], folded,
            "cannot be untangled with its boundary as it is: 2 of 2 inverted cells are "
            "still inverted")
