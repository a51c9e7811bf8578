// neomesh runs on PETSc (and MPI). A program that has not initialized PETSc itself creates one
// Session for its lifetime; one that has (a PETSc or MPI application) does not need it.
#pragma once

namespace neomesh {

class Session {
 public:
  // Initializes MPI and PETSc unless already done (then changes nothing). `argc`/`argv` go to
  // PETSc, which reads its own options (-hess_ksp_type ...) from them; both may be null.
  Session(int* argc = nullptr, char*** argv = nullptr);
  // Finalizes what the constructor initialized.
  ~Session();
  Session(const Session&) = delete;
  Session& operator=(const Session&) = delete;

 private:
  bool initialized_petsc_ = false;
};

}  // namespace neomesh
