// What a PlexMesh holds, for the files of the mesh layer (readers, writers); other layers use
// mesh.hpp only.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "mesh/input_mesh.hpp"
#include "mesh/plex_mesh.hpp"

namespace neomesh {

struct PlexMesh::Impl {
  MPI_Comm comm = MPI_COMM_NULL;
  OwnedDM dm;            // distributed cells and vertices (plex_builder.hpp)
  int dim = 2;           // of the cells
  bool surface = false;  // 2D cells in space (InputMesh::surface): 3 coordinates per vertex
  int coord_dim() const { return surface ? 3 : dim; }
  std::string source;
  PetscInt global_num_cells = 0;
  PetscInt global_num_vertices = 0;
  std::vector<PhysicalGroup> groups;  // the same on every rank, sorted by (dim, tag)
  // Rank 0 only, for the writers: per input cell its physical tag (0 for none), and the facets
  // and points of physical groups in input numbering (input_topology.hpp).
  std::vector<int> cell_tags;
  TaggedEntities facets, points;
  // Rank 0 only: the input's point and cell data in input numbering, written back unchanged.
  std::vector<DataArray> point_data, cell_data;
  TimeSteps steps;                              // rank 0 only, as the data
  std::shared_ptr<const PlaneEmbedding> plane;  // 2D off z = 0 (input_mesh.hpp)
  // Second-order cells (on every rank) and, on rank 0 only, their nodes beyond the corners in
  // input numbering (input_mesh.hpp).
  bool curved = false;
  HighOrderNodes high_order;
  // The coordinates' one owner is view->coords; the DMPlex's are brought up to date only when
  // someone asks for the DM (PlexMesh::dm()), not at every move.
  std::unique_ptr<MeshView> view;
  bool dm_coordinates_stale = false;
  std::uint64_t coordinates_version = 0;  // set_coordinates calls so far
  std::unique_ptr<DofMap> dofs;
};

// The mesh layer's way in: Impl by name, and PlexMesh's private constructor.
struct MeshAccess {
  using Impl = PlexMesh::Impl;
  static const Impl& impl(const PlexMesh& mesh) { return *mesh.impl_; }
  static PlexMesh create(std::unique_ptr<Impl> impl) { return PlexMesh(std::move(impl)); }
};

}  // namespace neomesh
