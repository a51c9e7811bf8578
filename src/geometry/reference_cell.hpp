// Reference and optimal cells, quadrature, shape-function gradients and corner Jacobians.
//
// Conventions (docs/method.md §1, docs/cell-types.md): Q1 cells map from [-1,1]^d with
// vertices in tensor order (cell_type.hpp); simplices use their edge matrix
// E = [x1-x0, x2-x0(, x3-x0)]; wedges map from triangle × [-1,1] and pyramids from [-1,1]^3
// with the top face collapsed onto the apex. The optimal cell of desired volume v is the
// square/cube of edge v^(1/d), the equilateral triangle or the regular tetrahedron, the right
// prism on an equilateral triangle with height equal to its edge, or the square pyramid with
// equilateral side faces, scaled to volume v.
#pragma once

#include <array>
#include <cmath>

#include <Eigen/Dense>

#include "mesh/cell_type.hpp"

namespace neomesh {

template <int Dim>
using Vector = Eigen::Matrix<double, Dim, 1>;
template <int Dim>
using Matrix = Eigen::Matrix<double, Dim, Dim>;

// Compile-time facts of a cell type: spatial dimension and number of vertices.
template <CellType Type>
struct CellTraits {
  static constexpr int dim = dimension(Type);
  static constexpr int vertices = num_vertices(Type);
  static constexpr bool simplex = is_simplex(Type);
  static constexpr CellShape shape = facts(Type).shape;
  using Coordinates = Eigen::Matrix<double, dim, vertices>;  // one column per vertex
};

// The Jacobian at corner frame k of the cell-type table (CornerFrame): its columns are the
// frame's edges, so det > 0 on a valid cell and, for Q1 cells, the unit square/cube has J = I.
// `x` has one column per vertex: dim rows for a cell of its own dimension, or 3 for a triangle
// or quadrilateral in space (a surface cell: J is then 3 × 2).
template <CellType Type, typename Derived>
Eigen::Matrix<double, Derived::RowsAtCompileTime, CellTraits<Type>::dim> corner_jacobian(
    const Eigen::MatrixBase<Derived>& x, int k) {
  constexpr int dim = CellTraits<Type>::dim;
  const CornerFrame& frame = facts(Type).corners[k];
  Eigen::Matrix<double, Derived::RowsAtCompileTime, dim> edges;
  for (int j = 0; j < dim; ++j) {
    const double sign = ((frame.flip >> j) & 1) ? -1.0 : 1.0;
    edges.col(j) = sign * (x.col(frame.ends[j]) - x.col(frame.vertex));
  }
  return edges;
}

// C_k: corner frame k as a linear map of the vertices, corner_jacobian(x, k) = x C_kᵀ.
template <CellType Type>
typename CellTraits<Type>::Coordinates corner_frame_map(int k) {
  const CornerFrame& frame = facts(Type).corners[k];
  typename CellTraits<Type>::Coordinates c = CellTraits<Type>::Coordinates::Zero();
  for (int j = 0; j < CellTraits<Type>::dim; ++j) {
    const double sign = ((frame.flip >> j) & 1) ? -1.0 : 1.0;
    c(j, frame.ends[j]) += sign;
    c(j, frame.vertex) -= sign;
  }
  return c;
}

// Gauss–Legendre rule on [-1, 1] with n = 1..5 points (exact for degree 2n-1).
struct GaussRule1D {
  int size = 0;
  std::array<double, 5> points{};
  std::array<double, 5> weights{};
};
GaussRule1D gauss_legendre(int n);

// Tensor Gauss rule on [-1,1]^Dim: point q = (i0, i1, ...) with weight w_i0 · w_i1 · ...
template <int Dim>
struct TensorGaussRule {
  static constexpr int max_points = Dim == 2 ? 25 : 125;
  int size = 0;
  std::array<Vector<Dim>, max_points> points;
  std::array<double, max_points> weights{};

