"""VTK legacy (.vtk) inputs as a user gives them: a mesh written by meshio in ASCII and binary
smooths to the same points as its Gmsh twin, and every .vtk of Mesquite's test suite
(../shared/corpus/mesquite, skipped without it) is read or refused in one line for a reason a
user can act on. Run with NEOMESH=path/to/neomesh."""
import glob
import os

import numpy as np
import pytest

from conftest import CORPUS, DATA, expect_one_error_line, needs_corpus, neomesh, read_mesh, run

MESQUITE = os.path.join(CORPUS, "mesquite")

# Why neomesh may refuse a real file: cells it does not optimize, or 2D cells off one plane.
HONEST = ("second-order", "polygon", "only 1D", "no 2D or 3D", "structured grid",
          "a surface mesh")
# Files meshio cannot read (it fails on them with an IndexError) that neomesh refuses: two are
# malformed, refused naming the line. (neomesh reads the triPatch files, which list more
# CELL_TYPES than CELLS, as VTK's reader does, taking the first ones: test_curved.py.)
MESHIO_CANNOT_READ = {
    # "3 a b c d" per cell: quadrilaterals that announce 3 points, 8192 CELL_TYPES for 4096 CELLS.
    "2D/vtk/quads/untangled/shashkov_quad_opt.vtk": "shashkov_quad_opt.vtk:7768: not a valid VTK",
    # CELLS 30 80 for 30 quadrilaterals (150 numbers).
    "2D/vtk/quads/untangled/unstrquad.vtk": "unstrquad.vtk:64: not a valid VTK file",
}


def twins(tmp, case, level, binary):
    """A generated mesh as a .vtk (written by meshio) and as its Gmsh twin (cells only, as the
    .vtk has no groups)."""
    import meshio
    generated = os.path.join(tmp, case + ".msh")
    neomesh("generate", case, "--level", level, "--jitter", "0.2", "-o", generated)
    m = read_mesh(generated)
    top = max(m.cells, key=lambda c: c.data.shape[1] if c.type != "line" else 0).type
    cells = [(c.type, c.data) for c in m.cells if c.type == top]
    vtk = os.path.join(tmp, f"{case}-{'bin' if binary else 'ascii'}.vtk")
    meshio.write(vtk, meshio.Mesh(m.points, cells), file_format="vtk", binary=binary)
    msh = os.path.join(tmp, case + "-twin.msh")
    meshio.write(msh, meshio.Mesh(m.points, cells), file_format="gmsh22", binary=False)
    return vtk, msh


@pytest.mark.parametrize("binary", [False, True], ids=["ascii", "binary"])
@pytest.mark.parametrize("case, level", [("box-quad", 3), ("box-tri", 3), ("box-tet", 2),
                                         ("box-hex", 2), ("box-wedge", 2)])
def test_a_vtk_file_smooths_as_its_gmsh_twin(tmp, case, level, binary):
    vtk, msh = twins(tmp, case, level, binary)
    out_vtk, out_msh = os.path.join(tmp, "from-vtk.msh"), os.path.join(tmp, "from-msh.msh")
    neomesh("smooth", vtk, "-o", out_vtk, "--quiet")
    neomesh("smooth", msh, "-o", out_msh, "--quiet")
    a, b = read_mesh(out_vtk), read_mesh(out_msh)
    assert np.array_equal(a.points, b.points)
    assert np.array_equal(read_mesh(msh).points[:, :2], read_mesh(vtk).points[:, :2])
    # The commands that read a mesh take it too.
    run_ok = [("quality", vtk), ("convert", vtk, "-o", os.path.join(tmp, "c.vtu"))]
    for args in run_ok:
        neomesh(*args)


def test_wedges_keep_their_orientation_from_vtk_to_vtu(tmp):
    # VTK lists a wedge's triangles the other way round than Gmsh (meshio converts between the
    # two): vtk_mixed_3d.vtk's wedge is read right side out, and a .vtu holds the wedges meshio
    # reads from the .msh it was converted from.
    quality = neomesh("quality", os.path.join(DATA, "vtk_mixed_3d.vtk")).stdout
    assert "inverted cells: 0" in quality
    msh, vtu = os.path.join(DATA, "prism_v41.msh"), os.path.join(tmp, "out.vtu")
    neomesh("convert", msh, "-o", vtu)
    wedges = lambda m: [c.data.tolist() for c in m.cells if c.type == "wedge"]
    assert wedges(read_mesh(vtu)) == wedges(read_mesh(msh))


def test_an_unknown_extension_names_the_formats_read(tmp):
    path = os.path.join(tmp, "mesh.stl")
    open(path, "w").write("solid x\n")
    expect_one_error_line(neomesh("quality", path, expect=1), ["Gmsh .msh", "FEAT3 .xml",
                                                               "VTK legacy .vtk"])


@needs_corpus
def test_every_mesquite_file_is_read_or_refused_in_one_line():
    files = sorted(glob.glob(os.path.join(MESQUITE, "**", "*.vtk"), recursive=True))
    assert len(files) >= 100
    problems, read = [], 0
    for path in files:
        name = os.path.relpath(path, MESQUITE)
        proc = run([os.environ.get("NEOMESH", "neomesh"), "quality", path], expect=None,
                   timeout=120)
        if proc.returncode == 0:
            read += 1
            if name in MESHIO_CANNOT_READ:
                problems.append(f"{name}: read, but expected '{MESHIO_CANNOT_READ[name]}'")
            continue
        lines = proc.stderr.strip().splitlines()
        reasons = [MESHIO_CANNOT_READ[name]] if name in MESHIO_CANNOT_READ else HONEST
        if proc.returncode != 1 or len(lines) != 1 or not any(r in lines[0] for r in reasons):
            problems.append(f"{name}: exit {proc.returncode}: {proc.stderr.strip()[:300]}")
    assert not problems, "\n".join(problems)
    assert read >= 90
