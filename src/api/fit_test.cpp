// Fitting through the public API: Optimizer::adapt with a LevelSet, Mesh::interface, and the
// fields and facet group a fit leaves for Mesh::write.
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <neomesh/neomesh.hpp>

namespace neomesh {
namespace {

using ::testing::HasSubstr;

// n × n quadrilaterals on [-1,1]², vertex j (n + 1) + i at column i, row j.
Mesh grid(int n) {
  std::vector<double> coordinates;
  std::vector<std::int64_t> cells;
  const double h = 2.0 / n;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) coordinates.insert(coordinates.end(), {-1 + i * h, -1 + j * h});
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const std::int64_t v = j * (n + 1) + i;
      cells.insert(cells.end(), {v, v + 1, v + n + 2, v + n + 1});
    }
  const std::vector<CellType> types(static_cast<std::size_t>(n * n), CellType::Quadrilateral);
  return Mesh::from_arrays(MPI_COMM_SELF, 2, coordinates, cells, types, "grid");
}

// Distance from the circle of radius r around the origin of every vertex of `group`.
double largest_distance(const Mesh& mesh, const FacetGroup& group, double r) {
  std::map<std::int64_t, std::size_t> position;
  const std::vector<std::int64_t> numbers = mesh.vertex_numbers();
  for (std::size_t i = 0; i < numbers.size(); ++i) position[numbers[i]] = i;
  const std::vector<double> x = mesh.coordinates();
  double largest = 0.0;
  for (std::int64_t v : group.vertices) {
    const std::size_t i = position.at(v);
    largest = std::max(largest, std::abs(std::hypot(x[2 * i], x[2 * i + 1]) - r));
  }
  return largest;
}

TEST(Fit, PullsAClosedChainOfEdgesOntoTheCircle) {
  Mesh mesh = grid(16);
  const LevelSet circle = LevelSet::sphere({0.0, 0.0}, 0.5);
  const FacetGroup before = mesh.interface(circle);
  ASSERT_GT(before.offsets.size(), 8u);

  Optimizer optimizer(mesh);
  const Result result = optimizer.adapt(SizeField::sphere({0.0, 0.0}, 0.5), circle);
  ASSERT_TRUE(result.fit.has_value());
  EXPECT_EQ(result.fit->level_set, circle.expression());
  EXPECT_LE(result.fit->max_distance, 1e-10);
  EXPECT_EQ(result.quality_after.inverted, 0);
  EXPECT_GT(result.volume_ratio.cells, 0);

  const std::vector<FacetGroup> groups = optimizer.facet_groups();
  ASSERT_EQ(groups.size(), 1u);
  EXPECT_EQ(groups[0].name, "interface");
  EXPECT_EQ(static_cast<std::int64_t>(groups[0].offsets.size()) - 1, result.fit->facets);
  EXPECT_LE(largest_distance(mesh, groups[0], 0.5), 1e-10);
  // A closed chain: every vertex ends two of its edges.
  std::map<std::int64_t, int> ends;
  for (std::int64_t v : groups[0].vertices) ++ends[v];
  for (const auto& [v, count] : ends) EXPECT_EQ(count, 2) << "vertex " << v;

  // Per vertex of vertex_numbers(): 1 on the interface, φ ≈ 0 there.
  const std::vector<Field> fields = optimizer.vertex_fields();
  ASSERT_EQ(fields.size(), 2u);
  EXPECT_EQ(fields[0].values.size(), mesh.vertex_numbers().size());
  double on = 0.0;
  for (std::size_t i = 0; i < fields[0].values.size(); ++i)
    if (fields[0].values[i] == 1.0) {
      on += 1.0;
      EXPECT_LE(std::abs(fields[1].values[i]), 1e-10);
    }
  EXPECT_EQ(on, static_cast<double>(result.fit->vertices));

  // The next adapt() releases the interface: no fit, no interface outputs.
  const Result plain = optimizer.adapt(SizeField::sphere({0.0, 0.3}, 0.5));
  EXPECT_FALSE(plain.fit.has_value());
  EXPECT_TRUE(optimizer.facet_groups().empty());
  EXPECT_TRUE(optimizer.vertex_fields().empty());
}

// A LevelSet alone is the size field |φ| and the interface, at its one time.
TEST(Fit, OneLevelSetIsTheSizeFieldAndTheInterface) {
  const std::string phi = "sqrt(x^2+(y-0.1*t)^2)-0.5";
  Mesh two = grid(16), one = grid(16);
  SizeField field = SizeField::level_set(phi);
  LevelSet interface = LevelSet::expression(phi);
  field.set_time(1.0);
  interface.set_time(1.0);
  const Result apart = Optimizer(two).adapt(field, interface);
  LevelSet moving = LevelSet::expression(phi);
  moving.set_time(1.0);
  const Result together = Optimizer(one).adapt(moving);
  ASSERT_TRUE(together.fit.has_value());
  EXPECT_EQ(together.fit->facets, apart.fit->facets);
  EXPECT_EQ(together.history.size(), apart.history.size());
  EXPECT_EQ(one.coordinates(), two.coordinates());
}

TEST(Fit, TheNextSmoothReleasesTheInterfaceToo) {
  Mesh mesh = grid(16);
  Optimizer optimizer(mesh);
  const LevelSet circle = LevelSet::sphere({0.0, 0.0}, 0.5);
  optimizer.adapt(SizeField::sphere({0.0, 0.0}, 0.5), circle);
  ASSERT_FALSE(optimizer.facet_groups().empty());
  // Smoothing with the adaptation's energy and boundary keeps the functional, not the fit.
  SmoothOptions smooth;
  smooth.energy = AdaptOptions().energy;
  smooth.boundary = AdaptOptions().boundary;
  smooth.sizes = SizeMode::Uniform;
  const Result result = optimizer.smooth(smooth);
  EXPECT_EQ(result.quality_after.inverted, 0);
  EXPECT_TRUE(optimizer.facet_groups().empty());
  EXPECT_TRUE(optimizer.vertex_fields().empty());
  for (const Field& f : optimizer.cell_fields()) EXPECT_NE(f.name, "inside");
}

TEST(Fit, ALevelSetWithoutInterfaceOrOutOfRangeIsAnError) {
  const Mesh mesh = grid(4);
  try {
    mesh.interface(LevelSet::expression("x^2+y^2+1"));
    FAIL() << "no interface inside the mesh";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("fit: the level set x^2+y^2+1 is ≥ 0 at every cell centre"));
  }
  EXPECT_THROW(LevelSet::sphere({0.0, 0.0}, 0.0), Error);
  EXPECT_THROW(LevelSet::sphere({0.0}, 1.0), Error);
  EXPECT_THROW(LevelSet::plane({0.0, 0.0}, {0.0, 0.0}), Error);
  EXPECT_THROW(LevelSet::expression("x + w"), Error);
}

TEST(Fit, WritesTheInterfaceAsAPhysicalGroupOfTheMsh) {
  Mesh mesh = grid(16);
  Optimizer optimizer(mesh);
  optimizer.adapt(SizeField::sphere({0.0, 0.0}, 0.5), LevelSet::sphere({0.0, 0.0}, 0.5));
  const auto path = std::filesystem::path(::testing::TempDir()) / "fit_test_interface.msh";
  mesh.write(path, optimizer.cell_fields(), optimizer.vertex_fields(), optimizer.facet_groups());
  const Mesh read = Mesh::read(path, MPI_COMM_SELF);
  EXPECT_EQ(read.num_cells(), mesh.num_cells());
  std::ifstream in(path);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_THAT(text, HasSubstr("\"interface\""));
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace neomesh
