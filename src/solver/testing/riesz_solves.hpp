// The Riesz solve L s = g of one mesh (boundary fixed, optimal-cell Laplacian) with the amg
// solver two ways: BoomerAMG on the dn × dn vector Laplacian, and the scalar Laplacian's MAIJ
// with one hierarchy applied per component; and the vector Laplacian once more by CG
// preconditioned with that per-component hierarchy (as the δ̃ solve is). For the serial and
// the 2-rank tests of linear_solver.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "energy/functional.hpp"
#include "generate/generate.hpp"
#include "solver/linear_solver.hpp"

namespace neomesh {

struct RieszSolves {
  double size = 0.0;         // ‖s‖ of the block solve
  double per_component = 0;  // ‖s − s'‖ for the per-component solve
  double borrowed = 0.0;     // ‖s − s''‖ for CG on the vector L with the per-component PC
  LinearSolver::Outcome block, scalar;
  std::string description;  // of the per-component solver
};

inline double distance(Vec a, Vec b) {
  OwnedVec d;
  NM_PETSC(VecDuplicate(a, d.out()));
  NM_PETSC(VecWAXPY(d, -1.0, b, a));
  double n = 0.0;
  NM_PETSC(VecNorm(d, NORM_2, &n));
  return n;
}

inline RieszSolves solve_riesz_both_ways(const MeshView& view, const DofMap& dofs, double rtol) {
  const MPI_Comm comm = dofs.comm();
  const Functional functional(EnergyOptions{},
                              Problem(view, dofs, view.on_boundary)
                                  .with_desired_volumes(std::vector<double>(view.num_cells, 1.0)));
  OwnedVec x = dofs.create_global_vector();  // unused by the optimal cells' L
  OwnedMat vector = functional.create_laplacian_matrix();
  OwnedMat scalar = functional.create_scalar_laplacian_matrix();
  functional.assemble_laplacian(RieszLaplacian::OptimalCells, x, vector);
  functional.assemble_laplacian(RieszLaplacian::OptimalCells, x, scalar);

  // g: smooth, zero at fixed dofs (the boundary vertices') like a gradient.
  OwnedVec g = dofs.create_global_vector();
  {
    PetscInt first = 0;
    NM_PETSC(VecGetOwnershipRange(g, &first, nullptr));
    VecWriteView out(g);
    for (PetscInt i = 0; i < out.size(); ++i) out[i] = std::sin(0.01 * (first + i));
    for (PetscInt l = 0; l < dofs.num_local_dofs(); ++l)
      if (view.owned[l / view.dim] && view.on_boundary[l / view.dim])
        out[dofs.global_dof()[l] - first] = 0.0;
  }

  RieszSolves r;
  OwnedVec s = dofs.create_global_vector(), s1 = dofs.create_global_vector(),
           s2 = dofs.create_global_vector();
  LinearSolver block(comm, LinearSolverKind::Amg, "blocktest_", view.dim, rtol);
  block.set_operator(vector, false);
  block.setup();
  r.block = block.solve(g, s);
  NM_PETSC(VecNorm(s, NORM_2, &r.size));

  LinearSolver per_component(comm, LinearSolverKind::Amg, "scalartest_", view.dim, rtol);
  per_component.precondition_per_component(ComponentOperators::Shared);
  per_component.set_operator(scalar, false);
  per_component.setup();
  r.scalar = per_component.solve(g, s1);
  r.per_component = distance(s, s1);
  r.description = per_component.description();

  LinearSolver borrowing(comm, LinearSolverKind::Amg, "borrowtest_", view.dim, rtol);
  borrowing.precondition_with(per_component);
  borrowing.set_operator(vector, false);
  borrowing.solve(g, s2);
  r.borrowed = distance(s, s2);
  return r;
}

// Jittered quadrilaterals and tetrahedra.
inline std::vector<MeshData> riesz_test_meshes() {
  MeshData quads = box(CellType::Quadrilateral, 24);
  jitter(quads, 2.0 / 24, 0.2, 7);
  MeshData tets = box(CellType::Tetrahedron, 8);
  jitter(tets, 2.0 / 8, 0.1, 8);
  std::vector<MeshData> meshes;
  meshes.push_back(std::move(quads));
  meshes.push_back(std::move(tets));
  return meshes;
}

// Both ways give s to the solves' tolerance (1e-8), and the borrowed preconditioner works.
inline void expect_same_riesz_representative(const MeshView& view, const DofMap& dofs) {
  constexpr double kRtol = 1e-8;
  const RieszSolves r = solve_riesz_both_ways(view, dofs, kRtol);
  EXPECT_TRUE(r.block.converged);
  EXPECT_TRUE(r.scalar.converged);
  EXPECT_GT(r.size, 0.0);
  EXPECT_LE(r.per_component, 1e-6 * r.size);
  EXPECT_LE(r.borrowed, 1e-6 * r.size);
  EXPECT_EQ(r.description,
            fmt::format("KSP cg, PC hypre boomeramg of the scalar matrix, once for each of {} "
                        "components, rtol 1e-08, at most 10000 iterations",
                        view.dim));
}

}  // namespace neomesh
