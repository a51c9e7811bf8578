"""FEAT3 meshes smoothed as FEAT3 reads them: every mesh of the shared corpus (../shared/corpus
from the repository root; skipped without it), the rotor meshes with their chart files, ends
with exit 0 and no inverted cell; the minimum scaled Jacobian does not drop below the input's
except for the meshes listed in KNOWN_WORSE (docs/boundary.md says why). All 94 meshes take
about a minute on one core."""
import glob
import json
import os

import pytest

from conftest import DATA, SOURCE, neomesh
from feat3_charts import CHARTS

CORPUS = os.path.join(SOURCE, "..", "shared", "corpus", "feat3")
# The worst cell ends up below the file's, at most down to this: the vertices placed on their
# charts (FEAT3's semantics) lower it, and the quality guard cannot pull a cell back above where
# the placement left it (6-digit coordinates: 1e-4 and less; unit-axe-tria: vertices up to 0.161
# off its circle); FEAT3's own optimized rotor loses a cell in the thin gap between the screws.
KNOWN_WORSE = {"contract_3d_01_hexa_800": 0.8320, "contract_4to1_full_quad_86": 0.9999,
               "unit_shell_hexa_24": 0.7865, "venturi-pipe-tria": 0.2437,
               "unit-axe-tria": 0.477, "screws_2d_mesh_quad_opt_ss_360_1": 0.398}


def meshes():
    files = sorted(glob.glob(os.path.join(CORPUS, "*.xml")))
    return [os.path.basename(f)[:-4] for f in files if "_chart_" not in f]


@pytest.mark.skipif(not os.path.isdir(CORPUS), reason=f"no corpus at {CORPUS}")
@pytest.mark.parametrize("name", meshes() or ["none"])
def test_smooth_every_feat3_mesh(name, tmp):
    inputs = [os.path.join(CORPUS, name + ".xml")]
    if name in CHARTS:
        inputs.insert(0, os.path.join(CORPUS, CHARTS[name]))
    report = os.path.join(tmp, "r.json")
    neomesh("smooth", *inputs, "-o", os.path.join(tmp, "out.msh"), "--quiet", "--report", report,
            timeout=120)
    r = json.load(open(report))
    assert r["quality_after"]["inverted"] == 0
    before = r["quality_before"]["metrics"]["scaled_jacobian"]["min"]
    after = r["quality_after"]["metrics"]["scaled_jacobian"]["min"]
    assert after >= min(before - 1e-12, KNOWN_WORSE.get(name, 1)), \
        f"min scaled Jacobian {before} -> {after}"


@pytest.mark.skipif(not os.path.isdir(CORPUS), reason=f"no corpus at {CORPUS}")
def test_the_rotor_passes_feat3s_own_optimizer_with_the_worst_cell_repair(tmp):
    """screws_2d_mesh_quad_360_1 with its Bezier charts: FEAT3's own optimizer reaches a worst
    scaled Jacobian of 0.4835. Ideal targets leave two cells in the gap at 0.299 (the next worst
    at 0.52); moving the vertices around them, the boundary ones along the screws (the
    worst-cell repair, on by default), lifts them, without collapsing an edge (which the scaled Jacobian
    alone does not see: the edge ratio stays below the input's)."""
    inputs = [os.path.join(CORPUS, "screws_2d_chart_bezier_24_28.xml"),
              os.path.join(CORPUS, "screws_2d_mesh_quad_360_1.xml")]
    report = os.path.join(tmp, "r.json")
    neomesh("smooth", *inputs, "-o", os.path.join(tmp, "out.vtu"), "--quiet", "--report", report,
            "--targets", "ideal", timeout=120)
    r = json.load(open(report))
    repair = r["worst_cell_repair"]
    assert repair["min_scaled_jacobian_before"] < 0.35 and repair["vertices_moved"] > 0, repair
    assert r["quality_after"]["metrics"]["scaled_jacobian"]["min"] >= 0.75
    assert r["quality_after"]["metrics"]["edge_ratio"]["max"] <= \
        r["quality_before"]["metrics"]["edge_ratio"]["max"]
    assert r["quality_after"]["metrics"]["scaled_jacobian"]["mean"] > 0.96
    assert r["quality_after"]["inverted"] == 0


