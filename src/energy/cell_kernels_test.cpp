#include "energy/cell_kernels.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <array>
#include <random>

#include "core/testing/finite_differences.hpp"

namespace neomesh {
namespace {

using testing::fd_gradient;
using testing::fd_jacobian;
using testing::relative_error;

constexpr double kFdTolerance = 1e-6;  // relative error allowed against central differences

template <CellType Type>
using Coordinates = typename NeoHookeKernel<Type>::Coordinates;

// The optimal cell of volume v (docs/method.md §1, docs/cell-types.md), vertex 0 at the
// origin for simplices, wedges and pyramids and the square/cube [0, h]^d for Q1 cells.
template <CellType Type>
Coordinates<Type> optimal_cell(double volume) {
  constexpr int dim = CellTraits<Type>::dim;
  Coordinates<Type> x;
  const double edge = std::pow(volume, 1.0 / dim);
  if constexpr (CellTraits<Type>::shape == CellShape::Wedge ||
                CellTraits<Type>::shape == CellShape::Pyramid) {
    x = edge * unit_optimal_cell<Type>();
  } else if constexpr (CellTraits<Type>::simplex) {
    x.col(0).setZero();
    x.template rightCols<dim>() = edge * unit_optimal_simplex_edges<dim>();
  } else {
    for (int i = 0; i < CellTraits<Type>::vertices; ++i)
      x.col(i) = 0.5 * edge * (q1_vertex<dim>(i) + Vector<dim>::Ones());
  }
  return x;
}

// The optimal cell of volume `volume`, sheared and stretched by a random map near the
// identity and with every vertex moved by up to 15% of the edge length: a valid, generic cell.
template <CellType Type>
Coordinates<Type> perturbed_cell(double volume, std::mt19937& rng) {
  constexpr int dim = CellTraits<Type>::dim;
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Matrix<dim> map = Matrix<dim>::Identity();
  for (int i = 0; i < dim; ++i)
    for (int j = 0; j < dim; ++j) map(i, j) += 0.25 * u(rng);
  Coordinates<Type> x = 1.3 * map * optimal_cell<Type>(volume);
  const double edge = std::pow(volume, 1.0 / dim);
  for (int i = 0; i < x.size(); ++i) x.data()[i] += 0.15 * edge * u(rng);
  return x;
}

template <typename T>
class CellKernelTest : public ::testing::Test {};
using CellTypes = ::testing::Types<CellTag<CellType::Triangle>, CellTag<CellType::Quadrilateral>,
                                   CellTag<CellType::Tetrahedron>, CellTag<CellType::Hexahedron>,
                                   CellTag<CellType::Wedge>, CellTag<CellType::Pyramid>>;
TYPED_TEST_SUITE(CellKernelTest, CellTypes);

// `corner_weight` > 0: the worst-cell phase's energy, with corner samples.
template <CellType Type>
NeoHookeKernel<Type> thesis_kernel(double corner_weight = 0.0) {
  return NeoHookeKernel<Type>(NeoHooke<CellTraits<Type>::dim>{1.0, 10.0, 1.0}, 3, corner_weight);
}

constexpr double kCornerWeights[] = {0.0, 0.4};

TYPED_TEST(CellKernelTest, OptimalCellHasZeroEnergyAndGradient) {
  constexpr CellType Type = TypeParam::value;
  for (double w : kCornerWeights)
    for (double volume : {1.0, 0.01, 7.0}) {
      const NeoHookeKernel<Type> kernel = thesis_kernel<Type>(w);
      const Coordinates<Type> x = optimal_cell<Type>(volume);
      typename NeoHookeKernel<Type>::Gradient g;
      EXPECT_NEAR(kernel.energy_and_gradient(x, volume, g), 0.0, 1e-14);
      EXPECT_LT(g.norm(), 1e-13);
      const CellMeasure m = kernel.measure(x, volume);
      EXPECT_NEAR(m.volume, volume, 1e-14 * volume);
      EXPECT_NEAR(m.min_det, 1.0, 1e-14);
    }
}

TYPED_TEST(CellKernelTest, GradientMatchesFiniteDifferencesOfEnergy) {
  constexpr CellType Type = TypeParam::value;
  std::mt19937 rng(11);
  for (double w : kCornerWeights)
    for (int trial = 0; trial < 5; ++trial) {
      const NeoHookeKernel<Type> kernel = thesis_kernel<Type>(w);
      const double volume = 0.5 + trial;
      Coordinates<Type> x = perturbed_cell<Type>(volume, rng);
      typename NeoHookeKernel<Type>::Gradient g;
      kernel.energy_and_gradient(x, volume, g);
      const double step = 1e-6 * std::pow(volume, 1.0 / CellTraits<Type>::dim);
      const auto fd = fd_gradient(
          [&](const Coordinates<Type>& y) { return kernel.energy(y, volume); }, x, step);
      EXPECT_LT(relative_error(g, fd), kFdTolerance) << "analytic\n" << g << "\nfd\n" << fd;
    }
}

TYPED_TEST(CellKernelTest, HessianMatchesFiniteDifferencesOfGradient) {
  constexpr CellType Type = TypeParam::value;
  using Kernel = NeoHookeKernel<Type>;
  std::mt19937 rng(12);
  for (double w : kCornerWeights)
    for (int trial = 0; trial < 5; ++trial) {
      const Kernel kernel = thesis_kernel<Type>(w);
      const double volume = 0.5 + trial;
      Coordinates<Type> x = perturbed_cell<Type>(volume, rng);
      typename Kernel::Block h;
      ASSERT_TRUE(kernel.hessian(x, volume, 1.0, h));
      const double step = 1e-6 * std::pow(volume, 1.0 / Kernel::dim);
      const auto gradient = [&](const Coordinates<Type>& y) {
        typename Kernel::Gradient g;
        kernel.energy_and_gradient(y, volume, g);
        return g;
      };
      const typename Kernel::Block fd = fd_jacobian(gradient, x, step);
      EXPECT_LT(relative_error(h, fd), kFdTolerance);
      EXPECT_EQ((h - h.transpose()).norm(), 0.0);  // exactly symmetric
    }
}

// H(α) = B1 + α B2 + B3 is affine in α, and B3/μ at any cell is the optimal-cell Laplacian.
TYPED_TEST(CellKernelTest, HessianSplitsIntoLaplacianAndRest) {
  constexpr CellType Type = TypeParam::value;
  using Kernel = NeoHookeKernel<Type>;
  const Kernel kernel = thesis_kernel<Type>();
  std::mt19937 rng(13);
  const double volume = 2.0;
  const Coordinates<Type> x = perturbed_cell<Type>(volume, rng);
  typename Kernel::Block h0, h1, half, laplacian;
  kernel.hessian(x, volume, 0.0, h0);
  kernel.hessian(x, volume, 1.0, h1);
  kernel.hessian(x, volume, 0.5, half);
  EXPECT_LT(relative_error(half, 0.5 * (h0 + h1)), 1e-14);
  kernel.optimal_laplacian(volume, laplacian);
  const Kernel laplacian_only(NeoHooke<Kernel::dim>{1e-300, 1.0, 0.0}, 3);  // λ → 0, μ = 1
  typename Kernel::Block b3;
  laplacian_only.hessian(x, volume, 0.0, b3);
  EXPECT_LT(relative_error(b3, laplacian), 1e-13);
}

TYPED_TEST(CellKernelTest, LaplacianOfCurrentCellEqualsOptimalAtOptimalCell) {
  constexpr CellType Type = TypeParam::value;
  using Kernel = NeoHookeKernel<Type>;
  const Kernel kernel = thesis_kernel<Type>();
  const double volume = 0.3;
  typename Kernel::Block optimal, current;
  kernel.optimal_laplacian(volume, optimal);
  ASSERT_TRUE(kernel.current_laplacian(optimal_cell<Type>(volume), volume, current));
  EXPECT_LT(relative_error(current, optimal), 1e-13);
  // Translations are in the kernel: each row sums to zero over each component.
  const Coordinates<Type> ones = Coordinates<Type>::Ones();
  EXPECT_LT(
      (optimal * Eigen::Map<const Eigen::Matrix<double, Kernel::dofs, 1>>(ones.data())).norm(),
      1e-12 * optimal.norm());
}

TYPED_TEST(CellKernelTest, InvertedCellIsInfiniteAndRejected) {
  constexpr CellType Type = TypeParam::value;
  using Kernel = NeoHookeKernel<Type>;
  const Kernel kernel = thesis_kernel<Type>();
  Coordinates<Type> x = optimal_cell<Type>(1.0);
  x.row(0) *= -1.0;  // mirror image: det G < 0 everywhere
  EXPECT_TRUE(std::isinf(kernel.energy(x, 1.0)));
  typename Kernel::Gradient g;
  EXPECT_TRUE(std::isinf(kernel.energy_and_gradient(x, 1.0, g)));
  typename Kernel::Block h;
  EXPECT_FALSE(kernel.hessian(x, 1.0, 1.0, h));
  EXPECT_LT(kernel.measure(x, 1.0).min_det, 0.0);
}

// The output's cell fields take both at once: the same values as energy() and measure(), bit
// for bit, on valid cells, with corner samples, and where the energy is infinite.
TYPED_TEST(CellKernelTest, EnergyAndMeasureAreEnergyAndMeasureBitForBit) {
  constexpr CellType Type = TypeParam::value;
  std::mt19937 rng(14);
  for (double w : kCornerWeights) {
    const NeoHookeKernel<Type> kernel = thesis_kernel<Type>(w);
    for (int trial = 0; trial < 4; ++trial) {
      const double volume = 0.5 + trial;
      Coordinates<Type> x = perturbed_cell<Type>(volume, rng);
      if (trial == 3) x.row(0) *= -1.0;  // inverted
      const auto [energy, measure] = kernel.energy_and_measure(x, volume);
      const CellMeasure alone = kernel.measure(x, volume);
      EXPECT_EQ(energy, kernel.energy(x, volume));
      EXPECT_EQ(measure.volume, alone.volume);
      EXPECT_EQ(measure.min_det, alone.min_det);
      EXPECT_EQ(std::isinf(energy), trial == 3);
    }
  }
}

// A dart: vertex 3 of the unit square pulled in to (0.45, 0.45). det J is positive at all
// 3×3 Gauss points but negative at that corner, so the line search must not accept it.
TEST(QuadKernel, NonConvexQuadWithPositiveGaussPointsIsInfinite) {
  using Kernel = NeoHookeKernel<CellType::Quadrilateral>;
  const Kernel kernel = thesis_kernel<CellType::Quadrilateral>();
  Coordinates<CellType::Quadrilateral> x;
  x << 0.0, 1.0, 0.0, 0.45, 0.0, 0.0, 1.0, 0.45;
  ASSERT_GT(kernel.measure(x, 1.0).min_det, 0.0) << "the Gauss points alone look fine";
  EXPECT_TRUE(std::isinf(kernel.energy(x, 1.0)));
  typename Kernel::Gradient g;
  EXPECT_TRUE(std::isinf(kernel.energy_and_gradient(x, 1.0, g)));
}

// A pyramid whose apex is pushed through its base is inverted; so is one whose base is folded
// into a dart, though every Gauss point of a mildly folded base may look fine.
// A quad whose corner at vertex 3 straightens (180°) keeps healthy Gauss points: the thesis'
// energy hardly changes, while corner samples put the law's barrier there.
TEST(QuadKernel, CornerSamplesMakeAFlatteningCornerCostly) {
  constexpr CellType Type = CellType::Quadrilateral;
  const auto flattened = [](double gap) {
    Coordinates<Type> x = optimal_cell<Type>(1.0);  // vertices (0,0) (1,0) (0,1) (1,1)
    x.col(3).setConstant(0.5 + gap);  // beyond the diagonal from (1,0) to (0,1) by `gap`
    return x;
  };
  const NeoHookeKernel<Type> gauss = thesis_kernel<Type>(), corners = thesis_kernel<Type>(0.4);
  const Coordinates<Type> near = flattened(1e-3), flat = flattened(1e-9);
  EXPECT_LT(gauss.energy(flat, 1.0) - gauss.energy(near, 1.0), 0.1);
  EXPECT_GT(corners.energy(flat, 1.0) - corners.energy(near, 1.0), 20.0);
  typename NeoHookeKernel<Type>::Gradient g;
  corners.energy_and_gradient(flat, 1.0, g);
  EXPECT_LT(g.col(3).sum(), -1e6);  // descent (−g) pushes vertex 3 back out, hard
}

TEST(PyramidKernel, ApexBelowTheBaseOrFoldedBaseIsInfinite) {
  const auto kernel = thesis_kernel<CellType::Pyramid>();
  Coordinates<CellType::Pyramid> x = optimal_cell<CellType::Pyramid>(1.0);
  Coordinates<CellType::Pyramid> below = x;
  below(2, 4) = -0.1;
  EXPECT_TRUE(std::isinf(kernel.energy(below, 1.0)));
  Coordinates<CellType::Pyramid> dart = x;
  dart.col(3).head<2>() = 0.45 * x.col(3).head<2>();  // base corner 3 pulled inside
  EXPECT_TRUE(std::isinf(kernel.energy(dart, 1.0)));
  EXPECT_TRUE(std::isfinite(kernel.energy(x, 1.0)));
}

// The wedge's optimal cell is the right prism: stretching it vertically costs energy. Turning
// the top triangle by 180° about the axis keeps every corner positive (the triangles stay
// horizontal) but collapses the mid-height section to a point, where a Gauss point lies.
TEST(WedgeKernel, StretchCostsEnergyAndHalfTurnOfTheTopIsInfinite) {
  const auto kernel = thesis_kernel<CellType::Wedge>();
  const Coordinates<CellType::Wedge> x = optimal_cell<CellType::Wedge>(1.0);
  Coordinates<CellType::Wedge> tall = x;
  tall.row(2) *= 2.0;
  EXPECT_GT(kernel.energy(tall, 1.0), 0.1);
  Coordinates<CellType::Wedge> turned = x;
  const Vector<3> centre = x.rightCols<3>().rowwise().mean();
  for (int i = 3; i < 6; ++i) {
    const Vector<3> r = x.col(i) - centre;
    turned.col(i) = centre + Vector<3>(-r[0], -r[1], r[2]);
  }
  EXPECT_TRUE(kernel.corners_admissible(turned));
  EXPECT_TRUE(std::isinf(kernel.energy(turned, 1.0)));
}

// A target shape S with det S = 1: stretched, sheared and turned (a boundary-layer cell).
template <int Dim>
Matrix<Dim> anisotropic_shape(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Matrix<Dim> S = Matrix<Dim>::Identity();
  S(0, 0) = 8.0;  // 8 : 1 along the first direction
  for (int i = 0; i < Dim; ++i)
    for (int j = 0; j < Dim; ++j) S(i, j) += 0.3 * u(rng);
  return S / std::pow(S.determinant(), 1.0 / Dim);
}

template <int Dim>
Matrix<Dim> rotation(double angle) {
  if constexpr (Dim == 2) {
    return Eigen::Rotation2Dd(angle).toRotationMatrix();
  } else {
    return Eigen::AngleAxisd(angle, Vector<3>(1.0, -2.0, 0.5).normalized()).toRotationMatrix();
  }
}

// The kernel's form of a shape: S⁻ᵀ (Targets makes it).
template <int Dim>
Matrix<Dim> inverse_transpose(const Matrix<Dim>& S) {
  return S.inverse().transpose();
}

// The target cell itself (S times the optimal cell of the volume) has zero energy and gradient;
// so does every rotation of it (only SᵀS counts), and a cell that differs from it does not.
TYPED_TEST(CellKernelTest, TargetCellIsTheMinimumForEveryRotation) {
  constexpr CellType Type = TypeParam::value;
  constexpr int dim = CellTraits<Type>::dim;
  std::mt19937 rng(15);
  const NeoHookeKernel<Type> kernel = thesis_kernel<Type>();
  for (int trial = 0; trial < 3; ++trial) {
    const double volume = 0.3 + trial;
    const Matrix<dim> S = anisotropic_shape<dim>(rng);
    const Matrix<dim> inv_t = inverse_transpose(S);
    const CellTarget<dim> target(volume, inv_t.data());
    for (const Matrix<dim>& Q : {Matrix<dim>(Matrix<dim>::Identity()), rotation<dim>(0.8)}) {
      const Coordinates<Type> x = Q * S * optimal_cell<Type>(volume);
      typename NeoHookeKernel<Type>::Gradient g;
      EXPECT_NEAR(kernel.energy_and_gradient(x, target, g), 0.0, 1e-11 * volume);
      EXPECT_LT(g.norm(), 1e-10 * std::pow(volume, 1.0 - 1.0 / dim));
      EXPECT_NEAR(kernel.measure(x, target).volume, volume, 1e-12 * volume);
    }
    // The same cell is far from the ideal one: the thesis' target sees a large energy.
    EXPECT_GT(kernel.energy(S * optimal_cell<Type>(volume), volume), 1.0 * volume);
  }
}

// The derivatives with a shaped target, for both laws, against central differences.
template <typename Kernel>
void expect_derivatives_match_with_shaped_targets(const Kernel& kernel, std::mt19937& rng) {
  constexpr int dim = Kernel::dim;
  using X = typename Kernel::Coordinates;
  for (int trial = 0; trial < 4; ++trial) {
    const double volume = 0.5 + trial;
    const Matrix<dim> S = anisotropic_shape<dim>(rng);
    const Matrix<dim> inv_t = inverse_transpose(S);
    const CellTarget<dim> target(volume, inv_t.data());
    // A generic cell near the target cell.
    X x = S * perturbed_cell<Kernel::type>(volume, rng);
    typename Kernel::Gradient g;
    if (!std::isfinite(kernel.energy_and_gradient(x, target, g))) continue;
    const double step = 1e-6 * std::pow(volume, 1.0 / dim);
    const auto fd = fd_gradient([&](const X& y) { return kernel.energy(y, target); }, x, step);
    EXPECT_LT(relative_error(g, fd), kFdTolerance) << "analytic\n" << g << "\nfd\n" << fd;
    typename Kernel::Block h;
    ASSERT_TRUE(kernel.hessian(x, target, 1.0, h));
    const auto gradient = [&](const X& y) {
      typename Kernel::Gradient gy;
      kernel.energy_and_gradient(y, target, gy);
      return gy;
    };
    EXPECT_LT(relative_error(h, fd_jacobian(gradient, x, step)), kFdTolerance);
    EXPECT_EQ((h - h.transpose()).norm(), 0.0);
  }
}

TYPED_TEST(CellKernelTest, DerivativesWithShapedTargetsMatchFiniteDifferences) {
  constexpr CellType Type = TypeParam::value;
  std::mt19937 rng(16);
  for (double w : kCornerWeights)
    expect_derivatives_match_with_shaped_targets(thesis_kernel<Type>(w), rng);
  const RegularizedNeoHooke<CellTraits<Type>::dim> untangling{1.0, 10.0, 0.1};
  expect_derivatives_match_with_shaped_targets(make_untangling_kernel<Type>(untangling, 3), rng);
}

// Renumbering the vertices by a symmetry of the optimal cell that keeps the orientation
// (even permutations of a simplex; rotations of the square/cube in tensor order) leaves
// the cell energy unchanged.
template <CellType Type>
std::vector<std::array<int, CellTraits<Type>::vertices>> orientation_preserving_renumberings() {
  if constexpr (Type == CellType::Triangle) {
    return {{1, 2, 0}, {2, 0, 1}};
  } else if constexpr (Type == CellType::Tetrahedron) {
    return {{1, 2, 0, 3}, {0, 2, 3, 1}, {1, 0, 3, 2}, {3, 2, 1, 0}, {2, 3, 0, 1}};
  } else if constexpr (Type == CellType::Quadrilateral) {
    // Vertex i moves to the position of the 90° rotation of ξ_i: (ξ0, ξ1) → (−ξ1, ξ0).
    return {{1, 3, 0, 2}, {3, 2, 1, 0}, {2, 0, 3, 1}};
  } else if constexpr (Type == CellType::Wedge) {
    // Rotations of the triangle by 120°, and the half turn that swaps top and bottom.
    return {{1, 2, 0, 4, 5, 3}, {2, 0, 1, 5, 3, 4}, {3, 5, 4, 0, 2, 1}};
  } else if constexpr (Type == CellType::Pyramid) {
    // Rotations of the base about the axis through the apex, as for the quadrilateral.
    return {{1, 3, 0, 2, 4}, {3, 2, 1, 0, 4}, {2, 0, 3, 1, 4}};
  } else {
    // Rotations by 90° about z: (ξ0, ξ1, ξ2) → (−ξ1, ξ0, ξ2); by 120° about the diagonal:
    // (ξ0, ξ1, ξ2) → (ξ2, ξ0, ξ1); by 180° about z: (ξ0, ξ1, ξ2) → (−ξ0, −ξ1, ξ2).
    return {{1, 3, 0, 2, 5, 7, 4, 6}, {0, 2, 4, 6, 1, 3, 5, 7}, {3, 2, 1, 0, 7, 6, 5, 4}};
  }
}

TYPED_TEST(CellKernelTest, EnergyIndependentOfVertexNumberingUpToSymmetry) {
  constexpr CellType Type = TypeParam::value;
  const NeoHookeKernel<Type> kernel = thesis_kernel<Type>();
  std::mt19937 rng(14);
  const double volume = 0.7;
  const Coordinates<Type> x = perturbed_cell<Type>(volume, rng);
  const double energy = kernel.energy(x, volume);
  for (const auto& renumbering : orientation_preserving_renumberings<Type>()) {
    Coordinates<Type> y;
    for (int i = 0; i < CellTraits<Type>::vertices; ++i) y.col(i) = x.col(renumbering[i]);
    EXPECT_NEAR(kernel.energy(y, volume), energy, 1e-13 * energy);
  }
}

}  // namespace
}  // namespace neomesh
