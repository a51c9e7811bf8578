#include "core/petsc.hpp"

namespace neomesh {

void check_petsc(PetscErrorCode code, const char* call, const char* file, int line) {
  if (code == 0) return;
  const char* text = nullptr;
  char* specific = nullptr;
  PetscErrorMessage(code, &text, &specific);
  throw Error(fmt::format("PETSc error {} in {} ({}:{}): {}{}{}", static_cast<int>(code), call,
                          file, line, text ? text : "", specific ? ": " : "",
                          specific ? specific : ""));
}

VecReadView::VecReadView(Vec v) : vec_(v) {
  NM_PETSC(VecGetLocalSize(v, &size_));
  NM_PETSC(VecGetArrayRead(v, &data_));
}
VecReadView::~VecReadView() {
  VecRestoreArrayRead(vec_, &data_);
}

VecWriteView::VecWriteView(Vec v) : vec_(v) {
  NM_PETSC(VecGetLocalSize(v, &size_));
  NM_PETSC(VecGetArray(v, &data_));
}
VecWriteView::~VecWriteView() {
  VecRestoreArray(vec_, &data_);
}

int mpi_rank(MPI_Comm comm) {
  int r = 0;
  MPI_Comm_rank(comm, &r);
  return r;
}
int mpi_size(MPI_Comm comm) {
  int s = 1;
  MPI_Comm_size(comm, &s);
  return s;
}

}  // namespace neomesh
