#include "solver/component_preconditioner.hpp"

#include <utility>

namespace neomesh {

namespace {

// part[i] = whole[d · i + j] over this rank's entries (each rank owns whole vertices). By
// hand rather than VecStrideGather, which needs the block size on the Vec.
PetscErrorCode gather(Vec whole, int d, int j, Vec part) {
  PetscFunctionBeginUser;
  const PetscScalar* in = nullptr;
  PetscScalar* out = nullptr;
  PetscInt n = 0;
  PetscCall(VecGetLocalSize(part, &n));
  PetscCall(VecGetArrayRead(whole, &in));
  PetscCall(VecGetArrayWrite(part, &out));
  for (PetscInt i = 0; i < n; ++i) out[i] = in[d * i + j];
  PetscCall(VecRestoreArrayWrite(part, &out));
  PetscCall(VecRestoreArrayRead(whole, &in));
  PetscFunctionReturn(0);
}

// whole[d · i + j] = part[i]; the other components are left as they are.
PetscErrorCode scatter(Vec part, int d, int j, Vec whole) {
  PetscFunctionBeginUser;
  const PetscScalar* in = nullptr;
  PetscScalar* out = nullptr;
  PetscInt n = 0;
  PetscCall(VecGetLocalSize(part, &n));
  PetscCall(VecGetArrayRead(part, &in));
  PetscCall(VecGetArray(whole, &out));
  for (PetscInt i = 0; i < n; ++i) out[d * i + j] = in[i];
  PetscCall(VecRestoreArray(whole, &out));
  PetscCall(VecRestoreArrayRead(part, &in));
  PetscFunctionReturn(0);
}

}  // namespace

ComponentPreconditioner::ComponentPreconditioner(OwnedPC scalar, int components)
    : scalar_(std::move(scalar)), components_(components) {}

void ComponentPreconditioner::install(PC shell) {
  NM_PETSC(PCSetType(shell, PCSHELL));
  NM_PETSC(PCShellSetContext(shell, this));
  NM_PETSC(PCShellSetApply(shell, apply));
  NM_PETSC(PCShellSetView(shell, view));
  NM_PETSC(PCShellSetName(shell, "per component"));
}

void ComponentPreconditioner::set_operator(Mat scalar, bool same_values) {
  NM_PETSC(PCSetOperators(scalar_, scalar, scalar));
  NM_PETSC(PCSetReusePreconditioner(scalar_, same_values ? PETSC_TRUE : PETSC_FALSE));
  NM_PETSC(MatCreateVecs(scalar, x_.out(), y_.out()));
}

void ComponentPreconditioner::setup() {
  NM_PETSC(PCSetUp(scalar_));
}

PetscErrorCode ComponentPreconditioner::apply(PC shell, Vec x, Vec y) {
  PetscFunctionBeginUser;
  void* context = nullptr;
  PetscCall(PCShellGetContext(shell, &context));
  const ComponentPreconditioner& p = *static_cast<const ComponentPreconditioner*>(context);
  for (int j = 0; j < p.components_; ++j) {
    PetscCall(gather(x, p.components_, j, p.x_));
    PetscCall(PCApply(p.scalar_, p.x_, p.y_));  // sets P₁ up first if A₁ changed
    PetscCall(scatter(p.y_, p.components_, j, y));
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
  PetscCall(PCView(p.scalar_, viewer));
  PetscCall(PetscViewerASCIIPopTab(viewer));
  PetscFunctionReturn(0);
}

}  // namespace neomesh
