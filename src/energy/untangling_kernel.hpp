// energy/untangling_kernel.hpp — the untangling energy of one cell and its derivatives
// (docs/untangling.md): Σ_s v w_s W_ε(G_s) over sample points s of the optimal cell, with the
// regularized law of regularized_neo_hooke.hpp. Same conventions as cell_kernels.hpp
// (G = X D_sᵀ, vertex-major local dofs), same interface, but finite for every X.
//
// Sample points: a cell is inverted when det G ≤ 0 somewhere the Neo-Hookean phase looks,
// so the untangling energy looks at the same places:
// - simplices: their one point (G is constant);
// - quadrilaterals: the four corners, weight 1/4 each (det G is bilinear: positive corners
//   make it positive everywhere);
// - hexahedra, wedges, pyramids: the corner frames of the cell-type table (a pyramid's four
//   base corners and four apex frames) and the Gauss points of the Neo-Hookean rule, half the
//   weight each (positive corners are necessary in 3D, not sufficient).
// At a corner frame, G is the frame's Jacobian times that of the optimal cell's frame⁻¹.
#pragma once

#include <algorithm>
#include <array>
#include <limits>

#include "energy/cell_kernels.hpp"
#include "energy/regularized_neo_hooke.hpp"

namespace neomesh {

template <CellType Type>
class UntanglingKernel {
 public:
  static constexpr int dim = CellTraits<Type>::dim;
  static constexpr int vertices = CellTraits<Type>::vertices;
  static constexpr int dofs = dim * vertices;
  using Coordinates = typename CellTraits<Type>::Coordinates;
  using Gradient = Coordinates;
  using Block = Eigen::Matrix<double, dofs, dofs>;

  UntanglingKernel(const RegularizedNeoHooke<dim>& law, int gauss_points) : law_(law) {
    // The corner frames of the cell-type table, then (3D, not simplices) the Gauss points.
    const bool gauss_too = dim == 3 && !CellTraits<Type>::simplex;
    const int corners = facts(Type).num_corners;
    const Coordinates optimal = unit_optimal_cell<Type>();
    for (int k = 0; k < corners; ++k) {
      // J_k = X C_kᵀ (the frame's edges); G = J_k J_k,opt⁻¹ = X (J_k,opt⁻ᵀ C_k)ᵀ.
      const Gradient edges = corner_edges(k);
      const Matrix<dim> optimal_jacobian = optimal * edges.transpose();
      add(optimal_jacobian.inverse().transpose() * edges, (gauss_too ? 0.5 : 1.0) / corners);
    }
    if (gauss_too) {
      const OptimalCellQuadrature<Type> rule(gauss_points);
      for (int q = 0; q < rule.size; ++q) add(rule.unit_gradients[q], 0.5 * rule.unit_weights[q]);
    }
  }

  // Σ_s v w_s W_ε(G_s); always finite.
  double energy(const Coordinates& x, double volume) const {
    const double scale = inverse_edge(volume);
    double sum = 0.0;
    for (int s = 0; s < size_; ++s)
      sum += volume * weights_[s] * law_.energy(x * (scale * gradients_[s]).transpose());
    return sum;
  }

  // The energy and its gradient Σ_s v w_s P(G_s) D_s.
  double energy_and_gradient(const Coordinates& x, double volume, Gradient& gradient) const {
    const double scale = inverse_edge(volume);
    double sum = 0.0;
    gradient.setZero();
    for (int s = 0; s < size_; ++s) {
      const Gradient basis = scale * gradients_[s];
      const Matrix<dim> G = x * basis.transpose();
      const RegularizedDeterminant r = law_.at(G.determinant());
      const double weight = volume * weights_[s];
      sum += weight * (r.phi + 0.5 * law_.mu * (G.squaredNorm() - dim));
      gradient.noalias() += weight * (r.dphi * cofactor(G) + law_.mu * G) * basis;
    }
    return sum;
  }

