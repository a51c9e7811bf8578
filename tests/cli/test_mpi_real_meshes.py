"""2 MPI ranks give the serial result on real meshes of every kind (../shared/corpus; skipped
without it): FEAT3 meshes sliding on their charts (a separate Bezier chart file among them, 2D and
3D), Mesquite's tangled meshes (untangled first), a mixed triangle-quadrilateral mesh, triangles,
hexahedra and tetrahedra. Iterated to a tight defect (`--no-practical --tol 1e-11`), the vertices
agree to 1e-8 of the mesh's size and the energies to 1e-8 relative; the two meshes whose optimum
the method does not reach so (NOT_TIGHT) agree within the default stopping rule's tolerance
(docs/user-guide.md, "Parallel runs"); a rerun on 2 ranks writes the same file byte for byte."""
import filecmp
import json
import os

import numpy as np
import pytest

from conftest import CORPUS, needs_corpus, needs_mpi, neomesh, read_mesh

pytestmark = [needs_mpi, needs_corpus]

FEAT3 = os.path.join(CORPUS, "feat3")
TANGLED_QUADS = os.path.join(CORPUS, "mesquite", "2D", "vtk", "quads", "tangled")
MESHES = {
    "flowbench_c2d_03_quad_64": [os.path.join(FEAT3, "flowbench_c2d_03_quad_64.xml")],
    "rotor": [os.path.join(FEAT3, "screws_2d_chart_bezier_24_28.xml"),
              os.path.join(FEAT3, "screws_2d_mesh_quad_360_1.xml")],
    "venturi-pipe-tria": [os.path.join(FEAT3, "venturi-pipe-tria.xml")],
    "flowbench_c3d_00_hexa_48": [os.path.join(FEAT3, "flowbench_c3d_00_hexa_48.xml")],
    "flowbench_c3d_02_hexa_192": [os.path.join(FEAT3, "flowbench_c3d_02_hexa_192.xml")],
    "tangled_quad": [os.path.join(TANGLED_QUADS, "tangled_quad.vtk")],
    "inverted-hole-1": [os.path.join(TANGLED_QUADS, "inverted-hole-1.vtk")],
    "overt_hyb_1": [os.path.join(CORPUS, "mesquite", "2D", "vtk", "mixed", "untangled",
                                 "overt_hyb_1.vtk")],
    "tri_20258": [os.path.join(CORPUS, "mesquite", "2D", "vtk", "tris", "untangled",
                               "tri_20258.vtk")],
    "large_box_hex_1000": [os.path.join(CORPUS, "mesquite", "3D", "vtk", "hexes", "untangled",
                                        "large_box_hex_1000.vtk")],
    "cub_wedge_like": [os.path.join(CORPUS, "mesquite", "3D", "vtk", "tets", "untangled",
                                    "cub_wedge_like.vtk")],
}


# Their optimum with the default targets (kept quadrilaterals aim at rectangles) squeezes a few
# cells, and the method does not reach a defect of 1e-11 in 200 iterations (the rotor stalls at
# 1.0, overt_hyb_1 at 8e-4): they run with the default stopping rule, and agree within its
# tolerance (docs/user-guide.md, "Parallel runs").
NOT_TIGHT = {"rotor": 1.1e-3, "overt_hyb_1": 1.1e-3}


def smooth(tmp, name, ranks, suffix=""):
    out = os.path.join(tmp, f"{name}-{ranks}{suffix}.vtu")
    report = os.path.join(tmp, f"{name}-{ranks}{suffix}.json")
    tight = [] if name in NOT_TIGHT else ["--no-practical", "--tol", "1e-11"]
    # Without the worst-cell repair, whose max-min choices the round-off between the runs can
    # flip (docs/user-guide.md, "Parallel runs"): the optimum is what must agree.
    neomesh("smooth", *MESHES[name], "-o", out, "--quiet", "--report", report, *tight,
            "--no-repair", ranks=ranks, timeout=300)
    with open(report) as f:
        return out, json.load(f)


@pytest.mark.parametrize("name", list(MESHES))
def test_two_ranks_give_the_serial_result(tmp, name):
    serial_out, serial = smooth(tmp, name, 1)
    parallel_out, parallel = smooth(tmp, name, 2)
    assert parallel["processes"] == 2
    a, b = read_mesh(serial_out), read_mesh(parallel_out)
    assert [c.data.tolist() for c in a.cells] == [c.data.tolist() for c in b.cells]
    size = np.ptp(a.points, axis=0).max()
    worst = np.abs(a.points - b.points).max() / size
    bound = NOT_TIGHT.get(name, 1e-8)
    assert worst <= bound, f"{name}: 2 ranks moved a vertex {worst:.2e} of the mesh size away"
    energies = [r["result"]["final_energy"] for r in (serial, parallel)]
    # Relative to the energy, or to one cell's worth where the optimum is a round-off zero.
    scale = max(abs(energies[0]), serial["cells"] * 1e-12)
    energy_bound = 5e-5 if name in NOT_TIGHT else 1e-8
    assert abs(energies[0] - energies[1]) <= energy_bound * scale, f"{name}: energies {energies}"
    assert parallel["quality_after"]["inverted"] == 0


@pytest.mark.parametrize("name", ["rotor", "tangled_quad"])
def test_a_rerun_on_two_ranks_writes_the_same_file(tmp, name):
    first, _ = smooth(tmp, name, 2)
    again, _ = smooth(tmp, name, 2, "-again")
    assert filecmp.cmp(first, again, shallow=False), f"{name}: the rerun wrote another file"
