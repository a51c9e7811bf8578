// The boundary to PETSc: error checking that turns a PETSc error code into neomesh::Error,
// and small RAII owners for PETSc objects so that no code path leaks or double-destroys.
#pragma once

#include <petscdm.h>
#include <petscdmplex.h>
#include <petscksp.h>
#include <petscmat.h>
#include <petscsf.h>
#include <petscvec.h>

#include <utility>

#include "core/error.hpp"

namespace neomesh {

// Throws neomesh::Error carrying PETSc's own message when `code` is non-zero.
void check_petsc(PetscErrorCode code, const char* call, const char* file, int line);

}  // namespace neomesh

#define NM_PETSC(call) ::neomesh::check_petsc((call), #call, __FILE__, __LINE__)

namespace neomesh {

// Owner of one PETSc object handle (Vec, Mat, KSP, DM, IS, PetscSection, ...). Moves, never
// copies; destroys with the matching XxxDestroy on scope exit.
template <typename Handle, PetscErrorCode (*Destroy)(Handle*)>
class PetscOwner {
 public:
  PetscOwner() = default;
  explicit PetscOwner(Handle h) : handle_(h) {}
  PetscOwner(const PetscOwner&) = delete;
  PetscOwner& operator=(const PetscOwner&) = delete;
  PetscOwner(PetscOwner&& other) noexcept : handle_(std::exchange(other.handle_, nullptr)) {}
  PetscOwner& operator=(PetscOwner&& other) noexcept {
    if (this != &other) {
      reset();
      handle_ = std::exchange(other.handle_, nullptr);
    }
    return *this;
  }
  ~PetscOwner() { reset(); }

  void reset() {
    if (handle_) Destroy(&handle_);
    handle_ = nullptr;
  }
  // For PETSc creation functions: `VecCreate(comm, v.out())`.
  Handle* out() {
    reset();
    return &handle_;
  }
  Handle get() const { return handle_; }
  operator Handle() const { return handle_; }
  explicit operator bool() const { return handle_ != nullptr; }

 private:
  Handle handle_ = nullptr;
};

using OwnedVec = PetscOwner<Vec, VecDestroy>;
using OwnedMat = PetscOwner<Mat, MatDestroy>;
using OwnedKSP = PetscOwner<KSP, KSPDestroy>;
using OwnedDM = PetscOwner<DM, DMDestroy>;
using OwnedIS = PetscOwner<IS, ISDestroy>;
using OwnedSection = PetscOwner<PetscSection, PetscSectionDestroy>;
using OwnedSF = PetscOwner<PetscSF, PetscSFDestroy>;
using OwnedScatter = PetscOwner<VecScatter, VecScatterDestroy>;

// A new Vec with v's layout and values (a state to go back to).
OwnedVec copy_of(Vec v);

// Read-only / read-write views of a Vec's local array, restored on scope exit.
class VecReadView {
 public:
  explicit VecReadView(Vec v);
  ~VecReadView();
  VecReadView(const VecReadView&) = delete;
  VecReadView& operator=(const VecReadView&) = delete;
  const PetscScalar* data() const { return data_; }
  PetscInt size() const { return size_; }
  const PetscScalar& operator[](PetscInt i) const { return data_[i]; }

 private:
  Vec vec_;
  const PetscScalar* data_ = nullptr;
  PetscInt size_ = 0;
};

class VecWriteView {
 public:
  explicit VecWriteView(Vec v);
  ~VecWriteView();
  VecWriteView(const VecWriteView&) = delete;
  VecWriteView& operator=(const VecWriteView&) = delete;
  PetscScalar* data() { return data_; }
  PetscInt size() const { return size_; }
  PetscScalar& operator[](PetscInt i) { return data_[i]; }

 private:
  Vec vec_;
  PetscScalar* data_ = nullptr;
  PetscInt size_ = 0;
};

// Before PetscInitialize: a process not started by mpiexec skips Open MPI's singleton daemon
// and network-transport probing (unless the user's environment says otherwise).
void configure_singleton_mpi();

int mpi_rank(MPI_Comm comm = PETSC_COMM_WORLD);
int mpi_size(MPI_Comm comm = PETSC_COMM_WORLD);

// The scalar AIJ matrix A of a MATMAIJ made by MatCreateMAIJ(A, d) (the d-component operator
// that applies A to each interlaced component), or null if `m` is not a MAIJ.
Mat maij_scalar(Mat m);

}  // namespace neomesh
