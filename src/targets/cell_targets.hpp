// What each cell is pulled towards: the one builder of the cells' targets (docs/method.md §5,
// §9), for smoothing and for adaptation alike. The energy sees the result as its Targets
// (energy/problem.hpp); the Picard iteration asks for it anew at every update (adapt/picard.hpp).
//
// One name per concept, here and in the code that builds or uses targets:
//   target (cell)     what the energy pulls a cell towards: a desired volume, a target shape and
//                     a weight (CellTargets).
//   desired volume    v_K, the absolute volume of cell K's target; over all ranks they sum to the
//                     mesh volume |Ω| (the thesis' word; CellTargets::volumes,
//                     Problem::desired_volumes(), the report's cell field "desired_volume").
//   relative volume   a desired volume before it is scaled to |Ω|: what a size field gives
//                     (floor + d^p, det M^(-1/2), a file's per-cell values) and what the volume
//                     source picks (1, the input volume, its average).
//   volume source     where smoothing takes its relative volumes from: uniform, input or
//                     smoothed (public: SizeMode, SmoothOptions::sizes, `smooth --sizes`).
//   target mode       what shape smoothing aims at: the ideal cell, the input cell, or the input
//                     cell where its design is coherent (public: TargetMode,
//                     SmoothOptions::targets, `--targets`).
//   size field        a field over the domain giving relative volumes (isotropic) or a metric
//                     (anisotropic) at the cells' centroids (SizeField).
//   metric            M(x), symmetric positive definite: the target is its unit ball, of
//                     relative volume det(M)^(-1/2) and target shape M^(-1/2).
//   field options     how a size field's relative volumes become desired volumes: floor and
//                     power p of floor + d^p, the bound on the ratio of volumes, the passes of
//                     smoothing log v (public: SizeFieldOptions, AdaptOptions::field, the
//                     options' paths field.*; a file's per-cell values: `adapt --volumes`).
//   cell size         h, a length: v^(1/d) of a desired volume (the practical criterion's
//                     scale, local_cell_size) or a metric's 1/sqrt(λ). Only lengths are sizes.
//   target shape      S (dim × dim, det S = 1): the target's stretch and turn; empty for the
//                     thesis' ideal cells.
//   weight            k, the factor of a cell's energy (with target shapes).
//   input share       w ∈ [0, 1], how much of its input cell a cell's target keeps
//                     (CellTargets::input_share; the report's "target_input_share").
#pragma once

#include <span>
#include <variant>
#include <vector>

#include <neomesh/options.hpp>
#include <neomesh/size_field.hpp>

#include "mesh/dof_map.hpp"
#include "mesh/mesh_view.hpp"

namespace neomesh {

struct CellTargets {
  std::vector<double> volumes;      // per local cell the desired volume (summing to |Ω|)
  std::vector<double> shapes;       // per local cell dim² (column-major, det 1); empty: all ideal
  std::vector<double> weights;      // per local cell k (with shapes)
  std::vector<double> input_share;  // per local cell w
};

// Ideal targets of the given desired volumes (input share 0).
CellTargets ideal_targets(std::vector<double> volumes);

// What smoothing asks for (`smooth --targets`, `--sizes`).
struct SmoothingRequest {
  TargetMode mode = TargetMode::Smoothed;
  SizeMode volume_source = SizeMode::Smoothed;
};

// What adaptation asks for: a size field, isotropic or a metric, and its field options.
// `field` must outlive the request.
struct AdaptationRequest {
  const SizeField* field = nullptr;
  SizeFieldOptions field_options;
};

using TargetRequest = std::variant<SmoothingRequest, AdaptationRequest>;

// The local cells as the caller measured them: what a request needs of them (the rest may stay
// empty).
struct MeasuredCells {
  // Adaptation: the coordinates (num_vertices × dim, local order) whose cells' centroids the
  // size field is evaluated at.
  std::span<const double> coords = {};
  // Smoothing: each cell's actual volume.
  std::span<const double> volumes = {};
  // Each cell's Jacobian at its centre relative to its unit ideal cell
  // (Functional::cell_jacobians; dim² per cell): smoothing's input cells (mode Input or
  // Smoothed), or what a metric's target shapes are turned by (size_field.hpp: target_shapes).
  std::span<const double> jacobians = {};
  // Smoothing (mode Input or Smoothed): each cell's longest over shortest edge.
  std::span<const double> edge_ratios = {};
  // Adaptation: what the desired volumes sum to (smoothing's sum to that of `volumes`).
  double mesh_volume = 0.0;
};

// Whether `request` needs MeasuredCells::jacobians.
bool needs_jacobians(const TargetRequest& request);

// The targets of the local cells of `view` (MeshView order) for `request`. Throws Error where
// the size field does not fit the mesh (size_field.hpp). Collective.
CellTargets build_targets(const TargetRequest& request, const MeshView& view, const DofMap& dofs,
                          const MeasuredCells& cells);

}  // namespace neomesh
