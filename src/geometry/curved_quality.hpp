// The quality of a mesh of second-order cells (input_mesh.hpp's high-order nodes): per cell the
// validity certificate and the curved scaled Jacobian of curved_cell.hpp, and their summary.
#pragma once

#include <neomesh/quality.hpp>

#include "geometry/curved_cell.hpp"
#include "mesh/input_mesh.hpp"

namespace neomesh {

// The whole mesh's curved cells (a curved InputMesh, e.g. gathered on rank 0). Throws Error for a
// mesh without second-order cells.
CurvedQualitySummary curved_quality(const InputMesh& mesh);

// The curved scaled Jacobian of cell `c` of a curved mesh whose points (curved_point_coordinates)
// are `x`.
CurvedScaledJacobian curved_cell_quality(const InputMesh& mesh, const std::vector<double>& x,
                                         PetscInt c);

}  // namespace neomesh
