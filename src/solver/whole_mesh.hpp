// The whole mesh on rank 0, vertices and cells in input order, for the worst-cell repairs
// (worst_cell_repair.hpp, curved_repair.hpp), which search on one process so that every number
// of ranks gives the same result.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "mesh/cell_type.hpp"
#include "mesh/curved_type.hpp"
#include "mesh/dof_map.hpp"
#include "mesh/mesh_view.hpp"
#include "solver/worst_cell_repair.hpp"

namespace neomesh {

struct WholeMesh {
  int dim = 0;
  bool surface = false;                 // triangles and quadrilaterals in space (MeshView)
  std::vector<std::int64_t> vertex_id;  // input number per vertex (ascending)
  std::vector<double> coords;           // dim per vertex
  std::vector<std::uint8_t> fixed;      // per coordinate
  std::vector<int> geometry;            // per vertex: what it slides on, or -1
  std::vector<CellType> types;          // per cell (ascending input number)
  std::vector<std::int8_t> curved;      // per cell: its CurvedType, or -1 for a straight cell
  std::vector<std::int64_t> offsets;    // cell c's vertices: vertices[offsets[c], offsets[c+1])
  std::vector<std::int64_t> vertices;   // indices into vertex_id
};

// Gathers the owned vertices of `view` at `local` (dim values per local vertex), how `freedom`
// lets them move, and all cells (straight or curved: every node a vertex) to rank 0 by input
// number; empty elsewhere. Collective.
WholeMesh gather_whole_mesh(const MeshView& view, std::span<const double> local,
                            const RepairFreedom& freedom, MPI_Comm comm);

// Collective: writes the coordinates `coords` (dim per vertex) of the vertices with input
// numbers `ids` (ascending), given on rank 0, into x on the ranks that own them. Returns how
// many vertices that was.
std::int64_t scatter_moved(const MeshView& view, const DofMap& dofs, std::vector<std::int64_t> ids,
                           std::vector<double> coords, Vec x);

}  // namespace neomesh
