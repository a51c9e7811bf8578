"""CGNS files (.cgns) as users bring them: written by another program (CGNS' own
tetgen_to_cgns, from the cgns-convert tools) they read as the mesh it wrote, with its boundary
sections as facet groups; neomesh's own .cgns reads back unchanged (read -> write -> read: the
same coordinates, cells, cell groups and facet groups, MIXED sections included), and a run on a
.cgns changes nothing but the coordinates. Run with NEOMESH=path/to/neomesh."""
import ctypes
import ctypes.util
import os
import re
import shutil

import numpy as np
import pytest

from conftest import (DATA, RANKS, expect_nothing_else_changed, expect_one_error_line, neomesh,
                      read_mesh, run)
from test_formats import cells, convert, expect_same, facet_groups, generated

meshio = pytest.importorskip("meshio", reason="python3-meshio is not installed")
pytestmark = pytest.mark.skipif(os.environ.get("NEOMESH_CGNS") == "0",
                                reason="neomesh is built without CGNS (cmake -DNEOMESH_CGNS=OFF)")
TETGEN_TO_CGNS = shutil.which("tetgen_to_cgns")


def cgns_library():
    """The CGNS library's C API (ctypes) and its cgsize_t: meshio and h5py write one zone only."""
    name = ctypes.util.find_library("cgns")
    if name is None:
        pytest.skip("the CGNS library (libcgns) is not installed")
    header = "/usr/include/cgnstypes.h"
    text = open(header).read() if os.path.exists(header) else ""
    wide = re.search(r"#define CG_BUILD_64BIT\s+1", text) and \
        not re.search(r"#define CG_BUILD_LEGACY\s+1", text)
    return ctypes.CDLL(name), ctypes.c_long if wide else ctypes.c_int


def write_zones(path, points, zones, connected):
    """A 3D .cgns file of one unstructured zone per entry of `zones` (lists of hexahedra,
    Gmsh's node order = CGNS'), each with its own 1-based node numbering of the `points` its
    hexahedra use and its hexahedra in a section "fluid", as Pointwise writes a block per zone.
    With `connected`, each zone names the nodes it shares with each other zone by a 1-to-1
    connectivity; without, only their coordinates are equal."""
    lib, cgsize = cgns_library()
    unstructured, real_double, integer, hexa_8 = 3, 4, 2, 17
    vertex, abutting_1to1, point_list, point_list_donor = 2, 4, 2, 3

    lib.cg_get_error.restype = ctypes.c_char_p

    def ok(status):
        assert status == 0, lib.cg_get_error().decode()

    def array(ctype, values):
        return (ctype * len(values))(*values)

    nodes = [sorted({int(v) for h in hexes for v in h}) for hexes in zones]
    local = [{v: i + 1 for i, v in enumerate(n)} for n in nodes]
    f, base, zone, index = ctypes.c_int(), ctypes.c_int(), ctypes.c_int(), ctypes.c_int()
    ok(lib.cg_open(path.encode(), 1, ctypes.byref(f)))
    ok(lib.cg_base_write(f, b"Base", 3, 3, ctypes.byref(base)))
    for z, hexes in enumerate(zones):
        size = array(cgsize, [len(nodes[z]), len(hexes), 0])
        ok(lib.cg_zone_write(f, base, f"block-{z + 1}".encode(), size, unstructured,
                             ctypes.byref(zone)))
        for d, axis in enumerate("XYZ"):
            coordinates = array(ctypes.c_double, [float(points[v][d]) for v in nodes[z]])
            ok(lib.cg_coord_write(f, base, zone, real_double, f"Coordinate{axis}".encode(),
                                  coordinates, ctypes.byref(index)))
        connectivity = array(cgsize, [local[z][int(v)] for h in hexes for v in h])
        ok(lib.cg_section_write(f, base, zone, b"fluid", hexa_8, cgsize(1), cgsize(len(hexes)),
                                0, connectivity, ctypes.byref(index)))
        for other in range(len(zones)):
            shared = sorted(set(nodes[z]) & set(nodes[other])) if other != z else []
            if connected and shared:
                ok(lib.cg_conn_write(
                    f, base, zone, f"to block-{other + 1}".encode(), vertex, abutting_1to1,
                    point_list, cgsize(len(shared)), array(cgsize, [local[z][v] for v in shared]),
                    f"block-{other + 1}".encode(), unstructured, point_list_donor, integer,
                    cgsize(len(shared)), array(cgsize, [local[other][v] for v in shared]),
                    ctypes.byref(index)))
    ok(lib.cg_close(f))
    return path


