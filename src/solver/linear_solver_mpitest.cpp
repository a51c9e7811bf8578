// Under `mpiexec -n 2`: the Riesz solve with the scalar Laplacian's MAIJ and one BoomerAMG
// hierarchy per component gives the s of the block hierarchy on a distributed mesh too (the
// MAIJ's rows are the DofMap's on each rank).
#include <gtest/gtest.h>

#include "mesh/plex_mesh.hpp"
#include "solver/linear_solver.hpp"
#include "solver/testing/riesz_solves.hpp"
#include "solver/testing/stored_zeros.hpp"

namespace neomesh {
namespace {

TEST(DistributedLinearSolver, PerComponentRieszSolveMatchesTheBlockSolve) {
  ASSERT_EQ(mpi_size(), 2);
  for (const MeshData& data : riesz_test_meshes()) {
    MeshData empty;  // what ranks other than 0 pass
    empty.dim = data.dim;
    const PlexMesh mesh =
        PlexMesh::from_data(mpi_rank() == 0 ? data : empty, "test", PETSC_COMM_WORLD);
    ASSERT_GT(mesh.view().num_cells, 0);  // both ranks hold cells
    ASSERT_LT(mesh.view().num_cells, data.num_cells());
    expect_same_riesz_representative(mesh.view(), mesh.dofs());
  }
}

// Each rank copies its rows; columns owned by the other rank stay where they were.
TEST(DistributedLinearSolver, WithoutStoredZerosKeepsTheOperator) {
  ASSERT_EQ(mpi_size(), 2);
  const OwnedMat A = laplacian_with_stored_zeros(PETSC_COMM_WORLD, 12);
  const OwnedMat P = without_stored_zeros(A);
  ASSERT_TRUE(P);
  EXPECT_EQ(stored_entries(P), stored_entries(A) / 2);
  EXPECT_EQ(product_difference(A, P), 0.0);
}

}  // namespace
}  // namespace neomesh
