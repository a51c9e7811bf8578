// Checks shared by the mesh layer's tests.
#pragma once

#include <algorithm>

#include "mesh/mesh.hpp"
#include "mesh/validate.hpp"

namespace neomesh::testing {

// The smallest scaled corner Jacobian over the rank's cells, in MeshView's canonical order:
// positive iff every cell is positively oriented.
inline double min_view_jacobian(const MeshView& view) {
  double worst = 1.0;
  double x[8 * 3];
  for (const CellBlock& block : view.blocks)
    for (PetscInt c = 0; c < block.size(); ++c) {
      for (int i = 0; i < num_vertices(block.type); ++i)
        std::copy_n(view.coords.data() + block.cell(c)[i] * view.dim, view.dim, x + i * view.dim);
      worst = std::min(worst, min_scaled_corner_jacobian(block.type, x));
    }
  return worst;
}

}  // namespace neomesh::testing
