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

  // The samples: OptimalCellQuadrature's corner frames and, in 3D, its Gauss points.
  UntanglingKernel(const RegularizedNeoHooke<dim>& law, int gauss_points)
      : law_(law), samples_(gauss_points, corner_weight()) {}

  // Σ_s v w_s W_ε(G_s); always finite.
  double energy(const Coordinates& x, double volume) const {
    const double scale = inverse_edge(volume);
    double sum = 0.0;
    for (int s = 0; s < samples_.size; ++s)
      sum += volume * samples_.unit_weights[s] *
             law_.energy(x * (scale * samples_.unit_gradients[s]).transpose());
    return sum;
  }

  // The energy and its gradient Σ_s v w_s P(G_s) D_s.
  double energy_and_gradient(const Coordinates& x, double volume, Gradient& gradient) const {
    const double scale = inverse_edge(volume);
    double sum = 0.0;
    gradient.setZero();
    for (int s = 0; s < samples_.size; ++s) {
      const Gradient basis = scale * samples_.unit_gradients[s];
      const Matrix<dim> G = x * basis.transpose();
      const RegularizedDeterminant r = law_.at(G.determinant());
      const double weight = volume * samples_.unit_weights[s];
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
    for (int s = 0; s < samples_.size; ++s) {
      const Gradient basis = scale * samples_.unit_gradients[s];
      const Matrix<dim> G = x * basis.transpose();
      const RegularizedDeterminant r = law_.at(G.determinant());
      const double weight = volume * samples_.unit_weights[s];
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
    for (int s = 0; s < samples_.size; ++s)
      m = std::min(m, (x * (scale * samples_.unit_gradients[s]).transpose()).determinant());
    return m;
  }

 private:
  // Quadrilaterals: the corners alone; other non-simplices: corners and Gauss points, half
  // each.
  static constexpr double corner_weight() {
    return CellTraits<Type>::simplex ? 0.0 : dim == 2 ? 1.0 : 0.5;
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
  OptimalCellQuadrature<Type> samples_;
};

}  // namespace neomesh
