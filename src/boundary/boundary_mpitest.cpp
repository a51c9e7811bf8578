// Under `mpiexec -n 2`: a rank sees only some boundary facets of the vertices it shares
// with the other rank; Boundary must still give every local vertex, ghosts included, the
// mask of the whole mesh.
#include <gtest/gtest.h>

#include <cmath>

#include "boundary/boundary.hpp"
#include "generate/generate.hpp"
#include "mesh/plex_mesh.hpp"

namespace neomesh {
namespace {

void expect_box_mask_on_every_rank(CellType type, int n) {
  MeshData empty;  // what ranks other than 0 pass
  empty.dim = dimension(type);
  const MeshData data = box(type, n);
  PlexMesh mesh =
      PlexMesh::from_data(mpi_rank(PETSC_COMM_WORLD) == 0 ? data : empty, "box", PETSC_COMM_WORLD);
  const MeshView& view = mesh.view();
  ASSERT_GT(view.num_cells, 0) << "the test needs cells on every rank";
  const std::vector<std::uint8_t> slide =
      Boundary(view, mesh.dofs(), BoundaryOptions(BoundaryMode::Slide)).fixed_dofs().flags;
  const int d = view.dim;
  for (PetscInt v = 0; v < view.num_vertices; ++v)
    for (int j = 0; j < d; ++j)
      EXPECT_EQ(slide[v * d + j], std::abs(view.coords[v * d + j]) == 1.0)
          << "rank " << mpi_rank(PETSC_COMM_WORLD) << ", vertex " << v << " ("
          << (view.owned[v] ? "owned" : "ghost") << "), component " << j;
}

TEST(FixedDofs, DistributedHexBoxGetsTheSerialMask) {
  expect_box_mask_on_every_rank(CellType::Hexahedron, 4);
}

// A tet may touch a face vertex with an edge only: the rank that holds just such tets of a
// vertex learns its mask from the other rank.
TEST(FixedDofs, DistributedTetBoxGetsTheSerialMask) {
  expect_box_mask_on_every_rank(CellType::Tetrahedron, 4);
}

}  // namespace
}  // namespace neomesh
