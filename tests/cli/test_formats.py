"""VTK XML (.vtu, .pvtu), Medit (.mesh) and Exodus II (.exo) files as users bring them: written by meshio (an
independent writer) they read as the mesh meshio wrote, and neomesh's own outputs read back
unchanged (read -> write -> read: the same coordinates, cells and groups). Run with
NEOMESH=path/to/neomesh."""
import os

import numpy as np
import pytest

from conftest import DATA, RANKS, expect_one_error_line, neomesh, read_mesh, run

meshio = pytest.importorskip("meshio", reason="python3-meshio is not installed")

TOP = {"triangle": 2, "quad": 2, "tetra": 3, "hexahedron": 3, "wedge": 3, "pyramid": 3}


def cells(mesh):
    """The cells (elements of the highest dimension) of a meshio mesh: {type: array}, and the
    cell blocks' physical groups (Gmsh's, or Medit's references) in their order, or None."""
    dim = max(TOP.get(b.type, 0) for b in mesh.cells)
    out, groups = {}, []
    tags = mesh.cell_data.get("gmsh:physical") or mesh.cell_data.get("medit:ref")
    for k, block in enumerate(mesh.cells):
        if TOP.get(block.type, 0) != dim:
            continue
        out[block.type] = np.concatenate([out[block.type], block.data]) \
            if block.type in out else block.data
        if tags is not None:
            groups.extend(tags[k].tolist())
    return out, groups if tags is not None else None


def facet_groups(mesh):
    """Sorted (group, sorted vertices) of the boundary facets of a .msh's physical groups."""
    dim = max(TOP.get(b.type, 0) for b in mesh.cells)
    tags = mesh.cell_data.get("gmsh:physical", [])
    facet_types = {2: ("line",), 3: ("triangle", "quad")}[dim]
    return sorted((int(t), tuple(sorted(f))) for k, b in enumerate(mesh.cells)
                  if b.type in facet_types for f, t in zip(b.data.tolist(), tags[k]))


def expect_same(a, b, groups=True, atol=0.0):
    assert np.allclose(a.points[:, :2], b.points[:, :2], rtol=0, atol=atol)
    ca, ga = cells(a)
    cb, gb = cells(b)
    assert ca.keys() == cb.keys()
    for t in ca:
        assert np.array_equal(ca[t], cb[t]), t
    if groups:
        assert ga == gb


def generated(tmp, case, level):
    """A generated, jittered mesh as meshio reads it: its cells only."""
    msh = os.path.join(tmp, case + ".msh")
    neomesh("generate", case, "--level", level, "--jitter", "0.2", "-o", msh)
    m = read_mesh(msh)
    top, _ = cells(m)
    return meshio.Mesh(m.points, list(top.items()))


def convert(tmp, source, name):
    out = os.path.join(tmp, name)
    neomesh("convert", source, "-o", out)
    return out


CASES = [("box-tri", "2"), ("box-quad", "2"), ("box-tet", "1"), ("box-hex", "1"),
         ("box-wedge", "1")]
VTU_ENCODINGS = {"ascii": dict(binary=False), "base64": dict(binary=True, compression=None),
                 "zlib": dict(binary=True, compression="zlib"),
                 "zlib-uint64": dict(binary=True, compression="zlib", header_type="UInt64")}


@pytest.mark.parametrize("encoding", VTU_ENCODINGS)
@pytest.mark.parametrize("case, level", CASES)
def test_a_vtu_written_by_meshio_reads_as_meshio_wrote_it(tmp, case, level, encoding):
    mesh = generated(tmp, case, level)
    vtu = os.path.join(tmp, "in.vtu")
    meshio.write(vtu, mesh, file_format="vtu", **VTU_ENCODINGS[encoding])
    # meshio writes ASCII coordinates with 12 digits.
    atol = 1e-10 if encoding == "ascii" else 0.0
    expect_same(read_mesh(convert(tmp, vtu, "out.msh")), mesh, groups=False, atol=atol)


@pytest.mark.parametrize("source", ["mixed_tri_quad_v41.msh", "cube_hex_v41.msh",
                                    "prism_v41.msh"])