  explicit TensorGaussRule(int points_per_direction) {
    const GaussRule1D g = gauss_legendre(points_per_direction);
    const int n = g.size;
    size = Dim == 2 ? n * n : n * n * n;
    for (int q = 0; q < size; ++q) {
      int rest = q;
      weights[q] = 1.0;
      for (int j = 0; j < Dim; ++j) {
        points[q][j] = g.points[rest % n];
        weights[q] *= g.weights[rest % n];
        rest /= n;
      }
    }
  }
};

// Gradients of the 2^Dim Q1 basis functions at ξ ∈ [-1,1]^Dim, one column per vertex
// (tensor order): N_i(ξ) = Π_j (1 + s_ij ξ_j)/2 with s_ij = ±1 the vertex's sign.
template <int Dim>
Eigen::Matrix<double, Dim, (1 << Dim)> q1_gradients(const Vector<Dim>& xi) {
  Eigen::Matrix<double, Dim, (1 << Dim)> grad;
  for (int i = 0; i < (1 << Dim); ++i) {
    for (int j = 0; j < Dim; ++j) {
      double g = 1.0;
      for (int k = 0; k < Dim; ++k) {
        const double s = ((i >> k) & 1) ? 1.0 : -1.0;
        g *= (k == j) ? 0.5 * s : 0.5 * (1.0 + s * xi[k]);
      }
      grad(j, i) = g;
    }
  }
  return grad;
}

// Reference position of Q1 vertex i (tensor order) in [-1,1]^Dim.
template <int Dim>
Vector<Dim> q1_vertex(int i) {
  Vector<Dim> xi;
  for (int j = 0; j < Dim; ++j) xi[j] = ((i >> j) & 1) ? 1.0 : -1.0;
  return xi;
}

// Edge matrix of the unit-volume optimal simplex (equilateral triangle / regular tet)
// with vertex 0 at the origin; columns are a1 - a0, a2 - a0 (, a3 - a0).
template <int Dim>
Matrix<Dim> unit_optimal_simplex_edges() {
  Matrix<Dim> e;
  if constexpr (Dim == 2) {
    e << 1.0, 0.5, 0.0, std::sqrt(3.0) / 2.0;  // area √3/4
    e *= std::sqrt(4.0 / std::sqrt(3.0));
  } else {
    e << 1.0, 0.5, 0.5, 0.0, std::sqrt(3.0) / 2.0, std::sqrt(3.0) / 6.0, 0.0, 0.0,
        std::sqrt(6.0) / 3.0;  // volume √2/12
    e *= std::cbrt(12.0 / std::sqrt(2.0));
  }
  return e;
}

// Gradients of the wedge's shape functions at (r, s, ζ), r, s ≥ 0, r + s ≤ 1, ζ ∈ [-1, 1],
// one column per vertex: N_i = λ_i (1 − ζ)/2, N_{i+3} = λ_i (1 + ζ)/2 with the barycentric
// λ = (1 − r − s, r, s).
inline Eigen::Matrix<double, 3, 6> wedge_gradients(const Vector<3>& xi) {
  const double lambda[3] = {1.0 - xi[0] - xi[1], xi[0], xi[1]};
  const double dlambda[2][3] = {{-1.0, 1.0, 0.0}, {-1.0, 0.0, 1.0}};
  Eigen::Matrix<double, 3, 6> grad;
  for (int i = 0; i < 3; ++i)
    for (int level = 0; level < 2; ++level) {
      const double z = level ? 0.5 * (1.0 + xi[2]) : 0.5 * (1.0 - xi[2]);
      const int v = i + 3 * level;
      grad(0, v) = dlambda[0][i] * z;
      grad(1, v) = dlambda[1][i] * z;
      grad(2, v) = (level ? 0.5 : -0.5) * lambda[i];
    }
  return grad;
}

// Gradients of the pyramid's shape functions at ξ ∈ [-1,1]^3, one column per vertex: the
// trilinear map of the cube with its top face collapsed onto the apex (Duffy), N_i =
// B_i(ξ0, ξ1) (1 − ξ2)/2 for the base (tensor order, B_i bilinear) and N_4 = (1 + ξ2)/2.
// On the cell they are the rational pyramid functions; at the apex (ξ2 = 1) the map is
// singular, which quadrature points never reach.
inline Eigen::Matrix<double, 3, 5> pyramid_gradients(const Vector<3>& xi) {
  const Vector<2> base(xi[0], xi[1]);
  const Eigen::Matrix<double, 2, 4> b = q1_gradients<2>(base);
  Eigen::Matrix<double, 3, 5> grad;
  for (int i = 0; i < 4; ++i) {
    double value = 1.0;  // B_i
    for (int j = 0; j < 2; ++j) value *= 0.5 * (1.0 + (((i >> j) & 1) ? 1.0 : -1.0) * base[j]);
    grad(0, i) = b(0, i) * 0.5 * (1.0 - xi[2]);
    grad(1, i) = b(1, i) * 0.5 * (1.0 - xi[2]);
    grad(2, i) = -0.5 * value;
  }
  grad.col(4) << 0.0, 0.0, 0.5;
  return grad;
}

// Quadrature on the reference cell of a wedge or pyramid, in the coordinates of
// wedge_gradients / pyramid_gradients: Σ_q w_q g(ξ_q) det J(ξ_q) approximates ∫_K g.
// - wedge: a symmetric triangle rule (1 point of degree 1, 3 of degree 2 or Radon's 7 of
//   degree 5 for n = 1, 2, ≥ 3) times n Gauss points in ζ;
// - pyramid: the conical (Duffy) product rule with the rays to the apex integrated exactly.
//   With B the bilinear base map, det J = (1 − ξ2)²/8 · det[∂B/∂ξ0, ∂B/∂ξ1, apex − B], and
//   the (1 − ξ2)/2 of the first two columns cancels in G = ∇τ ∇τ_opt⁻¹ (and in the basis
//   gradients on the optimal cell): everything the energy needs is constant along each ray
//   but for the factor (1 − ξ2)², whose integral over [-1, 1] is 8/3. So n × n Gauss points
//   on the base, placed at mid-height ξ2 = 0, with weights w_i w_j · 8/3. No point lies at
//   the apex, where the map is singular.
template <CellType Type>
struct ReferenceRule {
  static_assert(Type == CellType::Wedge || Type == CellType::Pyramid);
  static constexpr int max_points = Type == CellType::Wedge ? 7 * 5 : 25;
  int size = 0;
  std::array<Vector<3>, max_points> points;
  std::array<double, max_points> weights{};

