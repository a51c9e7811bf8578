// Checks that a mesh read from a file (or generated) is one neomesh can optimize: finite
// coordinates, valid vertex indices, no repeated vertex in a cell, and every cell positively
// oriented with non-zero volume in canonical order (an inverted or degenerate cell).
// Cell numbers in messages are 0-based indices among the cells, in input order.
//
// Mirrored cells: a cell whose corner Jacobians are all negative is not inverted but listed in
// the other orientation (FEAT3 meshes with clockwise quads, mirrored hexahedra, Gmsh surfaces
// meshed with the normal along -z). validate() reorients it (its local vertex order is
// mirrored; a curved cell's other nodes follow its corners) and every output keeps the new,
// positive order. Only a cell with corner Jacobians
// of mixed sign or zero is inverted or degenerate, or a mirrored cell that folds over a
// neighbour (the two run around their common facet the same way).
//
// A surface mesh is checked further: its edges and whether it crosses itself
// (surface_defects.hpp).
#pragma once

#include <string>
#include <vector>

#include <mpi.h>

#include "mesh/cell_type.hpp"
#include "mesh/input_mesh.hpp"

namespace neomesh {

// The first defect of `mesh` as a sentence ("cell 12 (0-based) is inverted ..."), or "".
// With `keep_inverted`, inverted and degenerate cells are not defects (for inspecting a mesh).
std::string find_defect(const InputMesh& mesh, bool keep_inverted = false);

// Reorients every mirrored cell of `mesh`; returns their indices, ascending.
std::vector<PetscInt> orient_mirrored_cells(InputMesh& mesh);

// After orient_mirrored_cells: the first pair of cells on the same side of their common facet
// as a sentence ("cell 3 (0-based, a triangle) is inverted (it folds over cell 7)"), or "".
std::string find_fold(const InputMesh& mesh, const std::vector<PetscInt>& mirrored);

// Collective: on rank 0 reorients mirrored cells, then throws Error "<source>: <defect>" on
// every rank if rank 0's `mesh` has a defect (a surface's included, with or without
// `keep_inverted`).
// With `keep_inverted` (quality and render count and draw inverted cells, smooth untangles
// them), inverted and degenerate cells are kept; mirrored cells are reoriented one by one if
// that leaves no fold, else all cells are if most of them are mirrored.
void validate(InputMesh& mesh, const std::string& source, MPI_Comm comm,
              bool keep_inverted = false);

// The smallest Jacobian determinant of a cell at its vertices, relative to the cube of its
// longest edge from each vertex (≤ 0 for an inverted or degenerate cell). `x` holds the
// cell's vertex coordinates in canonical order, `dimension(type)` values per vertex.
double min_scaled_corner_jacobian(CellType type, const double* x);

}  // namespace neomesh
