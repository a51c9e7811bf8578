// Optimizer::smooth called again on a moved mesh: a warm call starts in the Newton regime and
// ends at the optimum a cold call on the same input reaches; what it keeps is dropped when the
// problem changes.
#include <neomesh/optimizer.hpp>

#include <algorithm>
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include <neomesh/generate.hpp>

namespace neomesh {
namespace {

// Every 20th interior vertex moved by up to a tenth of a cell in each coordinate: a time step
// of a simulation (bench/smooth_call moves every 100th of a larger mesh).
void move_some_vertices(Mesh& mesh, double cell) {
  std::vector<double> x = mesh.coordinates();
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-0.1 * cell, 0.1 * cell);
  const int d = mesh.coordinate_dim();
  for (std::size_t v = 0; v < x.size() / d; v += 20) {
    const double r = std::hypot(x[d * v], x[d * v + 1]);
    if (r > 1.0 + cell && r < 2.0 - cell)  // inside the quarter annulus 1 ≤ r ≤ 2
      for (int a = 0; a < d; ++a) x[d * v + a] += u(rng);
  }
  mesh.set_coordinates(x);
}

bool starts_with_antigradient_steps(const Result& r) {
  return !r.history.empty() && r.history.front().used_s;
}

// From a smoothed 16 × 16 quarter annulus with some vertices moved: smooth() warm, then cold
// from the same input on the same Optimizer (so with the same boundary classification).
struct WarmAndCold {
  Result warm, cold;
  double max_distance = 0.0;  // between their outputs, in cell widths
};
WarmAndCold warm_and_cold(const SmoothOptions& options) {
  const double cell = 1.0 / 16;
  Mesh mesh = Mesh::generate({.name = "annulus-quad", .size = 16, .jitter = 0.2});
  Optimizer optimizer(mesh);
  const Result first = optimizer.smooth(options);
  EXPECT_TRUE(starts_with_antigradient_steps(first));
  move_some_vertices(mesh, cell);
  const std::vector<double> moved = mesh.coordinates();
  WarmAndCold r;
  r.warm = optimizer.smooth(options);
  const std::vector<double> warm = mesh.coordinates();
  mesh.set_coordinates(moved);
  optimizer.forget_warm_start();
  r.cold = optimizer.smooth(options);
  const std::vector<double> cold = mesh.coordinates();
  for (std::size_t i = 0; i < warm.size(); ++i)
    r.max_distance = std::max(r.max_distance, std::abs(warm[i] - cold[i]) / cell);
  return r;
}

TEST(WarmSmoothing, AWarmMinimizationReachesTheColdOneInFewerIterations) {
  SmoothOptions minimization;
  minimization.quality_guard = false;  // the minimization alone
  const WarmAndCold r = warm_and_cold(minimization);
  EXPECT_FALSE(starts_with_antigradient_steps(r.warm));
  EXPECT_TRUE(starts_with_antigradient_steps(r.cold));
  EXPECT_EQ(r.warm.initial_energy, r.cold.initial_energy);  // the same problem
  EXPECT_LT(r.warm.history.size(), r.cold.history.size());  // 3 against 9
  // The same optimum to the stopping tolerance: both stopped at a full Newton step that moved
  // no vertex more than newton_move_rtol cell widths (1e-3 apart; F 8e-6 apart relatively).
  EXPECT_LT(r.max_distance, SolverOptions().newton_move_rtol);
  EXPECT_NEAR(r.warm.final_energy, r.cold.final_energy, 2e-5 * r.cold.final_energy);
}

TEST(WarmSmoothing, AWarmCallEndsWithTheColdCallsQuality) {
  // The worst cells' repair after the minimum is a local search that starts from the
  // minimizations' slightly different points: the outputs are 0.018 cell widths apart.
  const WarmAndCold r = warm_and_cold({});
  EXPECT_LT(r.warm.history.size(), r.cold.history.size());
  EXPECT_LT(r.max_distance, 0.05);
  EXPECT_NEAR(r.warm.quality_after.scaled_jacobian.min, r.cold.quality_after.scaled_jacobian.min,
              1e-3);
  EXPECT_NEAR(r.warm.quality_after.scaled_jacobian.mean, r.cold.quality_after.scaled_jacobian.mean,
              1e-4);
}

TEST(WarmSmoothing, OtherOptionsOrAnAdaptationStartCold) {
  Mesh mesh = Mesh::generate({.name = "annulus-quad", .size = 8, .jitter = 0.2});
  Optimizer optimizer(mesh);
  optimizer.smooth();
  move_some_vertices(mesh, 1.0 / 8);
  EXPECT_FALSE(starts_with_antigradient_steps(optimizer.smooth()));  // warm

  SmoothOptions energy;
  energy.energy.lambda = 2.0;  // another energy: another problem
  move_some_vertices(mesh, 1.0 / 8);
  EXPECT_TRUE(starts_with_antigradient_steps(optimizer.smooth(energy)));
  move_some_vertices(mesh, 1.0 / 8);
  EXPECT_FALSE(starts_with_antigradient_steps(optimizer.smooth(energy)));  // warm again

  SmoothOptions ideal = energy;
  ideal.targets = TargetMode::Ideal;  // other targets
  move_some_vertices(mesh, 1.0 / 8);
  EXPECT_TRUE(starts_with_antigradient_steps(optimizer.smooth(ideal)));

  SmoothOptions given_alpha = ideal;
  given_alpha.solver.advanced.alpha0 = 0.5;  // an explicit α₀ wins over the warm α
  move_some_vertices(mesh, 1.0 / 8);
  const Result given = optimizer.smooth(given_alpha);
  ASSERT_FALSE(given.history.empty());
  EXPECT_EQ(given.history.front().alpha, 0.5);

  optimizer.adapt(SizeField::level_set("x - 1.2"));  // the desired volumes are the field's
  move_some_vertices(mesh, 1.0 / 8);
  EXPECT_TRUE(starts_with_antigradient_steps(optimizer.smooth(ideal)));
}

}  // namespace
}  // namespace neomesh
