"""The second-order meshes of the shared Mesquite corpus (../shared/corpus/mesquite/*/vtk/quadratic:
tri6, quad9, tet10, hex20, hex27), each smoothed with the defaults and judged by the rules of
../shared/tools/corpus_check.py with the certificate as the validity test (docs/method.md §11):

  RIGHT    exit 0; every cell certified valid (det J > 0 everywhere, not only at sample points);
           the same number of points; a planar input stays in its plane; the least curved
           scaled Jacobian not below the input's (input certified valid) or above 1e-3 (input
           with cells not certified valid);
  REFUSED  exit 1, one 'neomesh: error:' line saying why, nothing written, and only where
           HONEST below says the refusal is right;
  WRONG    anything else.

The shared tool judges a curved output by the straight scaled Jacobian of its corners, which says
nothing of whether the curved cells fold. Files that take more than a few seconds are long tests:
they run with NEOMESH_LONG_TESTS=1 (their seconds on 2 loaded cores are in LONG). Skipped without
the corpus. Run with NEOMESH=path/to/neomesh."""
import glob
import json
import os

import numpy as np
import pytest

from conftest import CORPUS, describe, neomesh, read_mesh

QUADRATIC = sorted(glob.glob(os.path.join(CORPUS, "mesquite", "*", "vtk", "quadratic", "*.vtk")))

# Refusals that are right, by file name: a word the one error line must hold.
HONEST = {}
# Files whose run takes more than a few seconds, with the seconds a run took.
LONG = {"cutCube": 8, "hexCyl": 27, "sphereCylinder_1194_inv": 28, "sphereCylinder_22492": 113,
        "sphereCylinder_22492_inv": 74}
LONG_TESTS = os.environ.get("NEOMESH_LONG_TESTS") == "1"


def name_of(path):
    return os.path.basename(path).rsplit(".", 1)[0]


def curved_quality(path, json_path):
    neomesh("quality", path, "--json", json_path)
    with open(json_path) as f:
        return json.load(f)["curved"]


def judge(path, tmp):
    """(verdict, why) for one file, as the docstring says."""
    name = name_of(path)
    out, report = os.path.join(tmp, "out.msh"), os.path.join(tmp, "r.json")
    proc = neomesh("smooth", path, "-o", out, "--quiet", "--report", report, expect=None,
                   timeout=600)
    errors = [line for line in proc.stderr.splitlines() if line.strip()]
    if proc.returncode != 0:
        if (proc.returncode == 1 and len(errors) == 1 and errors[0].startswith("neomesh: error:")
                and name in HONEST and HONEST[name] in errors[0] and not os.path.exists(out)):
            return "REFUSED", errors[0]
        return "WRONG", describe(proc)
    before = curved_quality(path, os.path.join(tmp, "before.json"))
    after = curved_quality(out, os.path.join(tmp, "after.json"))
    sa, sb = before["scaled_jacobian"]["min"], after["scaled_jacobian"]["min"]
    why = []
    if after["not_certified_valid"]:
        why.append(f"{after['not_certified_valid']} cells not certified valid")
    if before["not_certified_valid"] == 0 and sb < sa - 1e-12:
        why.append(f"worse least curved scaled Jacobian {sa:.3g} -> {sb:.3g}")
    if before["not_certified_valid"] and sb <= 1e-3:
        why.append(f"untangled to least curved scaled Jacobian {sb:.2e}")
    try:
        mi = read_mesh(path)
    except Exception:  # meshio cannot read triPatch_*: the input as convert writes it
        given = os.path.join(tmp, "in.msh")
        neomesh("convert", path, "-o", given)
        mi = read_mesh(given)
    mo = read_mesh(out)
    if len(mi.points) != len(mo.points):
        why.append("point count changed")
    elif mi.cells[0].data.shape[1] in (6, 8, 9):  # a 2D mesh: it stays in its plane
        centre = mi.points.mean(0)
        normal = np.linalg.svd(mi.points - centre, full_matrices=False)[2][-1]
        scale = np.abs(mi.points - centre).max()
        flat_in = np.abs((mi.points - centre) @ normal).max()
        off = np.abs((mo.points - centre) @ normal).max()
        if flat_in < 1e-4 * scale and off > max(10 * flat_in, 1e-9 * scale):
            why.append(f"left its plane by {off:.2e}")
    if why:
        return "WRONG", ", ".join(why)
    return "RIGHT", f"least curved scaled Jacobian {sa:.3g} -> {sb:.3g}"


def case(path):
    name = name_of(path)
    marks = [pytest.mark.skipif(not LONG_TESTS, reason=f"long ({LONG[name]} s): "
                                "NEOMESH_LONG_TESTS=1 runs it")] if name in LONG else []
    return pytest.param(path, id=name, marks=marks)


@pytest.mark.skipif(not QUADRATIC, reason=f"the real meshes are not at {CORPUS}")
def test_the_corpus_has_its_nineteen_quadratic_files():
    # 11 in 2D (tri6, quad9; the six triPatch_* among them), 8 in 3D (tet10, hex20, hex27).
    assert len(QUADRATIC) == 19
    assert set(LONG) | set(HONEST) <= {name_of(p) for p in QUADRATIC}


@pytest.mark.parametrize("path", [case(p) for p in QUADRATIC])
def test_each_quadratic_mesquite_mesh_comes_out_right_by_the_certificate(tmp, path):
    verdict, why = judge(path, tmp)
    print(f"{verdict} {name_of(path)}: {why}")
    assert verdict in ("RIGHT", "REFUSED"), why
