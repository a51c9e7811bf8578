// One preconditioner of a scalar n × n matrix A₁, applied to each of the d components of a
// vector with interlaced dofs (dof = d · vertex + component): a preconditioner of
// MatCreateMAIJ(A₁, d) = A₁ ⊗ I for the set-up cost of one scalar preconditioner. The Riesz
// Laplacian is such an operator when no vertex slides (Functional::laplacian_is_scalar): one
// BoomerAMG hierarchy of the scalar Laplacian serves all d components, where a hierarchy of
// the dn × dn block matrix costs d scalar set-ups and treats the components as unrelated
// points (docs/method.md §4).
//
// hypre (Debian's build) runs on one core, and its V-cycles are most of a large 2D run's
// solves. On one rank with several OpenMP threads, further preconditioners of A₁, built alike,
// let the components be preconditioned at the same time, one per thread: hypre's solvers share
// no state, and each PETSc object is used by one thread only. Each component goes through the
// same arithmetic as on one thread, so the result does not depend on the thread count. The
// further set-ups cost what the first did, and a hierarchy applied a few times does not pay
// them back (quads 300², hexes 40³: as much time set up as saved), so they are built the way
// one decides to buy skis instead of renting them: once the time they would have saved since
// the first set-up reaches that set-up's time. At most twice the best choice's cost, whatever
// the number of applications to come. Each holds a hierarchy (about 8 % of a large 2D run's
// memory), so they are built only where the machine has twice that to spare; the copy of A₁ in
// hypre's format that each would make is made once and shared, as hypre's V-cycles only read
// it.
#pragma once

#include <vector>

#include "core/petsc.hpp"

namespace neomesh {

using OwnedPC = PetscOwner<PC, PCDestroy>;

class ComponentPreconditioner {
 public:
  // `scalars`: one or more preconditioners of A₁, configured alike (type and options set, the
  // operator not yet). The first serves every component until the others pay for their
  // set-up; then as many components as preconditioners are preconditioned at once.
  ComponentPreconditioner(std::vector<OwnedPC> scalars, int components);
  ComponentPreconditioner(const ComponentPreconditioner&) = delete;
  ComponentPreconditioner& operator=(const ComponentPreconditioner&) = delete;

  // Makes `shell` apply this preconditioner (PCSHELL; PCView shows the scalar one). This
  // object must outlive the shell's use.
  void install(PC shell);
  // Uses A₁ from now on; with `same_values` the preconditioner built for the previous A₁
  // (hierarchy, factorization) is kept.
  void set_operator(Mat scalar, bool same_values);
  // Builds the first scalar preconditioner now (else the first application does).
  void setup();
  // How many components are preconditioned at once now.
  int concurrent() const { return ready_; }

  PC scalar() const { return scalars_.front(); }
  int components() const { return components_; }

 private:
  // y_j = P₁⁻¹ x_j for each component j.
  static PetscErrorCode apply(PC shell, Vec x, Vec y);
  static PetscErrorCode view(PC shell, PetscViewer viewer);

  // y_j = P₁⁻¹ x_j with the preconditioner of `slot`; `x`, `y`: the whole vectors' arrays.
  PetscErrorCode apply_to_component(int slot, int j, const PetscScalar* x, PetscScalar* y) const;
  // Sets the first preconditioner up if A₁ changed, timing it.
  PetscErrorCode setup_first();

  std::vector<OwnedPC> scalars_;
  int components_;
  Mat operator_ = nullptr;  // A₁, as set_operator gave it
  // A₁ in hypre's format for all of scalars_ where they are several (all BoomerAMG); null
  // where there is one, which converts A₁ itself if it needs to.
  OwnedMat hypre_copy_;
  // Per preconditioner: one component of the input and of the output.
  std::vector<OwnedVec> x_, y_;
  bool first_ready_ = false;  // scalars_[0] is set up for the current A₁
  int ready_ = 1;             // scalars_[0, ready_) are set up for the current A₁
  bool declined_ = false;     // the others are not built for the current A₁ (no memory)
  // The longest set-up of scalars_[0] so far, and the most memory one took.
  double setup_seconds_ = 0.0, setup_bytes_ = 0.0;
  double would_have_saved_ = 0.0;  // by the other preconditioners, since the last set-up
};

}  // namespace neomesh
