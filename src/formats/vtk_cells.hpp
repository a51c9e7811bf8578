// The cells of VTK files, legacy (.vtk) and XML (.vtu): VTK's cell types, and the cells as a
// file lists them (VTK type and points of each) turned into an InputMesh.
//
// Cells: triangles, quadrilaterals (and pixels), tetrahedra, hexahedra (and voxels), wedges and
// pyramids; polygons of 3 and 4 vertices are triangles and quadrilaterals. The cells are the
// elements of the highest dimension, as for Gmsh files. Elements of one dimension lower
// (lines in 2D; triangles, quadrilaterals in 3D) with a positive physical tag are the facets of
// facet groups (as neomesh and meshio write Gmsh's boundary groups); other lower-dimensional
// elements are skipped (vertex elements too, as Gmsh's point elements are). Cells keep their file
// order, vertices are the points some cell uses, in file order. A 2D mesh gets coordinates in its
// plane (plane_embedding.hpp).
//
// Second-order cells (VTK's quadratic cells 22-29 and its Lagrange cells of order 2, 69-72, of
// the types of curved_type.hpp) make a curved mesh (InputMesh::high_order): their corners are
// the vertices, their other points its high-order nodes, in file order; quadratic facets of
// groups keep their corners.
//
// Point and cell data follow the vertices and cells (the data of skipped points and elements is
// dropped; a curved mesh's point data is not kept). Group names come as meshio writes Gmsh's: a
// field data array per group, named by the group, holding its tag and dimension.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "mesh/input_mesh.hpp"

namespace neomesh {

// The cell types of VTK (vtkCellType.h) neomesh reads or names in an error. `vertices` is -1
// for cells of any number of vertices; pixels and voxels list their vertices in tensor order,
// which is neomesh's canonical order.
struct VtkType {
  int vtk;
  int dim;  // -1: an empty cell
  int order;
  int vertices;
  std::optional<CellType> cell;
  const char* name;
};
inline constexpr int kPixel = 8, kVoxel = 11, kPolyVertex = 2, kPolyLine = 4, kStrip = 6,
                     kPolygon = 7;
// The type of VTK number `vtk`, or null for a number VTK does not define.
const VtkType* vtk_type(long long vtk);

// The cells as the file lists them: VTK type and points of each.
struct VtkCells {
  std::vector<double> xyz;  // 3 per point
  std::vector<int> types;   // per cell, a number vtk_type() knows
  std::vector<std::int64_t> offsets = {0};
  std::vector<std::int64_t> points;  // of each cell, in VTK order, each < xyz.size() / 3
  // Per cell: its physical group (> 0), or 0; empty when the file gives none.
  std::vector<int> tags;
  // Per point and per cell of the file.
  std::vector<DataArray> point_data;
  std::vector<DataArray> cell_data;
  // Group names (from field data): name, tag and dimension.
  std::vector<PhysicalGroup> names;
  // The file's version predates VTK 9.1's order of Lagrange hexahedra (curved_type.hpp).
  bool old_lagrange_hexahedra = false;
};

// A name from field data that names a group: an array of two integers, tag (> 0) and
// dimension (0..3). Returns false for any other array.
bool group_name_array(const std::vector<double>& values, PhysicalGroup& group);

// The mesh of the cells of the highest dimension. Throws Error naming `file` unless they are
// 2D or 3D cells neomesh reads (second-order cells of other types, cells of both orders,
// polyhedra, polygons of more than 4 vertices, 1D cells only) or if a cell repeats a vertex. The
// positive tags of the cells become cell groups, those of facets facet groups, named by `names`
// where they match. Throws Error if a facet of a group is not on the mesh's vertices.
InputMesh input_from_vtk_cells(const VtkCells& cells, const std::string& file);

}  // namespace neomesh
