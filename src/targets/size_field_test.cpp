#include "targets/size_field.hpp"

#include <cmath>
#include <fstream>
#include <numeric>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include "core/error.hpp"
#include "core/testing/test_data.hpp"
#include "generate/generate.hpp"
#include "generate/serial_view.hpp"

namespace neomesh {
namespace {

using ::testing::HasSubstr;

// The distance a field assigns to one point: a one-cell "mesh" would do, but evaluating
// through a tiny box keeps the test on the public interface.
double distance_at(const SizeField& field, std::vector<double> point) {
  const MeshData mesh = box(point.size() == 2 ? CellType::Triangle : CellType::Tetrahedron, 1);
  MeshView view = serial_view(mesh);
  // Collapse every vertex onto the point: the centroid is the point.
  std::vector<double> coords(view.coords.size());
  for (std::size_t i = 0; i < coords.size(); ++i) coords[i] = point[i % point.size()];
  return relative_volumes(field, view, coords, {.floor = 0.0, .power = 1.0}, PETSC_COMM_SELF)[0];
}

void expect_error(const std::function<void()>& f, const std::string& message) {
  try {
    f();
    FAIL() << "expected an error containing: " << message;
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr(message));
  }
}

TEST(SizeField, DistanceToCircleAndSphere) {
  const SizeField circle = SizeField::sphere({0.0, 0.0}, 0.7);
  EXPECT_NEAR(distance_at(circle, {0.0, 0.0}), 0.7, 1e-15);
  EXPECT_NEAR(distance_at(circle, {0.3, 0.4}), 0.2, 1e-15);
  EXPECT_NEAR(distance_at(circle, {0.0, -1.0}), 0.3, 1e-15);
  const SizeField sphere = SizeField::sphere({1.0, 0.0, 0.0}, 0.5);
  EXPECT_NEAR(distance_at(sphere, {1.0, 0.0, 2.0}), 1.5, 1e-15);
}

TEST(SizeField, DistanceToPlane) {
  const SizeField line = SizeField::plane({0.0, 0.5}, {0.0, 2.0});  // y = 0.5
  EXPECT_NEAR(distance_at(line, {0.3, -0.5}), 1.0, 1e-15);
  const SizeField plane = SizeField::plane({0.0, 0.0, 0.0}, {1.0, 1.0, 1.0});
  EXPECT_NEAR(distance_at(plane, {1.0, 1.0, 1.0}), std::sqrt(3.0), 1e-15);
}

TEST(SizeField, DistanceToBoxSurface) {
  const SizeField b = SizeField::box({-0.5, -0.5}, {0.5, 0.25});
  EXPECT_NEAR(distance_at(b, {0.0, 0.0}), 0.25, 1e-15);  // inside: nearest face (top)
  EXPECT_NEAR(distance_at(b, {1.0, 0.0}), 0.5, 1e-15);   // outside a face
  EXPECT_NEAR(distance_at(b, {0.8, 0.65}), 0.5, 1e-15);  // outside a corner: (0.3, 0.4)
}

TEST(SizeField, LevelSetExpression) {
  const SizeField phi = SizeField::level_set("sqrt(x^2 + y^2 + z^2) - 0.7");
  EXPECT_NEAR(distance_at(phi, {0.3, 0.4}), 0.2, 1e-15);
  EXPECT_NEAR(distance_at(phi, {0.0, 0.0, 0.2}), 0.5, 1e-15);
}

TEST(SizeField, FloorAndPower) {
  const MeshData mesh = box(CellType::Quadrilateral, 2);  // centroids (±0.5, ±0.5)
  const MeshView view = serial_view(mesh);
  const SizeField circle = SizeField::sphere({0.0, 0.0}, 0.2);
  const double d = std::sqrt(0.5) - 0.2;
  for (double v :
       relative_volumes(circle, view, view.coords, {.floor = 0.1, .power = 3.0}, PETSC_COMM_SELF))
    EXPECT_NEAR(v, 0.1 + d * d * d, 1e-15);
}

TEST(SizeField, DesiredVolumesSumToTheMeshVolume) {
  const MeshData mesh = box(CellType::Quadrilateral, 8);
  const MeshView view = serial_view(mesh);
  const DofMap dofs = DofMap::serial(2, view.num_vertices);
  const SizeField circle = SizeField::sphere({0.0, 0.0}, 0.7);
  for (const SizeFieldOptions& o :
       {SizeFieldOptions::thesis(), SizeFieldOptions{.max_ratio = 10.0, .smoothing_passes = 0},
        SizeFieldOptions{.max_ratio = 0.0, .smoothing_passes = 2}}) {
    const std::vector<double> v =
        desired_volumes_from_field(circle, o, view, dofs, view.coords, 4.0);
    EXPECT_NEAR(std::accumulate(v.begin(), v.end(), 0.0), 4.0, 1e-12);
    const auto [min, max] = std::minmax_element(v.begin(), v.end());
    if (o.ratio() > 0) {
      EXPECT_NEAR(*max / *min, o.ratio(), 1e-9);
    }
  }
}

TEST(SizeField, SmoothingLimitsTheJumpBetweenNeighbours) {
  const MeshData mesh = box(CellType::Quadrilateral, 16);
  const MeshView view = serial_view(mesh);
  const DofMap dofs = DofMap::serial(2, view.num_vertices);
  const SizeField line = SizeField::plane({0.0, 0.0}, {1.0, 0.0});
  // Cells in a row along x: the largest ratio of consecutive volumes.
  auto worst_jump = [&](const SizeFieldOptions& o) {
    const std::vector<double> v = desired_volumes_from_field(line, o, view, dofs, view.coords, 4.0);
    double worst = 1.0;
    for (int i = 0; i + 1 < 16; ++i) worst = std::max({worst, v[i + 1] / v[i], v[i] / v[i + 1]});
    return worst;
  };
  // At the line, the raw field jumps from 1e-8-ish to 3/16: smoothing brings it near 1.
  const double raw = worst_jump(SizeFieldOptions::thesis());
  const double smoothed = worst_jump({.floor = 1e-8, .max_ratio = 100, .smoothing_passes = 3});
  EXPECT_GT(raw, 2.0);
  EXPECT_LT(smoothed, 2.0);
}

TEST(SizeField, CellValuesFromAFile) {
  const MeshData mesh = box(CellType::Quadrilateral, 2);
  const MeshView view = serial_view(mesh);
  const auto dir = testing::scratch_dir("SizeField.CellValuesFromAFile");
  std::ofstream(dir / "sizes.txt") << "1\n2.5\n  3e-1 \n4\n\n";
  const SizeField field = SizeField::read_cell_values(dir / "sizes.txt");
  EXPECT_THAT(relative_volumes(field, view, view.coords, {}, PETSC_COMM_SELF),
              ::testing::ElementsAre(1.0, 2.5, 0.3, 4.0));

  std::ofstream(dir / "short.txt") << "1\n2\n3\n";
  expect_error(
      [&] {
        relative_volumes(SizeField::read_cell_values(dir / "short.txt"), view, view.coords, {},
                         PETSC_COMM_SELF);
      },
      "the size field has 3 values but the mesh has 4 cells");
  std::ofstream(dir / "text.txt") << "1\n2\nlarge\n4\n";
  expect_error([&] { SizeField::read_cell_values(dir / "text.txt"); },
               "text.txt:3: expected one number per line, got 'large'");
  std::ofstream(dir / "negative.txt") << "1\n2\n-3\n4\n";
  expect_error(
      [&] {
        relative_volumes(SizeField::read_cell_values(dir / "negative.txt"), view, view.coords, {},
                         PETSC_COMM_SELF);
      },
      "size field is negative at cell 2 (centroid -0.5, 0.5)");
  expect_error([&] { SizeField::read_cell_values(dir / "missing.txt"); },
               "cannot open the size file");
}

TEST(SizeField, BadInputIsReportedInOneLine) {
  expect_error(
      [] {
        SizeField::sphere({0.0, 0.0}, 0.0);
      },
      "the radius of a circle must be positive (got 0)");
  expect_error([] { SizeField::sphere({0.0}, 1.0); },
               "the centre of a circle/sphere needs 2 or 3 coordinates (got 1)");
  expect_error([] { SizeField::plane({0.0, 0.0}, {0.0, 0.0}); }, "normal of the plane");
  expect_error([] { SizeField::box({0.0, 0.0}, {1.0, 0.0}); }, "must be below its upper corner");
  expect_error([] { SizeField::level_set("sqrt(x^2 + y^2"); },
               "cannot parse the level-set expression 'sqrt(x^2 + y^2': ");
  expect_error([] { SizeField::level_set("w + 1"); }, "cannot parse the level-set expression");

  const MeshData mesh = box(CellType::Quadrilateral, 2);
  const MeshView view = serial_view(mesh);
  expect_error(
      [&] {
        relative_volumes(SizeField::level_set("sqrt(x)"), view, view.coords, {}, PETSC_COMM_SELF);
      },
      "size field is NaN at cell 0 (centroid -0.5, -0.5)");
  expect_error(
      [&] {
        relative_volumes(SizeField::level_set("1/(x+0.5)"), view, view.coords, {}, PETSC_COMM_SELF);
      },
      "size field is infinite at cell 0");
  expect_error(
      [&] {
        relative_volumes(SizeField::sphere({0.0, 0.0, 0.0}, 1.0), view, view.coords, {},
                         PETSC_COMM_SELF);
      },
      "is 3D but the mesh is 2D");
}

// The target shape (M^(-1/2) turned by `rotation`, the cells' Jacobian) and the relative volume a
// metric field gives a point, through a mesh collapsed onto it as in distance_at.
struct MetricAt {
  Eigen::Matrix2d shape;
  double volume;
};
MetricAt metric_at(const SizeField& field, std::vector<double> point,
                   const Eigen::Matrix2d& rotation = Eigen::Matrix2d::Identity()) {
  const MeshData mesh = box(CellType::Triangle, 1);
  MeshView view = serial_view(mesh);
  std::vector<double> coords(view.coords.size());
  for (std::size_t i = 0; i < coords.size(); ++i) coords[i] = point[i % 2];
  std::vector<double> jacobians;
  for (PetscInt c = 0; c < view.num_cells; ++c)
    jacobians.insert(jacobians.end(), rotation.data(), rotation.data() + 4);
  const std::vector<double> shapes = target_shapes(field, view, coords, jacobians);
  return {Eigen::Map<const Eigen::Matrix2d>(shapes.data()),
          relative_volumes(field, view, coords, {}, PETSC_COMM_SELF)[0]};
}

TEST(SizeField, AStretchedCircleHasItsSizesAcrossAndAlongIt) {
  const SizeField field =
      SizeField::sphere({0.0, 0.0}, 1.0).stretched({.normal = 0.01, .tangent = 0.1, .width = 0.05});
  EXPECT_TRUE(field.anisotropic());
  EXPECT_FALSE(SizeField::sphere({0.0, 0.0}, 1.0).anisotropic());
  // Within the width, on the x axis: size 0.01 across (x), 0.1 along (y); on the y axis turned.
  MetricAt m = metric_at(field, {1.02, 0.0});
  EXPECT_TRUE(m.shape.isApprox(Eigen::Vector2d(0.01, 0.1).asDiagonal().toDenseMatrix(), 1e-6))
      << m.shape;
  EXPECT_NEAR(m.volume, 0.01 * 0.1, 1e-9);
  m = metric_at(field, {0.0, -0.99});
  EXPECT_TRUE(m.shape.isApprox(Eigen::Vector2d(0.1, 0.01).asDiagonal().toDenseMatrix(), 1e-6));
  // At 45°: the eigenvectors are the diagonals.
  const double r = 1.0 / std::sqrt(2.0);
  m = metric_at(field, {r, r});
  EXPECT_NEAR((m.shape * Eigen::Vector2d(r, r)).norm(), 0.01, 1e-8);
  EXPECT_NEAR((m.shape * Eigen::Vector2d(-r, r)).norm(), 0.1, 1e-8);
  // 0.06 from the circle, 0.01 beyond the width: 0.01 + 4 · 0.01 across (the default grading).
  m = metric_at(field, {1.06, 0.0});
  EXPECT_NEAR(m.shape(0, 0), 0.05, 1e-8);
  EXPECT_NEAR(m.shape(1, 1), 0.1, 1e-8);
  // Far away: isotropic, the tangential size.
  m = metric_at(field, {3.0, 0.0});
  EXPECT_TRUE(m.shape.isApprox(0.1 * Eigen::Matrix2d::Identity(), 1e-8));
}

TEST(SizeField, TargetShapesTurnWithTheCell) {
  // The energy sees SᵀS: S = M^(-1/2) R makes the cell's physical stretch J Rᵀ the target.
  const SizeField field = SizeField::metric({"100", "0", "1"});  // sizes 0.1 along x, 1 along y
  const Eigen::Matrix2d rotation = Eigen::Rotation2Dd(0.4).toRotationMatrix();
  const MetricAt m = metric_at(field, {0.3, 0.2}, rotation);
  const Eigen::Matrix2d root = Eigen::Vector2d(0.1, 1.0).asDiagonal();
  EXPECT_TRUE(m.shape.isApprox(root * rotation, 1e-12)) << m.shape;
  EXPECT_NEAR(m.volume, 0.1, 1e-12);
}

TEST(SizeField, AMetricFromExpressions) {
  // M = [[4, 1], [1, 4]] · (1 + x): eigenvalues 5 (1 + x) and 3 (1 + x).
  const SizeField field = SizeField::metric({"4*(1+x)", "1+x", "4*(1+x)"});
  const MetricAt m = metric_at(field, {1.0, 0.5});
  const Eigen::Matrix2d metric = (m.shape * m.shape.transpose()).inverse();
  EXPECT_TRUE(metric.isApprox(Eigen::Matrix2d{{8, 2}, {2, 8}}, 1e-12)) << metric;
  EXPECT_NEAR(m.volume, 1 / std::sqrt(60.0), 1e-12);
}

TEST(SizeField, ABadMetricIsReportedWithItsCell) {
  expect_error(
      [] {
        metric_at(SizeField::metric({"1", "2", "1"}), {0.5, 0.5});
      },
      "the metric is not symmetric positive definite at cell 0 (centroid 0.5, 0.5): "
      "eigenvalues -1, 3");
  expect_error([] { metric_at(SizeField::metric({"1", "0", "x/0"}), {0.5, 0.5}); }, "not finite");
  expect_error([] { SizeField::metric({"1", "0"}); }, "a metric needs 3 entries");
  expect_error([] { SizeField::metric({"1", "0", "z*"}); }, "cannot parse the metric entry m22");
  expect_error(
      [] {
        SizeField::cell_values({1.0}).stretched({0.1, 0.2, 0.1});
      },
      "only a field of the distance to a surface can be stretched");
  expect_error(
      [] {
        SizeField::plane({0, 0}, {1, 0}).stretched({0.2, 0.1, 0.1});
      },
      "a stretch needs sizes 0 < normal ≤ tangent");
  expect_error(
      [] {
        SizeField::plane({0, 0}, {1, 0}).stretched({0.1, 0.2, 0.1, 0.0});
      },
      "a stretch needs a grading > 0");
}

}  // namespace
}  // namespace neomesh
