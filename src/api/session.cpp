#include <neomesh/session.hpp>

#include <petscsys.h>

#include "core/petsc.hpp"

namespace neomesh {

Session::Session(int* argc, char*** argv) {
  PetscBool up = PETSC_FALSE;
  NM_PETSC(PetscInitialized(&up));
  if (up) return;
  configure_singleton_mpi();
  NM_PETSC(PetscInitialize(argc, argv, nullptr, nullptr));
  initialized_petsc_ = true;
}

Session::~Session() {
  if (initialized_petsc_) PetscFinalize();
}

}  // namespace neomesh
