// Reference and optimal cells, Gauss quadrature and Q1 shape-function gradients.
//
// Conventions (docs/method.md §1): Q1 cells map from [-1,1]^d with vertices in tensor order
// (cell_type.hpp); simplices use their edge matrix E = [x1-x0, x2-x0(, x3-x0)]. The optimal
// cell of desired volume v is the square/cube of edge v^(1/d), the equilateral triangle
// or the regular tetrahedron scaled to volume v.
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
  using Coordinates = Eigen::Matrix<double, dim, vertices>;  // one column per vertex
};

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

}  // namespace neomesh
