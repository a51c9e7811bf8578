#include "mesh/plane_embedding.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "core/error.hpp"

namespace neomesh {
namespace {

// A 3×3 grid of points x = origin + i a + j b (3 values per point).
std::vector<double> grid(const double (&origin)[3], const double (&a)[3], const double (&b)[3]) {
  std::vector<double> xyz;
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i)
      for (int d = 0; d < 3; ++d) xyz.push_back(origin[d] + i * a[d] + j * b[d]);
  return xyz;
}

TEST(PlaneEmbedding, ThePlaneZEqualsZeroIsXy) {
  std::vector<double> uv;
  const auto xyz = grid({0, 0, 0}, {1, 0, 0}, {0, 2, 0});
  const PlaneEmbedding plane = PlaneEmbedding::fit(xyz, uv, "in.msh").value();
  EXPECT_TRUE(plane.is_xy());
  for (int p = 0; p < 9; ++p) {
    EXPECT_EQ(uv[2 * p], xyz[3 * p]);
    EXPECT_EQ(uv[2 * p + 1], xyz[3 * p + 1]);
  }
}

TEST(PlaneEmbedding, AnAxisPlaneKeepsItsConstantAndTheOtherCoordinatesExactly) {
  std::vector<double> uv;
  const auto xyz = grid({0.1, -5, 0.3}, {0.7, 0, 0}, {0, 0, 0.3});  // y = -5
  const PlaneEmbedding plane = PlaneEmbedding::fit(xyz, uv, "in.msh").value();
  EXPECT_FALSE(plane.is_xy());
  EXPECT_EQ(plane.describe(), "y = -5");
  uv[0] += 0.01;  // one vertex moves in the plane
  const std::vector<double> back = plane.to_space(uv);
  for (int p = 0; p < 9; ++p) EXPECT_EQ(back[3 * p + 1], -5.0) << p;
  for (std::size_t i = 3; i < xyz.size(); ++i) EXPECT_EQ(back[i], xyz[i]) << i;
  EXPECT_EQ(back[2], xyz[2] + 0.01);  // u = z for the plane y = const
}

TEST(PlaneEmbedding, ATiltedPlaneGivesUnmovedVerticesBackBitForBit) {
  std::vector<double> uv;
  const double s = 1 / std::sqrt(3.0);
  const auto xyz = grid({1, 2, 3}, {s, s, s}, {0.2, -0.1, -0.1});
  const PlaneEmbedding plane = PlaneEmbedding::fit(xyz, uv, "in.msh").value();
  EXPECT_FALSE(plane.is_xy());
  // In-plane distances are those of space.
  const double du = uv[2] - uv[0], dv = uv[3] - uv[1];
  EXPECT_NEAR(std::hypot(du, dv), 1.0, 1e-14);

  std::vector<double> moved = uv;
  moved[8] += 0.05, moved[9] -= 0.02;  // vertex 4
  const std::vector<double> back = plane.to_space(moved);
  for (int p = 0; p < 9; ++p) {
    if (p == 4) continue;
    for (int d = 0; d < 3; ++d) EXPECT_EQ(back[3 * p + d], xyz[3 * p + d]) << p;
  }
  // The moved vertex lies in the plane, 0.05385 from where it was.
  const double n[3] = {0, 1 / std::sqrt(2.0), -1 / std::sqrt(2.0)};  // a × b, normalized
  double off = 0, dist = 0;
  for (int d = 0; d < 3; ++d) {
    off += (back[12 + d] - xyz[12 + d]) * n[d];
    dist += std::pow(back[12 + d] - xyz[12 + d], 2);
  }
  EXPECT_NEAR(off, 0.0, 1e-15);
  EXPECT_NEAR(std::sqrt(dist), std::hypot(0.05, 0.02), 1e-15);
}

TEST(PlaneEmbedding, DigitsOfAFileAreNoiseButACurvedSurfaceIsNoPlane) {
  std::vector<double> uv;
  auto xyz = grid({0, 0, 0}, {1, 0, 1}, {0, 1, 0});
  xyz[3 * 4] += 1e-7;  // a coordinate stored with few digits
  EXPECT_TRUE(PlaneEmbedding::fit(xyz, uv, "in.msh").has_value());
  xyz[3 * 4] += 1e-3;  // a bump: a surface
  EXPECT_FALSE(PlaneEmbedding::fit(xyz, uv, "bump.msh").has_value())
      << "a curved surface was taken as a plane";
}

TEST(PlaneEmbedding, ANonFiniteCoordinateIsNamedNotTakenForASurface) {
  std::vector<double> uv;
  auto xyz = grid({0, 0, 0}, {1, 0, 0}, {0, 1, 0});
  xyz[3 * 5 + 2] = std::nan("");
  try {
    PlaneEmbedding::fit(xyz, uv, "nan.msh");
    FAIL() << "a NaN coordinate was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("nan.msh: vertex 5 (0-based) has a non-finite"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace neomesh
