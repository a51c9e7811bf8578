// LinearSolver's BoomerAMG defaults reach hypre and leave the options database as it was;
// the per-component preconditioner of the scalar Laplacian solves as the block hierarchy does.
#include "solver/linear_solver.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <string>

#include "generate/serial_view.hpp"
#include "solver/testing/riesz_solves.hpp"
#include "solver/testing/stored_zeros.hpp"

namespace neomesh {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

// What PCView prints of the solver's preconditioner (hypre's settings need an ASCII viewer).
std::string view_pc(const LinearSolver& solver) {
  PC pc = nullptr;
  NM_PETSC(KSPGetPC(solver.ksp(), &pc));
  // One file per process: ctest runs these tests in parallel processes, which overwrote and
  // removed one another's view of a shared file (an empty view failed them now and then).
  const std::string path =
      testing::TempDir() + "linear_solver_test_pc_" + std::to_string(getpid()) + ".txt";
  PetscViewer viewer = nullptr;
  NM_PETSC(PetscViewerASCIIOpen(PETSC_COMM_SELF, path.c_str(), &viewer));
  NM_PETSC(PCView(pc, viewer));
  NM_PETSC(PetscViewerDestroy(&viewer));
  std::ifstream in(path);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::remove(path.c_str());
  return text;
}

bool in_database(const char* option) {
  PetscBool has = PETSC_FALSE;
  NM_PETSC(PetscOptionsHasName(nullptr, nullptr, option, &has));
  return has == PETSC_TRUE;
}

TEST(LinearSolver, AmgDefaultsReachHypreAndLeaveNoOptionBehind) {
  const LinearSolver solver(PETSC_COMM_SELF, LinearSolverKind::Amg, "amgtest_", 3, 1e-4);
  const std::string pc = view_pc(solver);
  EXPECT_THAT(pc, HasSubstr("HMIS"));
  EXPECT_THAT(pc, HasSubstr("Chebyshev"));
  EXPECT_FALSE(in_database("-amgtest_pc_hypre_boomeramg_coarsen_type"));
  EXPECT_FALSE(in_database("-amgtest_pc_hypre_boomeramg_relax_type_all"));
}

TEST(LinearSolver, TwoDimensionalAmgSmoothsWithGaussSeidelBothWays) {
  const LinearSolver solver(PETSC_COMM_SELF, LinearSolverKind::Amg, "amg2d_", 2, 1e-4);
  const std::string pc = view_pc(solver);
  EXPECT_THAT(pc, HasSubstr("Relax down          l1-Gauss-Seidel"));
  EXPECT_THAT(pc, HasSubstr("Relax up            backward-l1-Gauss-Seidel"));
  EXPECT_THAT(pc, Not(HasSubstr("HMIS")));
  EXPECT_FALSE(in_database("-amg2d_pc_hypre_boomeramg_relax_type_down"));
  EXPECT_FALSE(in_database("-amg2d_pc_hypre_boomeramg_relax_type_up"));
}

// A smoother given for both legs is used on both: the default legs do not override it.
TEST(LinearSolver, ASmootherForBothLegsWinsOverTheDefaultLegs) {
  NM_PETSC(PetscOptionsSetValue(nullptr, "-legs_pc_hypre_boomeramg_relax_type_all", "Jacobi"));
  const LinearSolver solver(PETSC_COMM_SELF, LinearSolverKind::Amg, "legs_", 2, 1e-4);
  const std::string pc = view_pc(solver);
  EXPECT_THAT(pc, Not(HasSubstr("Gauss-Seidel")));
  EXPECT_THAT(pc, HasSubstr("Relax up            Jacobi"));
  EXPECT_FALSE(in_database("-legs_pc_hypre_boomeramg_relax_type_down"));
  NM_PETSC(PetscOptionsClearValue(nullptr, "-legs_pc_hypre_boomeramg_relax_type_all"));
}

TEST(LinearSolver, AnOptionTheCallerGaveWinsAndStays) {
  NM_PETSC(PetscOptionsSetValue(nullptr, "-given_pc_hypre_boomeramg_coarsen_type", "PMIS"));
  const LinearSolver solver(PETSC_COMM_SELF, LinearSolverKind::Amg, "given_", 3, 1e-4);
  const std::string pc = view_pc(solver);
  EXPECT_THAT(pc, HasSubstr("PMIS"));
  EXPECT_THAT(pc, Not(HasSubstr("HMIS")));
  EXPECT_TRUE(in_database("-given_pc_hypre_boomeramg_coarsen_type"));
  NM_PETSC(PetscOptionsClearValue(nullptr, "-given_pc_hypre_boomeramg_coarsen_type"));
}

// The scalar preconditioner reads the solver's options and the BoomerAMG defaults, which it
// leaves behind as little as the block one does.
TEST(LinearSolver, PerComponentPreconditionerReadsTheOptions) {
  NM_PETSC(PetscOptionsSetValue(nullptr, "-percomp_pc_hypre_boomeramg_interp_type", "FF1"));
  LinearSolver solver(PETSC_COMM_SELF, LinearSolverKind::Amg, "percomp_", 3, 1e-4);
  solver.precondition_per_component(ComponentOperators::Shared);
  const std::string pc = view_pc(solver);
  EXPECT_THAT(pc, HasSubstr("applied to each of 3 components"));
  EXPECT_THAT(pc, HasSubstr("HMIS"));
  EXPECT_THAT(pc, HasSubstr("Chebyshev"));
  EXPECT_THAT(pc, HasSubstr("FF1"));
  EXPECT_FALSE(in_database("-percomp_pc_hypre_boomeramg_coarsen_type"));
  EXPECT_FALSE(in_database("-percomp_pc_hypre_boomeramg_relax_type_all"));
  LinearSolver own(PETSC_COMM_SELF, LinearSolverKind::Amg, "percomp_", 3, 1e-4);
  own.precondition_per_component(ComponentOperators::Own);
  const std::string own_pc = view_pc(own);
  EXPECT_THAT(own_pc, HasSubstr("one for each of 3 components, each of its own matrix"));
  EXPECT_THAT(own_pc, HasSubstr("FF1"));
  EXPECT_THAT(own.description(), HasSubstr("of each component's matrix, for each of 3 components"));
  NM_PETSC(PetscOptionsClearValue(nullptr, "-percomp_pc_hypre_boomeramg_interp_type"));
  EXPECT_THROW(LinearSolver(PETSC_COMM_SELF, LinearSolverKind::Direct, "percomp_", 3, 1e-4)
                   .precondition_per_component(ComponentOperators::Shared),
               Error);
}

// L s = g with the scalar Laplacian's MAIJ and one hierarchy per component gives the s of the
// block hierarchy to the solve's tolerance, and the δ̃ solve's borrowed preconditioner works.
TEST(LinearSolver, PerComponentRieszSolveMatchesTheBlockSolve) {
  for (const MeshData& mesh : riesz_test_meshes()) {
    const MeshView view = serial_view(mesh);
    expect_same_riesz_representative(view, DofMap::serial(view.dim, view.num_vertices));
  }
}

TEST(LinearSolver, WithoutStoredZerosKeepsTheOperatorAndDropsTheZeros) {
  const OwnedMat A = laplacian_with_stored_zeros(PETSC_COMM_SELF, 12);
  const OwnedMat P = without_stored_zeros(A);
  ASSERT_TRUE(P);
  EXPECT_EQ(stored_entries(A), 2 * 2 * (10 * 10 * 5 + 44));  // both components, zeros too
  EXPECT_EQ(stored_entries(P), 2 * (10 * 10 * 5 + 44));
  PetscInt bs = 0;
  NM_PETSC(MatGetBlockSize(P, &bs));
  EXPECT_EQ(bs, 2);
  EXPECT_EQ(product_difference(A, P), 0.0);
  // A matrix without (many) zeros is used as it is.
  EXPECT_FALSE(without_stored_zeros(P));
}

// The AMG hierarchy is built for the operator without its zeros; CG still multiplies by A.
TEST(LinearSolver, AmgBuildsItsHierarchyForTheOperatorWithoutItsZeros) {
  const OwnedMat A = laplacian_with_stored_zeros(PETSC_COMM_SELF, 30);
  LinearSolver solver(PETSC_COMM_SELF, LinearSolverKind::Amg, "zerofree_", 2, 1e-8);
  solver.set_operator(A, false);
  OwnedVec b, x;
  NM_PETSC(MatCreateVecs(A, x.out(), b.out()));
  NM_PETSC(VecSet(b, 1.0));
  const LinearSolver::Outcome out = solver.solve(b, x);
  EXPECT_TRUE(out.converged);
  Mat amat = nullptr, pmat = nullptr;
  NM_PETSC(KSPGetOperators(solver.ksp(), &amat, &pmat));
  EXPECT_EQ(amat, A.get());
  EXPECT_EQ(stored_entries(pmat), stored_entries(A) / 2);
  OwnedVec r;
  NM_PETSC(VecDuplicate(b, r.out()));
  NM_PETSC(MatMult(A, x, r));
  EXPECT_LT(distance(r, b), 1e-7 * std::sqrt(2.0 * 30 * 30));
}

}  // namespace
}  // namespace neomesh
