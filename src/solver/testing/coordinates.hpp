// The solver layer's tests: coordinates as the global Vec the solvers work on.
#pragma once

#include <vector>

#include "core/petsc.hpp"
#include "mesh/dof_map.hpp"

namespace neomesh::testing {

// A global Vec of `dofs` holding `coords` (a serial DofMap: the MeshView's vertex order).
inline OwnedVec vector_of(const DofMap& dofs, const std::vector<double>& coords) {
  OwnedVec v = dofs.create_global_vector();
  VecWriteView out(v);
  for (PetscInt i = 0; i < out.size(); ++i) out[i] = coords[i];
  return v;
}

}  // namespace neomesh::testing
