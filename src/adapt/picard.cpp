#include "adapt/picard.hpp"

#include <cmath>

namespace neomesh {

namespace {

bool converged(StopReason reason) {
  return reason == StopReason::DefectAbsolute || reason == StopReason::DefectRelative ||
         reason == StopReason::Practical;
}

}  // namespace

PicardResult picard(const MeshView& view, Vec x, const TargetsAt& targets,
                    const SetTargets& set_targets, const PicardOptions& options,
                    const QuasiNewtonOptions& method_options, const Observer& observe) {
  CellTargets current = targets(x);
  const Functional& first = set_targets(current);
  const DofMap& dofs = first.dofs();
  // QuasiNewton keeps this Vec; updates overwrite its values.
  OwnedVec cell_size = local_cell_size(view, dofs, current.volumes);
  QuasiNewton method(first, method_options, cell_size);
  method.restart(x);

  PicardResult result;
  result.run.initial_energy = method.energy();
  result.run.initial_defect = method.defect();
  int since_update = 0;
  auto update = [&] {
    CellTargets next = targets(x);
    const double w = options.relaxation;
    for (std::size_t i = 0; i < next.volumes.size(); ++i)
      next.volumes[i] = (1.0 - w) * current.volumes[i] + w * next.volumes[i];
    current = std::move(next);
    const Functional& functional = set_targets(current);
    OwnedVec size = local_cell_size(view, dofs, current.volumes);
    NM_PETSC(VecCopy(size, cell_size));
    // A new problem: new F, g, Riesz Laplacian, k_min antigradient steps.
    method.restart(x, functional);
    const int k = result.run.history.empty() ? 0 : result.run.history.back().k;
    result.update_iterations.push_back(k);
    since_update = 0;
    if (observe.volumes_updated)
      observe.volumes_updated(k, static_cast<int>(result.update_iterations.size()));
  };
  auto updates_left = [&] {
    return static_cast<int>(result.update_iterations.size()) < options.min_updates;
  };

  for (;;) {
    if (const auto stop = method.stop_reason()) {
      // Converged for these volumes: update them, unless enough updates were made; after
      // the last update the run ends on a minimizer for well-defined desired volumes.
      if (!converged(*stop) || !updates_left()) {
        result.run.reason = *stop;
        break;
      }
      update();
      continue;
    }
    const IterationRecord& rec = result.run.history.emplace_back(method.step(x));
    if (observe.iteration) observe.iteration(rec);
    ++since_update;
    if (!updates_left() || method.stop_reason()) continue;
    const double step_norm = std::ldexp(rec.direction_norm, -rec.armijo_steps);  // σ‖δ‖
    const bool settled = (!rec.used_s && rec.max_move <= options.update_move) ||
                         (options.update_step_norm > 0 && step_norm < options.update_step_norm);
    if (settled || since_update >= options.update_every) update();
  }
  result.run.final_energy = method.energy();
  result.run.final_defect = method.defect();
  result.run.times = method.times();
  return result;
}

}  // namespace neomesh
