// Checks that a mesh read from a file (or generated) is one neomesh can optimize: finite
// coordinates, valid vertex indices, no repeated vertex in a cell, and every cell positively
// oriented with non-zero volume in canonical order (an inverted or degenerate cell).
// Cell numbers in messages are 0-based indices among the cells, in input order.
#pragma once

#include <string>

#include <mpi.h>

#include "mesh/cell_type.hpp"
#include "mesh/input_mesh.hpp"

namespace neomesh {

// The first defect of `mesh` as a sentence ("cell 12 (0-based) is inverted ..."), or "".
std::string find_defect(const InputMesh& mesh);

// Collective: throws Error "<source>: <defect>" on every rank if rank 0's `mesh` has one.
void validate(const InputMesh& mesh, const std::string& source, MPI_Comm comm);

// The smallest Jacobian determinant of a cell at its vertices, relative to the cube of its
// longest edge from each vertex (≤ 0 for an inverted or degenerate cell). `x` holds the
// cell's vertex coordinates in canonical order, `dimension(type)` values per vertex.
double min_scaled_corner_jacobian(CellType type, const double* x);

}  // namespace neomesh