@pytest.mark.parametrize("ext", [".vtu", ".vtk", ".mesh", ".exo"])
def test_neomesh_reads_its_own_output_back(tmp, source, ext):
    """.msh -> ext -> .msh keeps coordinates, cells, cell groups and facet groups of the .msh ->
    .msh conversion, and (but Medit, which has no names) the groups' names."""
    direct = read_mesh(convert(tmp, os.path.join(DATA, source), "direct.msh"))
    middle = convert(tmp, os.path.join(DATA, source), "middle" + ext)
    again = read_mesh(convert(tmp, middle, "again.msh"))
    expect_same(again, direct)
    assert facet_groups(again) == facet_groups(direct)
    if ext != ".mesh":
        names = {k: v.tolist() for k, v in direct.field_data.items()}
        assert {k: v.tolist() for k, v in again.field_data.items()} == names


@pytest.mark.parametrize("ranks", RANKS)
@pytest.mark.parametrize("ext", [".vtu", ".vtk", ".mesh", ".exo"])
def test_a_smoothed_file_smooths_again_as_its_msh_twin(tmp, ext, ranks):
    """`neomesh smooth out.vtu -o again.vtu`: the output of a run is an input, the same mesh
    as the .msh the run writes (coordinates to the last bit)."""
    source = os.path.join(tmp, "box.msh")
    neomesh("generate", "box-tri", "--level", "2", "--jitter", "0.2", "-o", source)
    first = {e: os.path.join(tmp, "out" + e) for e in (ext, ".msh")}
    again = {e: os.path.join(tmp, "again" + e) for e in (ext, ".msh")}
    for e in first:
        neomesh("smooth", source, "-o", first[e], "--quiet", ranks=ranks)
        neomesh("smooth", first[e], "-o", again[e], "--quiet", ranks=ranks)
    a, b = read_mesh(again[ext]), read_mesh(again[".msh"])
    assert np.array_equal(a.points[:, :2], b.points[:, :2])


@pytest.mark.parametrize("ext", [".mesh", ".exo"])
def test_the_facet_groups_of_a_generated_mesh_survive_medit_and_exodus(tmp, ext):
    """Exodus keeps the groups' names too, as block and side set names."""
    source = os.path.join(tmp, "square.msh")
    neomesh("generate", "square-midpoint", "--level", "2", "-o", source)
    direct = read_mesh(convert(tmp, source, "direct.msh"))
    again = read_mesh(convert(tmp, convert(tmp, source, "middle" + ext), "again.msh"))
    expect_same(again, direct)
    assert facet_groups(again) == facet_groups(direct) != []
    if ext == ".exo":
        assert again.field_data.keys() == direct.field_data.keys()


