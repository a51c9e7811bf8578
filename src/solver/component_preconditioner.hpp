// A preconditioner of a dn × dn matrix that couples no two of the d components of a vector with
// interlaced dofs (dof = d · vertex + component), made of scalar n × n preconditioners applied
// to each component. The Riesz Laplacian is such a matrix when no vertex slides (docs/method.md
// §4), in one of two forms:
//
// - Shared: every component holds the same A₁ (every vertex has all or none of its coordinates
//   fixed; Functional::laplacian_is_scalar), and the matrix is MatCreateMAIJ(A₁, d) = A₁ ⊗ I.
//   One preconditioner of A₁ serves all d components: the set-up cost of one scalar
//   preconditioner, where a hierarchy of the dn × dn matrix costs d scalar set-ups.
// - Own: component j holds its own A_j, A₁ with the Dirichlet rows of the coordinates fixed in
//   that direction (a vertex on a plane x = const keeps x and moves in y and z). Each component
//   has a preconditioner of its A_j (rows and columns j, j + d, … of the matrix): the matrix is
//   block diagonal, so this is a preconditioner of the whole as exact as one of the dn × dn
//   matrix, for about the same set-up.
//
// hypre (Debian's build) runs on one core, and its V-cycles are most of a large 2D run's
// solves. On one rank with several OpenMP threads (`concurrent`), components are preconditioned
// at the same time, one per thread: hypre's solvers share no state, and each PETSc object is
// used by one thread only. Each component goes through the same arithmetic as on one thread,
// so the result does not depend on the thread count.
//
// Own: every component has its preconditioner from the start. Shared: further preconditioners
// of A₁, built alike, let components run at once; their set-ups cost what the first did, and a
// hierarchy applied a few times does not pay them back (quads 300², hexes 40³: as much time set
// up as saved), so they are built the way one decides to buy skis instead of renting them: once
// the time they would have saved since the first set-up reaches that set-up's time. At most
// twice the best choice's cost, whatever the number of applications to come. Each holds a
// hierarchy (about 8 % of a large 2D run's memory), so they are built only where the machine
// has twice that to spare beyond what the run's expected peak still needs (spare_bytes,
// core/memory.hpp): the memory check admits a run for its estimate, which leaves them out. The
// copy of A₁ in hypre's format that each would make is made once
// and shared, as hypre's V-cycles only read it.
//
// With BoomerAMG, the operator is copied into hypre's format when it is given, and the copies
// also multiply (product()): the caller need not keep the operator's own matrix, which is then
// held once instead of twice (the largest matrix of a run after H(α); docs/benchmarks.md,
// "Memory").
#pragma once

#include <vector>

#include "core/petsc.hpp"

namespace neomesh {

using OwnedPC = PetscOwner<PC, PCDestroy>;

enum class ComponentOperators { Shared, Own };

class ComponentPreconditioner {
 public:
  // `scalars`: the scalar preconditioners, configured alike (type and options set, the operator
  // not yet); Own: exactly one per component. Shared: the first serves every component until
  // the others pay for their set-up; then as many components as preconditioners are
  // preconditioned at once. `boomeramg`: they are all hypre's BoomerAMG (their operators are
  // then converted to hypre's format here). `concurrent`: components may be preconditioned on
  // several threads at once (one rank; every Shared preconditioner beyond the first needs it).
  ComponentPreconditioner(std::vector<OwnedPC> scalars, int components, ComponentOperators kind,
                          bool boomeramg, bool concurrent);
  ComponentPreconditioner(const ComponentPreconditioner&) = delete;
  ComponentPreconditioner& operator=(const ComponentPreconditioner&) = delete;

  // Makes `shell` apply this preconditioner (PCSHELL; PCView shows the first scalar one). This
  // object must outlive the shell's use.
  void install(PC shell);
  // Uses `matrix` from now on: A₁ (Shared) or the dn × dn matrix (Own). With `same_values` the
  // preconditioners built for the previous values (hierarchy, factorization) are kept.
  // BoomerAMG: `matrix` is copied into hypre's format now and not kept (with `same_values` the
  // copies take the new values and the hierarchies stay as they were).
  void set_operator(Mat matrix, bool same_values);
  // BoomerAMG: the dn × dn operator as a matrix that multiplies (MATSHELL) with the copies in
  // hypre's format, each component by its own; null otherwise. Made by the first set_operator;
  // valid while this object lives.
  Mat product() const { return product_; }
  // Builds the preconditioners every component needs now (else the first application does).
  void setup();
  // How many components are preconditioned at once now.
  int concurrent() const;

  PC scalar() const { return scalars_.front(); }
  int components() const { return components_; }
  ComponentOperators kind() const { return kind_; }

 private:
  // y_j = P_j⁻¹ x_j for each component j.
  static PetscErrorCode apply(PC shell, Vec x, Vec y);
  static PetscErrorCode view(PC shell, PetscViewer viewer);
  // y_j = A_j x_j for each component j (product()'s MATOP_MULT).
  static PetscErrorCode multiply(Mat shell, Vec x, Vec y);

  // y_j = op(slot, x_j) for each component j, `threads` components at once, with the slot
  // (preconditioner, hypre matrix, work vectors) of component j or of the thread.
  template <class Op>
  PetscErrorCode for_each_component(Vec x, Vec y, int threads, Op op) const;
  // Sets up what every component needs for the current operator, if not yet, timing it.
  PetscErrorCode setup_first();
  // The operators of the preconditioners: Shared, one hypre copy of A₁ and views of it
  // (BoomerAMG only); Own, each A_j (converted to hypre's format where the preconditioners are
  // BoomerAMG).
  PetscErrorCode give_shared_operator(Mat scalar);
  PetscErrorCode give_own_operators(Mat vector);
  // product_, of `rows` rows (all components) here and `global_rows` in all.
  void make_product(MPI_Comm comm, PetscInt rows, PetscInt global_rows);
  // Shared: builds the further preconditioners once they have paid for it (see above).
  PetscErrorCode buy_further(double seconds_applied);

  std::vector<OwnedPC> scalars_;
  int components_;
  ComponentOperators kind_;
  bool boomeramg_, concurrent_;
  // Per preconditioner, its operator in hypre's format (BoomerAMG only). Shared: [0] owns the
  // one copy of A₁, the others are views of it.
  std::vector<OwnedMat> hypre_;
  OwnedMat product_;  // BoomerAMG: see product()
  // Own, not BoomerAMG: A_j, kept for its preconditioner.
  std::vector<OwnedMat> parts_;
  // Per preconditioner: one component of the input and of the output.
  std::vector<OwnedVec> x_, y_;
  bool first_ready_ = false;  // what every component needs is set up for the current operator
  int ready_ = 1;             // Shared: scalars_[0, ready_) are set up for the current A₁
  bool declined_ = false;     // Shared: the others are not built for the current A₁ (no memory)
  // Shared: the longest set-up of scalars_[0] so far, and the most memory one took.
  double setup_seconds_ = 0.0, setup_bytes_ = 0.0;
  double would_have_saved_ = 0.0;  // by the other preconditioners, since the last set-up
};

}  // namespace neomesh
