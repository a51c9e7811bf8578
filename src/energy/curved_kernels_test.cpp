#include "energy/curved_kernels.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cstdio>
#include <random>
#include <type_traits>

#include "core/testing/finite_differences.hpp"

namespace neomesh {
namespace {

using testing::fd_gradient;
using testing::fd_jacobian;
using testing::kFdTolerance;
using testing::relative_error;

template <CurvedType Type>
using Nodes = typename CurvedTraits<Type>::Nodes;
template <CurvedType Type>
using Corners = Eigen::Matrix<double, CurvedTraits<Type>::dim, CurvedTraits<Type>::corners>;

template <CurvedType Type>
using CurvedTag = std::integral_constant<CurvedType, Type>;

// The optimal straight cell of volume v in canonical corner order (cell_kernels.hpp's).
template <CurvedType Type>
Corners<Type> optimal_corners(double volume) {
  return std::pow(volume, 1.0 / CurvedTraits<Type>::dim) *
         unit_optimal_cell<CurvedTraits<Type>::linear>();
}

// A random straight cell near the optimal one of volume v: a random map near 1.2 I applied to
// it, every corner then moved by up to 10% of the edge.
template <CurvedType Type>
Corners<Type> straight_corners(double volume, std::mt19937& rng, double jitter = 0.1) {
  constexpr int dim = CurvedTraits<Type>::dim;
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const Matrix<dim> map =
      1.2 * Matrix<dim>::Identity() + 0.2 * Matrix<dim>::NullaryExpr([&] { return u(rng); });
  Corners<Type> c = map * optimal_corners<Type>(volume);
  const double edge = std::pow(volume, 1.0 / dim);
  for (int i = 0; i < c.size(); ++i) c.data()[i] += jitter * edge * u(rng);
  return c;
}

// Where the higher-order nodes inside the faces and the cell go when a curved cell is made.
enum class Interior {
  Random,   // moved at random as the edge nodes are: generic bubbles, for derivative checks
  Blended,  // where the serendipity map of the edges puts them (quadrilateral9, hexahedron27,
            // wedge18)
};

// The serendipity sibling of a Lagrange cell, whose nodes are its first ones.
template <CurvedType Type>
constexpr CurvedType serendipity() {
  return Type == CurvedType::Quadrilateral9 ? CurvedType::Quadrilateral8
         : Type == CurvedType::Hexahedron27 ? CurvedType::Hexahedron20
         : Type == CurvedType::Wedge18      ? CurvedType::Wedge15
                                            : Type;
}

// A valid curved cell: a random straight one whose edge nodes are then moved by up to `bend`
// times the edge in each coordinate, and its face and centre nodes as `interior` says.
template <CurvedType Type>
Nodes<Type> curved_cell(double volume, std::mt19937& rng, double bend = 0.1,
                        Interior interior = Interior::Random) {
  constexpr int dim = CurvedTraits<Type>::dim;
  constexpr CurvedType Edges = serendipity<Type>();
  constexpr int edge_nodes = CurvedTraits<Edges>::nodes;
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double edge = std::pow(volume, 1.0 / dim);
  for (;;) {
    Nodes<Type> x = straight_curved_cell<Type>(straight_corners<Type>(volume, rng));
    for (int i = CurvedTraits<Type>::corners; i < CurvedTraits<Type>::nodes; ++i)
      for (int a = 0; a < dim; ++a) x(a, i) += bend * edge * u(rng);
    if (interior == Interior::Blended)
      for (int i = edge_nodes; i < CurvedTraits<Type>::nodes; ++i)
        x.col(i) = x.template leftCols<edge_nodes>() * curved_basis<Edges>(reference_node<Type>(i));
    if (certify_jacobian<Type>(x).validity == Validity::Valid) return x;
  }
}

template <CurvedType Type>
CurvedNeoHookeKernel<Type> thesis_kernel(double corner_weight = 0.0,
                                         int points = kCurvedGaussPoints) {
  return CurvedNeoHookeKernel<Type>(NeoHooke<CurvedTraits<Type>::dim>{1.0, 10.0, 1.0}, points,
                                    corner_weight);
}

template <CurvedType Type>
CurvedUntanglingKernel<Type> untangling_kernel() {
  return make_curved_untangling_kernel<Type>(
      RegularizedNeoHooke<CurvedTraits<Type>::dim>{1.0, 10.0, 0.05});
}

// Gradient and Hessian of any kernel against central differences at x.
template <typename Kernel>
void expect_derivatives_match_finite_differences(const Kernel& kernel,
                                                 const typename Kernel::Coordinates& x,
                                                 double volume) {
  using X = typename Kernel::Coordinates;
  const double step = 1e-6 * std::pow(volume, 1.0 / Kernel::dim);
  typename Kernel::Gradient g;
  ASSERT_TRUE(std::isfinite(kernel.energy_and_gradient(x, volume, g)));
  const X fd = fd_gradient([&](const X& y) { return kernel.energy(y, volume); }, x, step);
  EXPECT_LT(relative_error(g, fd), kFdTolerance) << "analytic\n" << g << "\nfd\n" << fd;

  typename Kernel::Block h;
  ASSERT_TRUE(kernel.hessian(x, volume, 1.0, h));
  const auto gradient = [&](const X& y) {
    typename Kernel::Gradient gy;
    kernel.energy_and_gradient(y, volume, gy);
    return gy;
  };
  const typename Kernel::Block fd_h = fd_jacobian(gradient, x, step);
  EXPECT_LT(relative_error(h, fd_h), kFdTolerance);
  EXPECT_EQ((h - h.transpose()).norm(), 0.0);
}

template <typename T>
class CurvedKernelTest : public ::testing::Test {};
using CurvedTypes =
    ::testing::Types<CurvedTag<CurvedType::Triangle6>, CurvedTag<CurvedType::Quadrilateral8>,
                     CurvedTag<CurvedType::Quadrilateral9>, CurvedTag<CurvedType::Tetrahedron10>,
                     CurvedTag<CurvedType::Hexahedron20>, CurvedTag<CurvedType::Hexahedron27>,
                     CurvedTag<CurvedType::Wedge15>, CurvedTag<CurvedType::Wedge18>>;
TYPED_TEST_SUITE(CurvedKernelTest, CurvedTypes);

TYPED_TEST(CurvedKernelTest, OptimalStraightCellHasZeroEnergyAndGradient) {
  constexpr CurvedType Type = TypeParam::value;
  for (double volume : {1.0, 0.01, 7.0}) {
    const Nodes<Type> x = straight_curved_cell<Type>(optimal_corners<Type>(volume));
    typename CurvedNeoHookeKernel<Type>::Gradient g;
    EXPECT_NEAR(thesis_kernel<Type>().energy_and_gradient(x, volume, g), 0.0, 1e-13);
    EXPECT_LT(g.norm(), 1e-12);
    const CellMeasure m = thesis_kernel<Type>().measure(x, volume);
    EXPECT_NEAR(m.volume, volume, 1e-14 * volume);
  }
}

TYPED_TEST(CurvedKernelTest, NeoHookeDerivativesMatchFiniteDifferences) {
  constexpr CurvedType Type = TypeParam::value;
  std::mt19937 rng(21);
  for (double w : {0.0, 0.4})
    for (int trial = 0; trial < 3; ++trial) {
      const double volume = 0.5 + trial;
      expect_derivatives_match_finite_differences(thesis_kernel<Type>(w),
                                                  curved_cell<Type>(volume, rng, 0.15), volume);
    }
}

TYPED_TEST(CurvedKernelTest, UntanglingDerivativesMatchFiniteDifferences) {
  constexpr CurvedType Type = TypeParam::value;
  std::mt19937 rng(22);
  const auto kernel = untangling_kernel<Type>();
  for (int trial = 0; trial < 3; ++trial) {
    const double volume = 0.5 + trial;
    expect_derivatives_match_finite_differences(kernel, curved_cell<Type>(volume, rng, 0.15),
                                                volume);
  }
  // A folded cell: the first mid-edge node pulled back behind corner 0, so det J < 0 there.
  Nodes<Type> folded = curved_cell<Type>(1.0, rng, 0.05);
  const int mid = CurvedTraits<Type>::corners;  // the node of edge (0, 1) in every type
  folded.col(mid) = folded.col(0) - 0.3 * (folded.col(1) - folded.col(0));
  EXPECT_TRUE(std::isinf(thesis_kernel<Type>().energy(folded, 1.0)));
  expect_derivatives_match_finite_differences(kernel, folded, 1.0);
}

TYPED_TEST(CurvedKernelTest, InvariantUnderTranslationAndRotation) {
  constexpr CurvedType Type = TypeParam::value;
  constexpr int dim = CurvedTraits<Type>::dim;
  std::mt19937 rng(23);
  const Nodes<Type> x = curved_cell<Type>(2.0, rng);
  Matrix<dim> rotation;
  if constexpr (dim == 2) {
    rotation = Eigen::Rotation2Dd(0.7).toRotationMatrix();
  } else {
    rotation = Eigen::AngleAxisd(0.7, Vector<3>(1.0, 2.0, -0.5).normalized()).toRotationMatrix();
  }
  const Nodes<Type> moved = (rotation * x).colwise() + Vector<dim>::Constant(3.5);
  const auto kernel = thesis_kernel<Type>();
  typename CurvedNeoHookeKernel<Type>::Gradient g, g_moved;
  const double e = kernel.energy_and_gradient(x, 2.0, g);
  EXPECT_NEAR(kernel.energy_and_gradient(moved, 2.0, g_moved), e, 1e-12 * e);
  EXPECT_LT(relative_error(g_moved, rotation * g), 1e-12);
}

// The corner gradient of a straight cell given as order 2 with its higher-order nodes slaved to
// the corners: node i sits at Σ_c L_c(ξ_i) x_c, so ∂/∂x_c = Σ_i L_c(ξ_i) ∂/∂x_i.
template <CurvedType Type>
Corners<Type> slaved_gradient(const Nodes<Type>& node_gradient) {
  Corners<Type> g;
  for (int k = 0; k < g.size(); ++k) {
    Corners<Type> unit = Corners<Type>::Zero();
    unit.data()[k] = 1.0;
    g.data()[k] = node_gradient.cwiseProduct(straight_curved_cell<Type>(unit)).sum();
  }
  return g;
}

// A straight cell given as order 2 has the straight cell's energy, and with its higher-order
// nodes kept at their straight places the same corner gradient. Simplices: G is constant, so
// any rule gives the one-point value. Quadrilaterals and hexahedra: the Q1 kernel with the same
// Gauss rule and corner samples (its default rule has 3 points per direction, the curved one
// kCurvedGaussPoints = 4: they agree to the rules' error only, so the check takes the same n).
// Wedges: the straight wedge's rule (a symmetric triangle rule) is not the curved one's, so the
// check takes prisms, affine images of the optimal one, whose G is constant.
TYPED_TEST(CurvedKernelTest, StraightCellAsOrderTwoEqualsTheLinearKernel) {
  constexpr CurvedType Type = TypeParam::value;
  constexpr CellType Linear = CurvedTraits<Type>::linear;
  constexpr int dim = CurvedTraits<Type>::dim;
  std::mt19937 rng(24);
  for (int n : {2, 3}) {
    const double w = CurvedTraits<Type>::simplex ? 0.0 : 0.3;
    const NeoHookeKernel<Linear> linear(NeoHooke<dim>{1.0, 10.0, 1.0}, n, w);
    const CurvedNeoHookeKernel<Type> curved = thesis_kernel<Type>(w, n);
    const UntanglingKernel<Linear> linear_untangling(RegularizedNeoHooke<dim>{1.0, 10.0, 0.05}, n,
                                                     w);
    const CurvedUntanglingKernel<Type> curved_untangling(RegularizedNeoHooke<dim>{1.0, 10.0, 0.05},
                                                         n, w);
    for (int trial = 0; trial < 3; ++trial) {
      const double volume = 0.7 + trial;
      const Corners<Type> c =
          straight_corners<Type>(volume, rng, CurvedTraits<Type>::wedge ? 0.0 : 0.1);
      const Nodes<Type> x = straight_curved_cell<Type>(c);
      typename NeoHookeKernel<Linear>::Gradient g1;
      typename CurvedNeoHookeKernel<Type>::Gradient g2;
      const double e1 = linear.energy_and_gradient(c, volume, g1);
      EXPECT_NEAR(curved.energy_and_gradient(x, volume, g2), e1, 1e-12 * e1);
      EXPECT_LT(relative_error(slaved_gradient<Type>(g2), g1), 1e-11);
      const double u1 = linear_untangling.energy_and_gradient(c, volume, g1);
      EXPECT_NEAR(curved_untangling.energy_and_gradient(x, volume, g2), u1, 1e-12 * u1);
      EXPECT_LT(relative_error(slaved_gradient<Type>(g2), g1), 1e-11);
    }
  }
}

TYPED_TEST(CurvedKernelTest, InvertedCellIsInfiniteAndRejected) {
  constexpr CurvedType Type = TypeParam::value;
  using Kernel = CurvedNeoHookeKernel<Type>;
  std::mt19937 rng(25);
  Nodes<Type> x = curved_cell<Type>(1.0, rng);
  x.row(0) *= -1.0;  // mirror image: det J < 0 everywhere
  const Kernel kernel = thesis_kernel<Type>();
  EXPECT_TRUE(std::isinf(kernel.energy(x, 1.0)));
  typename Kernel::Block h;
  EXPECT_FALSE(kernel.hessian(x, 1.0, 1.0, h));
  EXPECT_TRUE(std::isfinite(untangling_kernel<Type>().energy(x, 1.0)));
}

// The polynomial parts are integrated exactly at the default rule: the Laplacian ∫ ∇φ̂_i·∇φ̂_j
// (degree 2(p − 1), as tr GᵀG) and the volume ∫ det J agree with the 5-point rule's.
TYPED_TEST(CurvedKernelTest, DefaultRuleIntegratesThePolynomialPartsExactly) {
  constexpr CurvedType Type = TypeParam::value;
  using Kernel = CurvedNeoHookeKernel<Type>;
  std::mt19937 rng(26);
  const Kernel kernel = thesis_kernel<Type>(), fine = thesis_kernel<Type>(0.0, 5);
  typename Kernel::Block l, l_fine;
  kernel.optimal_laplacian(1.3, l);
  fine.optimal_laplacian(1.3, l_fine);
  EXPECT_LT(relative_error(l, l_fine), 1e-13);
  const Nodes<Type> x = curved_cell<Type>(1.3, rng, 0.2);
  EXPECT_NEAR(kernel.measure(x, 1.3).volume, fine.measure(x, 1.3).volume, 1e-13);
}

// The worst relative change of the energy from n to n + 1 points per direction (n = 1..4) over
// 20 random cells, printed on one line.
template <CurvedType Type>
std::array<double, 4> rule_changes(double bend, Interior interior, const char* label) {
  std::mt19937 rng(27);
  std::array<Nodes<Type>, 20> cells;
  for (Nodes<Type>& x : cells) x = curved_cell<Type>(1.0, rng, bend, interior);
  std::array<double, 4> worst{};  // worst[n - 1]: from n to n + 1 points
  std::printf("%-14s %-9s", std::string(name(Type)).c_str(), label);
  for (int n = 1; n < 5; ++n) {
    const auto rule = thesis_kernel<Type>(0.0, n), finer = thesis_kernel<Type>(0.0, n + 1);
    for (const Nodes<Type>& x : cells) {
      const double e_finer = finer.energy(x, 1.0);
      worst[n - 1] = std::max(worst[n - 1], std::abs(rule.energy(x, 1.0) - e_finer) / e_finer);
    }
    std::printf("  %d→%d: %.1e", n, n + 1, worst[n - 1]);
  }
  std::printf("\n");
  return worst;
}

// On moderately curved cells (edge nodes moved by up to 5% of the edge in each coordinate, face
// and centre nodes blended from the edges) the energy at the default rule changes by less than
// 1e-6 (relative) with one more point per direction, and the rule before it does not reach
// that: the default is the smallest that does. Also prints the changes on more strongly
// curved cells (10%, interior nodes moved at random too), which the default does not resolve
// to 1e-6 (docs/method.md §12 quotes both).
TYPED_TEST(CurvedKernelTest, DefaultRuleIsConverged) {
  constexpr CurvedType Type = TypeParam::value;
  const std::array<double, 4> worst = rule_changes<Type>(0.05, Interior::Blended, "moderate");
  rule_changes<Type>(0.1, Interior::Random, "strong");
  EXPECT_LT(worst[kCurvedGaussPoints - 1], 1e-6);
  EXPECT_GT(worst[kCurvedGaussPoints - 2], 1e-6);
}

// A patch of six triangles around vertex 0 (outer vertices 1..6 counter-clockwise), each with
// desired volume `volume`, given as order 1 and as order 2 with straight edges.
struct TrianglePatch {
  static constexpr CurvedType Type = CurvedType::Triangle6;
  using Linear = NeoHookeKernel<CellType::Triangle>;
  std::array<Vector<2>, 7> vertices;
  double volume;
  Linear linear{NeoHooke<2>{1.0, 10.0, 1.0}, 1};
  CurvedNeoHookeKernel<Type> curved = thesis_kernel<Type>();

