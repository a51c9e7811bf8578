// Sliding boundary vertices (boundary/boundary.hpp) in the quasi-Newton method: on a box
// whose desired volumes grow along x, the boundary vertices follow the grading within their
// faces, so the energy ends lower than with fixed boundary vertices, while every vertex stays
// exactly on the box faces it started on and the corners stay put.
#include <gtest/gtest.h>

#include <cmath>

#include "mesh/generate.hpp"
#include "solver/thesis_problem.hpp"

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
  p.functional->set_desired_volumes(volumes);
  p.cell_size = local_cell_size(p.view, p.dofs, volumes);

  QuasiNewtonOptions options;
  options.energy_roundoff = energy_roundoff(p.energy, d, p.volume);
  const QuasiNewtonResult result = p.minimize(options);
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

}  // namespace
}  // namespace neomesh
