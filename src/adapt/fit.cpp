#include "adapt/fit.hpp"

#include <algorithm>
#include <cmath>

#include "core/error.hpp"
#include "core/log.hpp"
#include "geometry/quality.hpp"

namespace neomesh {

namespace {

// Antigradient steps at the start of a stage: a stage starts near a minimizer (the last
// stage's, with the interface moved a little), where quasi-Newton steps are safe.
constexpr int kStageKmin = 0;

// No cell inverted anywhere, corners included (the energy sees Q1 cells at Gauss points only).
bool valid(const Functional& functional, const MeshView& view, const DofMap& dofs, Vec x) {
  int ok = std::isfinite(functional.value(x)) ? 1 : 0;
  std::vector<double> local(static_cast<std::size_t>(dofs.num_local_dofs()));
  dofs.global_to_local(x, local);
  // A corner's scaled Jacobian has its det J's sign (0 at a zero-length edge).
  for (double sj : cell_scaled_jacobians(view, local, &dofs))
    if (!(sj > 0.0)) ok = 0;
  MPI_Allreduce(MPI_IN_PLACE, &ok, 1, MPI_INT, MPI_MIN, dofs.comm());
  return ok == 1;
}

// Sweeps that spread the interface's move over the vertices around it (one ring each).
constexpr int kSpreadSweeps = 16;

// Moves the interface vertices of x onto their levels of the constraint's stage, and the free
// vertices around them part of the way along: Jacobi sweeps of the mean move over each
// vertex's cells, the interface's moves held, the boundary's zero. The cells next to the
// interface make room instead of being run over, which lets a stage go further.
void move_to_stage(const MeshView& view, const DofMap& dofs, const InterfaceConstraint& constraint,
                   Vec x) {
  const int d = view.dim;
  const auto n = static_cast<std::size_t>(dofs.num_local_dofs());
  std::vector<double> before(n), move(n);
  dofs.global_to_local(x, before);
  constraint.project(x);
  dofs.global_to_local(x, move);
  for (std::size_t i = 0; i < n; ++i) move[i] -= before[i];
  std::vector<std::uint8_t> held(view.num_vertices, 0);
  for (PetscInt u : constraint.vertices()) held[u] = 1;
  for (PetscInt u = 0; u < view.num_vertices; ++u)
    if (view.on_boundary[u]) held[u] = 1;  // (its move is zero)
  std::vector<double> sum(n), count(n);    // count: per vertex, in each of its dim entries
  for (int sweep = 0; sweep < kSpreadSweeps; ++sweep) {
    std::fill(sum.begin(), sum.end(), 0.0);
    std::fill(count.begin(), count.end(), 0.0);
    for (const CellBlock& block : view.blocks) {
      const int nv = block.nodes();
      for (PetscInt c = 0; c < block.size(); ++c) {
        const PetscInt* cell = block.cell(c);
        double mean[3] = {0, 0, 0};
        for (int i = 0; i < nv; ++i)
          for (int j = 0; j < d; ++j) mean[j] += move[cell[i] * d + j] / nv;
        for (int i = 0; i < nv; ++i)
          for (int j = 0; j < d; ++j) {
            sum[cell[i] * d + j] += mean[j];
            count[cell[i] * d + j] += 1.0;
          }
      }
    }
    dofs.sum_over_ranks(sum);  // a vertex's cells may lie on several ranks
    dofs.sum_over_ranks(count);
    for (PetscInt u = 0; u < view.num_vertices; ++u)
      if (!held[u] && count[u * d] > 0)
        for (int j = 0; j < d; ++j) move[u * d + j] = sum[u * d + j] / count[u * d];
  }
  for (PetscInt u = 0; u < view.num_vertices; ++u)
    if (!held[u] && view.owned[u]) {
      for (int j = 0; j < d; ++j) before[u * d + j] += move[u * d + j];
      NM_PETSC(VecSetValues(x, d, dofs.global_dof().data() + u * d, before.data() + u * d,
                            INSERT_VALUES));
    }
  NM_PETSC(VecAssemblyBegin(x));
  NM_PETSC(VecAssemblyEnd(x));
}

void append(PicardResult& all, const PicardResult& stage) {
  if (all.run.history.empty()) {
    all.run.initial_energy = stage.run.initial_energy;
    all.run.initial_defect = stage.run.initial_defect;
  }
  const int offset = static_cast<int>(all.run.history.size());
  for (IterationRecord rec : stage.run.history) {
    rec.k += offset;
    all.run.history.push_back(rec);
  }
  for (int k : stage.update_iterations) all.update_iterations.push_back(k + offset);
  all.run.reason = stage.run.reason;
  all.run.final_energy = stage.run.final_energy;
  all.run.final_defect = stage.run.final_defect;
}

}  // namespace

FitResult fit_interface(const MeshView& view, const DofMap& dofs, Vec x,
                        const LevelSetFunction& phi, const FitHooks& hooks,
                        const PicardOptions& last_stage, const QuasiNewtonOptions& method,
                        const FitOptions& options, const Observer& observe) {
  FitResult result;
  {
    std::vector<double> local(static_cast<std::size_t>(dofs.num_local_dofs()));
    dofs.global_to_local(x, local);
    result.interface = find_interface(view, dofs, local, phi);
  }
  result.constraint =
      std::make_shared<InterfaceConstraint>(view, dofs, phi, result.interface.vertices, x);
  // The functional of the constrained problem with the latest targets.
  const Functional* functional = &hooks.constrain(sliding_vertices(result.constraint));
  const SetTargets set_targets = [&](const CellTargets& t) -> const Functional& {
    return *(functional = &hooks.set_targets(t));
  };

  OwnedVec accepted = copy_of(x);
  const double smallest = std::ldexp(1.0, -options.max_halvings);
  double step = 1.0;  // the whole way at once if the cells allow it
  while (result.constraint->stage() < 1.0) {
    const double from = result.constraint->stage(), to = std::min(1.0, from + step);
    result.constraint->set_stage(to);
    move_to_stage(view, dofs, *result.constraint, x);
    bool ok = valid(*functional, view, dofs, x);
    if (!ok) detail("  fit: moving the interface to stage {:.3g} would invert a cell\n", to);
    if (ok) {
      PicardOptions stage = last_stage;
      QuasiNewtonOptions stage_method = method;
      stage_method.advanced.kmin = std::min(stage_method.advanced.kmin, kStageKmin);
      if (to < 1.0) {
        stage.min_updates = 0;  // the volumes of the stage's start will do
        if (options.stage_iterations > 0) stage_method.max_iterations = options.stage_iterations;
      }
      const PicardResult r =
          picard(view, x, hooks.targets, set_targets, stage, stage_method, observe);
      append(result.picard, r);
      ok = valid(*functional, view, dofs, x);
      detail("  fit: stage {:.3g}: {} iterations{}\n", to, r.run.history.size(),
             ok ? "" : ", then a cell corner inverted: undone");
    }
    if (ok) {
      ++result.stages;
      NM_PETSC(VecCopy(x, accepted));
      step = std::min(1.0, 2 * step);
      continue;
    }
    ++result.retries;
    NM_PETSC(VecCopy(accepted, x));
    result.constraint->set_stage(from);
    step /= 2;
    if (step < smallest)
      fail(
          "fit: could not pull the interface of {} onto its zero set without inverting a "
          "cell (stuck {:.0f}% of the way); a finer mesh near the interface may help",
          phi.expression(), 100 * from);
  }
  result.max_distance = result.constraint->max_distance(x);
  return result;
}

}  // namespace neomesh
