#include "mesh/dof_map.hpp"

#include <numeric>

namespace neomesh {

DofMap::DofMap(MPI_Comm comm, int dim, PetscInt num_local_vertices, PetscInt num_owned_dofs,
               PetscSF sf, std::vector<PetscInt> global_dof)
    : comm_(comm), dim_(dim), num_owned_dofs_(num_owned_dofs), global_dof_(std::move(global_dof)) {
  if (static_cast<PetscInt>(global_dof_.size()) != num_local_vertices * dim)
    fail("DofMap: {} global indices for {} local vertices of dimension {}", global_dof_.size(),
         num_local_vertices, dim);
  NM_PETSC(PetscObjectReference(reinterpret_cast<PetscObject>(sf)));
  *sf_.out() = sf;
  MPI_Allreduce(&num_owned_dofs_, &num_global_dofs_, 1, MPIU_INT, MPI_SUM, comm_);
}

DofMap DofMap::serial(int dim, PetscInt num_vertices) {
  const PetscInt n = num_vertices * dim;
  OwnedSF sf;
  NM_PETSC(PetscSFCreate(PETSC_COMM_SELF, sf.out()));
  // Identity graph: leaf i ↔ root i.
  std::vector<PetscSFNode> roots(n);
  for (PetscInt i = 0; i < n; ++i) roots[i] = {0, i};
  NM_PETSC(PetscSFSetGraph(sf, n, n, nullptr, PETSC_COPY_VALUES, roots.data(), PETSC_COPY_VALUES));
  NM_PETSC(PetscSFSetUp(sf));
  std::vector<PetscInt> global(n);
  std::iota(global.begin(), global.end(), PetscInt{0});
  return DofMap(PETSC_COMM_SELF, dim, num_vertices, n, sf, std::move(global));
}

OwnedVec DofMap::create_global_vector() const {
  OwnedVec v;
  NM_PETSC(VecCreateMPI(comm_, num_owned_dofs_, num_global_dofs_, v.out()));
  NM_PETSC(VecZeroEntries(v));
  return v;
}

void DofMap::global_to_local(Vec global, std::span<double> local) const {
  VecReadView roots(global);
  NM_PETSC(PetscSFBcastBegin(sf_, MPIU_SCALAR, roots.data(), local.data(), MPI_REPLACE));
  NM_PETSC(PetscSFBcastEnd(sf_, MPIU_SCALAR, roots.data(), local.data(), MPI_REPLACE));
}

void DofMap::add_local_to_global(std::span<const double> local, Vec global) const {
  VecWriteView roots(global);
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
