"""`neomesh curve`: a straight mesh raised to second order with its boundary on the exact
geometry, written only when every curved cell is certified valid."""
import json
import math
import os

import pytest

from conftest import CORPUS, expect_one_error_line, needs_corpus, neomesh, read_mesh


def quality(tmp, path):
    report = os.path.join(tmp, "quality.json")
    neomesh("quality", path, "--json", report)
    with open(report) as f:
        return json.load(f)


def ring_msh(path, around, inner, outer):
    """A ring of `around` quadrilaterals between radii `inner` and `outer` (one layer), Gmsh 2.2,
    its circles in the physical groups "inner" and "outer"."""
    nodes = [(r * math.cos(2 * math.pi * i / around), r * math.sin(2 * math.pi * i / around))
             for r in (inner, outer) for i in range(around)]
    elements = []
    for i in range(around):
        j = (i + 1) % around
        elements.append(f"1 2 1 1 {i + 1} {j + 1}")
        elements.append(f"1 2 2 2 {around + i + 1} {around + j + 1}")
        elements.append(f"3 2 3 3 {i + 1} {j + 1} {around + j + 1} {around + i + 1}")
    with open(path, "w") as f:
        f.write("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$PhysicalNames\n3\n"
                '1 1 "inner"\n1 2 "outer"\n2 3 "ring"\n$EndPhysicalNames\n')
        f.write(f"$Nodes\n{len(nodes)}\n")
        f.writelines(f"{k + 1} {x!r} {y!r} 0\n" for k, (x, y) in enumerate(nodes))
        f.write(f"$EndNodes\n$Elements\n{len(elements)}\n")
        f.writelines(f"{k + 1} {e}\n" for k, e in enumerate(elements))
        f.write("$EndElements\n")


def test_an_annulus_is_raised_with_its_arcs_nodes_on_the_circles(tmp):
    straight, curved = os.path.join(tmp, "annulus.msh"), os.path.join(tmp, "curved.msh")
    neomesh("generate", "annulus-quad", "--level", "2", "-o", straight)
    proc = neomesh("curve", straight, "-o", curved, "--order", "2",
                   "--shape", "inner=circle:0,0,1", "--shape", "outer=circle:0,0,2")
    assert "certified valid" in proc.stdout
    q = quality(tmp, curved)
    assert q["curved"]["cells"] == {"quadrilateral9": 16}
    assert q["curved"]["not_certified_valid"] == 0
    points = read_mesh(curved).points
    radii = [math.hypot(x, y) for x, y, _ in points]
    # Raising adds 40 edge and 16 centre nodes to the 25 vertices; the arcs' 8 + 10 lie on them.
    assert len(points) == 25 + 40 + 16
    for target in (1.0, 2.0):
        near = [r for r in radii if abs(r - target) < 0.05]
        assert len(near) == 9, (target, near)
        assert max(abs(r - target) for r in near) <= 1e-12


def test_a_thin_layer_folded_under_a_coarse_circle_is_untangled_onto_valid_cells(tmp):
    # Six cells 0.05 thick under a circle of radius 0.5 cut into six arcs: each arc bulges
    # h^2/(8R) ~ 0.06 > 0.05 into its cell, so raising folds all six; optimizing the nodes inside
    # (the boundary's held on the circles) unfolds them.
    straight, curved = os.path.join(tmp, "ring.msh"), os.path.join(tmp, "curved.msh")
    ring_msh(straight, 6, 0.5, 0.55)
    proc = neomesh("curve", straight, "-o", curved,
                   "--shape", "inner=circle:0,0,0.5", "--shape", "outer=circle:0,0,0.55")
    assert "least curved scaled Jacobian -" in proc.stdout  # folded once placed
    q = quality(tmp, curved)
    assert q["curved"]["not_certified_valid"] == 0
    assert q["curved"]["scaled_jacobian"]["min"] > 0.5
    points = read_mesh(curved).points
    radii = [math.hypot(x, y) for x, y, _ in points]
    for target in (0.5, 0.55):
        near = [r for r in radii if abs(r - target) < 0.01]
        assert len(near) == 12, (target, near)
        assert max(abs(r - target) for r in near) <= 1e-12
    # Without shapes the ring stays straight, and valid.
    neomesh("curve", straight, "-o", curved)
    assert quality(tmp, curved)["curved"]["not_certified_valid"] == 0


