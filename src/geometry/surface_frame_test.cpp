#include "geometry/surface_frame.hpp"

#include <gtest/gtest.h>

#include <random>

namespace neomesh {
namespace {

template <typename T>
class SurfaceFrameTest : public ::testing::Test {};
using SurfaceCellTypes =
    ::testing::Types<CellTag<CellType::Triangle>, CellTag<CellType::Quadrilateral>>;
TYPED_TEST_SUITE(SurfaceFrameTest, SurfaceCellTypes);

// For random non-planar cells: Q is orthonormal with t1 × t2 = n, t1 along the first edge's
// part in the plane, and n across the diagonals (a triangle's: its edges), pointing to the side
// from which they turn counter-clockwise.
TYPED_TEST(SurfaceFrameTest, FrameIsOrthonormalAlongTheNormalAndTheFirstEdge) {
  constexpr CellType Type = TypeParam::value;
  using Coordinates = Eigen::Matrix<double, 3, CellTraits<Type>::vertices>;
  std::mt19937 rng(21);
  std::uniform_real_distribution<double> u(-0.2, 0.2);
  for (int trial = 0; trial < 5; ++trial) {
    Coordinates x = Coordinates::Zero();
    x.template topRows<2>() = unit_optimal_cell<Type>();
    x += Coordinates::NullaryExpr([&] { return u(rng); });
    const SurfaceFrame frame = *surface_cell_frame<Type>(x);
    const Vector<3> normal = *surface_cell_normal<Type>(x);
    EXPECT_LT((frame.transpose() * frame - Matrix<2>::Identity()).norm(), 1e-15);
    EXPECT_LT((frame.col(0).cross(frame.col(1)) - normal).norm(), 1e-15);
    const Vector<3> first = x.col(1) - x.col(0);
    EXPECT_NEAR(frame.col(0).dot(first), (first - first.dot(normal) * normal).norm(), 1e-15);
    const bool triangle = Type == CellType::Triangle;
    const Vector<3> d0 = x.col(triangle ? 1 : 3) - x.col(0),
                    d1 = x.col(2) - x.col(triangle ? 0 : 1);
    EXPECT_LT(std::abs(normal.dot(d0)) + std::abs(normal.dot(d1)), 1e-15);
    EXPECT_GT(normal.dot(d0.cross(d1)), 0.0);
    EXPECT_GT(normal[2], 0.9);  // the cell's +z side, as in 2D
  }
  EXPECT_FALSE(surface_cell_frame<Type>(Coordinates::Zero()).has_value());
}

}  // namespace
}  // namespace neomesh
