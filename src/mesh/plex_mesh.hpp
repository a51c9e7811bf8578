// PlexMesh: a DMPlex plus what neomesh needs around it — where it came from (for error
// messages), its physical groups, and the flat views the numerics run on.
//
// Serial by default; under `mpiexec -n P` from_data/from_input take the mesh on rank 0 and
// distribute the cells over the ranks (DMPlexDistribute, no overlap). Reading a mesh file:
// load_mesh() (formats/mesh_io.hpp).
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "core/petsc.hpp"
#include "mesh/dof_map.hpp"
#include "mesh/mesh_data.hpp"
#include "mesh/mesh_view.hpp"

namespace neomesh {

struct InputMesh;  // input_mesh.hpp

class PlexMesh {
 public:
  // Builds a mesh from arrays given on rank 0 (other ranks pass an empty MeshData).
  static PlexMesh from_data(const MeshData& data, const std::string& source,
                            MPI_Comm comm = PETSC_COMM_WORLD, bool keep_inverted = false);

  // Builds a mesh from an InputMesh on rank 0 (other ranks pass an empty one). `cell_groups`
  // (rank 0; empty: none) keeps groups of consecutive cells on one rank (distribute_plex in
  // plex_builder.hpp).
  static PlexMesh from_input(InputMesh& input, const std::string& source,
                             MPI_Comm comm = PETSC_COMM_WORLD, bool keep_inverted = false,
                             std::span<const PetscInt> cell_groups = {});

  PlexMesh(PlexMesh&&) noexcept;
  PlexMesh& operator=(PlexMesh&&) noexcept;
  ~PlexMesh();

  MPI_Comm comm() const;
  // The DMPlex, its coordinates brought up to date with view().coords.
  DM dm() const;
  int dim() const;
  const std::string& source() const;  // file name or generator name, for messages
  PetscInt global_num_cells() const;
  PetscInt global_num_vertices() const;
  // True for a mesh of second-order cells (InputMesh::high_order): the DMPlex and the view hold
  // their corners, the writers their other nodes too.
  bool curved() const;

  // This rank's cells and vertices as flat arrays (built once, cached).
  const MeshView& view() const;
  // The layout of per-vertex vectors with dim() components (built once, cached).
  const DofMap& dofs() const;

  // Current vertex coordinates as a global Vec laid out by dofs() (a new Vec).
  OwnedVec coordinates() const;
  // Moves the vertices: `coords` is a global Vec laid out by dofs(). view().coords is the one
  // place that holds them (dm() updates the DMPlex's when asked).
  void set_coordinates(Vec coords);
  // Moves a curved mesh's high-order nodes (rank 0; the other ranks pass nothing): `x` holds
  // dim() coordinates per node, in input numbering (a 2D mesh's in its plane). Collective.
  void set_high_order_nodes(std::span<const double> x);
  // On a surface mesh: the surface its vertices slide on, view().boundary, becomes its cells at
  // the current coordinates (the caller moved the surface). A new BoundarySurface: what was
  // built on the old one keeps it and tells by comparing pointers. Collective.
  void move_surface_to_coordinates();
  // Changes with every set_coordinates: what was computed from the coordinates at another
  // version is stale.
  std::uint64_t coordinates_version() const;

 private:
  struct Impl;
  explicit PlexMesh(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
  friend struct MeshAccess;  // for the writers in this layer
};

}  // namespace neomesh
