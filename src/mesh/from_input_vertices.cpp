#include "mesh/from_input_vertices.hpp"

namespace neomesh {

FromInputVertices::FromInputVertices(const MeshView& view, PetscInt input_vertices, MPI_Comm comm)
    : view_(view) {
  if (mpi_size(comm) == 1) return;  // a star forest of every vertex costs more than a copy
  const PetscInt nv = view.num_vertices;
  std::vector<PetscSFNode> remote(nv);
  for (PetscInt v = 0; v < nv; ++v) remote[v] = {0, view.input_vertex[v]};
  NM_PETSC(PetscSFCreate(comm, sf_.out()));
  NM_PETSC(PetscSFSetGraph(sf_, input_vertices, nv, nullptr, PETSC_COPY_VALUES, remote.data(),
                           PETSC_COPY_VALUES));
}

void FromInputVertices::broadcast(const void* table, void* out, MPI_Datatype type, int k) const {
  // k values per vertex as one unit, so that one star forest serves every k.
  MPI_Datatype unit = type;
  if (k != 1) {
    MPI_Type_contiguous(k, type, &unit);
    MPI_Type_commit(&unit);
  }
  NM_PETSC(PetscSFBcastBegin(sf_, unit, table, out, MPI_REPLACE));
  NM_PETSC(PetscSFBcastEnd(sf_, unit, table, out, MPI_REPLACE));
  if (k != 1) MPI_Type_free(&unit);
}

}  // namespace neomesh
