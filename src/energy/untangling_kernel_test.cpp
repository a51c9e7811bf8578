#include "energy/cell_kernels.hpp"

#include <gtest/gtest.h>

#include <random>

#include "core/testing/finite_differences.hpp"

namespace neomesh {
namespace {

using testing::fd_gradient;
using testing::fd_jacobian;
using testing::relative_error;

template <CellType Type>
using Coordinates = typename UntanglingKernel<Type>::Coordinates;

template <typename T>
class UntanglingKernelTest : public ::testing::Test {};
using CellTypes = ::testing::Types<CellTag<CellType::Triangle>, CellTag<CellType::Quadrilateral>,
                                   CellTag<CellType::Tetrahedron>, CellTag<CellType::Hexahedron>,
                                   CellTag<CellType::Wedge>, CellTag<CellType::Pyramid>>;
TYPED_TEST_SUITE(UntanglingKernelTest, CellTypes);

template <CellType Type>
UntanglingKernel<Type> kernel_with(double epsilon) {
  return make_untangling_kernel<Type>({1.0, 10.0, epsilon}, 3);
}

// The unit cell of the type (edge 1, vertex 0 at the origin; the optimal wedge/pyramid) with every
// vertex moved by up to `amplitude` in each coordinate: with amplitude 0.6 most such cells are
// tangled.
template <CellType Type>
Coordinates<Type> shaken_cell(double amplitude, std::mt19937& rng) {
  constexpr int dim = CellTraits<Type>::dim;
  std::uniform_real_distribution<double> u(-amplitude, amplitude);
  Coordinates<Type> x;
  if constexpr (CellTraits<Type>::simplex) {
    x.col(0).setZero();
    x.template rightCols<dim>() = Matrix<dim>::Identity();
  } else if constexpr (CellTraits<Type>::shape == CellShape::Tensor) {
    for (int i = 0; i < CellTraits<Type>::vertices; ++i)
      x.col(i) = 0.5 * (q1_vertex<dim>(i) + Vector<dim>::Ones());
  } else {
    x = unit_optimal_cell<Type>();
  }
  for (int i = 0; i < x.size(); ++i) x.data()[i] += u(rng);
  return x;
}

// Valid, tangled and mirrored cells, a wide and a narrow ε.
TYPED_TEST(UntanglingKernelTest, GradientAndHessianMatchFiniteDifferences) {
  constexpr CellType Type = TypeParam::value;
  using Kernel = UntanglingKernel<Type>;
  std::mt19937 rng(21);
  int tangled = 0;
  for (double epsilon : {0.5, 0.05}) {
    const Kernel kernel = kernel_with<Type>(epsilon);
    for (int trial = 0; trial < 8; ++trial) {
      const double volume = 0.5 + 0.25 * trial;
      Coordinates<Type> x = shaken_cell<Type>(trial < 2 ? 0.1 : 0.4, rng);
      if (trial % 2) x.row(0) *= -1.0;  // mirrored
      tangled += kernel.measure(x, volume).min_det <= 0.0;
      const auto energy = [&](const Coordinates<Type>& y) { return kernel.energy(y, volume); };
      const auto gradient = [&](const Coordinates<Type>& y) {
        typename Kernel::Gradient g;
        kernel.energy_and_gradient(y, volume, g);
        return g;
      };
      const typename Kernel::Gradient g = gradient(x);
      EXPECT_NEAR(
          energy(x),
          [&] {
            typename Kernel::Gradient unused;
            return kernel.energy_and_gradient(x, volume, unused);
          }(),
          1e-14 * std::abs(energy(x)));
      EXPECT_LT(relative_error(g, fd_gradient(energy, x, 1e-6)), 1e-6) << "trial " << trial;
      typename Kernel::Block h;
      ASSERT_TRUE(kernel.hessian(x, volume, 1.0, h));
      EXPECT_LT(relative_error(h, fd_jacobian(gradient, x, 1e-6)), 1e-6) << "trial " << trial;
      EXPECT_EQ((h - h.transpose()).norm(), 0.0);  // exactly symmetric
    }
  }
  EXPECT_GE(tangled, 6) << "the test must see tangled cells";
}

TYPED_TEST(UntanglingKernelTest, HessianIsAffineInAlpha) {
  constexpr CellType Type = TypeParam::value;
  using Kernel = UntanglingKernel<Type>;
  const Kernel kernel = kernel_with<Type>(0.1);
  std::mt19937 rng(22);
  const Coordinates<Type> x = shaken_cell<Type>(0.6, rng);
  typename Kernel::Block h0, h1, half;
  kernel.hessian(x, 1.3, 0.0, h0);
  kernel.hessian(x, 1.3, 1.0, h1);
  kernel.hessian(x, 1.3, 0.5, half);
  EXPECT_LT(relative_error(half, 0.5 * (h0 + h1)), 1e-13);
}

// On valid simplices W_ε → the Neo-Hookean W (κ = 0) as ε → 0 (χ − D ≈ ε²/4D, times φ′): the
// hand-over to the Neo-Hookean phase does not change the objective much. (Q1 cells are
// sampled at other points than the Neo-Hookean rule.)
template <typename T>
class UntanglingSimplexTest : public ::testing::Test {};
using Simplices = ::testing::Types<CellTag<CellType::Triangle>, CellTag<CellType::Tetrahedron>>;
TYPED_TEST_SUITE(UntanglingSimplexTest, Simplices);

TYPED_TEST(UntanglingSimplexTest, EnergyTendsToNeoHookean) {
  constexpr CellType Type = TypeParam::value;
  std::mt19937 rng(23);
  const Coordinates<Type> x = shaken_cell<Type>(0.1, rng);
  const NeoHookeKernel<Type> neo_hooke(NeoHooke<CellTraits<Type>::dim>{1.0, 10.0, 0.0}, 3);
  const double exact = neo_hooke.energy(x, 0.8);
  ASSERT_TRUE(std::isfinite(exact));
  for (double epsilon : {1e-2, 1e-3, 1e-4})
    EXPECT_NEAR(kernel_with<Type>(epsilon).energy(x, 0.8), exact, 100 * epsilon * epsilon);
}

// The optimal cell (G = I at every sample) is the minimum, up to O(ε²), for every type.
TYPED_TEST(UntanglingKernelTest, OptimalCellIsStationaryAsEpsilonVanishes) {
  constexpr CellType Type = TypeParam::value;
  const Coordinates<Type> x = unit_optimal_cell<Type>();
  for (double epsilon : {1e-2, 1e-4}) {
    typename UntanglingKernel<Type>::Gradient g;
    const double energy = kernel_with<Type>(epsilon).energy_and_gradient(x, 1.0, g);
    EXPECT_NEAR(energy, 0.0, 10 * epsilon * epsilon);
    EXPECT_LT(g.norm(), 100 * epsilon * epsilon);
  }
}

// A mirrored cell: det G < 0 at every sample; finite energy, far above the optimal cell's,
// and the gradient points towards unfolding it.
TYPED_TEST(UntanglingKernelTest, MirroredCellIsFiniteAndCostly) {
  constexpr CellType Type = TypeParam::value;
  using Kernel = UntanglingKernel<Type>;
  const Kernel kernel = kernel_with<Type>(0.01);
  std::mt19937 rng(24);
  Coordinates<Type> x = shaken_cell<Type>(0.0, rng);
  const double unit_volume = 1.0;
  const double good = kernel.energy(x, unit_volume);
  x.row(0) *= -1.0;
  EXPECT_LT(kernel.measure(x, unit_volume).min_det, 0.0);
  typename Kernel::Gradient g;
  const double bad = kernel.energy_and_gradient(x, unit_volume, g);
  EXPECT_TRUE(std::isfinite(bad));
  EXPECT_GT(bad, good + 10.0);
  EXPECT_GT(g.norm(), 0.0);
}

}  // namespace
}  // namespace neomesh
