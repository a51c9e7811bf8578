// FacetTable: the facets (edges of 2D cells, faces of 3D cells) of a whole mesh on rank 0,
// found by hashing each cell's facets by their sorted vertices. It gives what interpolating a
// DMPlex would (each facet once, its vertex order, the cells on either side) at a fraction of
// the time and memory.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "mesh/input_mesh.hpp"

namespace neomesh {

// Per cell, the cells that share a facet with it, ascending (CSR).
struct CellGraph {
  std::vector<PetscInt> offsets = {0};
  std::vector<PetscInt> neighbours;
};

class FacetTable {
 public:
  // Keeps a reference to `mesh`.
  explicit FacetTable(const InputMesh& mesh);

  PetscInt size() const { return static_cast<PetscInt>(cells_.size()); }
  bool on_boundary(PetscInt f) const { return cells_[f][1] < 0; }

  // The facet's vertices in the order of DMPlex's facet closure, the order in which the first
  // cell (in cell order) that has the facet lists them (CellFacts::facets). Returns their number.
  int vertices(PetscInt f, PetscInt out[4]) const;

  // The facet with these vertices (in any order), or -1.
  PetscInt find(const PetscInt* vertices, int n) const;

  // The graph PETSc partitions an interpolated mesh by: neighbours across facets.
  CellGraph cell_graph() const;

 private:
  using Key = std::array<PetscInt, 4>;  // sorted vertices, then -1
  static Key key(const PetscInt* vertices, int n);
  PetscInt lookup(const Key& key) const;

  const InputMesh& mesh_;
  std::vector<Key> keys_;
  std::vector<std::array<PetscInt, 2>> cells_;  // first cell; second cell or -1
  std::vector<std::uint8_t> local_;             // facet's index among its first cell's facets
  std::vector<PetscInt> head_, next_;           // per smallest vertex, a list of its facets
};

}  // namespace neomesh