@pytest.mark.parametrize("case, level", CASES[:4])
def test_a_medit_file_written_by_meshio_keeps_its_references(tmp, case, level):
    mesh = generated(tmp, case, level)
    refs = [np.where(np.arange(len(b.data)) < len(b.data) // 2, 1, 2) for b in mesh.cells]
    mesh.cell_data["medit:ref"] = refs
    path = os.path.join(tmp, "in.mesh")
    meshio.write(path, mesh, file_format="medit")
    out = read_mesh(convert(tmp, path, "out.msh"))
    expect_same(out, mesh)


def test_the_pieces_of_a_pvtu_make_the_whole_mesh(tmp):
    """Two .vtu pieces written by meshio, each with its own copy of the points they share, read
    as the mesh they were cut from (coinciding points joined)."""
    whole = generated(tmp, "box-tri", "2")
    triangles = whole.cells[0].data
    half = len(triangles) // 2
    sources = []
    for k, part in enumerate((triangles[:half], triangles[half:])):
        used = np.unique(part)
        renumber = np.full(len(whole.points), -1)
        renumber[used] = np.arange(len(used))
        name = f"piece_{k}.vtu"
        meshio.write(os.path.join(tmp, name),
                     meshio.Mesh(whole.points[used], [("triangle", renumber[part])]))
        sources.append(f'<Piece Source="{name}"/>')
    pvtu = os.path.join(tmp, "whole.pvtu")
    open(pvtu, "w").write(
        '<?xml version="1.0"?>\n<VTKFile type="PUnstructuredGrid" version="1.0">\n'
        '<PUnstructuredGrid GhostLevel="0">\n<PPoints><PDataArray type="Float64" '
        'NumberOfComponents="3"/></PPoints>\n' + "\n".join(sources) +
        "\n</PUnstructuredGrid>\n</VTKFile>\n")
    out = read_mesh(convert(tmp, pvtu, "out.msh"))
    assert len(out.points) == len(whole.points)
    assert sum(len(b.data) for b in out.cells if b.type == "triangle") == len(triangles)
    key = lambda p: sorted(map(tuple, np.round(p[:, :2], 12)))
    assert key(out.points) == key(whole.points)
    report = neomesh("quality", pvtu).stdout
    assert "inverted cells: 0" in report


def test_what_cannot_be_read_is_refused_in_one_line(tmp):
    lz4 = os.path.join(tmp, "lz4.vtu")
    open(lz4, "w").write('<VTKFile type="UnstructuredGrid" compressor="vtkLZ4DataCompressor">'
                         '<UnstructuredGrid/></VTKFile>')
    image = os.path.join(tmp, "image.vtu")
    open(image, "w").write('<VTKFile type="ImageData"><ImageData/></VTKFile>')
    quadratic = os.path.join(tmp, "q2.mesh")  # (Medit files agree on no order of these)
    open(quadratic, "w").write("MeshVersionFormatted 2\nDimension 3\nHexahedraQ2\n0\nEnd\n")
    for path, words in [(lz4, ["lz4.vtu", "vtkLZ4DataCompressor"]),
                        (image, ["image.vtu", "structured grid"]),
                        (quadratic, ["q2.mesh", "HexahedraQ2", "node order"])]:
        expect_one_error_line(neomesh("smooth", path, "-o", os.path.join(tmp, "o.mesh"),
                                      expect=1), words, [os.path.join(tmp, "o.mesh")])


@pytest.mark.skipif(os.environ.get("NEOMESH_CGNS") != "0", reason="neomesh is built with CGNS")
def test_without_cgns_a_cgns_file_is_refused_in_one_line(tmp):
    """A build with -DNEOMESH_CGNS=OFF refuses .cgns (read and write) in one line, no file."""
    out = os.path.join(tmp, "never.cgns")
    proc = neomesh("convert", os.path.join(DATA, "square_quad_v41.msh"), "-o", out, expect=None)
    expect_one_error_line(proc, ["never.cgns", "without CGNS"], [out])
    fake = os.path.join(tmp, "in.cgns")
    with open(fake, "w") as f:
        f.write("HDF5 or not, this build does not look\n")
    proc = neomesh("quality", fake, expect=None)
    expect_one_error_line(proc, ["in.cgns", "without CGNS"])


@pytest.mark.parametrize("ext", [".vtu", ".vtk", ".mesh", ".exo", ".cgns"])
def test_smoothing_a_mixed_3d_mesh_keeps_its_groups_in_every_format(tmp, ext):
    """Hexahedra beside wedges with named boundary groups (tests/data/mixed_hex_wedge.geo, by
    Gmsh): `smooth in.EXT -o out.EXT` gives back the same cells, and the same facets in each
    group (Medit has no group names: there, the same facets per reference)."""
    msh = os.path.join(tmp, "mixed.msh")
    run(["gmsh", "-3", os.path.join(DATA, "mixed_hex_wedge.geo"), "-format", "msh41", "-o", msh])
    source = convert(tmp, msh, "in" + ext)
    out = os.path.join(tmp, "out" + ext)
    neomesh("smooth", source, "-o", out, "--quiet")
    before, after = read_mesh(convert(tmp, source, "before.msh")), \
        read_mesh(convert(tmp, out, "after.msh"))
    assert not np.allclose(before.points, after.points)  # it smoothed
    expect_same(before, after, atol=np.inf)
    assert set(cells(after)[0]) == {"hexahedron", "wedge"}
    assert facet_groups(after) == facet_groups(before) != []
    if ext != ".mesh":
        assert set(after.field_data) == set(before.field_data) == \
            {"fluid", "bottom", "top", "inlet", "outlet"}
