// Reading VTK legacy files (.vtk, "# vtk DataFile Version 2.0 ... 5.1", ASCII and BINARY) on one
// process into an InputMesh:
//
//   DATASET UNSTRUCTURED_GRID   POINTS, then CELLS n size (each cell "k i0 .. ik-1") or the
//                               5.1 layout (CELLS with OFFSETS and CONNECTIVITY), CELL_TYPES
//   DATASET POLYDATA            POINTS, then POLYGONS of 3 or 4 vertices (VERTICES and LINES
//                               are skipped)
//
// Cells as vtk_cells.hpp says. The cell scalars "physical" (or "gmsh:physical"), as neomesh
// and meshio write them, are the elements' physical groups. The other POINT_DATA and CELL_DATA
// attributes (SCALARS, VECTORS, NORMALS, TENSORS, TENSORS6, GLOBAL_IDS, PEDIGREE_IDS) and FIELD
// arrays of as many tuples are point and cell data, named as the file names them ("%20" and
// the like decoded); bit arrays, COLOR_SCALARS, LOOKUP_TABLE, TEXTURE_COORDINATES and METADATA
// are skipped. The dataset's FIELD arrays of two integers name groups (vtk_cells.hpp).
//
// Binary files are big-endian (as VTK writes them). Errors name the line (ASCII) or the byte
// offset (binary) where the file stops making sense.
#pragma once

#include <filesystem>

#include "mesh/input_mesh.hpp"

namespace neomesh {

// Not collective (call it on rank 0). Throws Error naming the file for anything that is not a
// valid VTK legacy file or that neomesh cannot use (structured grids, second-order cells,
// polygons of more than 4 vertices, 1D cells only).
InputMesh read_vtk(const std::filesystem::path& path);

}  // namespace neomesh
