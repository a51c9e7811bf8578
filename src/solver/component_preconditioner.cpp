#include "solver/component_preconditioner.hpp"

#include <algorithm>
#include <utility>

#include <omp.h>

#include <petscmathypre.h>

#include "core/memory.hpp"

namespace neomesh {

ComponentPreconditioner::ComponentPreconditioner(std::vector<OwnedPC> scalars, int components)
    : scalars_(std::move(scalars)),
      components_(components),
      x_(scalars_.size()),
      y_(scalars_.size()) {}

void ComponentPreconditioner::install(PC shell) {
  NM_PETSC(PCSetType(shell, PCSHELL));
  NM_PETSC(PCShellSetContext(shell, this));
  NM_PETSC(PCShellSetApply(shell, apply));
  NM_PETSC(PCShellSetView(shell, view));
  NM_PETSC(PCShellSetName(shell, "per component"));
}

void ComponentPreconditioner::set_operator(Mat scalar, bool same_values) {
  if (scalar != operator_) hypre_copy_.reset();  // another pattern, maybe: converted anew
  operator_ = scalar;
  for (std::size_t k = 0; k < scalars_.size(); ++k) {
    if (!hypre_copy_) NM_PETSC(PCSetOperators(scalars_[k], scalar, scalar));
    NM_PETSC(PCSetReusePreconditioner(scalars_[k], same_values ? PETSC_TRUE : PETSC_FALSE));
    NM_PETSC(MatCreateVecs(scalar, x_[k].out(), y_[k].out()));
  }
  if (!same_values) {
    first_ready_ = false;
    ready_ = 1;
    declined_ = false;
  }
}

void ComponentPreconditioner::setup() {
  NM_PETSC(setup_first());
}

PetscErrorCode ComponentPreconditioner::setup_first() {
  PetscFunctionBeginUser;
  if (first_ready_) PetscFunctionReturn(0);
  const double resident = resident_bytes();
  const double start = MPI_Wtime();
  if (scalars_.size() > 1) {
    // New values go into the same hypre matrix: no second copy while they are converted.
    if (hypre_copy_) {
      Mat same = hypre_copy_;
      PetscCall(MatConvert(operator_, MATHYPRE, MAT_REUSE_MATRIX, &same));
    } else {
      PetscCall(MatConvert(operator_, MATHYPRE, MAT_INITIAL_MATRIX, hypre_copy_.out()));
    }
    // The others get views of its hypre matrix: each hypre matrix object holds the work
    // vectors its preconditioner's applications use, so they cannot share one object.
    hypre_ParCSRMatrix* shared = nullptr;
    PetscCall(MatHYPREGetParCSR(hypre_copy_, &shared));
    PetscCall(PCSetOperators(scalars_[0], operator_, hypre_copy_));
    for (std::size_t k = 1; k < scalars_.size(); ++k) {
      OwnedMat view;
      PetscCall(MatCreateFromParCSR(shared, MATHYPRE, PETSC_USE_POINTER, view.out()));
      PetscCall(PCSetOperators(scalars_[k], operator_, view));
    }
  }
  PetscCall(PCSetUp(scalars_[0]));
  // A set-up that found A₁ unchanged takes no time nor memory: what a further one costs is
  // the most seen.
  setup_seconds_ = std::max(setup_seconds_, MPI_Wtime() - start);
  setup_bytes_ = std::max(setup_bytes_, resident_bytes() - resident);
  would_have_saved_ = 0.0;
  first_ready_ = true;
  PetscFunctionReturn(0);
}

// part[i] = x[d · i + j] over this rank's entries (each rank owns whole vertices), P₁⁻¹, and
// y[d · i + j] = result[i]; the other components of y are left as they are.
PetscErrorCode ComponentPreconditioner::apply_to_component(int slot, int j, const PetscScalar* x,
                                                           PetscScalar* y) const {
  PetscFunctionBeginUser;
  const int d = components_;
  Vec part_in = x_[slot], part_out = y_[slot];
  PetscInt n = 0;
  PetscCall(VecGetLocalSize(part_in, &n));
  PetscScalar* in = nullptr;
  PetscCall(VecGetArrayWrite(part_in, &in));
  for (PetscInt i = 0; i < n; ++i) in[i] = x[d * i + j];
  PetscCall(VecRestoreArrayWrite(part_in, &in));
  PetscCall(PCApply(scalars_[slot], part_in, part_out));
  const PetscScalar* out = nullptr;
  PetscCall(VecGetArrayRead(part_out, &out));
  for (PetscInt i = 0; i < n; ++i) y[d * i + j] = out[i];
  PetscCall(VecRestoreArrayRead(part_out, &out));
  PetscFunctionReturn(0);
}

PetscErrorCode ComponentPreconditioner::apply(PC shell, Vec x, Vec y) {
  PetscFunctionBeginUser;
  void* context = nullptr;
  PetscCall(PCShellGetContext(shell, &context));
  ComponentPreconditioner& p = *static_cast<ComponentPreconditioner*>(context);
  PetscCall(p.setup_first());
  const double start = MPI_Wtime();
  const PetscScalar* in = nullptr;
  PetscScalar* out = nullptr;
  PetscCall(VecGetArrayRead(x, &in));
  PetscCall(VecGetArray(y, &out));
  const int threads = std::min(p.ready_, omp_get_max_threads());
  std::vector<PetscErrorCode> failed(p.components_, 0);
#pragma omp parallel for num_threads(threads) if (threads > 1)
  for (int j = 0; j < p.components_; ++j)
    failed[j] = p.apply_to_component(omp_get_thread_num(), j, in, out);
  PetscCall(VecRestoreArray(y, &out));
  PetscCall(VecRestoreArrayRead(x, &in));
  for (const PetscErrorCode e : failed) PetscCall(e);
  const int all = static_cast<int>(p.scalars_.size());
  if (p.ready_ < all && !p.declined_) {
    // With all of them, d components take ⌈d / all⌉ applications' time instead of d.
    const int rounds = (p.components_ + all - 1) / all;
    p.would_have_saved_ += (MPI_Wtime() - start) * (p.components_ - rounds) / p.components_;
    if (p.would_have_saved_ >= p.setup_seconds_) {
      p.declined_ = available_bytes() < 2.0 * (all - 1) * p.setup_bytes_;
      // One after the other: hypre's coarsening draws from one global random sequence,
      // reseeded at each set-up.
      for (int k = 1; k < all && !p.declined_; ++k) PetscCall(PCSetUp(p.scalars_[k]));
      if (!p.declined_) p.ready_ = all;
    }
  }
  PetscFunctionReturn(0);
}

PetscErrorCode ComponentPreconditioner::view(PC shell, PetscViewer viewer) {
  PetscFunctionBeginUser;
  void* context = nullptr;
  PetscCall(PCShellGetContext(shell, &context));
  const ComponentPreconditioner& p = *static_cast<const ComponentPreconditioner*>(context);
  PetscBool ascii = PETSC_FALSE;
  PetscCall(
      PetscObjectTypeCompare(reinterpret_cast<PetscObject>(viewer), PETSCVIEWERASCII, &ascii));
  if (!ascii) PetscFunctionReturn(0);
  PetscCall(PetscViewerASCIIPrintf(viewer, "applied to each of %d components:\n", p.components_));
  PetscCall(PetscViewerASCIIPushTab(viewer));
  PetscCall(PCView(p.scalar(), viewer));
  PetscCall(PetscViewerASCIIPopTab(viewer));
  PetscFunctionReturn(0);
}

}  // namespace neomesh