  // H(α) = B1 + α B2 + B3 (regularized_neo_hooke.hpp). With c_i = C ∇φ̂_i, block (i,j) is
  //   (φ″₊ + α φ″₋) c_i c_jᵀ + α φ′ S_ij + μ (∇φ̂_i·∇φ̂_j) I,
  // where S_ij = ∂²D/∂G² on (e_a ∇φ̂_iᵀ, e_b ∇φ̂_jᵀ) is skew: (S_ij)_ab = ε_ab (∇φ̂_i × ∇φ̂_j)
  // in 2D and ε_abc (G (∇φ̂_i × ∇φ̂_j))_c in 3D. Always succeeds (returns true).
  bool hessian(const Coordinates& x, double volume, double alpha, Eigen::Ref<Block> block) const {
    const double scale = inverse_edge(volume);
    block.setZero();
    for (int s = 0; s < size_; ++s) {
      const Gradient basis = scale * gradients_[s];
      const Matrix<dim> G = x * basis.transpose();
      const RegularizedDeterminant r = law_.at(G.determinant());
      const double weight = volume * weights_[s];
      const double volumetric = weight * (std::max(r.d2phi, 0.0) + alpha * std::min(r.d2phi, 0.0));
      const double twist = weight * alpha * r.dphi;
      const double mu = weight * law_.mu;
      const Gradient c = cofactor(G) * basis;
      for (int j = 0; j < vertices; ++j) {
        for (int i = j; i < vertices; ++i) {  // lower blocks; the upper ones are their transposes
          block.template block<dim, dim>(dim * i, dim * j) +=
              volumetric * c.col(i) * c.col(j).transpose() +
              twist * skew(G, basis.col(i), basis.col(j)) +
              mu * basis.col(i).dot(basis.col(j)) * Matrix<dim>::Identity();
        }
      }
    }
    block.template triangularView<Eigen::StrictlyUpper>() = block.transpose().eval();
    return true;
  }

  // The smallest det G over the sample points: ≤ 0 exactly when the cell is inverted or
  // degenerate where the Neo-Hookean phase would see it.
  double min_det(const Coordinates& x, double volume) const {
    const double scale = inverse_edge(volume);
    double m = std::numeric_limits<double>::infinity();
    for (int s = 0; s < size_; ++s)
      m = std::min(m, (x * (scale * gradients_[s]).transpose()).determinant());
    return m;
  }

 private:
  static constexpr int max_samples =
      CellTraits<Type>::simplex ? 1 : 8 + (dim == 3 ? max_quadrature_points<Type>() : 0);

  // C_k: the corner frame k as a map of the vertices, J_k = X C_kᵀ (corner_jacobian).
  static Gradient corner_edges(int k) {
    const CornerFrame& frame = facts(Type).corners[k];
    Gradient c = Gradient::Zero();
    for (int j = 0; j < dim; ++j) {
      const double sign = ((frame.flip >> j) & 1) ? -1.0 : 1.0;
      c(j, frame.ends[j]) += sign;
      c(j, frame.vertex) -= sign;
    }
    return c;
  }

  void add(const Gradient& unit_gradients, double weight) {
    gradients_[size_] = unit_gradients;
    weights_[size_] = weight;
    ++size_;
  }

  static double inverse_edge(double volume) { return std::pow(volume, -1.0 / dim); }

  // ∂²D/∂G² on (e_a uᵀ, e_b vᵀ) as a dim × dim matrix over (a, b).
  static Matrix<dim> skew(const Matrix<dim>& G, const Vector<dim>& u, const Vector<dim>& v) {
    Matrix<dim> S;
    if constexpr (dim == 2) {
      const double s = u[0] * v[1] - u[1] * v[0];
      S << 0.0, s, -s, 0.0;
    } else {
      const Vector<3> w = G * u.cross(v);
      S << 0.0, w[2], -w[1], -w[2], 0.0, w[0], w[1], -w[0], 0.0;
    }
    return S;
  }

  RegularizedNeoHooke<dim> law_;
  int size_ = 0;
  std::array<Gradient, max_samples> gradients_;
  std::array<double, max_samples> weights_{};
};

}  // namespace neomesh
