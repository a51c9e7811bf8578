// What makes a surface mesh (2D cells in space, InputMesh::surface) one that no placement of
// its vertices on its own cells can make valid, each found on rank 0 before the mesh is built:
// - an edge shared by more than two cells (a T-junction or a fin: not a surface);
// - two cells across an edge that run along it the same way (they face opposite sides);
// - two cells that share no vertex and cross each other (the surface intersects itself).
// Open boundaries (edges of one cell) and surfaces made of several pieces are fine. Vertex and
// cell numbers in messages are 0-based, in input order (describe_cell adds the file's element
// number).
#pragma once

#include <string>

#include "mesh/input_mesh.hpp"

namespace neomesh {

// The first edge shared by more than two cells, or the first pair of cells that run along their
// common edge the same way, as a sentence; or "". Edges are taken in order of their vertices.
std::string find_surface_edge_defect(const InputMesh& mesh);

// The first pair of cells (in order of the first, then the second) that share no vertex and
// cross, as a sentence; or "". Quadrilaterals are split into two triangles along the diagonal
// from their first vertex, as the discrete surface splits them. Cells are binned in a uniform
// grid of about their size, so a surface of n cells costs O(n log n). Only proper crossings
// count: cells that merely touch (a vertex on another cell, exactly coplanar edges) do not.
std::string find_surface_crossing(const InputMesh& mesh);

}  // namespace neomesh
