// Smoothing's desired volumes from the input cells, by the volume source (SizeMode, `--sizes`;
// the words are those of targets/cell_targets.hpp). Real meshes are graded — fine near a
// cylinder, coarse far away — so making every cell the same size would wreck them:
//   uniform   every cell gets |Ω| / N (the thesis' setting and its test cases)
//   input     every cell keeps its own input volume
//   smoothed  the input volumes averaged over neighbouring cells a few times: the grading
//             stays while noise from badly shaped cells is removed (default)
// All are scaled so that they sum to the mesh volume |Ω|. Cells with a non-positive input
// volume (inverted, to be untangled) take their neighbours' volumes.
#pragma once

#include <span>
#include <string_view>
#include <vector>

#include <neomesh/options.hpp>

#include "mesh/dof_map.hpp"
#include "mesh/mesh_view.hpp"

namespace neomesh {

// `cell_volumes`: actual volume of each local cell (MeshView order). Collective.
std::vector<double> desired_volumes_from_input(SizeMode volume_source, const MeshView& view,
                                               const DofMap& dofs,
                                               std::span<const double> cell_volumes);

// How many times the cells cover their domain: Σ|v_K| / Σ v_K over all ranks, for the actual
// (signed) cell volumes v_K. 1 for a mesh without inverted cells; a cell folded over its
// neighbours adds twice its volume (it covers the domain again and its negative volume is
// subtracted from the sum). +∞ if the volumes do not sum to a positive volume. Collective.
double domain_coverage(std::span<const double> cell_volumes, MPI_Comm comm);

// Above this coverage a tangled input is folded over itself throughout rather than in a few
// places: the cells of negative volume add up to more than half the domain, and the valid
// cells among them were stretched and squeezed along with them, so no input volume is a size.
constexpr double kFoldedCoverage = 2.0;

// Scales `volumes` (relative volumes, one per local cell) so that they sum to `total` over all
// ranks.
void normalize_volumes(std::vector<double>& volumes, double total, MPI_Comm comm);

// Averages per-cell values over the cells sharing a vertex with each cell: one pass
// cell → vertex (mean of incident cells) → cell (mean of its vertices). Collective.
std::vector<double> average_over_neighbours(const MeshView& view, const DofMap& dofs,
                                            std::span<const double> values);

}  // namespace neomesh
