// The chapter-6 cases of the thesis (docs/cases.md): [-1,1]^d adapted to the circle/sphere of
// radius 0.7 around the origin. The 3D case at 32³ is in picard_longtest.cpp.
#include "adapt/picard.hpp"

#include <gtest/gtest.h>

#include "adapt/testing/sphere_case.hpp"

namespace neomesh {
namespace {

using testing::adapt_to_sphere;
using testing::kAdaptEnergy;
using Outcome = testing::SphereOutcome;

bool converged(const Outcome& o) {
  return o.converged();
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

// neomesh's defaults: λ = 4 μ, sliding boundary vertices, ratio 32, one smoothing pass.
Outcome adapt_with_defaults(CellType type, int n) {
  return adapt_to_sphere(type, n, {}, {}, kAdaptEnergy, BoundaryMode::Slide);
}

// The issue's criteria for the circle and the sphere; measured: docs/adaptivity.md.
void expect_adapted(const Outcome& o, double min_scaled_jacobian) {
  EXPECT_TRUE(converged(o));
  EXPECT_EQ(o.inverted, 0);
  EXPECT_GE(o.q.within, 0.9);
  EXPECT_LE(o.near_far, 0.25);
  EXPECT_GE(o.min_scaled_jacobian, min_scaled_jacobian);
}

TEST(AdaptCircle, Quads32CrowdCellsAtTheCircle) {
  const Outcome o = adapt_with_defaults(CellType::Quadrilateral, 32);
  expect_adapted(o, 0.25);
  EXPECT_LE(o.result.run.history.size(), 60u);
}

TEST(AdaptCircle, Quads64CrowdCellsAtTheCircle) {
  expect_adapted(adapt_with_defaults(CellType::Quadrilateral, 64), 0.25);
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
  const Outcome o = adapt_with_defaults(CellType::Triangle, 32);
  expect_adapted(o, 0.15);
  EXPECT_LE(o.result.run.history.size(), 87u);
}

// The thesis' 3D failure (Table 6.2) is fixed by sliding boundary vertices and λ = 4 μ; the
// issue's 32³ case is in picard_longtest.cpp, 12³ keeps this test at about half a minute.
TEST(AdaptSphere, Hexes12MeetTheIssueCriteria) {
  expect_adapted(adapt_with_defaults(CellType::Hexahedron, 12), 0.3);
}

}  // namespace
}  // namespace neomesh
