#include "energy/surface_kernels.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>
#include <random>

#include "core/testing/finite_differences.hpp"

namespace neomesh {
namespace {

using testing::kFdTolerance;

template <CellType Type>
using Planar = typename CellTraits<Type>::Coordinates;  // 2 × vertices
template <CellType Type>
using Spatial = Eigen::Matrix<double, 3, CellTraits<Type>::vertices>;

// A generic valid 2D cell of area about `area`: the unit optimal cell scaled, mapped by a random
// matrix near the identity, every vertex moved by up to 10 % of the edge.
template <CellType Type>
Planar<Type> planar_cell(double area, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double edge = std::sqrt(area);
  const Matrix<2> map =
      Matrix<2>::Identity() + 0.2 * Matrix<2>::NullaryExpr([&] { return u(rng); });
  Planar<Type> y = edge * map * unit_optimal_cell<Type>();
  return y + 0.1 * edge * Planar<Type>::NullaryExpr([&] { return u(rng); });
}

// A rotation of space about a random axis by a random angle.
Matrix<3> random_rotation(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const Vector<3> axis = Vector<3>::NullaryExpr([&] { return u(rng); }).normalized();
  return Eigen::AngleAxisd(3.0 * u(rng), axis).toRotationMatrix();
}

// The 2D cell y placed in space: rotated by R and moved by `shift`.
template <CellType Type>
Spatial<Type> into_space(const Planar<Type>& y, const Matrix<3>& R, const Vector<3>& shift) {
  Spatial<Type> x = Spatial<Type>::Zero();
  x.template topRows<2>() = y;
  return (R * x).colwise() + shift;
}

// A non-planar cell and a frame tilted against it: a planar cell in space with every vertex
// moved by up to 10 % of the edge, and the planar cell's frame turned by up to 0.3 rad.
template <CellType Type>
std::pair<Spatial<Type>, SurfaceFrame> tilted_cell(double area, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Spatial<Type> x = into_space<Type>(planar_cell<Type>(area, rng), random_rotation(rng),
                                     Vector<3>(u(rng), u(rng), u(rng)));
  const Vector<3> axis = Vector<3>::NullaryExpr([&] { return u(rng); }).normalized();
  const SurfaceFrame frame =
      Eigen::AngleAxisd(0.3 * u(rng), axis).toRotationMatrix() * *surface_cell_frame<Type>(x);
  x += 0.1 * std::sqrt(area) * Spatial<Type>::NullaryExpr([&] { return u(rng); });
  return {x, frame};
}

// A target shape S (det S = 1) with a 6 : 1 stretch, given as S⁻ᵀ as CellTarget wants it.
Matrix<2> stretched_shape_inverse_t(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Matrix<2> S;
  S << 6.0 + 0.3 * u(rng), 0.3 * u(rng), 0.3 * u(rng), 1.0 + 0.3 * u(rng);
  S /= std::sqrt(S.determinant());
  return S.inverse().transpose();
}

template <CellType Type>
NeoHookeSurfaceKernel<Type> thesis_surface_kernel(double corner_weight = 0.0) {
  return NeoHookeSurfaceKernel<Type>(NeoHooke<2>{1.0, 10.0, 1.0}, 3, corner_weight);
}

template <CellType Type>
UntanglingSurfaceKernel<Type> untangling_surface_kernel() {
  return make_untangling_surface_kernel<Type>(RegularizedNeoHooke<2>{1.0, 10.0, 0.1}, 3);
}

template <typename T>
class SurfaceKernelTest : public ::testing::Test {};
using SurfaceCellTypes =
    ::testing::Types<CellTag<CellType::Triangle>, CellTag<CellType::Quadrilateral>>;
TYPED_TEST_SUITE(SurfaceKernelTest, SurfaceCellTypes);

// A 2D cell rotated into space, in the frame its vertices give, has the 2D kernel's energy,
// its gradient rotated, and its Hessian's vertex blocks rotated — for both laws.
template <typename Kernel, typename PlanarKernel>
void expect_rotated_copy_matches_2d(const Kernel& kernel, const PlanarKernel& planar,
                                    std::mt19937& rng) {
  constexpr CellType Type = Kernel::type;
  for (int trial = 0; trial < 3; ++trial) {
    const double area = 0.5 + trial;
    const Planar<Type> y = planar_cell<Type>(area, rng);
    const Matrix<3> R = random_rotation(rng);
    const Spatial<Type> x = into_space<Type>(y, R, Vector<3>(1.0, -2.0, 0.5));
    const SurfaceFrame frame = *surface_cell_frame<Type>(x);
    EXPECT_LT((frame.col(0).cross(frame.col(1)) - R.col(2)).norm(), 1e-14);

    typename PlanarKernel::Gradient g2;
    typename Kernel::Gradient g;
    const double e2 = planar.energy_and_gradient(y, area, g2);
    EXPECT_NEAR(kernel.energy_and_gradient(x, frame, area, g), e2, 1e-13 * e2);
    const SurfaceFrame plane = R.leftCols<2>();  // the xy plane rotated
    EXPECT_LT(testing::relative_error(g, plane * g2), 1e-13);

    typename PlanarKernel::Block h2;
    typename Kernel::Block h;
    ASSERT_TRUE(planar.hessian(y, area, 0.3, h2));
    ASSERT_TRUE(kernel.hessian(x, frame, area, 0.3, h));
    Eigen::Matrix<double, Kernel::dofs, PlanarKernel::dofs> lift =
        Eigen::Matrix<double, Kernel::dofs, PlanarKernel::dofs>::Zero();
    for (int i = 0; i < Kernel::vertices; ++i) lift.template block<3, 2>(3 * i, 2 * i) = plane;
    EXPECT_LT(testing::relative_error(h, lift * h2 * lift.transpose()), 1e-13);
  }
}

TYPED_TEST(SurfaceKernelTest, PlanarCellRotatedIntoSpaceIsThe2DCellRotated) {
  constexpr CellType Type = TypeParam::value;
  std::mt19937 rng(22);
  expect_rotated_copy_matches_2d(thesis_surface_kernel<Type>(),
                                 NeoHookeKernel<Type>(NeoHooke<2>{1.0, 10.0, 1.0}, 3), rng);
  const RegularizedNeoHooke<2> law{1.0, 10.0, 0.1};
  expect_rotated_copy_matches_2d(untangling_surface_kernel<Type>(),
                                 make_untangling_kernel<Type>(law, 3), rng);
}

// The optimal cell of the desired area, anywhere in space, is the minimum: zero energy and
// gradient, and its image has the desired area.
TYPED_TEST(SurfaceKernelTest, OptimalCellInSpaceHasZeroEnergyAndGradient) {
  constexpr CellType Type = TypeParam::value;
  std::mt19937 rng(23);
  const auto kernel = thesis_surface_kernel<Type>();
  for (double area : {0.01, 1.0, 7.0}) {
    const Spatial<Type> x = into_space<Type>(std::sqrt(area) * unit_optimal_cell<Type>(),
                                             random_rotation(rng), Vector<3>(3.0, 1.0, -1.0));
    const SurfaceFrame frame = *surface_cell_frame<Type>(x);
    typename NeoHookeSurfaceKernel<Type>::Gradient g;
    EXPECT_NEAR(kernel.energy_and_gradient(x, frame, area, g), 0.0, 1e-13);
    EXPECT_LT(g.norm(), 1e-12);
    EXPECT_NEAR(kernel.measure(x, frame, area).volume, area, 1e-14 * area);
  }
}

// Gradient and H(1) against central differences, for tilted non-planar cells, ideal and
// stretched targets; H(α) affine in α with its B3 the lifted target Laplacian; exact symmetry.
template <typename Kernel>
void expect_derivatives_match(const Kernel& kernel, double mu, std::mt19937& rng) {
  constexpr CellType Type = Kernel::type;
  using X = typename Kernel::Coordinates;
  for (int trial = 0; trial < 4; ++trial) {
    const double area = 0.5 + trial;
    const Matrix<2> shape = stretched_shape_inverse_t(rng);
    for (const CellTarget<2>& target : {CellTarget<2>(area), CellTarget<2>(area, shape.data())}) {
      const auto cell = tilted_cell<Type>(area, rng);
      const X& x = cell.first;
      const SurfaceFrame& frame = cell.second;
      typename Kernel::Gradient g;
      ASSERT_TRUE(std::isfinite(kernel.energy_and_gradient(x, frame, target, g)));
      const double step = 1e-6 * std::sqrt(area);
      const auto fd = testing::fd_gradient(
          [&](const X& y) { return kernel.energy(y, frame, target); }, x, step);
      EXPECT_LT(testing::relative_error(g, fd), kFdTolerance) << "analytic\n"
                                                              << g << "\nfd\n"
                                                              << fd;

      typename Kernel::Block h1, h0, half, laplacian;
      ASSERT_TRUE(kernel.hessian(x, frame, target, 1.0, h1));
      const auto gradient = [&](const X& y) {
        typename Kernel::Gradient gy;
        kernel.energy_and_gradient(y, frame, target, gy);
        return gy;
      };
      EXPECT_LT(testing::relative_error(h1, testing::fd_jacobian(gradient, x, step)), kFdTolerance);
      EXPECT_EQ((h1 - h1.transpose()).norm(), 0.0);
      kernel.hessian(x, frame, target, 0.0, h0);
      kernel.hessian(x, frame, target, 0.5, half);
      EXPECT_LT(testing::relative_error(half, 0.5 * (h0 + h1)), 1e-13);
      // B3 = μ L is in H(0); B1 is positive semi-definite, so H(0) − μ L is too.
      kernel.optimal_laplacian(frame, target, laplacian);
      EXPECT_GT(Eigen::SelfAdjointEigenSolver<typename Kernel::Block>(h0 - mu * laplacian)
                    .eigenvalues()
                    .minCoeff(),
                -1e-10 * h0.norm());
    }
  }
}

TYPED_TEST(SurfaceKernelTest, DerivativesMatchFiniteDifferences) {
  constexpr CellType Type = TypeParam::value;
  std::mt19937 rng(24);
  for (double w : {0.0, 0.4}) expect_derivatives_match(thesis_surface_kernel<Type>(w), 10.0, rng);
  expect_derivatives_match(untangling_surface_kernel<Type>(), 10.0, rng);
}

// With the frame fixed, a move along its normal is invisible: the energy is the same and the
// gradient has no normal part. With the frame recomputed from the moved cell, the energy
// changes only to second order (halving the move quarters the change).
TYPED_TEST(SurfaceKernelTest, MoveAlongTheNormalChangesTheEnergyOnlyToSecondOrder) {
  constexpr CellType Type = TypeParam::value;
  std::mt19937 rng(25);
  const auto kernel = thesis_surface_kernel<Type>();
  for (int trial = 0; trial < 3; ++trial) {
    const double area = 1.0 + trial;
    const Spatial<Type> x =
        into_space<Type>(planar_cell<Type>(area, rng), random_rotation(rng), Vector<3>::Zero());
    const SurfaceFrame frame = *surface_cell_frame<Type>(x);
    const Vector<3> normal = frame.col(0).cross(frame.col(1));
    typename NeoHookeSurfaceKernel<Type>::Gradient g;
    const double energy = kernel.energy_and_gradient(x, frame, area, g);
    EXPECT_LT((normal.transpose() * g).norm(), 1e-14 * g.norm());
    const auto moved = [&](double t) {
      Spatial<Type> y = x;
      y.col(trial % y.cols()) += t * std::sqrt(area) * normal;
      return y;
    };
    EXPECT_NEAR(kernel.energy(moved(0.1), frame, area), energy, 1e-14 * energy);
    const auto change = [&](double t) {
      const Spatial<Type> y = moved(t);
      return kernel.energy(y, *surface_cell_frame<Type>(y), area) - energy;
    };
    EXPECT_NEAR(change(1e-3) / change(5e-4), 4.0, 0.01);
  }
}

// The projection's error: a planar cell tilted by θ against its frame's plane has the energy
// of the flat cell up to O(θ²).
TYPED_TEST(SurfaceKernelTest, TiltAgainstTheFrameCostsSecondOrderInTheAngle) {
  constexpr CellType Type = TypeParam::value;
  std::mt19937 rng(26);
  const auto kernel = thesis_surface_kernel<Type>();
  const Spatial<Type> x =
      into_space<Type>(planar_cell<Type>(1.0, rng), Matrix<3>::Identity(), Vector<3>::Zero());
  const double flat = kernel.energy(x, *surface_cell_frame<Type>(x), 1.0);
  const auto error = [&](double theta) {
    const Matrix<3> tilt =
        Eigen::AngleAxisd(theta, Vector<3>(1.0, 2.0, 0.0).normalized()).toRotationMatrix();
    return kernel.energy(tilt * x, *surface_cell_frame<Type>(x), 1.0) - flat;
  };
  EXPECT_NEAR(error(1e-2) / error(5e-3), 4.0, 0.01);
  EXPECT_LT(std::abs(error(1e-2)), 1e-2 * flat);
}

// A cell folded against its frame (its image mirrored) is infinite for the thesis' law and
// finite, large, for the untangling law.
TYPED_TEST(SurfaceKernelTest, CellFoldedAgainstItsFrameIsInadmissible) {
  constexpr CellType Type = TypeParam::value;
  std::mt19937 rng(27);
  const auto [x, frame] = tilted_cell<Type>(1.0, rng);
  SurfaceFrame flipped = frame;
  flipped.col(1) *= -1.0;  // normal −n
  EXPECT_TRUE(NeoHookeSurfaceKernel<Type>::corners_admissible(x, frame));
  // (A triangle's one det G is checked at its quadrature point, not at corners.)
  if (Type == CellType::Quadrilateral) {
    EXPECT_FALSE(NeoHookeSurfaceKernel<Type>::corners_admissible(x, flipped));
  }
  EXPECT_TRUE(std::isinf(thesis_surface_kernel<Type>().energy(x, flipped, 1.0)));
  typename NeoHookeSurfaceKernel<Type>::Block h;
  EXPECT_FALSE(thesis_surface_kernel<Type>().hessian(x, flipped, 1.0, 1.0, h));
  const auto untangling = untangling_surface_kernel<Type>();
  EXPECT_GT(untangling.energy(x, flipped, 1.0), 10.0 * untangling.energy(x, frame, 1.0));
}

}  // namespace
}  // namespace neomesh
