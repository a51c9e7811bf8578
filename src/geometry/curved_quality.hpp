// The quality of a mesh of second-order cells (input_mesh.hpp's high-order nodes): per cell the
// validity certificate and the curved scaled Jacobian of curved_cell.hpp, and their summary.
#pragma once

#include <mpi.h>

#include <span>

#include <neomesh/quality.hpp>

#include "geometry/curved_cell.hpp"
#include "mesh/input_mesh.hpp"
#include "mesh/mesh_view.hpp"

namespace neomesh {

// The whole mesh's curved cells (a curved InputMesh, e.g. gathered on rank 0). Throws Error for a
// mesh without second-order cells.
CurvedQualitySummary curved_quality(const InputMesh& mesh);

// Collective: the same of a whole curved mesh on rank 0 (empty elsewhere), given to every
// process.
CurvedQualitySummary curved_quality_on_root(const InputMesh& mesh, MPI_Comm comm);

// Collective: the same of the curved cells of `cells` (a view of curved cells, CellBlock::curved,
// each cell on one process of `comm`) at `coords` (cells.dim values per local vertex), over all
// processes; every process gets the summary.
CurvedQualitySummary curved_quality(const MeshView& cells, std::span<const double> coords,
                                    MPI_Comm comm);

// Per cell of `cells` (curved cells, as above) at `coords`: whether the certificate finds it
// Valid. Cells where `only` is false are not examined (false); `only` empty: every cell.
std::vector<char> certified_valid(const MeshView& cells, std::span<const double> coords,
                                  std::span<const char> only = {});

// The curved scaled Jacobian of cell `c` of a curved mesh whose points (curved_point_coordinates)
// are `x`.
CurvedScaledJacobian curved_cell_quality(const InputMesh& mesh, const std::vector<double>& x,
                                         PetscInt c);

}  // namespace neomesh
