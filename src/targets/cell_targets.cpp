#include "targets/cell_targets.hpp"

#include <utility>

#include "targets/desired_volumes.hpp"
#include "targets/input_targets.hpp"
#include "targets/size_field.hpp"

namespace neomesh {

namespace {

CellTargets smoothing_targets(const SmoothingRequest& request, const MeshView& view,
                              const DofMap& dofs, const MeasuredCells& cells) {
  std::vector<double> ideal =
      desired_volumes_from_input(request.volume_source, view, dofs, cells.volumes);
  if (request.mode == TargetMode::Ideal) return ideal_targets(std::move(ideal));
  return input_targets(request.mode, view, dofs, cells.volumes, cells.jacobians, cells.edge_ratios,
                       std::move(ideal));
}

CellTargets adaptation_targets(const AdaptationRequest& request, const MeshView& view,
                               const DofMap& dofs, const MeasuredCells& cells) {
  return field_targets(*request.field, request.field_options, view, dofs, cells.coords,
                       cells.jacobians, cells.mesh_volume);
}

}  // namespace

CellTargets ideal_targets(std::vector<double> volumes) {
  CellTargets t;
  t.input_share.assign(volumes.size(), 0.0);
  t.volumes = std::move(volumes);
  return t;
}

bool needs_jacobians(const TargetRequest& request) {
  if (const auto* smoothing = std::get_if<SmoothingRequest>(&request))
    return smoothing->mode != TargetMode::Ideal;
  return std::get<AdaptationRequest>(request).field->anisotropic();
}

CellTargets build_targets(const TargetRequest& request, const MeshView& view, const DofMap& dofs,
                          const MeasuredCells& cells) {
  if (const auto* smoothing = std::get_if<SmoothingRequest>(&request))
    return smoothing_targets(*smoothing, view, dofs, cells);
  return adaptation_targets(std::get<AdaptationRequest>(request), view, dofs, cells);
}

}  // namespace neomesh
