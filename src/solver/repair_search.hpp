// What the worst-cell repairs (worst_cell_repair.hpp, curved_repair.hpp) share: the whole mesh
// on rank 0, vertices and cells in input order, where they search so that every number of ranks
// gives the same result; the pattern search's steps and directions; and the sweeps.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "core/petsc.hpp"
#include "mesh/cell_type.hpp"
#include "mesh/curved_type.hpp"
#include "mesh/dof_map.hpp"
#include "mesh/mesh_view.hpp"
#include "solver/worst_cell_repair.hpp"

namespace neomesh {

// The whole mesh on rank 0, vertices and cells in input order.
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

// The pattern search both repairs make, around one vertex (node) at a time.
// Step lengths of the search, in units of the vertex's shortest edge: the longest first; a
// shorter one is tried only when no direction of a longer one improved. Shorter steps only
// once these no longer lift the worst cell, and then without the long ones: tried by every
// vertex from the start, they cost 1.7x the time on Gmsh's twisted hex block for nothing
// (bench/hex_meshes.py); after the stall they take Mesquite's biased 1000-hex block from
// 0.994 to 0.997.
inline constexpr double kRepairSteps[] = {0.3, 0.1, 0.03, 0.01};
inline constexpr double kRepairFineSteps[] = {0.01, 0.003, 0.001};
// A move must raise the worst cell around the vertex by more than this.
inline constexpr double kRepairGain = 1e-9;
// ... and keep the vertex at least this fraction of its distance at the repair's start from
// each vertex of its cells: the scaled Jacobian measures angles, so without it a vertex sliding
// along the boundary could collapse an edge of a cell and still "improve" it.
inline constexpr double kRepairMinDistanceFraction = 0.5;

// Unit directions of the search: 16 in the plane, the 26 towards a cube's neighbours in 3D.
std::vector<std::array<double, 3>> repair_directions(int dim);

// The sweeps of a repair on rank 0, over the whole mesh gathered there: `make_search(mesh)`
// makes the search (worst_cell_repair.cpp's Repair, curved_repair.cpp's CurvedRepair), which
// has min_quality(), begin_sweep(), sweep(steps, moved) (appends the vertices it moves),
// undo_sweep() and done() (no sweep more). Sweeps run with kRepairSteps until one no longer
// lifts the worst cell (moves elsewhere may go on improving a little for long), then once more
// with kRepairFineSteps; a sweep that does not lift it is undone: its moves lift cells around a
// vertex at the cost of others and so only lower the mean (FEAT3's heat-v77-tria: 11 vertices
// moved, the worst cell unchanged, the mean scaled Jacobian 0.735 -> 0.719). x (a global Vec
// laid out by `dofs`) gets the moved vertices. Collective.
template <typename MakeSearch>
WorstCellRepair repair_in_sweeps(const MeshView& view, const DofMap& dofs,
                                 const RepairFreedom& freedom, Vec x, MakeSearch make_search) {
  const MPI_Comm comm = dofs.comm();
  const int d = view.dim;
  std::vector<double> local(dofs.num_local_dofs());
  dofs.global_to_local(x, local);
  WholeMesh mesh = gather_whole_mesh(view, local, freedom, comm);

  WorstCellRepair summary;
  std::vector<std::int64_t> moved_ids;
  std::vector<double> moved_coords;
  if (mpi_rank(comm) == 0) {
    auto repair = make_search(mesh);
    summary.min_before = repair.min_quality();
    std::vector<std::uint8_t> moved(mesh.vertex_id.size(), 0);  // per vertex
    std::vector<std::int64_t> moved_now;                        // by the sweep
    std::span<const double> steps = kRepairSteps;
    for (double worst = summary.min_before; summary.sweeps < kRepairMaxSweeps && !repair.done();) {
      repair.begin_sweep();
      moved_now.clear();
      repair.sweep(steps, moved_now);
      ++summary.sweeps;
      const double now = repair.min_quality();
      if (moved_now.empty() || !(now > worst + kRepairGain)) {
        repair.undo_sweep();
        if (steps.data() == kRepairFineSteps) break;
        steps = kRepairFineSteps;  // the same sweep again, with shorter steps
        continue;
      }
      for (std::int64_t v : moved_now) moved[v] = 1;
      worst = now;
    }
    summary.min_after = repair.min_quality();
    for (std::int64_t v = 0; v < static_cast<std::int64_t>(moved.size()); ++v) {
      if (!moved[v]) continue;
      moved_ids.push_back(mesh.vertex_id[v]);
      moved_coords.insert(moved_coords.end(), mesh.coords.begin() + d * v,
                          mesh.coords.begin() + d * (v + 1));
    }
  }
  MPI_Bcast(&summary.min_before, 1, MPI_DOUBLE, 0, comm);
  MPI_Bcast(&summary.min_after, 1, MPI_DOUBLE, 0, comm);
  MPI_Bcast(&summary.sweeps, 1, MPI_INT, 0, comm);
  summary.vertices_moved = scatter_moved(view, dofs, moved_ids, moved_coords, x);
  return summary;
}

}  // namespace neomesh
