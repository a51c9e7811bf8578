// MeshView: this rank's part of the mesh as flat arrays, for the numerics. Built once per
// mesh; hot loops run over it, never through DMPlex calls per cell.
//
// Cells are partitioned without overlap: every cell of the global mesh is in exactly one
// rank's view. Vertices are "local": every vertex that a local cell touches, owned by this
// rank or a ghost owned by another (see DofMap for how local and global vectors relate).
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <petscsys.h>

#include "mesh/cell_type.hpp"
#include "mesh/curved_type.hpp"

namespace neomesh {

// Cells of one type. `vertices` holds nodes() local vertex indices per cell: num_vertices(type)
// in canonical order (cell_type.hpp), or for second-order cells (`curved`, whose straight cell is
// `type`) every node in Gmsh's order (curved_cell.hpp), each node a vertex of the view. The
// block's cells are cells [first_cell, first_cell + size()) of the per-cell arrays.
struct CellBlock {
  CellType type = CellType::Quadrilateral;
  PetscInt first_cell = 0;
  std::vector<PetscInt> vertices;
  std::optional<CurvedType> curved = std::nullopt;

  int nodes() const { return curved ? facts(*curved).nodes : num_vertices(type); }
  PetscInt size() const { return static_cast<PetscInt>(vertices.size()) / nodes(); }
  const PetscInt* cell(PetscInt c) const { return vertices.data() + c * nodes(); }
};

struct BoundarySurface;  // boundary_surface.hpp

struct BoundaryPartInfo {
  std::string name;  // physical name (may be empty for unnamed Gmsh groups)
  int tag = 0;       // physical tag
};

struct MeshView {
  int dim = 2;  // coordinates per vertex
  // A surface mesh (docs/method.md, "Surface cells"): triangles and quadrilaterals in space,
  // dim = 3. Its boundary (`boundary`, `on_boundary`) is the surface itself: every vertex slides
  // on the input's cells, which play the part the boundary facets play in a volume mesh.
  bool surface = false;
  PetscInt num_vertices = 0;   // local: owned + ghost
  PetscInt num_cells = 0;      // cells of this rank (sum over blocks)
  std::vector<double> coords;  // num_vertices × dim, coordinates when the view was made
  std::vector<CellBlock> blocks;
  std::vector<std::uint8_t> owned;        // per local vertex: 1 if this rank owns it
  std::vector<std::uint8_t> on_boundary;  // per local vertex: 1 on the domain's boundary
  // Per local vertex: index into `parts` of a boundary part containing it, or -1. A vertex
  // where parts meet (a corner) has `part_count` > 1.
  std::vector<int> boundary_part;
  std::vector<std::uint8_t> part_count;
  std::vector<BoundaryPartInfo> parts;
  std::vector<PetscInt> global_cell;   // per local cell: cell number in the input file (0-based)
  std::vector<PetscInt> input_vertex;  // per local vertex: its number in the input (0-based)
  // The whole input boundary, the same on every rank (what sliding vertices slide on); a
  // surface mesh's is replaced when the caller moves the surface
  // (PlexMesh::move_surface_to_coordinates).
  std::shared_ptr<const BoundarySurface> boundary;

  // The dimension of the cells: dim, or 2 on a surface.
  int cell_dim() const { return surface ? 2 : dim; }
};

}  // namespace neomesh
