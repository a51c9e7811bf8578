"""Every kind of file the CLI writes is read by meshio (an independent reader) and, when it is
installed, by Gmsh: .msh from generate, smooth, adapt and convert (inputs with physical groups
on cells and facets, on facets only, and FEAT3 files) and .vtu. meshio must find the cells
neomesh reports, with a physical group for every cell block of a .msh file (meshio refuses a
file whose cells lack one while its facets have one).

meshio is the system's python3-meshio (scripts/setup.sh), which ctest's /usr/bin/python3
sees (a virtualenv's python3 may lack it); without it the tests are skipped.
"""
import os
import shutil
import subprocess

import pytest

from conftest import DATA, neomesh, read_mesh

pytest.importorskip("meshio", reason="python3-meshio is not installed (scripts/setup.sh)")

CELLS_3D, CELLS_2D = {"tetra", "hexahedron"}, {"triangle", "quad"}


def cells_of(path):
    """Number of cells (elements of the mesh's dimension) meshio reads from `path`."""
    mesh = read_mesh(path)
    types = CELLS_3D if any(block.type in CELLS_3D for block in mesh.cells) else CELLS_2D
    return sum(len(block.data) for block in mesh.cells if block.type in types), mesh


GENERATED = [("square-midpoint", "2"), ("cube-midpoint", "1"), ("box-tri", "2")]
# The inputs of smooth and convert: {tmp} is where the generated meshes are.
INPUTS = ["{tmp}/square-midpoint.msh", "{tmp}/cube-midpoint.msh",  # facet groups only
          os.path.join(DATA, "mixed_tri_quad_v41.msh"),          # cell groups too
          os.path.join(DATA, "cube_hex_v22.msh"),
          os.path.join(DATA, "feat_square_quad.xml")]
# (what wrote it, the file's name, the input it came from: the generated .msh for generate)
WRITTEN = [("generate", f"{case}{ext}", f"{{tmp}}/{case}.msh")
           for case, _ in GENERATED for ext in (".msh", ".vtu")] + \
          [(command, f"{command}-{i}{ext}", source)
           for i, source in enumerate(INPUTS) for ext in (".msh", ".vtu")
           for command in ("smooth", "convert")] + \
          [("adapt", "adapt.msh", "{tmp}/square-midpoint.msh")]


@pytest.fixture(scope="module")
def written(module_tmp):
    """Every file of WRITTEN written by neomesh in a directory: that directory."""
    def out(name):
        return os.path.join(module_tmp, name)
    for case, level in GENERATED:
        for ext in (".msh", ".vtu"):
            neomesh("generate", case, "--level", level, "-o", out(f"{case}{ext}"))
    for i, source in enumerate(INPUTS):
        source = source.format(tmp=module_tmp)
        for ext in (".msh", ".vtu"):
            neomesh("smooth", source, "-o", out(f"smooth-{i}{ext}"), "--quiet")
            neomesh("convert", source, "-o", out(f"convert-{i}{ext}"))
    neomesh("adapt", out("square-midpoint.msh"), "-o", out("adapt.msh"), "--circle",
            "0.5,0.5,0.25", "--quiet", "--max-iter", "5")
    return module_tmp


@pytest.mark.parametrize("command, name, source", WRITTEN,
                         ids=[f"{c} -> {n}" for c, n, _ in WRITTEN])
def test_meshio_and_gmsh_read_it(written, command, name, source):
    path, source = os.path.join(written, name), source.format(tmp=written)
    try:
        count, mesh = cells_of(path)
    except Exception as e:  # meshio's own exception types vary by version
        pytest.fail(f"{command} -> {name}: meshio cannot read it: {e}")
    if source.endswith(".msh") and os.path.exists(source):
        expected, _ = cells_of(source)
        assert count == expected, f"{command} -> {name}: {count} cells, the input has {expected}"
    if path.endswith(".msh") and "gmsh:physical" in mesh.cell_data:
        assert len(mesh.cell_data["gmsh:physical"]) == len(mesh.cells), \
            f"{command} -> {name}: physical groups on some blocks only"
    gmsh = shutil.which("gmsh")
    if gmsh and path.endswith(".msh"):
        again = path + ".again.msh"
        proc = subprocess.run([gmsh, "-0", path, "-format", "msh41", "-o", again],
                              capture_output=True, text=True, timeout=120)
        assert proc.returncode == 0 and "Error" not in proc.stdout + proc.stderr, \
            f"{command} -> {name}: gmsh: {proc.stdout[-500:]}"
        count_again, _ = cells_of(again)
        assert count_again == count, \
            f"{command} -> {name}: Gmsh keeps {count_again} of {count} cells"
    print(f"{command:9} {name:24} {count} cells, read by meshio{' and Gmsh' if gmsh else ''}")
