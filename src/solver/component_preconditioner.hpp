// One preconditioner of a scalar n × n matrix A₁, applied to each of the d components of a
// vector with interlaced dofs (dof = d · vertex + component): a preconditioner of
// MatCreateMAIJ(A₁, d) = A₁ ⊗ I for the set-up cost of one scalar preconditioner. The Riesz
// Laplacian is such an operator when no vertex slides (Functional::laplacian_is_scalar): one
// BoomerAMG hierarchy of the scalar Laplacian serves all d components, where a hierarchy of
// the dn × dn block matrix costs d scalar set-ups and treats the components as unrelated
// points (docs/method.md §4).
#pragma once

#include "core/petsc.hpp"

namespace neomesh {

using OwnedPC = PetscOwner<PC, PCDestroy>;

class ComponentPreconditioner {
 public:
  // `scalar`: the preconditioner of A₁, its type and options set, its operator not yet.
  ComponentPreconditioner(OwnedPC scalar, int components);
  ComponentPreconditioner(const ComponentPreconditioner&) = delete;
  ComponentPreconditioner& operator=(const ComponentPreconditioner&) = delete;

  // Makes `shell` apply this preconditioner (PCSHELL; PCView shows the scalar one). This
  // object must outlive the shell's use.
  void install(PC shell);
  // Uses A₁ from now on; with `same_values` the preconditioner built for the previous A₁
  // (hierarchy, factorization) is kept.
  void set_operator(Mat scalar, bool same_values);
  // Builds the scalar preconditioner now (else the first application does).
  void setup();

  PC scalar() const { return scalar_; }
  int components() const { return components_; }

 private:
  // y_j = P₁⁻¹ x_j for each component j.
  static PetscErrorCode apply(PC shell, Vec x, Vec y);
  static PetscErrorCode view(PC shell, PetscViewer viewer);

  OwnedPC scalar_;
  int components_;
  OwnedVec x_, y_;  // one component of the input and of the output
};

}  // namespace neomesh
