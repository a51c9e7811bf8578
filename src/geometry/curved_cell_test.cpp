#include "geometry/curved_cell.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <utility>

#include "geometry/quality.hpp"
#include "geometry/testing/curved_types.hpp"

namespace neomesh {

namespace {

using neomesh::testing::for_each_curved_type;

template <CurvedType Type>
using Corners = Eigen::Matrix<double, CurvedTraits<Type>::dim, CurvedTraits<Type>::corners>;

// A uniformly random point of the reference cell.
template <CurvedType Type>
Vector<CurvedTraits<Type>::dim> random_point(std::mt19937& rng) {
  constexpr int dim = CurvedTraits<Type>::dim;
  if constexpr (CurvedTraits<Type>::simplex || CurvedTraits<Type>::wedge) {
    // The wedge: the triangle's, then the axis' coordinate in [−1, 1].
    constexpr int simplex_dim = CurvedTraits<Type>::wedge ? 2 : dim;
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (;;) {
      Vector<dim> xi;
      for (int j = 0; j < dim; ++j) xi[j] = u(rng);
      if (xi.template head<simplex_dim>().sum() > 1.0) continue;
      if constexpr (CurvedTraits<Type>::wedge) xi[2] = 2.0 * xi[2] - 1.0;
      return xi;
    }
  } else {
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    Vector<dim> xi;
    for (int j = 0; j < dim; ++j) xi[j] = u(rng);
    return xi;
  }
}

// The reference cell's corners in canonical order, each moved by up to `jitter` per coordinate.
template <CurvedType Type>
Corners<Type> jittered_corners(std::mt19937& rng, double jitter) {
  constexpr int dim = CurvedTraits<Type>::dim;
  std::uniform_real_distribution<double> u(-jitter, jitter);
  Corners<Type> c;
  for (int v = 0; v < CurvedTraits<Type>::corners; ++v) {
    if constexpr (CurvedTraits<Type>::simplex)
      c.col(v) = v == 0 ? Vector<dim>::Zero() : Vector<dim>(Vector<dim>::Unit(v - 1));
    else if constexpr (CurvedTraits<Type>::wedge)
      c.col(v) = reference_node<Type>(v);  // canonical order is Gmsh's
    else
      c.col(v) = q1_vertex<dim>(v);
    for (int j = 0; j < dim; ++j) c(j, v) += u(rng);
  }
  return c;
}

// A curved cell: the jittered straight cell with every node moved by up to `bend` per coordinate.
template <CurvedType Type>
typename CurvedTraits<Type>::Nodes random_curved_cell(std::mt19937& rng, double jitter,
                                                      double bend) {
  typename CurvedTraits<Type>::Nodes x =
      straight_curved_cell<Type>(jittered_corners<Type>(rng, jitter));
  std::uniform_real_distribution<double> u(-bend, bend);
  for (int i = 0; i < x.size(); ++i) x(i) += u(rng);
  return x;
}

// det J of the straight cell with `corners` (canonical order) at reference point ξ.
template <CurvedType Type>
double linear_det(const Corners<Type>& c, const Vector<CurvedTraits<Type>::dim>& xi) {
  constexpr int dim = CurvedTraits<Type>::dim;
  if constexpr (CurvedTraits<Type>::simplex) {
    Matrix<dim> edges;
    for (int j = 0; j < dim; ++j) edges.col(j) = c.col(j + 1) - c.col(0);
    return edges.determinant();
  } else if constexpr (CurvedTraits<Type>::wedge) {
    return (c * wedge_gradients(xi).transpose()).determinant();
  } else {
    return (c * q1_gradients<dim>(xi).transpose()).determinant();
  }
}

// q(ξ) of curved_scaled_jacobian, computed here from its definition.
template <CurvedType Type>
double pointwise_scaled_jacobian(const typename CurvedTraits<Type>::Nodes& x,
                                 const Vector<CurvedTraits<Type>::dim>& xi) {
  constexpr int dim = CurvedTraits<Type>::dim;
  const Matrix<dim> j = curved_jacobian<Type>(x, xi);
  const CellType linear = CurvedTraits<Type>::linear;
  if constexpr (CurvedTraits<Type>::wedge) {
    // At corner k: the edges to the next two corners of its triangle, and the axis upwards.
    double q = 1.0;
    for (int k = 0; k < 6; ++k) {
      const int base = k - k % 3;
      Matrix<3> frame;
      frame << j * (reference_node<Type>(base + (k + 1) % 3) - reference_node<Type>(k)),
          j * (reference_node<Type>(base + (k + 2) % 3) - reference_node<Type>(k)),
          j * Vector<3>::UnitZ();
      q = std::min(
          q, frame.determinant() / frame.colwise().norm().prod() / facts(linear).ideal_corner_sine);
    }
    return q;
  } else if constexpr (!CurvedTraits<Type>::simplex) {
    return j.determinant() / j.colwise().norm().prod() / facts(linear).ideal_corner_sine;
  } else {
    double q = 1.0;
    for (int k = 0; k <= dim; ++k) {
      double product = 1.0;
      for (int m = 0; m <= dim; ++m)
        if (m != k) product *= (j * (reference_node<Type>(m) - reference_node<Type>(k))).norm();
      q = std::min(q, j.determinant() / product / facts(linear).ideal_corner_sine);
    }
    return q;
  }
}

// −1 over the optimal cell's corner sine: the least the pointwise measure q can be.
template <CurvedType Type>
double least_scaled_jacobian() {
  return -1.0 / facts(CurvedTraits<Type>::linear).ideal_corner_sine;
}

// The cell of the reference corners with its first mid-edge node (on edge (0, 1)) moved by
// `across` times the way to its mirror image through the corners' centroid: at 1 it lies on the
// opposite edge of a quadrilateral, tetrahedron or hexahedron, on the median to corner 2 of a
// triangle.
template <CurvedType Type>
typename CurvedTraits<Type>::Nodes pushed_cell(double across) {
  std::mt19937 unused;
  const Corners<Type> corners = jittered_corners<Type>(unused, 0.0);
  typename CurvedTraits<Type>::Nodes x = straight_curved_cell<Type>(corners);
  const int m = CurvedTraits<Type>::corners;
  const Vector<CurvedTraits<Type>::dim> centroid = corners.rowwise().mean();
  x.col(m) += across * 2.0 * (centroid - x.col(m));
  return x;
}

// A cell with det J > 0 everywhere whose undivided Bézier bounds do not show it. Tensor cells
// and wedges: the first mid-edge node pushed a little (by as much as the Lagrange and serendipity
// bases need to bend the edge alike). Simplices: a single moved node leaves det J affine — J is
// then a rank-one update of the straight cell's, det(J + u gᵀ) = det J (1 + gᵀ J⁻¹ u) with g linear
// — so its Bézier bounds are exact and never undecided; two moved nodes make it quadratic (cubic).
template <CurvedType Type>
typename CurvedTraits<Type>::Nodes slightly_pushed_cell() {
  using Traits = CurvedTraits<Type>;
  if constexpr (Type == CurvedType::Quadrilateral8) return pushed_cell<Type>(0.84);
  if constexpr (Type == CurvedType::Quadrilateral9) return pushed_cell<Type>(0.28);
  if constexpr (Type == CurvedType::Hexahedron20) return pushed_cell<Type>(0.44);
  if constexpr (Type == CurvedType::Hexahedron27) return pushed_cell<Type>(0.15);
  if constexpr (Type == CurvedType::Wedge15) return pushed_cell<Type>(0.4);
  if constexpr (Type == CurvedType::Wedge18) return pushed_cell<Type>(0.2);
  std::mt19937 unused;
  typename Traits::Nodes x = straight_curved_cell<Type>(jittered_corners<Type>(unused, 0.0));
  if constexpr (Type == CurvedType::Triangle6) {
    x.col(3) += Vector<2>(-0.25, 0.15);   // edge (0, 1)
    x.col(5) += Vector<2>(-0.25, -0.15);  // edge (2, 0)
  } else if constexpr (Type == CurvedType::Tetrahedron10) {
    x.col(4) += Vector<3>(-0.15, 0.15, 0.15);   // edge (0, 1)
    x.col(6) += Vector<3>(-0.25, -0.25, 0.05);  // edge (2, 0)
  }
  return x;
}

}  // namespace

// Gmsh's numbering (its manual, "Node ordering"): edges, faces and the centre in its order.
TEST(CurvedCell, NodesAreNumberedAsGmshNumbersThem) {
  EXPECT_EQ(reference_node<CurvedType::Triangle6>(4), Vector<2>(0.5, 0.5));
  EXPECT_EQ(reference_node<CurvedType::Triangle6>(5), Vector<2>(0.0, 0.5));
  EXPECT_EQ(reference_node<CurvedType::Quadrilateral8>(2), Vector<2>(1.0, 1.0));
  EXPECT_EQ(reference_node<CurvedType::Quadrilateral8>(7), Vector<2>(-1.0, 0.0));
  EXPECT_EQ(reference_node<CurvedType::Quadrilateral9>(8), Vector<2>(0.0, 0.0));
  EXPECT_EQ(reference_node<CurvedType::Tetrahedron10>(7), Vector<3>(0.0, 0.0, 0.5));
  EXPECT_EQ(reference_node<CurvedType::Tetrahedron10>(8), Vector<3>(0.0, 0.5, 0.5));
  EXPECT_EQ(reference_node<CurvedType::Tetrahedron10>(9), Vector<3>(0.5, 0.0, 0.5));
  EXPECT_EQ(reference_node<CurvedType::Hexahedron20>(6), Vector<3>(1.0, 1.0, 1.0));
  EXPECT_EQ(reference_node<CurvedType::Hexahedron20>(9), Vector<3>(-1.0, 0.0, -1.0));
  EXPECT_EQ(reference_node<CurvedType::Hexahedron20>(10), Vector<3>(-1.0, -1.0, 0.0));
  EXPECT_EQ(reference_node<CurvedType::Hexahedron20>(19), Vector<3>(0.0, 1.0, 1.0));
  EXPECT_EQ(reference_node<CurvedType::Hexahedron27>(20), Vector<3>(0.0, 0.0, -1.0));
  EXPECT_EQ(reference_node<CurvedType::Hexahedron27>(21), Vector<3>(0.0, -1.0, 0.0));
  EXPECT_EQ(reference_node<CurvedType::Hexahedron27>(22), Vector<3>(-1.0, 0.0, 0.0));
  EXPECT_EQ(reference_node<CurvedType::Hexahedron27>(25), Vector<3>(0.0, 0.0, 1.0));
  EXPECT_EQ(reference_node<CurvedType::Hexahedron27>(26), Vector<3>(0.0, 0.0, 0.0));
}

TEST(CurvedBasis, IsAPartitionOfUnityAndInterpolatesAtTheNodes) {
  for_each_curved_type([]<CurvedType Type>() {
    constexpr int n = CurvedTraits<Type>::nodes;
    std::mt19937 rng(1);
    for (int trial = 0; trial < 20; ++trial) {
      const auto xi = random_point<Type>(rng);
      EXPECT_NEAR(curved_basis<Type>(xi).sum(), 1.0, 1e-14);
      EXPECT_LT(curved_gradients<Type>(xi).rowwise().sum().norm(), 1e-13);
    }
    for (int i = 0; i < n; ++i) {
      const auto values = curved_basis<Type>(reference_node<Type>(i));
      for (int j = 0; j < n; ++j)
        EXPECT_NEAR(values[j], i == j ? 1.0 : 0.0, 1e-15) << i << ' ' << j;
    }
  });
}

TEST(CurvedBasis, GradientsMatchFiniteDifferences) {
  for_each_curved_type([]<CurvedType Type>() {
    constexpr int dim = CurvedTraits<Type>::dim;
    constexpr double h = 1e-6;
    std::mt19937 rng(2);
    for (int trial = 0; trial < 20; ++trial) {
      const auto xi = random_point<Type>(rng);
      const auto grad = curved_gradients<Type>(xi);
      for (int j = 0; j < dim; ++j) {
        const Vector<dim> step = h * Vector<dim>::Unit(j);
        const Eigen::Matrix<double, CurvedTraits<Type>::nodes, 1> fd =
            (curved_basis<Type>(xi + step) - curved_basis<Type>(xi - step)) / (2 * h);
        EXPECT_LT((grad.row(j).transpose() - fd).norm(), 1e-8);
      }
    }
  });
}

TEST(CurvedCell, StraightCellHasTheLinearCellsDetJEverywhere) {
  for_each_curved_type([]<CurvedType Type>() {
    std::mt19937 rng(3);
    for (int trial = 0; trial < 10; ++trial) {
      const Corners<Type> c = jittered_corners<Type>(rng, 0.2);
      const auto x = straight_curved_cell<Type>(c);
      for (int k = 0; k < CurvedTraits<Type>::corners; ++k)
        EXPECT_LT((x.col(linear_corners<Type>()[k]) - c.col(k)).norm(), 1e-15);
      for (int p = 0; p < 20; ++p) {
        const auto xi = random_point<Type>(rng);
        EXPECT_NEAR(curved_det<Type>(x, xi), linear_det<Type>(c, xi), 1e-13);
        EXPECT_LT((curved_map<Type>(x, xi) - straight_curved_cell<Type>(c) * curved_basis<Type>(xi))
                      .norm(),
                  1e-15);
      }
    }
  });
}

// The measure of a straight cell given as second order is quality.cpp's scaled Jacobian of the
// linear cell; for a simplex, q is constant, so both bounds are it too, and for a valid
// quadrilateral q is least at a corner, so the sampled bound is.
TEST(CurvedScaledJacobian, OfAStraightCellIsTheLinearCells) {
  for_each_curved_type([]<CurvedType Type>() {
    std::mt19937 rng(4);
    for (int trial = 0; trial < 10; ++trial) {
      const Corners<Type> c = jittered_corners<Type>(rng, 0.25);
      const double expected = cell_scaled_jacobian(CurvedTraits<Type>::linear, c.data());
      const CurvedScaledJacobian s = curved_scaled_jacobian<Type>(straight_curved_cell<Type>(c));
      EXPECT_EQ(s.certificate.validity, Validity::Valid);
      EXPECT_NEAR(s.scaled_jacobian, expected, 1e-12);
      EXPECT_LE(s.lower, s.upper);
      EXPECT_LE(s.upper, expected + 1e-12);
      if constexpr (CurvedTraits<Type>::simplex) {
        EXPECT_NEAR(s.lower, expected, 1e-12);
        EXPECT_NEAR(s.upper, expected, 1e-12);
      } else if constexpr (CurvedTraits<Type>::dim == 2) {
        EXPECT_NEAR(s.upper, expected, 1e-12);
      }
    }
  });
}

TEST(JacobianBezier, ReproducesDetJAtRandomPoints) {
  for_each_curved_type([]<CurvedType Type>() {
    std::mt19937 rng(5);
    for (int trial = 0; trial < 5; ++trial) {
      const auto x = random_curved_cell<Type>(rng, 0.2, 0.15);
      const Eigen::VectorXd c = jacobian_bezier_coefficients<Type>(x);
      for (int p = 0; p < 20; ++p) {
        const auto xi = random_point<Type>(rng);
        EXPECT_NEAR(bezier_value<Type>(c, xi), curved_det<Type>(x, xi), 1e-12);
      }
    }
  });
}

TEST(JacobianCertificate, BoundsContainSampledDetJ) {
  for_each_curved_type([]<CurvedType Type>() {
    std::mt19937 rng(6);
    std::array<int, 3> seen{};  // by Validity
    // (The wedge's 18 nodes on a reference cell of height 2 but unit triangle fold more often.)
    const double bend = CurvedTraits<Type>::wedge ? 0.2 : 0.3;
    for (int trial = 0; trial < 20; ++trial) {
      const auto x = random_curved_cell<Type>(rng, 0.2, bend);
      const CurvedScaledJacobian s = curved_scaled_jacobian<Type>(x);
      const JacobianCertificate& cert = s.certificate;
      EXPECT_LE(cert.min_det_lower, cert.min_det_upper);
      EXPECT_LE(s.lower, s.upper);
      EXPECT_GE(s.lower, least_scaled_jacobian<Type>());
      double lowest = INFINITY;
      for (int p = 0; p < 200; ++p) {
        const auto xi = random_point<Type>(rng);
        const double det = curved_det<Type>(x, xi);
        lowest = std::min(lowest, det);
        EXPECT_LE(cert.min_det_lower, det);
        EXPECT_LE(s.lower, pointwise_scaled_jacobian<Type>(x, xi));
      }
      if (lowest <= 0.0) {
        EXPECT_NE(cert.validity, Validity::Valid);
      }
      if (cert.validity == Validity::Valid) {
        EXPECT_GT(cert.min_det_lower, 0.0);
      }
      ++seen[static_cast<int>(cert.validity)];
    }
    // The random cells are bent enough that some are valid and some are not.
    EXPECT_GT(seen[static_cast<int>(Validity::Valid)], 0);
    EXPECT_GT(seen[static_cast<int>(Validity::Invalid)], 0);
  });
}

TEST(JacobianCertificate, MidEdgeNodePushedAcrossIsCertainlyInvalid) {
  for_each_curved_type([]<CurvedType Type>() {
    const CurvedScaledJacobian s = curved_scaled_jacobian<Type>(pushed_cell<Type>(1.25));
    EXPECT_EQ(s.certificate.validity, Validity::Invalid);
    EXPECT_LE(s.certificate.min_det_upper, 0.0);
    EXPECT_LE(s.scaled_jacobian, 0.0);
    EXPECT_EQ(s.lower, least_scaled_jacobian<Type>());
  });
}

TEST(JacobianCertificate, SlightlyPushedIsValidOnlyAfterSubdivision) {
  for_each_curved_type([]<CurvedType Type>() {
    const auto x = slightly_pushed_cell<Type>();
    const JacobianCertificate undivided = certify_jacobian<Type>(x, 0);
    EXPECT_EQ(undivided.validity, Validity::Undecided);
    EXPECT_LE(undivided.min_det_lower, 0.0);
    EXPECT_GT(undivided.min_det_upper, 0.0);

    const CurvedScaledJacobian s = curved_scaled_jacobian<Type>(x);
    EXPECT_EQ(s.certificate.validity, Validity::Valid);
    EXPECT_GE(s.certificate.depth, 1);
    EXPECT_GT(s.certificate.min_det_lower, 0.0);
    EXPECT_GT(s.lower, 0.0);
    EXPECT_LE(s.lower, s.upper);
    EXPECT_LE(s.upper, s.scaled_jacobian);
    // The certificate's bounds hold on a dense sample.
    std::mt19937 rng(8);
    for (int p = 0; p < 2000; ++p) {
      const auto xi = random_point<Type>(rng);
      EXPECT_GE(curved_det<Type>(x, xi), s.certificate.min_det_lower);
    }
  });
}

// Asked for a tolerance, the bounds of the minimum of q close in on it (given the depth: q is
// steep where det J is nearly 0).
TEST(CurvedScaledJacobian, BoundsCloseToTheTolerance) {
  for_each_curved_type([]<CurvedType Type>() {
    constexpr bool plane = CurvedTraits<Type>::dim == 2;
    constexpr double tolerance = plane ? 0.01 : 0.1;
    const auto x = slightly_pushed_cell<Type>();
    const CurvedScaledJacobian loose = curved_scaled_jacobian<Type>(x);
    const CurvedScaledJacobian s = curved_scaled_jacobian<Type>(x, plane ? 10 : 6, tolerance);
    EXPECT_LE(s.upper - s.lower, tolerance);
    EXPECT_GE(s.lower, loose.lower);
    EXPECT_LE(s.upper, loose.upper);
    EXPECT_EQ(s.scaled_jacobian, loose.scaled_jacobian);
    std::mt19937 rng(9);
    for (int p = 0; p < 500; ++p)
      EXPECT_LE(s.lower, pointwise_scaled_jacobian<Type>(x, random_point<Type>(rng)));
  });
}

// The square [−1,1]² with its mid-edge node 4 moved by δ = 0.68 towards the opposite edge:
// det J = 1 + δ (1 − ξ²)(η − ½), least at the edge's midpoint (0, −1), 1 − 1.5δ = −0.02. The
// undivided cell samples ξ = ±1, ±1/3 only, where det J ≥ 1 − 1.5δ · 8/9 ≈ 0.09: the fold lies
// between its sample points, and the subdivision finds it.
TEST(JacobianCertificate, FoldBetweenSamplePointsIsFoundBySubdivision) {
  const auto x = pushed_cell<CurvedType::Quadrilateral9>(0.34);
  EXPECT_EQ(certify_jacobian<CurvedType::Quadrilateral9>(x, 0).validity, Validity::Undecided);
  const JacobianCertificate cert = certify_jacobian<CurvedType::Quadrilateral9>(x);
  EXPECT_EQ(cert.validity, Validity::Invalid);
  EXPECT_LT(curved_det<CurvedType::Quadrilateral9>(x, Vector<2>(0.0, -1.0)), 0.0);
}

TEST(JacobianCertificate, UndecidedAtTheDepthLimitIsNotValid) {
  const auto x = slightly_pushed_cell<CurvedType::Hexahedron27>();
  const CurvedScaledJacobian s = curved_scaled_jacobian<CurvedType::Hexahedron27>(x, 0);
  EXPECT_EQ(s.certificate.validity, Validity::Undecided);
  EXPECT_EQ(s.scaled_jacobian, 0.0);
  EXPECT_EQ(s.lower, -1.0);  // the optimal hexahedron's corner sine is 1
}

}  // namespace neomesh
