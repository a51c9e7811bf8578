// Target cells for smoothing from the input cells (`--targets input|smoothed`; docs/method.md
// §9; the words are those of targets/cell_targets.hpp): per cell a desired volume, a target
// shape S (det S = 1) of the cell the energy pulls it towards, and a weight k of its energy.
// (`--targets ideal` needs none of this: the thesis' isotropic cells of the desired volumes the
// volume source, `--sizes`, gives, k = 1.)
//   TargetMode::Input      the input cell itself: its stretch and volume at its centre ("only
//                          untangle or repair": the input is the energy's minimum)
//   TargetMode::Smoothed   the input's design where it is coherent, ideal cells where it is
//                          noise
// Each cell's Jacobian at its centre, relative to its ideal cell, is J = s V R (det V = 1, R a
// rotation). A region stretched on purpose — a boundary layer, a graded CAD mesh — has its cells
// stretched alike: over the cells of the same type sharing a vertex with a cell, the mean of
// log V has an anisotropy Ā (log of largest over smallest stretch) close to the mean Â of
// their own. Noise stretches cells in scattered directions, which cancel in the mean. A cell
// keeps the share
//   w = ramp(Ā; kStretched) · ramp(Ā / Â; kCoherence)
// of its input cell: its size and, for a simplex or wedge, its shape S = V^w R; v = v_input^w
// v_sizes^(1−w) (then all volumes are scaled to the mesh volume). A mesher designs sizes and
// the stretch of a cell along its own edges (a layer's rectangles, a graded block's bricks),
// never skew: a kept quad, hexahedron or pyramid aims at the right-angled cell of its
// proportions — the rectangle or brick of its mean edge lengths, the right pyramid over the
// rectangle of its base edges — with the metric M of that cell, S_wᵀ S_w = M^w. A simplex has no
// right-angled form (a boundary layer of split quads is right triangles, which its affine
// stretch V keeps); a layer's prisms are extruded right prisms already, and a right-prism target
// moved the sphere's layer by up to 6 % (docs/method.md §9). Only cells of one type count:
// layers are made of one type, and the many
// tetrahedra or triangles around a layer's outer cells would hide it.
// A mesh generator's stretched cells are stretched along their edges (a layer's rectangles and
// prisms, a graded block's bricks); a mesh deformed afterwards (a moved vertex, a moved
// boundary) has its cells sheared, stretched across their edges, and a shear is no design: a
// cell whose stretch σ_max/σ_min exceeds its edge ratio (longest over shortest edge) by the
// factor f keeps the share w · (1 − ramp(f; kSheared)) only. (A 10:1 rectangle or right
// triangle: f = 1–1.15; a rhombus of 30°: f = 3.7; the thesis' square-midpoint, a grid
// deformed by moving its middle vertex: up to 25.) Simplices are judged by coherence alone:
// each is an affine image of the ideal one, and on FEAT3's triangle meshes (venturi-pipe-tria,
// the rotor's) the factor made the worst cell worse.
// A kept cell is as thin as its shortest edge, so its energy is small against that of its
// neighbours, which would squash it (a boundary layer's first heights: ±8 % with k = 1):
// its weight k = (C a)^w, with a = σ_max(V)^d the volume of the isotropic cell spanning its
// longest edge over its own, C = kKeptStiffness; prisms, what 3D layers are made of, are held
// by the many tetrahedra around them only with C = kKeptWedgeStiffness (docs/method.md has the
// measurements).
// When no cell is kept the targets are the ideal ones exactly (no shapes). Inverted input
// cells have no shape of their own: their targets are ideal (Optimizer::smooth takes ideal
// targets for every cell of a tangled input).
#pragma once

#include <span>
#include <vector>

#include <neomesh/options.hpp>

#include "mesh/dof_map.hpp"
#include "mesh/mesh_view.hpp"
#include "targets/cell_targets.hpp"

namespace neomesh {

// The constants of Smoothed (docs/method.md §9): the ramps' ends, of the mean's anisotropy (a
// grid of right triangles, 1.73 from the equilateral one, is never kept) and of the coherence
// Ā / Â; and C.
struct Ramp {
  double from, to;
};
inline constexpr Ramp kCoherence{0.5, 0.8}, kStretched{2.0, 3.5}, kSheared{2.0, 4.0};
inline constexpr double kKeptStiffness = 7.0;
inline constexpr double kKeptWedgeStiffness = 100.0;

// Whether a kept cell of this type aims at the right-angled cell of its proportions (quad,
// hexahedron, pyramid); simplices and wedges keep their input shape (see above).
inline bool right_angled_target(CellType type) {
  return !is_simplex(type) && type != CellType::Wedge;
}

// `cell_volumes`: each local cell's actual volume; `jacobians`: each local cell's Jacobian at
// its centre relative to its unit ideal cell (Functional::cell_jacobians); `edge_ratios`: each
// local cell's longest over shortest edge; `ideal_volumes`: the desired volumes of the ideal
// targets (desired_volumes.hpp), for the cells not kept. `mode`: Input or Smoothed. Collective.
CellTargets input_targets(TargetMode mode, const MeshView& view, const DofMap& dofs,
                          std::span<const double> cell_volumes, std::span<const double> jacobians,
                          std::span<const double> edge_ratios, std::vector<double> ideal_volumes);

// How many cells over all ranks keep all of their input cell (input share w = 1), part of it,
// or none. Collective.
struct KeptCells {
  long long all = 0, part = 0, none = 0;
};
KeptCells count_kept(std::span<const double> input_share, MPI_Comm comm);

}  // namespace neomesh