def two_blocks(tmp, connected):
    """A jittered box of hexahedra cut at x = 0 into two zones: the .cgns and the box."""
    source = os.path.join(tmp, "box.msh")
    neomesh("generate", "box-hex", "--level", "1", "--jitter", "0.2", "-o", source)
    box = read_mesh(source)
    hexes = next(b.data for b in box.cells if b.type == "hexahedron")
    left = box.points[hexes].mean(axis=1)[:, 0] < 0
    path = os.path.join(tmp, "blocks.cgns")
    return write_zones(path, box.points, [hexes[left], hexes[~left]], connected), box


def expect_same_groups(a, b):
    """The same cells and the same groups of cells and facets, up to the groups' numbers: CGNS
    names sections and BCs, it does not number them."""
    expect_same(a, b, groups=False)
    assert first_seen(cells(a)[1]) == first_seen(cells(b)[1])
    assert facet_sets(a) == facet_sets(b)


def first_seen(tags):
    """Each cell's group as the place of its tag among the tags in the order they first come."""
    order = list(dict.fromkeys(tags))
    return [order.index(t) for t in tags]


def facet_sets(mesh):
    """The facet groups, each as its sorted facets, sorted."""
    groups = facet_groups(mesh)
    return sorted(sorted(f for t, f in groups if t == tag) for tag in {t for t, _ in groups})


@pytest.mark.parametrize("source", ["mixed_tri_quad_v41.msh", "cube_hex_v41.msh",
                                    "prism_v41.msh", "cube_tet_v41.msh"])
def test_neomesh_reads_its_own_cgns_back(tmp, source):
    direct = read_mesh(convert(tmp, os.path.join(DATA, source), "direct.msh"))
    middle = convert(tmp, os.path.join(DATA, source), "middle.cgns")
    expect_same_groups(read_mesh(convert(tmp, middle, "again.msh")), direct)


def test_group_names_survive_cgns_as_section_and_bc_names(tmp):
    source = os.path.join(tmp, "square.msh")
    neomesh("generate", "square-midpoint", "--level", "2", "-o", source)
    direct = read_mesh(convert(tmp, source, "direct.msh"))
    again = read_mesh(convert(tmp, convert(tmp, source, "middle.cgns"), "again.msh"))
    expect_same_groups(again, direct)
    # (numbered 1, 2, ... in the order of their names, the groups keep their numbers)
    assert facet_groups(again) == facet_groups(direct) != []
    assert again.field_data.keys() == direct.field_data.keys()


def test_a_cell_group_of_several_types_is_one_mixed_section(tmp):
    """mixed_tri_quad_v41.msh's group of triangles and quadrilaterals, through one section."""
    source = os.path.join(tmp, "mixed.msh")
    m = read_mesh(os.path.join(DATA, "mixed_tri_quad_v41.msh"))
    cells = [(b.type, b.data) for b in m.cells if b.type in ("triangle", "quad")]
    meshio.write(source, meshio.Mesh(m.points, cells, cell_data={
        "gmsh:physical": [np.full(len(d), 3) for _, d in cells],
        "gmsh:geometrical": [np.full(len(d), 1) for _, d in cells]}),
        file_format="gmsh22", binary=False)
    direct = read_mesh(convert(tmp, source, "direct.msh"))
    again = read_mesh(convert(tmp, convert(tmp, source, "middle.cgns"), "again.msh"))
    expect_same_groups(again, direct)


