// The chapter-6 cases of the thesis (CASES.md): [-1,1]^d adapted to the circle/sphere of
// radius 0.7 around the origin.
#include "adapt/picard.hpp"

#include <cmath>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "adapt/volume_ratio.hpp"
#include "geometry/quality.hpp"
#include "mesh/generate.hpp"
#include "solver/thesis_problem.hpp"

namespace neomesh {
namespace {

constexpr double kRadius = 0.7;

struct Outcome {
  PicardResult result;
  int armijo_steps = 0, rejected = 0;
  VolumeRatioStats q;
  double min_scaled_jacobian = 0.0;
  int inverted = 0;
  // Mean volume of the cells within 0.05 of the surface over that of the cells farther
  // than 0.5 (centroids of the adapted mesh).
  double near_far = 0.0;
  double seconds = 0.0;
};

Outcome adapt_to_sphere(CellType type, int n, const SizeFieldOptions& sizes,
                        const PicardOptions& picard_options = {},
                        const EnergyOptions& energy = {}) {
  ThesisProblem p(box(type, n), energy);
  const int d = p.view.dim;
  const SizeField field = SizeField::sphere(std::vector<double>(d, 0.0), kRadius);
  QuasiNewtonOptions method;
  method.energy_roundoff = energy_roundoff(energy, d, p.volume);
  const double start = MPI_Wtime();
  Outcome out;
  out.result = picard(
      *p.functional, p.view, p.x, size_field_volumes(field, sizes, p.view, p.dofs, p.volume),
      [&](const std::vector<double>& v) { p.functional->set_desired_volumes(v); }, picard_options,
      method);
  out.seconds = MPI_Wtime() - start;
  for (const IterationRecord& r : out.result.run.history) {
    out.armijo_steps += r.armijo_steps;
    out.rejected += r.delta_solved && r.used_s;
  }
  out.q = volume_ratio_stats(p.functional->cell_fields(p.x).volume_ratio, PETSC_COMM_SELF);

  std::vector<double> coords(p.dofs.num_local_dofs());
  p.dofs.global_to_local(p.x, coords);
  const CellQuality quality = cell_quality(p.view, coords);
  out.min_scaled_jacobian =
      *std::min_element(quality.scaled_jacobian.begin(), quality.scaled_jacobian.end());
  const std::vector<double> centroids = cell_centroids(p.view, coords);
  double near = 0.0, far = 0.0;
  int near_cells = 0, far_cells = 0;
  for (PetscInt c = 0; c < p.view.num_cells; ++c) {
    out.inverted += quality.min_gauss_det[c] <= 0 || quality.min_corner_det[c] <= 0;
    double r2 = 0.0;
    for (int j = 0; j < d; ++j) r2 += centroids[c * d + j] * centroids[c * d + j];
    const double distance = std::abs(std::sqrt(r2) - kRadius);
    if (distance <= 0.05) near += quality.volume[c], ++near_cells;
    if (distance > 0.5) far += quality.volume[c], ++far_cells;
  }
  out.near_far = (near / near_cells) / (far / far_cells);
  std::string updates = fmt::format("{}", fmt::join(out.result.update_iterations, ", "));
  std::printf(
      "%s %d^%d: %zu iterations, %d Armijo steps, δ rejected %d times, updates after [%s], %s; "
      "Q in [0.5, 2]: %.1f%%, min %.3g, median %.3g, max %.3g; min scaled Jacobian %.3f; "
      "near/far volume %.3f; %.1f s\n",
      std::string(name(type)).c_str(), n, d, out.result.run.history.size(), out.armijo_steps,
      out.rejected, updates.c_str(), describe(out.result.run.reason).c_str(), 100 * out.q.within,
      out.q.min, out.q.median, out.q.max, out.min_scaled_jacobian, out.near_far, out.seconds);
  return out;
}

bool converged(const Outcome& o) {
  const StopReason r = o.result.run.reason;
  return r == StopReason::DefectAbsolute || r == StopReason::DefectRelative ||
         r == StopReason::Practical;
}

TEST(Picard, UpdatesAtLeastMinUpdatesTimesAndEndsConverged) {
  const PicardOptions options{.min_updates = 3, .update_every = 5};
  const Outcome o =
      adapt_to_sphere(CellType::Quadrilateral, 8, SizeFieldOptions::thesis(), options);
  EXPECT_TRUE(converged(o));
  ASSERT_EQ(o.result.update_iterations.size(), 3u);
  int previous = 0;
  for (int k : o.result.update_iterations) {
    EXPECT_GT(k, previous);
    EXPECT_LE(k - previous, options.update_every);
    previous = k;
  }
  // After the last update the method runs to convergence of that problem.
  EXPECT_GT(static_cast<int>(o.result.run.history.size()), previous);
}

// neomesh's defaults (docs/adaptivity.md): λ = μ, desired volumes bounded (ratio 100) and
// smoothed once, the Picard updates of picard.hpp.
const EnergyOptions kAdaptEnergy{.lambda = 1.0, .mu = 1.0};

TEST(AdaptCircle, Quads32CrowdCellsAtTheCircle) {
  const Outcome o = adapt_to_sphere(CellType::Quadrilateral, 32, {}, {}, kAdaptEnergy);
  EXPECT_TRUE(converged(o));
  EXPECT_EQ(o.inverted, 0);
  EXPECT_LE(o.near_far, 0.25);
  EXPECT_GE(o.min_scaled_jacobian, 0.3);
  EXPECT_LE(o.result.run.history.size(), 60u);
}

TEST(AdaptCircle, Quads64CrowdCellsAtTheCircle) {
  const Outcome o = adapt_to_sphere(CellType::Quadrilateral, 64, {}, {}, kAdaptEnergy);
  EXPECT_TRUE(converged(o));
  EXPECT_EQ(o.inverted, 0);
  EXPECT_LE(o.near_far, 0.25);
}

// The thesis' scheme (Table 6.1: 35 iterations, 84 Armijo steps at 32×32) converges too, but
// with μ = 10 the shape terms win: the cells at the circle stay larger.
TEST(AdaptCircle, ThesisSchemeQuads32) {
  const PicardOptions thesis{
      .min_updates = 7, .update_every = 8, .update_move = 0.0, .update_step_norm = 1e-6};
  const Outcome o =
      adapt_to_sphere(CellType::Quadrilateral, 32, SizeFieldOptions::thesis(), thesis);
  EXPECT_TRUE(converged(o));
  EXPECT_EQ(o.inverted, 0);
  EXPECT_EQ(o.result.update_iterations.size(), 7u);
  EXPECT_LE(o.near_far, 0.3);
}

// Thesis §6.3: 87 iterations and 237 Armijo steps at level 5.
TEST(AdaptCircleTri, Triangles32Converge) {
  const Outcome o = adapt_to_sphere(CellType::Triangle, 32, {}, {}, kAdaptEnergy);
  EXPECT_TRUE(converged(o));
  EXPECT_EQ(o.inverted, 0);
  EXPECT_LE(o.near_far, 0.25);
}

// The thesis' 3D failure (Table 6.2), at 16³ to stay fast: the defaults adapt clearly more
// than the thesis' scheme (near/far volume 0.67 at 16³), with good shapes. The 32³ targets
// of the issue (90% of Q in [0.5, 2], near/far ≤ 1/4) are not met yet: docs/adaptivity.md.
TEST(AdaptSphere, Hexes16AdaptBetterThanTheThesisScheme) {
  const Outcome o = adapt_to_sphere(CellType::Hexahedron, 16, {}, {}, kAdaptEnergy);
  EXPECT_TRUE(converged(o));
  EXPECT_EQ(o.inverted, 0);
  EXPECT_GE(o.min_scaled_jacobian, 0.2);
  EXPECT_LE(o.near_far, 0.55);
}

}  // namespace
}  // namespace neomesh
