// The exact FEAT3 chart shapes: Bezier curves and extrusions along z.
#include "boundary/shape.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include <Eigen/Geometry>

#include "core/error.hpp"

namespace neomesh {
namespace {

// B(t) = (2t, 4t(1 − t)): the parabola y = 2x − x² for x in [0, 2], one quadratic segment,
// followed by a straight segment from (2, 0) to (3, 0).
std::unique_ptr<Surface> parabola_and_line() {
  return make_bezier({{0, 0, 0}, {1, 2, 0}, {2, 0, 0}, {3, 0, 0}}, {0, 2, 3});
}

double parabola(double x) {
  return 2 * x - x * x;
}

// The distance from p to the curve, by brute force over 200001 samples of each segment.
double sampled_distance(const Point& p) {
  double best = 1e300;
  for (int k = 0; k <= 200000; ++k) {
    const double x = 2.0 * k / 200000;
    best = std::min(best, (Point(x, parabola(x), 0) - p).norm());
    best = std::min(best, (Point(2.0 + 0.5 * x, 0, 0) - p).norm());
  }
  return best;
}

TEST(Bezier, ClosestPointIsExactOnTheCurveAndNearest) {
  const auto curve = parabola_and_line();
  for (const Point& p : {Point(0.3, 1.5, 0), Point(1.0, 0.2, 0), Point(1.9, -0.4, 0),
                         Point(2.6, 0.3, 0), Point(-0.5, -0.1, 0), Point(1.0, 3.0, 0)}) {
    const Point q = curve->closest_point(p);
    if (q.x() <= 2.0) {
      EXPECT_NEAR(q.y(), parabola(q.x()), 1e-14) << p.transpose();
    } else {
      EXPECT_EQ(q.y(), 0.0) << p.transpose();
    }
    EXPECT_NEAR((q - p).norm(), sampled_distance(p), 1e-9) << p.transpose();
    // A point of the curve is its own closest point, to round-off.
    EXPECT_NEAR((curve->closest_point(q) - q).norm(), 0.0, 1e-14) << p.transpose();
  }
}

TEST(Bezier, NormalIsPerpendicularToTheTangent) {
  const auto curve = parabola_and_line();
  const double x = 0.7;
  const Point q(x, parabola(x), 0);
  const Point tangent = Point(1, 2 - 2 * x, 0).normalized();
  const Point n = curve->normal(q);
  EXPECT_NEAR(n.norm(), 1.0, 1e-15);
  EXPECT_NEAR(n.dot(tangent), 0.0, 1e-14);
  EXPECT_EQ(n.z(), 0.0);
}

// S t = dn/ds, checked against central differences of the normal along the curve.
void expect_shape_operator_matches_differences(const Surface& s, const Point& q,
                                               const Point& tangent) {
  const double h = 1e-5;
  const Point ahead = s.closest_point(q + h * tangent), behind = s.closest_point(q - h * tangent);
  const Point difference = (s.normal(ahead) - s.normal(behind)) / (ahead - behind).norm();
  const Point exact = s.shape_operator(q) * tangent;
  EXPECT_NEAR((exact - difference).norm(), 0.0, 1e-6 * (1 + difference.norm()))
      << "S t = " << exact.transpose() << ", differences " << difference.transpose();
}

TEST(Bezier, ShapeOperatorMatchesDifferencesOfTheNormal) {
  const auto curve = parabola_and_line();
  for (double x : {0.2, 1.0, 1.7}) {
    const Point q(x, parabola(x), 0);
    expect_shape_operator_matches_differences(*curve, q, Point(1, 2 - 2 * x, 0).normalized());
  }
  // The straight segment does not bend.
  EXPECT_NEAR(curve->shape_operator({2.5, 0, 0}).norm(), 0.0, 1e-15);
}

TEST(Bezier, RefusesDegreesFeat3DoesNotWrite) {
  EXPECT_THROW(make_bezier({{0, 0, 0}}, {0}), Error);
  std::vector<Point> seven(7, Point::Zero());
  EXPECT_THROW(make_bezier(seven, {0, 6}), Error);  // degree 6
}

TEST(Extrusion, OfACircleIsACylinder) {
  const auto extruded = make_extrusion(make_sphere({1, 0, 0}, 0.5, 2));
  const auto cylinder = make_cylinder({1, 0, 0}, {0, 0, 1}, 0.5);
  for (const Point& p : {Point(2, 1, 3), Point(0.9, 0.1, -1), Point(1, -2, 0.5)}) {
    const Point q = extruded->closest_point(p);
    EXPECT_NEAR((q - cylinder->closest_point(p)).norm(), 0.0, 1e-15);
    EXPECT_EQ(q.z(), p.z());
    EXPECT_NEAR((extruded->normal(q) - cylinder->normal(q)).norm(), 0.0, 1e-15);
    EXPECT_NEAR((extruded->shape_operator(q) - cylinder->shape_operator(q)).norm(), 0.0, 1e-14);
  }
}

TEST(Extrusion, OfABezierCurveBendsInThePlaneOnly) {
  const auto surface = make_extrusion(parabola_and_line());
  const double x = 0.4;
  const Point q(x, parabola(x), 2.0);
  EXPECT_NEAR((surface->closest_point(q + 0.01 * surface->normal(q)) - q).norm(), 0, 1e-14);
  expect_shape_operator_matches_differences(*surface, q, Point(1, 2 - 2 * x, 0).normalized());
  EXPECT_NEAR((surface->shape_operator(q) * Point(0, 0, 1)).norm(), 0.0, 1e-15);
}

// A quarter turn about y takes the extrusion's z axis to x: a pipe along x (FEAT3's
// flowbench_p3d pipe: angles="0 0.25 0" offset="0 0.205 0.205").
TEST(Extrusion, PlacedByRotationAndOffset) {
  const Matrix3 rotation = Eigen::AngleAxisd(M_PI / 2, Point::UnitY()).toRotationMatrix();
  const auto pipe =
      make_extrusion(make_sphere({0, 0, 0}, 0.205, 2), rotation, Point::Zero(), {0, 0.205, 0.205});
  const auto cylinder = make_cylinder({0, 0.205, 0.205}, {1, 0, 0}, 0.205);
  for (const Point& p : {Point(0.765, 0.3485, 0.0615), Point(2, 0.1, 0.3)}) {
    const Point q = pipe->closest_point(p);
    EXPECT_NEAR((q - cylinder->closest_point(p)).norm(), 0.0, 1e-15);
    EXPECT_NEAR(std::abs(pipe->normal(q).dot(cylinder->normal(q))), 1.0, 1e-15);
    EXPECT_NEAR((pipe->shape_operator(q) - cylinder->shape_operator(q)).norm(), 0.0, 1e-14);
  }
}

}  // namespace
}  // namespace neomesh