@pytest.mark.skipif(TETGEN_TO_CGNS is None, reason="tetgen_to_cgns (cgns-convert) is missing")
def test_a_cgns_file_written_by_tetgen_to_cgns_reads_as_it_wrote_it(tmp):
    """A tetrahedral box as TetGen files (nodes, tetrahedra, the floor's faces with marker 5),
    converted by the CGNS tools: the tetrahedra come out as written and the floor's faces as
    the facet group of their section."""
    mesh = generated(tmp, "box-tet", "1")
    tets = mesh.cells[0].data
    low = mesh.points[:, 2].min()
    floor = [tuple(sorted(f)) for t in tets.tolist()
             for f in ([t[0], t[1], t[2]], [t[0], t[1], t[3]], [t[0], t[2], t[3]],
                       [t[1], t[2], t[3]])
             if all(mesh.points[f, 2] == low)]
    assert floor
    base = os.path.join(tmp, "box")
    with open(base + ".node", "w") as f:
        f.write(f"{len(mesh.points)} 3 0 0\n")
        for i, p in enumerate(mesh.points):
            f.write(f"{i + 1} {p[0]!r} {p[1]!r} {p[2]!r}\n")
    with open(base + ".ele", "w") as f:
        f.write(f"{len(tets)} 4 0\n")
        for i, t in enumerate(tets + 1):
            f.write(f"{i + 1} {' '.join(map(str, t))}\n")
    with open(base + ".face", "w") as f:
        f.write(f"{len(floor)} 1\n")
        for i, face in enumerate(floor):
            f.write(f"{i + 1} {' '.join(str(v + 1) for v in face)} 5\n")
    run([TETGEN_TO_CGNS, base, base + ".cgns"])
    out = read_mesh(convert(tmp, base + ".cgns", "out.msh"))
    expect_same(out, mesh, groups=False, atol=1e-6)  # tetgen_to_cgns writes float32 coordinates
    assert facet_sets(out) == [sorted(floor)]
    # (tetgen_to_cgns names the section of the faces of its only marker "Triangles")
    assert [name for name, (_, dim) in out.field_data.items() if dim == 2] == ["Triangles"]


@pytest.mark.parametrize("ranks", RANKS)
def test_smoothing_a_cgns_file_changes_only_coordinates(tmp, ranks):
    source = os.path.join(tmp, "box.msh")
    neomesh("generate", "box-hex", "--level", "1", "--jitter", "0.2", "-o", source)
    cgns, out = convert(tmp, source, "in.cgns"), os.path.join(tmp, "out.cgns")
    neomesh("smooth", cgns, "-o", out, "--quiet", ranks=ranks)
    before, after = convert(tmp, cgns, "before.msh"), convert(tmp, out, "after.msh")
    expect_nothing_else_changed(before, after)  # (meshio does not read CGNS)
    before, after = read_mesh(before), read_mesh(after)
    assert facet_sets(after) == facet_sets(before) != []
    assert not np.array_equal(after.points, before.points)


@pytest.mark.parametrize("connected", [True, False])
def test_the_zones_of_a_cgns_file_read_as_one_mesh(tmp, connected):
    """Zones joined by their 1-to-1 connectivity, or else where their nodes coincide: the box
    they were cut from, its cells one group (each zone's section "fluid")."""
    path, box = two_blocks(tmp, connected)
    out = read_mesh(convert(tmp, path, "out.msh"))
    assert len(out.points) == len(box.points)
    as_points = lambda m: sorted(tuple(sorted(map(tuple, m.points[c].tolist())))
                                 for b in m.cells if b.type == "hexahedron" for c in b.data)
    assert as_points(out) == as_points(box)
    assert [name for name, (_, dim) in out.field_data.items() if dim == 3] == ["fluid"]


@pytest.mark.parametrize("ranks", RANKS)
def test_smoothing_a_cgns_file_of_several_zones(tmp, ranks):
    """The joined zones smooth as one mesh (written back as one zone), under MPI as on one
    process: the mesh read on two ranks is the mesh read on one."""
    path, _ = two_blocks(tmp, True)
    serial = convert(tmp, path, "serial.msh")
    out = os.path.join(tmp, "out.cgns")
    neomesh("smooth", path, "-o", out, "--quiet", ranks=ranks)
    after = convert(tmp, out, "after.msh")
    expect_nothing_else_changed(serial, after)
    assert not np.array_equal(read_mesh(after).points, read_mesh(serial).points)
    read = os.path.join(tmp, "read.msh")
    neomesh("convert", path, "-o", read, ranks=ranks)
    assert open(read, "rb").read() == open(serial, "rb").read()


def test_what_cannot_be_read_is_refused_in_one_line(tmp):
    garbage = os.path.join(tmp, "garbage.cgns")
    open(garbage, "w").write("not a CGNS file\n")
    out = os.path.join(tmp, "o.cgns")
    expect_one_error_line(neomesh("smooth", garbage, "-o", out, expect=1),
                          ["garbage.cgns", "CGNS"], [out])
