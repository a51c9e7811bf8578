#include "solver/worst_cells.hpp"

#include <algorithm>
#include <limits>

#include "geometry/quality.hpp"
#include "solver/untangle.hpp"

namespace neomesh {

namespace {

// The smallest scaled Jacobian over the cells other than simplices (+∞ without any), over all
// ranks.
double min_non_simplex_jacobian(const MeshView& view, const DofMap& dofs, Vec x) {
  std::vector<double> local(dofs.num_local_dofs());
  dofs.global_to_local(x, local);
  const std::vector<double> sj = cell_scaled_jacobians(view, local, &dofs);
  double m = std::numeric_limits<double>::infinity();
  for (const CellBlock& block : view.blocks)
    if (!is_simplex(block.type))
      for (PetscInt c = 0; c < block.size(); ++c) m = std::min(m, sj[block.first_cell + c]);
  MPI_Allreduce(MPI_IN_PLACE, &m, 1, MPI_DOUBLE, MPI_MIN, dofs.comm());
  return m;
}

}  // namespace

bool flat_cap(const MeshView& view, const DofMap& dofs, Vec x) {
  std::vector<double> local(dofs.num_local_dofs());
  dofs.global_to_local(x, local);
  const std::vector<double> sj = cell_scaled_jacobians(view, local, &dofs);
  const std::vector<double> ratio = cell_edge_ratios(view, local);
  int cap = 0;
  for (std::size_t c = 0; c < sj.size() && !cap; ++c)
    cap = sj[c] < kFlatCellJacobian && sj[c] * ratio[c] < kCapShape;
  MPI_Allreduce(MPI_IN_PLACE, &cap, 1, MPI_INT, MPI_MAX, dofs.comm());
  return cap != 0;
}

std::optional<CornerPhaseSummary> lift_flat_corners(
    const Functional& functional, const MeshView& view, const DofMap& dofs, Vec x,
    const QuasiNewtonOptions& options, Vec cell_size, Result& run,
    const std::function<void(const IterationRecord&)>& observe,
    const std::function<double(Vec)>& least_jacobian) {
  const auto measure = [&](Vec at) {
    return least_jacobian ? least_jacobian(at) : min_non_simplex_jacobian(view, dofs, at);
  };
  const double before = measure(x);
  if (!(before < kFlatCellJacobian)) return std::nullopt;
  // From a corner at det G ≈ 1e-10 the barrier's gradient is too steep for a line search:
  // the untangling energy, regularized at ε = kLiftedDet, first lifts such corners above it,
  // towards the desired volumes and, if that stalls, towards each cell's own volume (det G then
  // measures the shape alone: the small cells of a graded mesh are not taken for flat ones).
  const OwnedVec start = copy_of(x);
  const std::vector<double>& desired = functional.problem().desired_volumes();
  const std::vector<double> own = [&] {
    std::vector<double> v = functional.cell_fields(x).volume_ratio;  // actual / desired
    for (std::size_t c = 0; c < v.size(); ++c) v[c] *= desired[c];
    return v;
  }();
  int iterations = 0;
  bool lifted = false;
  for (const std::vector<double>* volumes : {&desired, &own}) {
    NM_PETSC(VecCopy(start, x));
    const Functional towards(functional.options(),
                             functional.problem().with_desired_volumes(*volumes));
    const UntangleResult lift = untangle(
        towards, x, options, cell_size,
        {.max_rounds = kLiftRounds, .stalled_rounds = 3, .tangled_below = kLiftedDet}, observe);
    run.history.insert(run.history.end(), lift.history.begin(), lift.history.end());
    iterations += static_cast<int>(lift.history.size());
    // The regularized energy is finite on inverted cells too: a lift that stalled with one
    // failed.
    lifted = towards.inversion(x, 0).count == 0;
    if (lifted) break;
  }
  if (!lifted) {  // the thesis' optimum is kept
    NM_PETSC(VecCopy(start, x));
    return CornerPhaseSummary{.min_scaled_jacobian_before = before,
                              .min_scaled_jacobian_after = before,
                              .iterations = iterations,
                              .gave_up = true};
  }
  const Functional corners(functional.options(),
                           functional.problem().with_corner_weight(kWorstCellCornerWeight));
  const SolverRun polish = minimize(corners, x, options, cell_size, observe);
  run.history.insert(run.history.end(), polish.history.begin(), polish.history.end());
  run.reason = polish.reason;
  run.final_energy = functional.value(x);
  run.final_defect = polish.final_defect;
  return CornerPhaseSummary{.min_scaled_jacobian_before = before,
                            .min_scaled_jacobian_after = measure(x),
                            .iterations = iterations + static_cast<int>(polish.history.size())};
}

}  // namespace neomesh
