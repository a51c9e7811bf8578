#include "mesh/dof_map.hpp"

#include <algorithm>
#include <numeric>

namespace neomesh {

DofMap::DofMap(MPI_Comm comm, int dim, PetscInt num_local_vertices, PetscInt num_owned_dofs,
               PetscSF sf, std::vector<PetscInt> global_dof)
    : comm_(comm), dim_(dim), num_owned_dofs_(num_owned_dofs), global_dof_(std::move(global_dof)) {
  if (static_cast<PetscInt>(global_dof_.size()) != num_local_vertices * dim)
    fail("DofMap: {} global indices for {} local vertices of dimension {}", global_dof_.size(),
         num_local_vertices, dim);
  if (sf) {
    NM_PETSC(PetscObjectReference(reinterpret_cast<PetscObject>(sf)));
    *sf_.out() = sf;
  } else if (mpi_size(comm_) != 1 || !is_identity(global_dof_) ||
             num_owned_dofs_ != num_local_dofs()) {
    fail("internal error: a DofMap without an SF whose local dofs are not the global ones");
  }
  MPI_Allreduce(&num_owned_dofs_, &num_global_dofs_, 1, MPIU_INT, MPI_SUM, comm_);
}

bool DofMap::is_identity(const std::vector<PetscInt>& global_dof) {
  for (std::size_t i = 0; i < global_dof.size(); ++i)
    if (global_dof[i] != static_cast<PetscInt>(i)) return false;
  return true;
}

DofMap DofMap::serial(int dim, PetscInt num_vertices) {
  const PetscInt n = num_vertices * dim;
  std::vector<PetscInt> global(n);
  std::iota(global.begin(), global.end(), PetscInt{0});
  return DofMap(PETSC_COMM_SELF, dim, num_vertices, n, nullptr, std::move(global));
}

OwnedVec DofMap::create_global_vector() const {
  OwnedVec v;
  NM_PETSC(VecCreateMPI(comm_, num_owned_dofs_, num_global_dofs_, v.out()));
  NM_PETSC(VecZeroEntries(v));
  return v;
}

void DofMap::global_to_local(Vec global, std::span<double> local) const {
  VecReadView roots(global);
  if (!sf_) {
    std::copy_n(roots.data(), num_local_dofs(), local.data());
    return;
  }
  NM_PETSC(PetscSFBcastBegin(sf_, MPIU_SCALAR, roots.data(), local.data(), MPI_REPLACE));
  NM_PETSC(PetscSFBcastEnd(sf_, MPIU_SCALAR, roots.data(), local.data(), MPI_REPLACE));
}

void DofMap::add_local_to_global(std::span<const double> local, Vec global) const {
  VecWriteView roots(global);
  if (!sf_) {
    for (PetscInt i = 0; i < num_local_dofs(); ++i) roots[i] += local[i];
    return;
  }
  NM_PETSC(PetscSFReduceBegin(sf_, MPIU_SCALAR, local.data(), roots.data(), MPI_SUM));
  NM_PETSC(PetscSFReduceEnd(sf_, MPIU_SCALAR, local.data(), roots.data(), MPI_SUM));
}

void DofMap::sum_over_ranks(std::span<double> local) const {
  if (mpi_size(comm_) == 1) return;
  OwnedVec global = create_global_vector();
  add_local_to_global(local, global);
  global_to_local(global, local);
}

}  // namespace neomesh
