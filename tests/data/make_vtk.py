"""Writes the VTK legacy test meshes tests/data/vtk_*.vtk (also the seeds fuzz/corpus/vtk):
    python3 tests/data/make_vtk.py tests/data && python3 tests/data/make_vtk.py fuzz/corpus/vtk"""
import struct, sys, os
out = sys.argv[1]
from mixed_3d_mesh import P, C

def be(fmt, vals): return struct.pack('>' + fmt * len(vals), *vals)

def write(name, binary, v51):
    b = bytearray()
    def t(s): b.extend(s.encode())
    t("# vtk DataFile Version %s\nneomesh test mesh\n%s\nDATASET UNSTRUCTURED_GRID\n" % ("5.1" if v51 else "3.0", "BINARY" if binary else "ASCII"))
    t("FIELD FieldData 1\nTIME 1 1 double\n")
    b.extend(be('d', [0.5]) + b"\n" if binary else b"0.5\n")
    t("POINTS %d %s\n" % (len(P), "double" if binary else "float"))
    flat = [x for p in P for x in p]
    b.extend(be('d', flat) + b"\n" if binary else ("\n".join(" ".join(repr(float(x)) for x in p) for p in P) + "\n").encode())
    if v51:
        offs = [0]
        for _, c in C: offs.append(offs[-1] + len(c))
        conn = [i for _, c in C for i in c]
        t("CELLS %d %d\nOFFSETS vtktypeint64\n" % (len(offs), len(conn)))
        b.extend(be('q', offs) + b"\n" if binary else (" ".join(map(str, offs)) + "\n").encode())
        t("CONNECTIVITY vtktypeint64\n")
        b.extend(be('q', conn) + b"\n" if binary else (" ".join(map(str, conn)) + "\n").encode())
    else:
        flat = [x for _, c in C for x in [len(c)] + c]
        t("CELLS %d %d\n" % (len(C), len(flat)))
        b.extend(be('i', flat) + b"\n" if binary else ("\n".join(" ".join(map(str, [len(c)] + c)) for _, c in C) + "\n").encode())
    t("CELL_TYPES %d\n" % len(C))
    types = [ty for ty, _ in C]
    b.extend(be('i', types) + b"\n" if binary else ("\n".join(map(str, types)) + "\n").encode())
    n = len(C)
    t("CELL_DATA %d\nSCALARS material int 1\nLOOKUP_TABLE default\n" % n)
    b.extend(be('i', [1] * n) + b"\n" if binary else (" ".join(["1"] * n) + "\n").encode())
    t("FIELD extra 2\nweights 2 %d float\n" % n)
    b.extend(be('f', [0.25] * 2 * n) + b"\n" if binary else (" ".join(["0.25"] * 2 * n) + "\n").encode())
    t("flags 1 %d unsigned_char\n" % n)
    b.extend(bytes([1] * n) + b"\n" if binary else (" ".join(["1"] * n) + "\n").encode())
    if v51:
        t("METADATA\nINFORMATION 0\n\n")
    m = len(P)
    t("POINT_DATA %d\nVECTORS velocity double\n" % m)
    b.extend(be('d', [0.0] * 3 * m) + b"\n" if binary else (" ".join(["0"] * 3 * m) + "\n").encode())
    t("SCALARS fixed int\nLOOKUP_TABLE my_table\n")
    b.extend(be('i', [0] * m) + b"\n" if binary else (" ".join(["0"] * m) + "\n").encode())
    t("LOOKUP_TABLE my_table 2\n")
    b.extend(bytes([0, 0, 0, 255, 255, 255, 255, 255]) + b"\n" if binary else b"0 0 0 1 1 1 1 1\n")
    t("NORMALS n float\n")
    b.extend(be('f', [0.0] * 3 * m) + b"\n" if binary else (" ".join(["0"] * 3 * m) + "\n").encode())
    open(os.path.join(out, name), "wb").write(bytes(b))

write("vtk_mixed_3d.vtk", False, False)
write("vtk_mixed_3d_bin.vtk", True, False)
write("vtk_mixed_3d_v51.vtk", False, True)
write("vtk_mixed_3d_v51_bin.vtk", True, True)

# POLYDATA: the unit square as two triangles and a quadrilateral, with its boundary as LINES.
open(os.path.join(out, "vtk_square_polydata.vtk"), "w").write("""# vtk DataFile Version 2.0
square of polygons
ASCII
DATASET POLYDATA
POINTS 6 float
0 0 0  0.5 0 0  1 0 0
0 1 0  0.5 1 0  1 1 0
VERTICES 1 2
1 0
LINES 2 6
2 0 1
2 1 2
POLYGONS 3 13
3 0 1 3
3 1 4 3
4 1 2 5 4
CELL_DATA 6
SCALARS id int 1
LOOKUP_TABLE default
0 1 2 3 4 5
""")

# Triangles in the plane through (0, 0, 1) with normal (0, 0.6, 0.8): (u, v) -> (u, 0.8 v, 1 - 0.6 v).
uv = [(0,0),(1,0),(2,0),(0,1),(1,1),(2,1)]
pts = "\n".join("%r %r %r" % (float(u), 0.8 * v, 1 - 0.6 * v) for u, v in uv)
open(os.path.join(out, "vtk_tilted_tri.vtk"), "w").write("""# vtk DataFile Version 3.0
tilted triangles
ASCII
DATASET UNSTRUCTURED_GRID
POINTS 6 double
%s
CELLS 4 16
3 0 1 4
3 0 4 3
3 1 2 5
3 1 5 4
CELL_TYPES 4
5 5 5 5
""" % pts)
