// The worst cells repaired locally (docs/method.md, "Worst cells"). The energy is a sum over
// cells: its optimum may leave a few cells far worse than all others where the boundary
// squeezes them (FEAT3's rotor: two cells at a scaled Jacobian of 0.30 in a mesh whose next
// worst is 0.52), because lifting them costs more energy elsewhere than it saves. Users judge a
// mesh by its worst cell, so after the optimization each interior vertex of the worst cells and
// of their neighbours is moved, one at a time, to where the worst cell around it is best: a
// pattern search over directions and step lengths (optimization-based smoothing, Freitag and
// Plassmann's max–min), accepting a move only if it raises the minimum scaled Jacobian of the
// vertex's cells. So no cell gets worse than the worst cell was. The mean can fall — each move
// lifts a vertex's worst cell at the cost of its others (Mesquite's flat-tet-sphere: 0.618 ->
// 0.579 over 3,811 moved vertices) — so a move that lowers it is refused below a floor.
//
// A boundary vertex moves as it slides: its fixed coordinates stay, and a trial point of a
// vertex on a curved boundary is put onto that boundary (the chart, shape or input facets it
// slides on) before it is judged. The search runs on rank 0 over the whole mesh in input
// numbering, so every number of ranks gives the same result.
#pragma once

#include <cstdint>
#include <functional>
#include <limits>
#include <span>
#include <vector>

#include "mesh/dof_map.hpp"
#include "mesh/mesh_view.hpp"

namespace neomesh {

// What the repair did.
struct WorstCellRepair {
  double min_before = 0.0, min_after = 0.0;  // the whole mesh's worst scaled Jacobian
  std::int64_t vertices_moved = 0;           // distinct vertices
  int sweeps = 0;
};

// The worst cells taken per sweep, and the sweeps at most; the repair ends earlier, at the
// first sweep with its shortest steps that does not lift the worst cell.
inline constexpr int kRepairWorstCells = 6;
inline constexpr int kRepairMaxSweeps = 400;
// The vertices of a cell that keeps its input cell as its target stay in the repair if that
// input cell's scaled Jacobian is at least this; for a kept quadrilateral, hexahedron or
// pyramid, whose target is right-angled, if the input cell and the optimum's are at least
// kKeptRightAngledMinScaledJacobian.
inline constexpr double kKeptCellMinScaledJacobian = 0.5;
// ... and if its target keeps at least this share of the input cell: a cell kept in part is a
// transition between a design and the ideal, no design of its own.
inline constexpr double kHeldInputShare = 0.5;
inline constexpr double kKeptRightAngledMinScaledJacobian = 0.9;

// How each local vertex may move.
struct RepairFreedom {
  std::vector<std::uint8_t> fixed;  // per local dof: 1 if that coordinate stays
  std::vector<int> geometry;        // per local vertex: what it slides on, or -1 (none)
  // Puts the point p (dim values) onto geometry g; called on rank 0 only.
  std::function<void(int g, std::span<double> p)> project;
};

// x (a global Vec laid out by `dofs`) is changed in place. No move that lowers the mesh's mean
// scaled Jacobian takes it below `min_mean`: smoothing's promise on the mean (quality_guard.hpp)
// is a budget the repair spends, not a trade it may lose. Likewise no move that raises the mean
// inverse mean ratio takes it above `max_mean_imr` (-∞: no move raises it; +∞, the default:
// not measured). Collective.
WorstCellRepair repair_worst_cells(const MeshView& view, const DofMap& dofs,
                                   const RepairFreedom& freedom, Vec x,
                                   double min_mean = -std::numeric_limits<double>::infinity(),
                                   double max_mean_imr = std::numeric_limits<double>::infinity());

}  // namespace neomesh
