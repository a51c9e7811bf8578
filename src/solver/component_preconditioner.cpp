#include "solver/component_preconditioner.hpp"

#include <algorithm>
#include <utility>

#include <omp.h>

#include <petscmathypre.h>

#include "core/error.hpp"
#include "core/memory.hpp"

namespace neomesh {

namespace {

// Converts `from` into hypre's format, into `to` if it holds the previous values (the same
// pattern): no second copy while they are converted.
PetscErrorCode convert_to_hypre(Mat from, OwnedMat& to) {
  PetscFunctionBeginUser;
  if (to) {
    Mat same = to;
    PetscCall(MatConvert(from, MATHYPRE, MAT_REUSE_MATRIX, &same));
  } else {
    PetscCall(MatConvert(from, MATHYPRE, MAT_INITIAL_MATRIX, to.out()));
  }
  PetscFunctionReturn(0);
}

}  // namespace

ComponentPreconditioner::ComponentPreconditioner(std::vector<OwnedPC> scalars, int components,
                                                 ComponentOperators kind, bool boomeramg,
                                                 bool concurrent)
    : scalars_(std::move(scalars)),
      components_(components),
      kind_(kind),
      boomeramg_(boomeramg),
      concurrent_(concurrent),
      hypre_(scalars_.size()),
      parts_(scalars_.size()),
      x_(scalars_.size()),
      y_(scalars_.size()) {
  if (kind_ == ComponentOperators::Own && static_cast<int>(scalars_.size()) != components_)
    fail("internal error: {} preconditioners for {} components of their own", scalars_.size(),
         components_);
}

void ComponentPreconditioner::install(PC shell) {
  NM_PETSC(PCSetType(shell, PCSHELL));
  NM_PETSC(PCShellSetContext(shell, this));
  NM_PETSC(PCShellSetApply(shell, apply));
  NM_PETSC(PCShellSetView(shell, view));
  NM_PETSC(PCShellSetName(shell, "per component"));
}

void ComponentPreconditioner::set_operator(Mat matrix, bool same_values) {
  const bool shared = kind_ == ComponentOperators::Shared;
  PetscInt rows = 0, global_rows = 0, held = -1;
  NM_PETSC(MatGetLocalSize(matrix, &rows, nullptr));
  NM_PETSC(MatGetSize(matrix, &global_rows, nullptr));
  const PetscInt per = shared ? 1 : components_;  // rows of `matrix` per row of a component
  if (x_[0]) NM_PETSC(VecGetSize(x_[0], &held));
  if (held != global_rows / per) {  // another mesh: other sizes
    for (OwnedMat& m : hypre_) m.reset();
    product_.reset();
    for (std::size_t k = 0; k < scalars_.size(); ++k)
      for (OwnedVec* v : {&x_[k], &y_[k]}) {
        NM_PETSC(VecCreate(PetscObjectComm(reinterpret_cast<PetscObject>(matrix)), v->out()));
        NM_PETSC(VecSetSizes(*v, rows / per, global_rows / per));
        NM_PETSC(VecSetType(*v, VECSTANDARD));
      }
  }
  if (shared && !boomeramg_)
    NM_PETSC(PCSetOperators(scalars_[0], matrix, matrix));
  else
    NM_PETSC(shared ? give_shared_operator(matrix) : give_own_operators(matrix));
  if (boomeramg_ && !product_)
    make_product(PetscObjectComm(reinterpret_cast<PetscObject>(matrix)), rows / per * components_,
                 global_rows / per * components_);
  for (OwnedPC& pc : scalars_)
    NM_PETSC(PCSetReusePreconditioner(pc, same_values ? PETSC_TRUE : PETSC_FALSE));
  if (!same_values) {
    first_ready_ = false;
    ready_ = 1;
    declined_ = false;
  }
}

void ComponentPreconditioner::make_product(MPI_Comm comm, PetscInt rows, PetscInt global_rows) {
  NM_PETSC(MatCreateShell(comm, rows, rows, global_rows, global_rows, this, product_.out()));
  for (const MatOperation op : {MATOP_MULT, MATOP_MULT_TRANSPOSE})
    NM_PETSC(MatShellSetOperation(product_, op, reinterpret_cast<void (*)(void)>(multiply)));
  NM_PETSC(MatSetOption(product_, MAT_SYMMETRIC, PETSC_TRUE));
  NM_PETSC(MatSetOption(product_, MAT_SYMMETRY_ETERNAL, PETSC_TRUE));
}

void ComponentPreconditioner::setup() {
  NM_PETSC(setup_first());
}

int ComponentPreconditioner::concurrent() const {
  const int at_once = kind_ == ComponentOperators::Own ? (concurrent_ ? components_ : 1) : ready_;
  return std::min(at_once, omp_get_max_threads());
}

PetscErrorCode ComponentPreconditioner::setup_first() {
  PetscFunctionBeginUser;
  if (first_ready_) PetscFunctionReturn(0);
  if (kind_ == ComponentOperators::Own) {
    // One after the other: hypre's coarsening draws from one global random sequence, reseeded
    // at each set-up.
    for (OwnedPC& pc : scalars_) PetscCall(PCSetUp(pc));
    first_ready_ = true;
    PetscFunctionReturn(0);
  }
  const double resident = resident_bytes();
  const double start = MPI_Wtime();
  PetscCall(PCSetUp(scalars_[0]));
  // A set-up that found A₁ unchanged takes no time nor memory: what a further one costs is
  // the most seen.
  setup_seconds_ = std::max(setup_seconds_, MPI_Wtime() - start);
  setup_bytes_ = std::max(setup_bytes_, resident_bytes() - resident);
  would_have_saved_ = 0.0;
  first_ready_ = true;
  PetscFunctionReturn(0);
}

PetscErrorCode ComponentPreconditioner::give_shared_operator(Mat scalar) {
  PetscFunctionBeginUser;
  PetscCall(convert_to_hypre(scalar, hypre_[0]));
  // The others get views of its hypre matrix: each hypre matrix object holds the work vectors
  // its preconditioner's applications use, so they cannot share one object.
  hypre_ParCSRMatrix* shared = nullptr;
  PetscCall(MatHYPREGetParCSR(hypre_[0], &shared));
  for (std::size_t k = 1; k < scalars_.size(); ++k)
    PetscCall(MatCreateFromParCSR(shared, MATHYPRE, PETSC_USE_POINTER, hypre_[k].out()));
  for (std::size_t k = 0; k < scalars_.size(); ++k)
    PetscCall(PCSetOperators(scalars_[k], hypre_[k], hypre_[k]));
  PetscFunctionReturn(0);
}

PetscErrorCode ComponentPreconditioner::give_own_operators(Mat vector) {
  PetscFunctionBeginUser;
  const MPI_Comm comm = PetscObjectComm(reinterpret_cast<PetscObject>(vector));
  PetscInt first = 0, end = 0;
  PetscCall(MatGetOwnershipRange(vector, &first, &end));
  for (int j = 0; j < components_; ++j) {
    // A_j: rows and columns j, j + d, … (each rank owns whole vertices).
    IS rows = nullptr;
    PetscCall(ISCreateStride(comm, (end - first) / components_, first + j, components_, &rows));
    OwnedMat part;
    const PetscErrorCode e = MatCreateSubMatrix(vector, rows, rows, MAT_INITIAL_MATRIX, part.out());
    PetscCall(ISDestroy(&rows));
    PetscCall(e);
    if (boomeramg_) {  // only hypre's copy is kept
      PetscCall(convert_to_hypre(part, hypre_[j]));
      PetscCall(PCSetOperators(scalars_[j], hypre_[j], hypre_[j]));
    } else {
      parts_[j] = std::move(part);
      PetscCall(PCSetOperators(scalars_[j], parts_[j], parts_[j]));
    }
  }
  PetscFunctionReturn(0);
}

// For component j: part[i] = x[d · i + j] over this rank's entries (each rank owns whole
// vertices), op(slot, part, result), and y[d · i + j] = result[i].
template <class Op>
PetscErrorCode ComponentPreconditioner::for_each_component(Vec x, Vec y, int threads, Op op) const {
  PetscFunctionBeginUser;
  const int d = components_;
  const bool own = kind_ == ComponentOperators::Own;
  const PetscScalar* in = nullptr;
  PetscScalar* out = nullptr;
  PetscCall(VecGetArrayRead(x, &in));
  PetscCall(VecGetArray(y, &out));
  const auto on_component = [&](int slot, int j) {
    PetscFunctionBeginUser;
    Vec part_in = x_[slot], part_out = y_[slot];
    PetscInt n = 0;
    PetscCall(VecGetLocalSize(part_in, &n));
    PetscScalar* a = nullptr;
    PetscCall(VecGetArrayWrite(part_in, &a));
    for (PetscInt i = 0; i < n; ++i) a[i] = in[d * i + j];
    PetscCall(VecRestoreArrayWrite(part_in, &a));
    PetscCall(op(slot, part_in, part_out));
    const PetscScalar* b = nullptr;
    PetscCall(VecGetArrayRead(part_out, &b));
    for (PetscInt i = 0; i < n; ++i) out[d * i + j] = b[i];
    PetscCall(VecRestoreArrayRead(part_out, &b));
    PetscFunctionReturn(0);
  };
  std::vector<PetscErrorCode> failed(d, 0);
#pragma omp parallel for num_threads(threads) if (threads > 1)
  for (int j = 0; j < d; ++j) failed[j] = on_component(own ? j : omp_get_thread_num(), j);
  PetscCall(VecRestoreArray(y, &out));
  PetscCall(VecRestoreArrayRead(x, &in));
  for (const PetscErrorCode e : failed) PetscCall(e);
  PetscFunctionReturn(0);
}

PetscErrorCode ComponentPreconditioner::apply(PC shell, Vec x, Vec y) {
  PetscFunctionBeginUser;
  void* context = nullptr;
  PetscCall(PCShellGetContext(shell, &context));
  ComponentPreconditioner& p = *static_cast<ComponentPreconditioner*>(context);
  PetscCall(p.setup_first());
  const double start = MPI_Wtime();
  PetscCall(p.for_each_component(x, y, p.concurrent(), [&p](int slot, Vec in, Vec out) {
    return PCApply(p.scalars_[slot], in, out);
  }));
  if (p.kind_ == ComponentOperators::Shared) PetscCall(p.buy_further(MPI_Wtime() - start));
  PetscFunctionReturn(0);
}

PetscErrorCode ComponentPreconditioner::multiply(Mat shell, Vec x, Vec y) {
  PetscFunctionBeginUser;
  void* context = nullptr;
  PetscCall(MatShellGetContext(shell, &context));
  const ComponentPreconditioner& p = *static_cast<const ComponentPreconditioner*>(context);
  // Every slot has a hypre matrix: as many components at once as there are slots.
  const int slots = static_cast<int>(p.scalars_.size());
  const int at_once = p.concurrent_ ? std::min(slots, omp_get_max_threads()) : 1;
  PetscCall(p.for_each_component(
      x, y, at_once, [&p](int slot, Vec in, Vec out) { return MatMult(p.hypre_[slot], in, out); }));
  PetscFunctionReturn(0);
}

PetscErrorCode ComponentPreconditioner::buy_further(double seconds_applied) {
  PetscFunctionBeginUser;
  const int all = static_cast<int>(scalars_.size());
  if (ready_ == all || declined_) PetscFunctionReturn(0);
  // With all of them, d components take ⌈d / all⌉ applications' time instead of d.
  const int rounds = (components_ + all - 1) / all;
  would_have_saved_ += seconds_applied * (components_ - rounds) / components_;
  if (would_have_saved_ < setup_seconds_) PetscFunctionReturn(0);
  declined_ = spare_bytes() < 2.0 * (all - 1) * setup_bytes_;
  // One after the other: hypre's coarsening draws from one global random sequence, reseeded
  // at each set-up.
  for (int k = 1; k < all && !declined_; ++k) PetscCall(PCSetUp(scalars_[k]));
  if (!declined_) ready_ = all;
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
  PetscCall(PetscViewerASCIIPrintf(viewer,
                                   p.kind_ == ComponentOperators::Own
                                       ? "one for each of %d components, each of its own matrix; "
                                         "the first:\n"
                                       : "applied to each of %d components:\n",
                                   p.components_));
  PetscCall(PetscViewerASCIIPushTab(viewer));
  PetscCall(PCView(p.scalar(), viewer));
  PetscCall(PetscViewerASCIIPopTab(viewer));
  PetscFunctionReturn(0);
}

}  // namespace neomesh
