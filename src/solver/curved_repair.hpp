// The worst curved cells repaired locally (docs/method.md §12, "The solver"), as
// worst_cell_repair.hpp repairs straight ones. The energy samples det J at its Gauss points and
// the certified barrier (QuasiNewtonOptions::admissible) stops its steps where a cell would fold
// between them, so the optimum of a curved boundary-layer mesh may keep a few cells far worse
// than the rest. Each node of the worst cells and of their neighbours (corners, edge, face and
// centre nodes alike) is moved, one at a time, to where the least curved scaled Jacobian of its
// cells is best: the same pattern search over directions and step lengths, a move accepted only
// if its cells stay certified valid and their worst rises. So no cell gets worse than the worst
// cell was.
//
// Each trial measures its cells over their whole reference cell (curved_scaled_jacobian: Bézier
// coefficients of det J, subdivided), which costs far more than a straight cell's corners: the
// search stops when it has computed kCurvedRepairAllowance coefficients plus
// kCurvedRepairPerCell for each coefficient of a whole cell of the mesh (the sphere of
// bench/curve_boundary_layer.py, 2,300 wedge18 and 1,207 tetrahedron10: its worst cell from
// 0.093 to 0.099, the whole `curve` in 10 s).
#pragma once

#include <cstdint>

#include "mesh/curved_type.hpp"
#include "mesh/dof_map.hpp"
#include "mesh/mesh_view.hpp"
#include "solver/worst_cell_repair.hpp"

namespace neomesh {

inline constexpr std::int64_t kCurvedRepairAllowance = 6'000'000;
inline constexpr std::int64_t kCurvedRepairPerCell = 1;

// The Bézier coefficients of det J on a whole cell of this type (curved_cell.hpp).
int jacobian_bezier_size(CurvedType type);

// x (a global Vec laid out by `dofs`, the node mesh's) is changed in place; `view` holds the
// curved cells (every block CellBlock::curved). min_before and min_after are the least curved
// scaled Jacobian; below −2 where a cell is not certified valid (its sampled value − 3).
// Collective.
WorstCellRepair repair_worst_curved_cells(const MeshView& view, const DofMap& dofs,
                                          const RepairFreedom& freedom, Vec x);

}  // namespace neomesh
