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
  const std::vector<double> sj = cell_scaled_jacobians(view, local);
  double m = std::numeric_limits<double>::infinity();
  for (const CellBlock& block : view.blocks)
    if (!is_simplex(block.type))
      for (PetscInt c = 0; c < block.size(); ++c) m = std::min(m, sj[block.first_cell + c]);
  MPI_Allreduce(MPI_IN_PLACE, &m, 1, MPI_DOUBLE, MPI_MIN, dofs.comm());
  return m;
}

}  // namespace

std::optional<CornerPhaseSummary> lift_flat_corners(
    Functional& functional, const MeshView& view, const DofMap& dofs, Vec x,
    const QuasiNewtonOptions& options, Vec cell_size, Result& run,
    const std::function<void(const IterationRecord&)>& observe) {
  const double before = min_non_simplex_jacobian(view, dofs, x);
  if (!(before < kFlatCellJacobian)) return std::nullopt;
  // From a corner at det G ≈ 1e-10 the barrier's gradient is too steep for a line search:
  // the untangling energy, regularized at ε = kLiftedDet, first lifts such corners above it.
  OwnedVec start;
  NM_PETSC(VecDuplicate(x, start.out()));
  NM_PETSC(VecCopy(x, start));
  const UntangleResult lifted = untangle(
      functional, x, options, cell_size,
      {.max_rounds = kLiftRounds, .stalled_rounds = 3, .tangled_below = kLiftedDet}, observe);
  run.history.insert(run.history.end(), lifted.history.begin(), lifted.history.end());
  // The regularized energy is finite on inverted cells too: if it stalled with one, the phase
  // gives up and keeps the thesis' optimum.
  if (functional.inversion(x, 0).count > 0) {
    NM_PETSC(VecCopy(start, x));
    return CornerPhaseSummary{.min_scaled_jacobian_before = before,
                              .min_scaled_jacobian_after = before,
                              .iterations = static_cast<int>(lifted.history.size()),
                              .gave_up = true};
  }
  functional.set_corner_weight(kWorstCellCornerWeight);
  const QuasiNewtonResult polish = minimize(functional, x, options, cell_size, observe);
  functional.set_corner_weight(0.0);
  run.history.insert(run.history.end(), polish.history.begin(), polish.history.end());
  run.reason = polish.reason;
  run.final_energy = functional.value(x);
  run.final_defect = polish.final_defect;
  return CornerPhaseSummary{
      .min_scaled_jacobian_before = before,
      .min_scaled_jacobian_after = min_non_simplex_jacobian(view, dofs, x),
      .iterations = static_cast<int>(lifted.history.size() + polish.history.size())};
}

}  // namespace neomesh
