#include "solver/untangle.hpp"

#include <algorithm>
#include <cmath>
#include <memory>

#include <mpi.h>

#include "energy/regularized_neo_hooke.hpp"

namespace neomesh {

namespace {

// The next ε (Garanzha et al. 2021, §3): the worst sample's χ shrinks by the relative energy
// decrease σ of the last round, at least 10%: ε such that χ_ε(D_min) = (1 − σ) χ_ε_old(D_min).
// Unlike their energy, W_ε can be negative, so σ is the decrease relative to |F| and kept in
// [0.1, 0.9] (a sign change of F would otherwise give σ > 1 and a negative target).
double next_epsilon(double epsilon, double min_det, double energy_before, double energy_after) {
  const double decrease =
      (energy_before - energy_after) / std::max(std::abs(energy_before), 1e-300);
  const double sigma = std::clamp(decrease, 0.1, 0.9);
  const double target = (1.0 - sigma) * regularized_det(min_det, epsilon);
  if (min_det >= target) return epsilon;  // only positive dets left: nothing to sharpen
  return 2.0 * std::sqrt(target * (target - min_det));
}

}  // namespace

UntangleResult untangle(const Functional& functional, Vec x, const QuasiNewtonOptions& options,
                        Vec cell_size, const UntangleOptions& untangle_options,
                        const std::function<void(const IterationRecord&)>& observe) {
  const double start = MPI_Wtime();
  UntangleResult result;
  const double below = untangle_options.tangled_below;
  result.before = result.after = functional.inversion(x, 10, below);
  if (result.before.count == 0) return result;

  // Every round restarts the method (k_min antigradient steps); the untangling energy is
  // finite everywhere, so the Neo-Hookean round-off level does not apply.
  QuasiNewtonOptions method = options;
  method.max_iterations = untangle_options.max_rounds * untangle_options.steps_per_round + 1;
  method.practical = false;
  double epsilon =
      std::max({untangle_options.initial_epsilon * std::abs(result.before.min_det), below, 1e-6});
  // A round's problem is the given one with the untangling energy of its ε.
  const auto untangling = [&functional](double eps) {
    return std::make_unique<const Functional>(functional.options(),
                                              functional.problem().with_untangling(eps));
  };
  // The next round's; the solver holds the current one until it restarts on the next.
  std::unique_ptr<const Functional> next = untangling(epsilon), current;
  QuasiNewton solver(*next, method, cell_size);
  Inversion best = result.before;
  int stalled = 0;
  for (int round = 1; round <= untangle_options.max_rounds; ++round) {
    if (past_deadline(options.deadline, functional.dofs().comm())) break;
    result.rounds = round;
    solver.restart(x, *next);
    current = std::move(next);
    const double energy_before = solver.energy();
    for (int step = 0; step < untangle_options.steps_per_round; ++step) {
      IterationRecord rec = solver.step(x);
      result.after = functional.inversion(x, 10, below);
      rec.untangling_round = round;
      rec.epsilon = epsilon;
      rec.inverted = result.after.count;
      rec.lifting_flat_corners = below > 0.0;
      result.history.push_back(rec);
      if (observe) observe(rec);
      if (result.after.count == 0 || solver.stop_reason()) break;
    }
    if (result.after.count == 0) break;
    const bool progress = result.after.count < best.count ||
                          result.after.min_det > best.min_det + 0.01 * std::abs(best.min_det);
    if (progress) best = result.after;
    stalled = progress ? 0 : stalled + 1;
    if (stalled >= untangle_options.stalled_rounds) break;
    epsilon = next_epsilon(epsilon, result.after.min_det, energy_before, solver.energy());
    next = untangling(epsilon);
  }
  result.seconds = MPI_Wtime() - start;
  return result;
}

}  // namespace neomesh
