// Reading VTK XML unstructured grids (.vtu) and their parallel form (.pvtu) on one process into
// an InputMesh.
//
// .vtu: <VTKFile type="UnstructuredGrid"> with one or more <Piece>s, each with <Points> and
// <Cells> (DataArrays "connectivity", "offsets", "types"). Every encoding VTK writes is read:
// format="ascii", "binary" (base64 inside the tag) and "appended" (in <AppendedData>,
// encoding="raw" or "base64"); uncompressed or compressed with vtkZLibDataCompressor;
// header_type UInt32 (the default) or UInt64; byte_order LittleEndian or BigEndian. Points
// are Float32 or Float64, the cell arrays of any integer type.
//
// Cells as vtk_cells.hpp says. The cell data "physical" (as neomesh writes it) or
// "gmsh:physical" (as meshio converts Gmsh's groups) gives the elements' groups; cells whose
// "vtkGhostType" marks them duplicates of another piece's are skipped. The other numeric point
// and cell data arrays are the mesh's point and cell data (String arrays are skipped); in a
// file of several pieces, the arrays that every piece has. The grid's <FieldData> arrays of two
// integers name groups (vtk_cells.hpp).
//
// .pvtu: <VTKFile type="PUnstructuredGrid"> whose <Piece Source="..."> name .vtu files
// (relative to the .pvtu's folder). The pieces, like the pieces of one .vtu, are read in order
// and concatenated into one mesh. A point that several pieces share is one vertex: pieces that
// all carry global point ids (the point data named by <PointData GlobalIds="...">) are joined
// by id, others where their points coincide exactly (the same three coordinates, as a
// partitioned mesh's pieces repeat their shared points). Points coinciding within one piece
// stay apart.
#pragma once

#include <filesystem>

#include "mesh/input_mesh.hpp"

namespace neomesh {

// Not collective (call it on rank 0). Throws Error naming the file for anything that is not a
// valid VTK XML file or that neomesh cannot use (structured grids, polydata, polyhedra,
// second-order cells, compressors other than zlib, 1D cells only).
InputMesh read_vtu(const std::filesystem::path& path);

// A .pvtu and the .vtu pieces it names, as above.
InputMesh read_pvtu(const std::filesystem::path& path);

}  // namespace neomesh
