// DofMap: how a per-vertex field with `dim` components (coordinates, gradient, direction)
// is laid out across ranks. A global PETSc Vec stores each vertex once, on its owning rank
// (dof = dim * vertex + component in PETSc's global numbering); a local array stores every
// vertex of the rank's MeshView, ghosts included, in MeshView's local vertex order.
//
// The numerics (energy/, solver/) see only this interface, never the DMPlex behind it.
#pragma once

#include <span>
#include <vector>

#include <petscsf.h>
#include <petscvec.h>

#include "core/petsc.hpp"

namespace neomesh {

class DofMap {
 public:
  // `sf` maps local dofs (leaves) to owned global dofs (roots); `global_dof` holds, per local
  // dof, its index in the global numbering. Takes a reference on `sf`. Null where local dof i is
  // global dof i on a single process: values are then copied, without an SF (whose graph holds
  // 16 bytes per dof for nothing).
  DofMap(MPI_Comm comm, int dim, PetscInt num_local_vertices, PetscInt num_owned_dofs, PetscSF sf,
         std::vector<PetscInt> global_dof);

  // A single process owning all `num_vertices` vertices (tests, serial tools).
  static DofMap serial(int dim, PetscInt num_vertices);

  MPI_Comm comm() const { return comm_; }
  int dim() const { return dim_; }
  PetscInt num_local_dofs() const { return static_cast<PetscInt>(global_dof_.size()); }
  PetscInt num_owned_dofs() const { return num_owned_dofs_; }
  PetscInt num_global_dofs() const { return num_global_dofs_; }
  const std::vector<PetscInt>& global_dof() const { return global_dof_; }

  // True if local dof i is global dof i on this one process: a global vector's array is then
  // the local array.
  bool local_is_global() const { return !sf_; }
  // A global vector (num_owned_dofs() entries on this rank), zeroed.
  OwnedVec create_global_vector() const;
  // local[i] = global value of local dof i (owned and ghost).
  void global_to_local(Vec global, std::span<double> local) const;
  // global += sum over ranks of their local contributions (ghost entries are sent to owners).
  void add_local_to_global(std::span<const double> local, Vec global) const;
  // local[i] = the sum over ranks of their local values of dof i, so that every rank holding
  // a vertex ends with the same total (sums over a vertex's cells when its cells lie on
  // several ranks). Collective; nothing to do on one process.
  void sum_over_ranks(std::span<double> local) const;

  // True if local dof i is global dof i for every i (so, on one process, no SF is needed).
  static bool is_identity(const std::vector<PetscInt>& global_dof);

 private:
  MPI_Comm comm_;
  int dim_;
  PetscInt num_owned_dofs_;
  PetscInt num_global_dofs_ = 0;
  OwnedSF sf_;  // null: local dof i is global dof i (one process)
  std::vector<PetscInt> global_dof_;
};

}  // namespace neomesh