  explicit ReferenceRule(int n) {
    const GaussRule1D g = gauss_legendre(n);
    if constexpr (Type == CellType::Pyramid) {
      const TensorGaussRule<2> base(n);
      size = base.size;
      for (int q = 0; q < size; ++q) {
        points[q] = Vector<3>(base.points[q][0], base.points[q][1], 0.0);
        weights[q] = base.weights[q] * 8.0 / 3.0;  // ∫ (1 − ξ2)² dξ2 / (1 − 0)²
      }
    } else {
      const auto triangle = triangle_rule(n);
      for (const auto& [r, s, w] : triangle)
        for (int k = 0; k < g.size; ++k) {
          if (w == 0.0) continue;
          points[size] = Vector<3>(r, s, g.points[k]);
          weights[size++] = w * g.weights[k];
        }
    }
  }

 private:
  // Points (r, s) and weights (summing to 1/2) of the triangle rule; unused entries weigh 0.
  static std::array<std::array<double, 3>, 7> triangle_rule(int n) {
    if (n <= 1) return {{{1.0 / 3.0, 1.0 / 3.0, 0.5}}};
    if (n == 2)
      return {{{1.0 / 6.0, 1.0 / 6.0, 1.0 / 6.0},
               {2.0 / 3.0, 1.0 / 6.0, 1.0 / 6.0},
               {1.0 / 6.0, 2.0 / 3.0, 1.0 / 6.0}}};
    const double r15 = std::sqrt(15.0);
    const double a = (6.0 - r15) / 21.0, b = (6.0 + r15) / 21.0;
    const double wa = (155.0 - r15) / 2400.0, wb = (155.0 + r15) / 2400.0;
    return {{{1.0 / 3.0, 1.0 / 3.0, 9.0 / 80.0},
             {a, a, wa},
             {1.0 - 2.0 * a, a, wa},
             {a, 1.0 - 2.0 * a, wa},
             {b, b, wb},
             {1.0 - 2.0 * b, b, wb},
             {b, 1.0 - 2.0 * b, wb}}};
  }
};

// Shape-function gradients of a wedge or pyramid at reference point ξ.
template <CellType Type>
Eigen::Matrix<double, 3, CellTraits<Type>::vertices> shape_gradients(const Vector<3>& xi) {
  if constexpr (Type == CellType::Wedge) {
    return wedge_gradients(xi);
  } else {
    return pyramid_gradients(xi);
  }
}

// The optimal cell of unit volume (one column per vertex, canonical order): the equilateral
// triangle or regular tetrahedron with vertex 0 at the origin, the unit square/cube centred at
// the origin, the right prism over the equilateral triangle of edge a with height a, or the
// pyramid over the square of edge a whose four side faces are equilateral triangles (apex
// height a/√2).
template <CellType Type>
typename CellTraits<Type>::Coordinates unit_optimal_cell() {
  constexpr int dim = CellTraits<Type>::dim;
  typename CellTraits<Type>::Coordinates y;
  if constexpr (CellTraits<Type>::shape == CellShape::Simplex) {
    y.col(0).setZero();
    y.template rightCols<dim>() = unit_optimal_simplex_edges<dim>();
  } else if constexpr (CellTraits<Type>::shape == CellShape::Tensor) {
    for (int i = 0; i < CellTraits<Type>::vertices; ++i) y.col(i) = 0.5 * q1_vertex<dim>(i);
  } else if constexpr (Type == CellType::Wedge) {
    const double a = std::cbrt(4.0 / std::sqrt(3.0));  // volume √3/4 a³ = 1
    for (int level = 0; level < 2; ++level) {
      y.col(3 * level) << 0.0, 0.0, level * a;
      y.col(3 * level + 1) << a, 0.0, level * a;
      y.col(3 * level + 2) << 0.5 * a, 0.5 * std::sqrt(3.0) * a, level * a;
    }
  } else {
    const double a = std::cbrt(3.0 * std::sqrt(2.0));  // volume a³/(3√2) = 1
    for (int i = 0; i < 4; ++i) y.col(i) << (i & 1) * a, ((i >> 1) & 1) * a, 0.0;
    y.col(4) << 0.5 * a, 0.5 * a, a / std::sqrt(2.0);
  }
  return y;
}

}  // namespace neomesh
