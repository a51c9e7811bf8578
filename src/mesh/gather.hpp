// The whole mesh on rank 0, for the writers: coordinates, cells and physical groups in input
// numbering (so a parallel run writes the same file as a serial one), with the fields.
#pragma once

#include <numeric>
#include <utility>
#include <vector>

#include <neomesh/field.hpp>

#include "core/petsc.hpp"
#include "mesh/input_mesh.hpp"
#include "mesh/plex_mesh.hpp"

namespace neomesh {

// What is written with a mesh: fields per local cell (MeshView order) and per local vertex
// (MeshView order; the owned vertices' values are written), facet groups (input vertex
// numbers).
struct MeshFields {
  std::vector<Field> cell;
  std::vector<Field> vertex;
  std::vector<FacetGroup> facet_groups;
};

// Concatenation of every rank's `local` on rank 0, with each rank's length.
template <typename T>
std::vector<T> gatherv(MPI_Comm comm, const std::vector<T>& local, MPI_Datatype type) {
  const int size = mpi_size(comm), rank = mpi_rank(comm);
  int count = static_cast<int>(local.size());
  std::vector<int> counts(size), offsets(size + 1, 0);
  MPI_Gather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, comm);
  std::partial_sum(counts.begin(), counts.end(), offsets.begin() + 1);
  std::vector<T> all(rank == 0 ? offsets[size] : 0);
  MPI_Gatherv(local.data(), count, type, all.data(), counts.data(), offsets.data(), type, 0, comm);
  return all;
}
// The same, taking `local`: on one rank it is the result (no copy), and elsewhere it is freed
// before returning, so that rank 0 does not hold its share twice while it builds on the result.
template <typename T>
std::vector<T> gatherv(MPI_Comm comm, std::vector<T>&& local, MPI_Datatype type) {
  if (mpi_size(comm) == 1) return std::move(local);
  std::vector<T> all = gatherv(comm, std::as_const(local), type);
  std::vector<T>().swap(local);
  return all;
}

struct GatheredMesh {
  InputMesh mesh;        // cells by input number; facets and points in physical groups; the
                         // input's point and cell data
  MeshFields fields;     // cell fields by input cell number, vertex fields by input vertex
  bool has_cell_groups;  // cells carry physical tags (written as the cell field "physical")
};

// Collective; the result is complete on rank 0 and empty elsewhere. Throws Error if a
// field's size does not match the mesh.
GatheredMesh gather_mesh(const PlexMesh& mesh, const MeshFields& fields);

// For the writers: where the input's data and the fields share a name (per vertex or per cell),
// the input's array keeps it and the field is renamed "neomesh_<name>". An input array of that
// name too (a field of an earlier run, renamed so) is replaced by the field.
void make_room_for_data(GatheredMesh& gathered);

}  // namespace neomesh
