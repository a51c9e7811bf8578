#include "adapt/size_field.hpp"

#include <cmath>
#include <fstream>
#include <numeric>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

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
    const std::vector<double> v = desired_volumes(circle, o, view, dofs, view.coords, 4.0);
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
    const std::vector<double> v = desired_volumes(line, o, view, dofs, view.coords, 4.0);
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

}  // namespace
}  // namespace neomesh
