// Sliding boundary vertices (boundary/boundary.hpp) in the quasi-Newton method: on a box
// whose desired volumes grow along x, the boundary vertices follow the grading within their
// faces, so the energy ends lower than with fixed boundary vertices, while every vertex stays
// exactly on the box faces it started on and the corners stay put. On a ring whose boundary
// vertices are bunched 3:1 along its circles, they spread out evenly along the circles.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <numbers>

#include "generate/generate.hpp"
#include "solver/testing/thesis_problem.hpp"

namespace neomesh {
namespace {

struct Outcome {
  double energy = 0.0;
  double max_tangential_move = 0.0;  // over boundary vertices, in their free coordinates
};

Outcome graded_box(CellType type, int n, BoundaryMode boundary) {
  ThesisProblem p(box(type, n), {}, boundary);
  const int d = p.view.dim;
  // v ∝ 4^x on [-1,1]^d: the cells at x = 1 want 16 times the volume of those at x = −1.
  std::vector<double> volumes(p.view.num_cells);
  double sum = 0.0;
  for (const CellBlock& block : p.view.blocks)
    for (PetscInt c = 0; c < block.size(); ++c) {
      double x = 0.0;
      for (int i = 0; i < num_vertices(block.type); ++i)
        x += p.view.coords[block.cell(c)[i] * d] / num_vertices(block.type);
      sum += volumes[block.first_cell + c] = std::pow(4.0, x);
    }
  for (double& v : volumes) v *= p.volume / sum;
  p.set_desired_volumes(volumes);
  p.cell_size = local_cell_size(p.view, p.dofs, volumes);

  QuasiNewtonOptions options;
  options.energy_roundoff = energy_roundoff(p.energy, d, p.volume);
  const SolverRun result = p.minimize(options);
  EXPECT_NE(result.reason, StopReason::LineSearchFailed);
  EXPECT_NE(result.reason, StopReason::MaxIterations);

  std::vector<double> x(p.dofs.num_local_dofs());
  p.dofs.global_to_local(p.x, x);
  Outcome out{.energy = result.final_energy};
  for (PetscInt v = 0; v < p.view.num_vertices; ++v) {
    for (int j = 0; j < d; ++j) {
      const double start = p.view.coords[v * d + j];
      // On a face x_j = ±1 the coordinate must not change at all: no projection fixes it up.
      if (std::abs(start) == 1.0)
        EXPECT_EQ(x[v * d + j], start) << "vertex " << v << " left its face";
      else if (p.view.on_boundary[v])
        out.max_tangential_move = std::max(out.max_tangential_move, std::abs(x[v * d + j] - start));
    }
  }
  return out;
}

void expect_sliding_helps(CellType type, int n) {
  const Outcome fixed = graded_box(type, n, BoundaryMode::Fixed);
  const Outcome slide = graded_box(type, n, BoundaryMode::Slide);
  EXPECT_EQ(fixed.max_tangential_move, 0.0);
  // The boundary vertices move by a good part of a cell (h = 2/n) towards x = −1 ...
  EXPECT_GT(slide.max_tangential_move, 0.25 * 2.0 / n);
  // ... and the energy ends clearly lower.
  EXPECT_LT(slide.energy, 0.9 * fixed.energy);
}

TEST(SlidingBoundary, QuadsFollowTheGradingAlongTheSides) {
  expect_sliding_helps(CellType::Quadrilateral, 8);
}

TEST(SlidingBoundary, HexesFollowTheGradingWithinFacesAndAlongEdges) {
  expect_sliding_helps(CellType::Hexahedron, 4);
}

struct RingOutcome {
  double worst_gap_ratio = 0.0;     // largest / smallest angular gap, over the circles
  double worst_radius_error = 0.0;  // largest |r − R| of a vertex of a circle
  double worst_height_error = 0.0;  // shell: largest |z − z₀| of a vertex of a top/bottom circle
  double min_det = 0.0;             // smallest det G at a quadrature point
  // Largest |r − R| relative to the sagitta R (1 − cos(g/2)) of the input's largest gap g.
  double worst_sagitta_ratio = 0.0;
  std::size_t iterations = 0;
};

// Smooths ring(type, n, m, 3) with sliding boundary vertices (on the given shapes, if any)
// and uniform desired volumes; measures the circles (the input's, by radius and height).
RingOutcome smooth_ring(CellType type, int n, int m,
                        const std::vector<std::pair<std::string, std::string>>& shapes) {
  BoundaryOptions options(BoundaryMode::Slide);
  options.shapes = shapes;
  ThesisProblem p(ring(type, n, m, 3.0), {}, options);
  QuasiNewtonOptions method;
  method.energy_roundoff = energy_roundoff(p.energy, p.view.dim, p.volume);
  const SolverRun result = p.minimize(method);
  EXPECT_NE(result.reason, StopReason::LineSearchFailed);
  EXPECT_NE(result.reason, StopReason::MaxIterations);

  const int d = p.view.dim;
  std::vector<double> x(p.dofs.num_local_dofs());
  p.dofs.global_to_local(p.x, x);
  RingOutcome out;
  out.iterations = result.history.size();
  // The input's largest angular gap is below 2π/n · 3/2 (θ' ranges over [1/2, 3/2]·2π).
  const double gap = 2 * std::numbers::pi / n * 1.5;
  std::map<std::pair<double, double>, std::vector<double>> circles;  // (R, z₀) → angles
  for (PetscInt v = 0; v < p.view.num_vertices; ++v) {
    const double* start = p.view.coords.data() + v * d;
    const double radius = std::hypot(start[0], start[1]);
    const double z = d == 3 ? start[2] : 0.0;
    const bool on_circle = std::abs(radius - 0.5) < 1e-12 || std::abs(radius - 1.0) < 1e-12;
    if (!on_circle || (d == 3 && z != 0.0 && z != 0.5)) continue;
    const double R = radius < 0.75 ? 0.5 : 1.0;
    const double error = std::abs(std::hypot(x[v * d], x[v * d + 1]) - R);
    out.worst_radius_error = std::max(out.worst_radius_error, error);
    out.worst_sagitta_ratio =
        std::max(out.worst_sagitta_ratio, error / (R * (1 - std::cos(gap / 2))));
    if (d == 3)
      out.worst_height_error = std::max(out.worst_height_error, std::abs(x[v * d + 2] - z));
    circles[{R, z}].push_back(std::atan2(x[v * d + 1], x[v * d]));
  }
  for (auto& [circle, angles] : circles) {
    std::sort(angles.begin(), angles.end());
    double smallest = 1e300, largest = 0.0;
    for (std::size_t i = 0; i < angles.size(); ++i) {
      const double g = i + 1 < angles.size() ? angles[i + 1] - angles[i]
                                             : angles[0] + 2 * std::numbers::pi - angles[i];
      smallest = std::min(smallest, g);
      largest = std::max(largest, g);
    }
    out.worst_gap_ratio = std::max(out.worst_gap_ratio, largest / smallest);
  }
  const CellFields fields = p.functional->cell_fields(p.x);
  out.min_det = *std::min_element(fields.min_det.begin(), fields.min_det.end());
  return out;
}

void expect_even_ring(CellType type, int n, int m) {
  const RingOutcome discrete = smooth_ring(type, n, m, {});
  EXPECT_LE(discrete.worst_gap_ratio, 1.2);
  EXPECT_LE(discrete.worst_sagitta_ratio, 1.0);  // on the input's polygons
  EXPECT_LE(discrete.worst_height_error, 1e-15);
  EXPECT_GT(discrete.min_det, 0.0);
  std::vector<std::pair<std::string, std::string>> shapes;
  if (dimension(type) == 2)
    shapes = {{"inner", "circle:0,0,0.5"}, {"outer", "circle:0,0,1"}};
  else
    shapes = {{"inner", "cylinder:0,0,0,0,0,1,0.5"}, {"outer", "cylinder:0,0,0,0,0,1,1"}};
  const RingOutcome exact = smooth_ring(type, n, m, shapes);
  std::printf(
      "%s ring %d x %d, 3:1 bunched: largest/smallest gap %.3f on the input's polygon (%zu "
      "iterations, radius error %.1e = %.2f sagittas), %.3f on the circles (%zu iterations, "
      "radius error %.1e)\n",
      std::string(name(type)).c_str(), n, m, discrete.worst_gap_ratio, discrete.iterations,
      discrete.worst_radius_error, discrete.worst_sagitta_ratio, exact.worst_gap_ratio,
      exact.iterations, exact.worst_radius_error);
  EXPECT_LE(exact.worst_gap_ratio, 1.2);
  EXPECT_LE(exact.worst_radius_error, 1e-10);  // on the circles themselves
  EXPECT_LE(exact.worst_height_error, 1e-14);
  EXPECT_GT(exact.min_det, 0.0);
}

TEST(SlidingBoundary, RingQuadsSpreadEvenlyAlongTheCircles) {
  expect_even_ring(CellType::Quadrilateral, 48, 4);
}

TEST(SlidingBoundary, RingTrianglesSpreadEvenlyAlongTheCircles) {
  expect_even_ring(CellType::Triangle, 48, 4);
}

TEST(SlidingBoundary, ShellHexesSpreadEvenlyAlongTheCirclesAndKeepTheirRidges) {
  expect_even_ring(CellType::Hexahedron, 24, 2);
}

// On the bunched ring sliding on its input polygons, H(α) and L disagree enough that the
// angle test rejects δ̃: blended, the direction passes the test with η_k = η exactly (and a δ̃
// that CG truncated at negative curvature, which this run meets, is never blended), and the
// thesis' choice (−s) never blends.
TEST(SlidingBoundary, RejectedDirectionsAreTurnedJustEnoughTowardsTheAntigradient) {
  for (RejectedDirection choice : {RejectedDirection::Blend, RejectedDirection::Antigradient}) {
    ThesisProblem p(ring(CellType::Triangle, 48, 4, 3.0), {}, BoundaryMode::Slide);
    QuasiNewtonOptions options;
    options.energy_roundoff = energy_roundoff(p.energy, p.view.dim, p.volume);
    options.advanced.rejected_direction = choice;
    const SolverRun result = p.minimize(options);
    EXPECT_NE(result.reason, StopReason::LineSearchFailed);
    int blended = 0;
    for (const IterationRecord& r : result.history) {
      if (!r.blended) continue;
      ++blended;
      EXPECT_NEAR(r.eta, options.advanced.eta, 1e-12) << "iteration " << r.k;
      EXPECT_FALSE(r.used_s);
      EXPECT_FALSE(r.delta_truncated) << "iteration " << r.k << ": negative curvature";
    }
    if (choice == RejectedDirection::Blend)
      EXPECT_GT(blended, 0);
    else
      EXPECT_EQ(blended, 0);
  }
}

}  // namespace
}  // namespace neomesh
