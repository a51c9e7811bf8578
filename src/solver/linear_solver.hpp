// The two linear solves of each quasi-Newton iteration (docs/method.md §4) as PETSc KSPs with
// option prefixes, so that users tune them without recompiling: `-hess_` for the
// quasi-Newton system H(α) δ̃ = −g, `-riesz_` for the Riesz representative L s = g.
//
// --linear-solver picks the defaults; any -hess_ksp_* / -riesz_pc_* option still wins:
//   amg     CG + hypre BoomerAMG (mesh-independent iteration counts; the default)
//   jacobi  CG + Jacobi (the thesis' PCG)
//   direct  Cholesky (MUMPS, works in parallel; the thesis used UMFPACK)
#pragma once

#include <memory>
#include <string>
#include <string_view>

#include <neomesh/options.hpp>

#include "core/petsc.hpp"
#include "solver/component_preconditioner.hpp"

namespace neomesh {

// A copy of A without its stored zeros, or null when they are under a tenth of its entries.
// The coupled Laplacian of a mesh with sliding vertices stores all dim² couplings of every
// pair of vertices, and only those of sliding vertices are nonzero (pave1: 70.8 entries per
// row, 27 of them nonzero). Collective.
OwnedMat without_stored_zeros(Mat A);

class LinearSolver {
 public:
  // `dim`: the mesh's dimension (AMG defaults differ in 3D); `rtol`: relative reduction of
  // the (unpreconditioned) residual at which to stop.
  LinearSolver(MPI_Comm comm, LinearSolverKind kind, const std::string& prefix, int dim,
               double rtol);

  // Uses `A` for the next solves. With `same_values` the preconditioner (AMG hierarchy,
  // factorization) of the previous operator is kept.
  void set_operator(Mat A, bool same_values);
  // True if set_operator copied A into the preconditioner's format and multiplies with that
  // copy (BoomerAMG per component): A need not be kept for the solves.
  bool copies_operator() const;
  // y = A x with the operator of the next solves.
  void multiply(Vec x, Vec y) const;
  // amg only, before set_operator: the operators will couple no two components, and are
  // preconditioned by scalar BoomerAMG preconditioners applied to each component
  // (component_preconditioner.hpp). Shared: the operators are MatCreateMAIJ(A₁, dim) of scalar
  // matrices A₁ (Functional::create_scalar_laplacian_matrix), and one hierarchy of A₁ serves
  // every component; Own: each component has a hierarchy of its own rows and columns. The
  // -<prefix>pc_ options, and the BoomerAMG defaults, apply to the scalar preconditioners.
  void precondition_per_component(ComponentOperators kind);
  // Builds the preconditioner now (else the next solve does), for timing it on its own.
  void setup();
  // From now on, precondition with `other`'s preconditioner as it is at each solve (built for
  // `other`'s operator); this solver's own PC options no longer apply. `other` must outlive
  // this solver.
  void precondition_with(const LinearSolver& other);

  struct Outcome {
    bool converged = false;
    // CG met negative curvature (the operator is not positive definite); x holds the last
    // iterate before it, which still decreases the quadratic model.
    bool indefinite = false;
    int iterations = 0;
    double residual = 0.0;  // final unpreconditioned residual norm
  };
  // Solves A x = b from x = 0; stops at rtol or when the residual is below `atol`.
  Outcome solve(Vec b, Vec x, double atol = 0.0);
  // x = M⁻¹ b, one application of the preconditioner (built for the operator if it was not).
  void apply_preconditioner(Vec b, Vec x);

  KSP ksp() const { return ksp_; }
  // "KSP cg, PC hypre boomeramg, rtol 0.0001, at most 10000 iterations": what PETSc will run,
  // after the options database's -<prefix> options; per component: "PC hypre boomeramg of
  // the scalar matrix, once for each of 3 components".
  std::string description() const;

 private:
  bool builds_amg_hierarchy() const;

  OwnedKSP ksp_;
  double rtol_;
  LinearSolverKind kind_;
  std::string prefix_;
  int dim_;
  std::unique_ptr<ComponentPreconditioner> components_;  // after precondition_per_component
  // AMG: the operator without its stored zeros, which the hierarchy is built for (null: the
  // operator itself).
  OwnedMat amg_matrix_;
  // Direct solves: the residual b − A x of the last solve, kept rather than allocated per
  // solve (a fresh vector's pages are faulted and zeroed again every time).
  OwnedVec residual_;
};

}  // namespace neomesh
