#include "energy/neo_hooke.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace neomesh {
namespace {

constexpr double kStep = 1e-6;         // central differences: error O(h²) ≈ 1e-12 relative
constexpr double kFdTolerance = 1e-6;  // relative error allowed against finite differences

template <int Dim>
Matrix<Dim> random_near_identity(std::mt19937& rng, double spread) {
  std::uniform_real_distribution<double> u(-spread, spread);
  Matrix<Dim> G = Matrix<Dim>::Identity();
  for (int i = 0; i < Dim; ++i)
    for (int j = 0; j < Dim; ++j) G(i, j) += u(rng);
  return G;
}

template <int Dim>
Matrix<Dim> rotation(double angle) {
  Matrix<Dim> Q = Matrix<Dim>::Identity();
  Q.template topLeftCorner<2, 2>() << std::cos(angle), -std::sin(angle), std::sin(angle),
      std::cos(angle);
  if constexpr (Dim == 3) {
    // Compose with a rotation about the x axis so that all three axes move.
    Matrix<3> R = Matrix<3>::Identity();
    R.bottomRightCorner<2, 2>() << std::cos(0.7), -std::sin(0.7), std::sin(0.7), std::cos(0.7);
    Q = R * Q;
  }
  return Q;
}

double relative_error(double a, double b) {
  return std::abs(a - b) / std::max(std::abs(b), 1.0);
}

template <int Dim>
double relative_error(const Matrix<Dim>& a, const Matrix<Dim>& b) {
  return (a - b).norm() / std::max(b.norm(), 1.0);
}

template <typename T>
class NeoHookeTest : public ::testing::Test {};
using Dimensions = ::testing::Types<std::integral_constant<int, 2>, std::integral_constant<int, 3>>;
TYPED_TEST_SUITE(NeoHookeTest, Dimensions);

// λ = 1, μ = 10 as in the thesis' tests; κ = λ.
template <int Dim>
NeoHooke<Dim> thesis_law() {
  return NeoHooke<Dim>{1.0, 10.0, 1.0};
}

TYPED_TEST(NeoHookeTest, VanishesWithZeroStressAtIdentity) {
  constexpr int Dim = TypeParam::value;
  const NeoHooke<Dim> law = thesis_law<Dim>();
  EXPECT_EQ(law.energy(Matrix<Dim>::Identity()), 0.0);
  EXPECT_LT(law.stress(Matrix<Dim>::Identity()).norm(), 1e-15);
}

TYPED_TEST(NeoHookeTest, PositiveAwayFromRotations) {
  constexpr int Dim = TypeParam::value;
  const NeoHooke<Dim> law = thesis_law<Dim>();
  std::mt19937 rng(1);
  for (int trial = 0; trial < 20; ++trial)
    EXPECT_GT(law.energy(random_near_identity<Dim>(rng, 0.1)), 0.0);
  EXPECT_GT(law.energy(1.01 * Matrix<Dim>::Identity()), 0.0);
}

TYPED_TEST(NeoHookeTest, InvariantUnderRotationsFromBothSides) {
  constexpr int Dim = TypeParam::value;
  const NeoHooke<Dim> law = thesis_law<Dim>();
  std::mt19937 rng(2);
  const Matrix<Dim> Q = rotation<Dim>(0.4);
  for (int trial = 0; trial < 10; ++trial) {
    const Matrix<Dim> G = random_near_identity<Dim>(rng, 0.3);
    const double w = law.energy(G);
    EXPECT_NEAR(law.energy(Q * G), w, 1e-13 * w);
    EXPECT_NEAR(law.energy(G * Q), w, 1e-13 * w);
    EXPECT_NEAR(law.energy(Q), 0.0, 1e-13);
  }
}

TYPED_TEST(NeoHookeTest, BlowsUpAsCellsDegenerate) {
  constexpr int Dim = TypeParam::value;
  const NeoHooke<Dim> law = thesis_law<Dim>();
  Matrix<Dim> G = Matrix<Dim>::Identity();
  double previous = 0.0;  // W grows like λ/2 (log det G)² + μ |log det G|
  for (double t : {1e-1, 1e-3, 1e-6, 1e-12, 1e-300}) {
    G(0, 0) = t;
    const double w = law.energy(G);
    EXPECT_GT(w, previous);
    EXPECT_GT(w, 0.5 * law.lambda * std::log(t) * std::log(t));
    EXPECT_TRUE(std::isfinite(w));
    previous = w;
  }
}

TYPED_TEST(NeoHookeTest, InfiniteNotNaNWhenInvertedOrDegenerate) {
  constexpr int Dim = TypeParam::value;
  const NeoHooke<Dim> law = thesis_law<Dim>();
  Matrix<Dim> G = Matrix<Dim>::Identity();
  for (double t : {0.0, -1e-9, -1.0}) {
    G(0, 0) = t;
    const double w = law.energy(G);
    EXPECT_TRUE(std::isinf(w) && w > 0.0) << "det G = " << t;
  }
  EXPECT_TRUE(std::isinf(law.energy(Matrix<Dim>::Zero())));
}

// Central differences of W in direction H against P : H, for G inside and beyond the
// κ-term's threshold c = e^(μ/λ+1) (there with μ/λ small so that c is reachable).
TYPED_TEST(NeoHookeTest, StressMatchesFiniteDifferencesOfEnergy) {
  constexpr int Dim = TypeParam::value;
  std::mt19937 rng(3);
  for (const NeoHooke<Dim> law : {thesis_law<Dim>(), NeoHooke<Dim>{2.0, 0.5, 3.0}}) {
    for (double growth : {1.0, 2.0}) {  // 2^Dim > e^1.25: the κ-term is active for the second law
      for (int trial = 0; trial < 10; ++trial) {
        const Matrix<Dim> G = growth * random_near_identity<Dim>(rng, 0.3);
        const Matrix<Dim> H = random_near_identity<Dim>(rng, 1.0);
        const double fd = (law.energy(G + kStep * H) - law.energy(G - kStep * H)) / (2 * kStep);
        EXPECT_LT(relative_error(law.stress(G).cwiseProduct(H).sum(), fd), kFdTolerance);
      }
    }
  }
}

TYPED_TEST(NeoHookeTest, TangentMatchesFiniteDifferencesOfStress) {
  constexpr int Dim = TypeParam::value;
  std::mt19937 rng(4);
  for (const NeoHooke<Dim> law : {thesis_law<Dim>(), NeoHooke<Dim>{2.0, 0.5, 3.0}}) {
    for (double growth : {1.0, 2.0}) {
      for (int trial = 0; trial < 10; ++trial) {
        const Matrix<Dim> G = growth * random_near_identity<Dim>(rng, 0.3);
        const Matrix<Dim> H = random_near_identity<Dim>(rng, 1.0);
        const Matrix<Dim> fd =
            (law.stress(G + kStep * H) - law.stress(G - kStep * H)) / (2 * kStep);
        EXPECT_LT(relative_error<Dim>(law.tangent(G, H, 1.0), fd), kFdTolerance);
      }
    }
  }
}

// B1 + α B2 + B3 is linear in α and symmetric: (T[H]:K) = (T[K]:H).
TYPED_TEST(NeoHookeTest, QuasiNewtonTangentIsSymmetricAndAffineInAlpha) {
  constexpr int Dim = TypeParam::value;
  const NeoHooke<Dim> law = thesis_law<Dim>();
  std::mt19937 rng(5);
  const Matrix<Dim> G = random_near_identity<Dim>(rng, 0.3);
  const Matrix<Dim> H = random_near_identity<Dim>(rng, 1.0);
  const Matrix<Dim> K = random_near_identity<Dim>(rng, 1.0);
  for (double alpha : {0.1, 0.5, 1.0}) {
    const double hk = law.tangent(G, H, alpha).cwiseProduct(K).sum();
    const double kh = law.tangent(G, K, alpha).cwiseProduct(H).sum();
    EXPECT_NEAR(hk, kh, 1e-12 * std::abs(hk));
  }
  const Matrix<Dim> mid = law.tangent(G, H, 0.5);
  const Matrix<Dim> ends = 0.5 * (law.tangent(G, H, 0.0) + law.tangent(G, H, 1.0));
  EXPECT_LT(relative_error<Dim>(mid, ends), 1e-13);
}

}  // namespace
}  // namespace neomesh
