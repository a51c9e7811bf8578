// Small queries on a DMPlex shared by the mesh layer's reader and view.
#pragma once

#include <cstdint>
#include <vector>

#include "core/petsc.hpp"

namespace neomesh {

// Vertices of `point`'s closure in closure order, as numbers relative to vStart.
std::vector<PetscInt> closure_vertices(DM dm, PetscInt point, PetscInt vStart, PetscInt vEnd);

// Per local point (relative to the chart start): 1 if another rank owns it (a leaf of the
// point SF).
std::vector<std::uint8_t> ghost_points(DM dm);

}  // namespace neomesh