  Corners<Type> corners(int k) const {  // triangle k: (0, k + 1, k + 2 mod 6)
    Corners<Type> c;
    c << vertices[0], vertices[1 + k], vertices[1 + (k + 1) % 6];
    return c;
  }
  double energy() const {
    double e = 0.0;
    for (int k = 0; k < 6; ++k) e += linear.energy(corners(k), volume);
    return e;
  }
  // Newton on vertex 0 with the order-1 energy: the order-1 optimum (outer vertices fixed).
  void optimize_vertex_0() {
    for (int iteration = 0; iteration < 50; ++iteration) {
      Vector<2> g = Vector<2>::Zero();
      Matrix<2> h = Matrix<2>::Zero();
      for (int k = 0; k < 6; ++k) {
        typename Linear::Gradient gk;
        typename Linear::Block hk;
        linear.energy_and_gradient(corners(k), volume, gk);
        linear.hessian(corners(k), volume, 1.0, hk);
        g += gk.col(0);
        h += hk.topLeftCorner<2, 2>();
      }
      const Vector<2> start = vertices[0], step = h.ldlt().solve(g);
      const double e0 = energy();
      for (double t = 1.0; t > 1e-8; t *= 0.5) {
        vertices[0] = start - t * step;
        if (energy() <= e0) break;
      }
    }
  }
  // The order-2 energy's gradient at the mid-node of interior edge (0, k + 1): node 3 (edge
  // (0,1)) of triangle k and node 5 (edge (2,0)) of triangle k − 1.
  Vector<2> mid_node_gradient(int k) const {
    typename CurvedNeoHookeKernel<Type>::Gradient a, b;
    curved.energy_and_gradient(straight_curved_cell<Type>(corners(k)), volume, a);
    curved.energy_and_gradient(straight_curved_cell<Type>(corners((k + 5) % 6)), volume, b);
    return a.col(3) + b.col(5);
  }
  // The Cauchy stress σ = P Gᵀ / det G of triangle k.
  Matrix<2> cauchy_stress(int k) const {
    const Corners<Type> c = corners(k);
    Matrix<2> edges;
    edges << c.col(1) - c.col(0), c.col(2) - c.col(0);
    const Matrix<2> G = edges * (std::sqrt(volume) * unit_optimal_simplex_edges<2>()).inverse();
    return NeoHooke<2>{1.0, 10.0, 1.0}.stress(G) * G.transpose() / G.determinant();
  }
};

// Is a straight mesh at the order-1 optimum, given as order 2 with its mid-nodes at the
// midpoints, stationary for the order-2 energy? Per straight triangle G is constant and
// ∫_{target} P ∇φ̂_m = ∫_K σ ∇φ_m = σ ∮ φ_m n = (2/3)|e| σ n_e for the mid-node m of edge e
// (φ_m = 4 λ_i λ_j vanishes on the other edges). Summed over the two triangles A, B of an
// interior edge: (2/3)|e| (σ_A − σ_B) n_A, the jump of the traction. The order-1 optimum makes
// Σ over each vertex's cells vanish, not each jump: the mid-nodes are not at rest, and moving
// them lowers the energy — the order-2 mesh curves.
TEST(StraightOrderTwoMesh, MidNodesAreNotStationaryAtTheLinearOptimum) {
  TrianglePatch patch;
  patch.vertices[0] = Vector<2>(0.1, -0.05);
  double area = 0.0;
  for (int k = 0; k < 6; ++k) {
    const double angle = 2.0 * M_PI * k / 6.0 + 0.2 * std::cos(1.7 * k);
    patch.vertices[1 + k] =
        (1.0 + 0.3 * std::sin(2.3 * k)) * Vector<2>(std::cos(angle), std::sin(angle));
  }
  for (int k = 0; k < 6; ++k) {
    const Corners<CurvedType::Triangle6> c = patch.corners(k);
    area +=
        0.5 * ((c.col(1) - c.col(0)).homogeneous().cross((c.col(2) - c.col(0)).homogeneous()))[2];
  }
  patch.volume = area / 6.0;
  patch.optimize_vertex_0();

  double jump = 0.0;
  for (int k = 0; k < 6; ++k) {
    const Vector<2> e = patch.vertices[1 + k] - patch.vertices[0];
    const Vector<2> outward_of_k(e[1], -e[0]);  // triangle k lies to the left of e
    const Vector<2> expected =
        (2.0 / 3.0) * (patch.cauchy_stress(k) - patch.cauchy_stress((k + 5) % 6)) * outward_of_k;
    const Vector<2> g = patch.mid_node_gradient(k);
    EXPECT_LT((g - expected).norm(), 1e-12 * expected.norm());
    jump = std::max(jump, g.norm());
  }
  // The vertex is at rest (order 1), the mid-nodes are not.
  Vector<2> g0 = Vector<2>::Zero();
  for (int k = 0; k < 6; ++k) {
    typename TrianglePatch::Linear::Gradient gk;
    patch.linear.energy_and_gradient(patch.corners(k), patch.volume, gk);
    g0 += gk.col(0);
  }
  EXPECT_LT(g0.norm(), 1e-10 * jump);
  EXPECT_GT(jump, 0.1);
  std::printf("largest mid-node gradient at the order-1 optimum: %.3g (energy %.4g)\n", jump,
              patch.energy());
}

// The other side: where every cell has the same stress (here a regular patch of equilateral
// triangles, each twice its desired volume) the traction does not jump and the interior
// mid-nodes are at rest, by symmetry.
TEST(StraightOrderTwoMesh, MidNodesAreStationaryWhereTheStressIsUniform) {
  TrianglePatch patch;
  patch.vertices[0].setZero();
  for (int k = 0; k < 6; ++k)
    patch.vertices[1 + k] = Vector<2>(std::cos(M_PI * k / 3.0), std::sin(M_PI * k / 3.0));
  patch.volume = 0.5 * std::sqrt(3.0) / 4.0;
  ASSERT_GT(patch.cauchy_stress(0).norm(), 1.0);
  for (int k = 0; k < 6; ++k) EXPECT_LT(patch.mid_node_gradient(k).norm(), 1e-12);
}

}  // namespace
}  // namespace neomesh
