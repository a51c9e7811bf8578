// Mesh::generate: every case's cell count at a small size, and options out of range.
#include <neomesh/generate.hpp>

#include <limits>
#include <map>
#include <string>

#include <gtest/gtest.h>

#include <neomesh/error.hpp>
#include <neomesh/mesh.hpp>

namespace neomesh {
namespace {

struct Expected {
  int size;
  std::int64_t cells;
};

// docs/cases.md: 2D refinements make 4× the cells; box-tri 2 per square, box-tet 6, box-wedge
// 2 and box-pyramid 6 per cube; the annulus cases split like the boxes.
const std::map<std::string, Expected>& expected() {
  static const std::map<std::string, Expected> all = {
      {"square-midpoint", {4, 16}}, {"cube-midpoint", {2, 8}}, {"square-random", {3, 9}},
      {"transition", {1, 20}},      {"circle-quad", {1, 20}},  {"triangle-equilateral", {2, 16}},
      {"triangle-curved", {1, 32}}, {"box-quad", {3, 9}},      {"box-tri", {3, 18}},
      {"box-hex", {2, 8}},          {"box-tet", {2, 48}},      {"box-wedge", {2, 16}},
      {"box-pyramid", {2, 48}},     {"annulus-quad", {3, 9}},  {"annulus-tri", {3, 18}},
      {"annulus-hex", {2, 8}},      {"annulus-tet", {2, 48}},
  };
  return all;
}

TEST(GenerateMesh, EveryCaseHasItsCellCountAndType) {
  ASSERT_EQ(generated_cases().size(), expected().size());
  for (const GeneratedCase& c : generated_cases()) {
    const Expected e = expected().at(std::string(c.name));
    const Mesh mesh = Mesh::generate({.name = std::string(c.name), .size = e.size});
    EXPECT_EQ(mesh.num_cells(), e.cells) << c.name;
    EXPECT_EQ(mesh.name(), c.name);
    const QualitySummary quality = mesh.quality();
    EXPECT_EQ(quality.cells_by_type[static_cast<int>(c.type)], e.cells) << c.name;
    EXPECT_EQ(quality.inverted, 0) << c.name;
  }
}

TEST(GenerateMesh, ALargeJitterKeepsInvertedCells) {
  const Mesh mesh = Mesh::generate({.name = "box-quad", .size = 16, .jitter = 0.9});
  EXPECT_GT(mesh.quality().inverted, 0);
  const Mesh calm = Mesh::generate({.name = "box-quad", .size = 16, .jitter = 0.2});
  EXPECT_EQ(calm.quality().inverted, 0);
  EXPECT_NEAR(calm.volume(), 4.0, 1e-12);  // only interior vertices move
  // The annulus' cells are as wide across (1/n) as the box's (2/n) at twice the cells.
  const Mesh annulus = Mesh::generate({.name = "annulus-quad", .size = 8, .jitter = 0.2});
  EXPECT_EQ(annulus.quality().inverted, 0);
  const Mesh plain = Mesh::generate({.name = "annulus-quad", .size = 8});
  EXPECT_NEAR(annulus.volume(), plain.volume(), 1e-12);
  EXPECT_NE(annulus.coordinates(), plain.coordinates());
}

TEST(GenerateMesh, SeedDecidesTheRandomMesh) {
  auto coordinates = [](unsigned seed) {
    return Mesh::generate({.name = "square-random", .size = 4, .seed = seed}).coordinates();
  };
  EXPECT_EQ(coordinates(1), coordinates(1));
  EXPECT_NE(coordinates(1), coordinates(2));
}

// The field an OptionError names, or "" if `options` are valid.
std::string bad_field(const GenerateOptions& options) {
  try {
    options.validate();
  } catch (const OptionError& e) {
    return e.field();
  }
  return "";
}

TEST(GenerateMesh, OptionsOutOfRangeNameTheirField) {
  EXPECT_EQ(bad_field({}), "");
  EXPECT_EQ(bad_field({.name = "hexagon"}), "name");
  EXPECT_EQ(bad_field({.name = "square-midpoint", .size = 3}), "size");
  EXPECT_EQ(bad_field({.name = "box-hex", .size = 0}), "size");
  EXPECT_EQ(bad_field({.name = "transition", .size = 0}), "");
  EXPECT_EQ(bad_field({.name = "transition", .size = -1}), "size");
  EXPECT_EQ(bad_field({.amplitude = 0.25}), "amplitude");
  EXPECT_EQ(bad_field({.jitter = 1.0}), "jitter");
  EXPECT_EQ(bad_field({.name = "transition", .size = 1, .jitter = 0.1}), "jitter");
  EXPECT_EQ(bad_field({.rotate_degrees = std::numeric_limits<double>::infinity()}),
            "rotate_degrees");
  EXPECT_THROW(Mesh::generate({.name = "box-quad", .size = 0}), OptionError);
}

}  // namespace
}  // namespace neomesh