@pytest.mark.skipif(not os.path.isdir(CORPUS), reason=f"no corpus at {CORPUS}")
def test_the_rotor_passes_feat3s_own_optimizer_with_the_defaults(tmp):
    """The same rotor with the defaults: the gap's stretched cells are kept as rectangles, and
    the repair moves the vertices of those the optimum left skewed: past FEAT3's 0.4835 (the
    kept cells held their vertices and stopped it at 0.273), no edge ratio above the input's."""
    inputs = [os.path.join(CORPUS, "screws_2d_chart_bezier_24_28.xml"),
              os.path.join(CORPUS, "screws_2d_mesh_quad_360_1.xml")]
    report = os.path.join(tmp, "r.json")
    neomesh("smooth", *inputs, "-o", os.path.join(tmp, "out.vtu"), "--quiet", "--report", report,
            timeout=120)
    r = json.load(open(report))
    assert r["targets"]["mode"] == "smoothed" and r["targets"]["cells_input"] > 0
    after, before = r["quality_after"]["metrics"], r["quality_before"]["metrics"]
    assert after["scaled_jacobian"]["min"] >= 0.5, after["scaled_jacobian"]
    assert after["scaled_jacobian"]["mean"] >= before["scaled_jacobian"]["mean"]
    assert after["edge_ratio"]["max"] <= before["edge_ratio"]["max"]


def test_chart_file_in_either_order_moves_the_vertex_onto_its_circle(tmp):
    mesh = os.path.join(DATA, "feat_chart_file_mesh.xml")
    charts = os.path.join(DATA, "feat_chart_file_charts.xml")
    for inputs in ([mesh, charts], [charts, mesh]):
        report = os.path.join(tmp, "r.json")
        p = neomesh("smooth", *inputs, "-o", os.path.join(tmp, "out.msh"), "--report", report)
        assert "charts: 1 boundary vertices moved onto their charts first (farthest by 0.02)" \
            in p.stdout
        change = json.load(open(report))["boundary_change"]
        assert change["moved_onto_charts"] == 1
    # quality and convert take the files as they are.
    neomesh("quality", charts, mesh)
    neomesh("convert", mesh, charts, "-o", os.path.join(tmp, "out.vtu"))


def test_missing_chart_is_a_notice(tmp):
    # A part on a chart no file defines slides on the input's facets (FEAT3's
    # scalexa_gendie_simple names a chart file that is not shipped).
    p = neomesh("smooth", os.path.join(DATA, "feat_part_on_missing_chart.xml"), "-o",
                os.path.join(tmp, "out.msh"))
    assert "notice:" in p.stdout and "chart 'nowhere'" in p.stdout
    p = neomesh("convert", os.path.join(DATA, "feat_part_on_missing_chart.xml"), "-o",
                os.path.join(tmp, "out.msh"))
    assert "notice:" in p.stdout and "chart 'nowhere'" in p.stdout


# adapt around each flowbench obstacle: its circle, the cylinder of the 3D channels, its sphere.
OBSTACLES = {**{f"flowbench_c2d_0{i}": ["--circle", "0.2,0.2,0.05"] for i in (0, 1, 2, 3, 4, 7, 8, 9)},
             "flowbench_c3d_01_hexa_128": ["--levelset", "sqrt((x-0.5)^2+(y-0.2)^2)-0.05"],
             "flowbench_s3d_02_hexa_80": ["--sphere", "0.5,0.2,0.205,0.05"]}


@pytest.mark.skipif(not os.path.isdir(CORPUS), reason=f"no corpus at {CORPUS}")
@pytest.mark.parametrize("prefix", sorted(OBSTACLES))
def test_adapt_around_every_flowbench_obstacle(prefix, tmp):
    # It used to end in a failed line search before the first update of the desired volumes,
    # with the worst cell worse than the input's.
    path = glob.glob(os.path.join(CORPUS, prefix + "*.xml"))[0]
    report = os.path.join(tmp, "r.json")
    neomesh("adapt", path, "-o", os.path.join(tmp, "out.msh"), "--quiet", "--report", report,
            *OBSTACLES[prefix], timeout=120)
    r = json.load(open(report))
    assert not r["result"]["stop_reason"].startswith("line search failed")
    assert len(r["picard"]["update_iterations"]) >= 1
    assert r["quality_after"]["inverted"] == 0
    before = r["quality_before"]["metrics"]["scaled_jacobian"]["min"]
    after = r["quality_after"]["metrics"]["scaled_jacobian"]["min"]
    # The guard holds the input's worst cell or 0.2, whichever is lower (AdaptOptions::
    # kGuardCeiling: grading changes the cells' shapes); flowbench_c2d_07: its 6-digit
    # coordinates placed on the circle cost 1e-5.
    assert after >= min(before, 0.2) - (1e-4 if prefix == "flowbench_c2d_07" else 1e-12), \
        f"min scaled Jacobian {before} -> {after}"
    print(f"{prefix}: min scaled Jacobian {before:.3f} -> {after:.3f}")