def test_wedges_are_raised_with_one_node_per_edge_and_quadrilateral_face(tmp):
    wedges, curved = os.path.join(tmp, "wedges.msh"), os.path.join(tmp, "curved.msh")
    neomesh("generate", "box-wedge", "--level", "1", "-o", wedges)
    straight = read_mesh(wedges)
    cells = next(b.data for b in straight.cells if b.type == "wedge")
    edges, faces = set(), set()
    for c in cells:
        for a, b in [(0, 1), (1, 2), (2, 0), (3, 4), (4, 5), (5, 3), (0, 3), (1, 4), (2, 5)]:
            edges.add(frozenset((c[a], c[b])))
        for face in [(0, 1, 4, 3), (1, 2, 5, 4), (2, 0, 3, 5)]:
            faces.add(frozenset(c[list(face)]))
    proc = neomesh("curve", wedges, "-o", curved)
    assert "certified valid" in proc.stdout
    q = quality(tmp, curved)
    assert q["curved"]["cells"] == {"wedge18": len(cells)}
    assert q["curved"]["not_certified_valid"] == 0
    # A straight box: every wedge18 is its straight wedge, as good as it.
    straight_min = quality(tmp, wedges)["metrics"]["scaled_jacobian"]["min"]
    assert q["curved"]["scaled_jacobian"]["min"] == pytest.approx(straight_min, rel=1e-12)
    assert len(read_mesh(curved).points) == len(straight.points) + len(edges) + len(faces)


def test_pyramids_an_unknown_part_and_order_3_are_refused_in_one_line(tmp):
    pyramids, out = os.path.join(tmp, "pyramids.msh"), os.path.join(tmp, "out.msh")
    neomesh("generate", "box-pyramid", "--level", "1", "-o", pyramids)
    expect_one_error_line(neomesh("curve", pyramids, "-o", out, expect=1),
                          ["pyramids cannot be raised"], [out])
    quads = os.path.join(tmp, "quads.msh")
    neomesh("generate", "annulus-quad", "--level", "1", "-o", quads)
    expect_one_error_line(neomesh("curve", quads, "-o", out, "--shape", "hole=circle:0,0,1",
                                  expect=1), ["no boundary part 'hole'"], [out])
    expect_one_error_line(neomesh("curve", quads, "-o", out, "--order", "3", expect=1),
                          ["--order 3"], [out])


@needs_corpus
def test_a_feat3_mesh_puts_its_nodes_on_its_charts(tmp):
    # FEAT3's flow around a cylinder: part bnd:c on the circle chart (0.2, 0.2), r = 0.05; the
    # outer box on a closed Bezier polyline. No shape given: the charts are the geometry.
    curved = os.path.join(tmp, "curved.msh")
    proc = neomesh("curve", os.path.join(CORPUS, "feat3", "flowbench_c2d_00_quad_130.xml"),
                   "-o", curved)
    assert "0 boundary nodes of parts without a shape or chart left straight" in proc.stdout
    assert quality(tmp, curved)["curved"]["not_certified_valid"] == 0
    points = read_mesh(curved).points
    radii = [math.hypot(x - 0.2, y - 0.2) for x, y, _ in points]
    near = [r for r in radii if abs(r - 0.05) < 0.002]
    assert len(near) == 24  # the circle's 12 vertices and 12 edge nodes
    assert max(abs(r - 0.05) for r in near) <= 1e-12
