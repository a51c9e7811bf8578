"""Writes the VTK XML test meshes tests/data/vtu_*.vtu and .pvtu (also the seeds fuzz/corpus/vtu):
    python3 tests/data/make_vtu.py tests/data && python3 tests/data/make_vtu.py fuzz/corpus/vtu
The mesh is make_vtk.py's: a hexahedron, a vertex, a wedge, a line, a pyramid and a
tetrahedron, an unused point, in every encoding VTK writes (each file says its encoding in its
name). Written by hand (struct, base64, zlib) so that each layout is exactly the one named."""
import base64, os, struct, sys, zlib
out = sys.argv[1]
from mixed_3d_mesh import P, C
OFFS, CONN, TYPES = [], [i for _, c in C for i in c], [t for t, _ in C]
for _, c in C: OFFS.append((OFFS[-1] if OFFS else 0) + len(c))
PHYSICAL = [7, 0, 7, 0, 8, 7]


def arrays(point_type, index_type):
    """(attributes, struct code, values) of each DataArray, in file order."""
    f = {"Float32": "f", "Float64": "d"}[point_type]
    i = {"Int32": "i", "Int64": "q", "UInt32": "I", "UInt64": "Q"}[index_type]
    return [('Name="physical" type="Int32"', "i", PHYSICAL),
            ('type="%s" NumberOfComponents="3"' % point_type, f, [x for p in P for x in p]),
            ('Name="connectivity" type="%s"' % index_type, i, CONN),
            ('Name="offsets" type="%s"' % index_type, i, OFFS),
            ('Name="types" type="UInt8"', "B", TYPES)]


def block(code, values, endian, header, compressed):
    """An array's bytes with its header: the byte count, or zlib blocks of 64 bytes."""
    data = struct.pack(endian + code * len(values), *values)
    h = {"UInt32": "I", "UInt64": "Q"}[header]
    if not compressed:
        return struct.pack(endian + h, len(data)), data
    pieces = [zlib.compress(data[k:k + 64]) for k in range(0, len(data), 64)]
    last = len(data) % 64
    head = struct.pack(endian + h * (3 + len(pieces)), len(pieces), 64, last, *map(len, pieces))
    return head, b"".join(pieces)


def write(name, form, point_type="Float64", index_type="Int64", header="UInt64",
          endian="<", compressed=False):
    order = "LittleEndian" if endian == "<" else "BigEndian"
    attributes = 'byte_order="%s" header_type="%s"' % (order, header)
    if compressed:
        attributes += ' compressor="vtkZLibDataCompressor"'
    tags, appended = [], b""
    for attrs, code, values in arrays(point_type, index_type):
        if form == "ascii":
            tags.append('<DataArray %s format="ascii">\n%s\n</DataArray>' %
                        (attrs, " ".join(map(repr if code in "fd" else str, values))))
            continue
        head, data = block(code, values, endian, header, compressed)
        if form == "binary":  # VTK encodes header and data separately
            text = (base64.b64encode(head) + base64.b64encode(data)).decode()
            tags.append('<DataArray %s format="binary">\n%s\n</DataArray>' % (attrs, text))
            continue
        chunk = head + data if form == "raw" else base64.b64encode(head) + base64.b64encode(data)
        tags.append('<DataArray %s format="appended" offset="%d"/>' % (attrs, len(appended)))
        appended += chunk
    text = ('<?xml version="1.0"?>\n<VTKFile type="UnstructuredGrid" version="1.0" %s>\n'
            '<UnstructuredGrid>\n<Piece NumberOfPoints="%d" NumberOfCells="%d">\n'
            '<PointData>\n</PointData>\n<CellData>\n%s\n</CellData>\n<Points>\n%s\n</Points>\n'
            '<Cells>\n%s\n</Cells>\n</Piece>\n</UnstructuredGrid>\n'
            % (attributes, len(P), len(C), tags[0], tags[1], "\n".join(tags[2:]))).encode()
    if form in ("raw", "base64"):
        text += b'<AppendedData encoding="%s">\n_' % form.encode() + appended + b"\n</AppendedData>\n"
    open(os.path.join(out, name), "wb").write(text + b"</VTKFile>\n")


write("vtu_mixed_3d_ascii.vtu", "ascii", "Float32", "Int32", "UInt32")
write("vtu_mixed_3d_binary.vtu", "binary", "Float64", "Int64", "UInt32")
write("vtu_mixed_3d_binary_zlib.vtu", "binary", "Float32", "UInt32", "UInt32", compressed=True)
write("vtu_mixed_3d_raw.vtu", "raw", "Float64", "Int64", "UInt64")
write("vtu_mixed_3d_raw_zlib_bigendian.vtu", "raw", "Float64", "Int32", "UInt64", ">", True)
write("vtu_mixed_3d_base64.vtu", "base64", "Float32", "UInt64", "UInt32")
write("vtu_mixed_3d_base64_zlib.vtu", "base64", "Float64", "Int64", "UInt64", compressed=True)

# Two pieces of the unit square's four triangles (each piece repeats the points of the shared
# edge x = 0.5), as .pvtu: without global ids (joined where points coincide) and with them.
SQUARE = {0: [(0,0,0),(0.5,0,0),(0.5,1,0),(0,1,0)], 1: [(0.5,0,0),(1,0,0),(1,1,0),(0.5,1,0)]}
IDS = {0: [0, 1, 4, 3], 1: [1, 2, 5, 4]}
for ids in (False, True):
    stem = "vtu_square_pieces" + ("_ids" if ids else "")
    for k in (0, 1):
        pd = ('<PointData GlobalIds="GlobalNodeId">\n<DataArray Name="GlobalNodeId" type="Int64" '
              'format="ascii">%s</DataArray>\n</PointData>' % " ".join(map(str, IDS[k]))) \
            if ids else "<PointData/>"
        pts = " ".join(repr(float(x)) for p in SQUARE[k] for x in p)
        open(os.path.join(out, "%s_%d.vtu" % (stem, k)), "w").write(
            '<?xml version="1.0"?>\n<VTKFile type="UnstructuredGrid" version="0.1">\n'
            '<UnstructuredGrid>\n<Piece NumberOfPoints="4" NumberOfCells="2">\n%s\n'
            '<Points><DataArray type="Float64" NumberOfComponents="3" format="ascii">%s'
            '</DataArray></Points>\n<Cells>\n'
            '<DataArray Name="connectivity" type="Int32" format="ascii">0 1 2 0 2 3</DataArray>\n'
            '<DataArray Name="offsets" type="Int32" format="ascii">3 6</DataArray>\n'
            '<DataArray Name="types" type="UInt8" format="ascii">5 5</DataArray>\n'
            '</Cells>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n' % (pd, pts))
    open(os.path.join(out, stem + ".pvtu"), "w").write(
        '<?xml version="1.0"?>\n<VTKFile type="PUnstructuredGrid" version="0.1">\n'
        '<PUnstructuredGrid GhostLevel="0">\n<PPoints><PDataArray type="Float64" '
        'NumberOfComponents="3"/></PPoints>\n<Piece Source="%s_0.vtu"/>\n'
        '<Piece Source="%s_1.vtu"/>\n</PUnstructuredGrid>\n</VTKFile>\n' % (stem, stem))
