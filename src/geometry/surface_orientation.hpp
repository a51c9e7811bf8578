// geometry/surface_orientation.hpp — which side each cell of a surface mesh faces: its
// reference normal, the one normal that the surface kernel's frames (energy/problem.hpp:
// surface_frames), the quality measures (quality.hpp) and the features of the surface
// (boundary/features.hpp) see the cell along (docs/method.md, "Folded surface cells").
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "mesh/dof_map.hpp"
#include "mesh/mesh_view.hpp"

namespace neomesh {

// Per polygon (triangle or quadrilateral) of a consistently oriented surface: 1 if it is folded
// over the surface around it. The polygons are CSR (`offsets`, `vertices`: indices into
// `coords`, 3 values per vertex) with their vertices in cyclic order. A polygon is folded when
// its own normal (Newell's) points against the sum of its vertices' normals, a vertex's normal
// being the sum of the unit normals of the polygons around it, each weighted by the polygon's
// interior angle at the vertex — so that the two sides of a ridge, however sharp, count alike
// whatever the sizes of their cells — and a polygon judged folded counting with its normal
// reversed. The judgement is repeated until it no longer changes (at most kFoldRounds times),
// so that a fold of several cells is found from its rim inwards. A polygon without area is not
// folded. `dofs` (3 components per vertex of `coords`) sums a vertex's normal over the ranks
// that hold its polygons; null: over these polygons alone (a whole surface on one process).
std::vector<std::uint8_t> folded_polygons(std::span<const PetscInt> offsets,
                                          std::span<const PetscInt> vertices,
                                          std::span<const double> coords, const DofMap* dofs);

// Per local cell of the surface mesh `view` its reference unit normal at `coords` (view.coords'
// layout), 3 numbers per cell: its own normal (surface_cell_normal), reversed where it is folded
// (folded_polygons); zero for a cell without area. `dofs` as for folded_polygons.
std::vector<double> surface_reference_normals(const MeshView& view, std::span<const double> coords,
                                              const DofMap* dofs);

}  // namespace neomesh
