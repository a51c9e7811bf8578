// energy/neo_hooke.hpp — the Neo-Hookean material law, and nothing else (docs/method.md §2–3).
//
// The argument G of every function is the deformation gradient ∇γ_K of the map from the
// optimal cell onto the actual cell ("optimal → actual"); it is a Dim × Dim matrix.
//
//   W(G) = λ/2 (log det G)² + μ/2 (tr GᵀG − d) − μ log det G + κ ((det G − c)₊)²,
//   c = e^(μ/λ+1)                                                   (thesis 4.1.1, 4.3)
//
// W is +∞ for det G ≤ 0 (an inverted or degenerate cell): log is never evaluated there.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

#include "geometry/reference_cell.hpp"

namespace neomesh {

// The quantities of W and its derivatives that depend only on G, computed once per
// quadrature point so that kernels do not recompute them per pair of basis functions.
template <int Dim>
struct Deformation {
  Matrix<Dim> G;
  double det = 0.0;      // J = det G
  double log_det = 0.0;  // log J; only meaningful when admissible()
  Matrix<Dim> inv_t;     // G⁻ᵀ; only meaningful when admissible()

  explicit Deformation(const Matrix<Dim>& gradient) : G(gradient), det(gradient.determinant()) {
    if (admissible()) {
      log_det = std::log(det);
      inv_t = G.inverse().transpose();
    }
  }
  // Without G⁻ᵀ (left unset: for W alone, not P or the tangent): the line search's energies and
  // the output's cell fields need no more, and the inverse was 44 % of building a point.
  struct EnergyOnly {};
  Deformation(const Matrix<Dim>& gradient, EnergyOnly) : G(gradient), det(gradient.determinant()) {
    if (admissible()) log_det = std::log(det);
  }
  // det G > 0 (false for NaN as well).
  bool admissible() const { return det > 0.0; }
};

// The coefficients of the split second derivative ∂²W/∂G² at one G (thesis §4.4). With
// M = G⁻ᵀ, applied to a direction H:
//   B1[H] = volumetric (M:H) M − growth M Hᵀ M    (λ-term plus the exact κ-term)
//   B2[H] = −b M Hᵀ M,  b = λ log det G − μ
//   B3[H] = μ H
// The quasi-Newton tangent is B1 + α B2 + B3.
struct TangentSplit {
  double volumetric;  // λ + 2κ (J² [J > c] + (J − c)₊ J)
  double growth;      // 2κ (J − c)₊ J
  double b;           // λ log J − μ
  double mu;          // μ

  // Coefficient of −M Hᵀ M in B1 + α B2.
  double rotational(double alpha) const { return growth + alpha * b; }
};

// B1 + α B2 at one point contracted with the basis gradients D (columns ∇φ̂_i), times the
// point's weight; B3 = μ H does not depend on G, and the kernel adds it once per cell. With
// m_i = G⁻ᵀ ∇φ̂_i, the (i,a),(j,b) entry of (B1 + α B2)[e_b ∇φ̂_jᵀ] : e_a ∇φ̂_iᵀ is
//   volumetric m_i[a] m_j[b] − (growth + α b) m_j[a] m_i[b],
// so block (i,j) is volumetric m_i m_jᵀ − (growth + α b) m_j m_iᵀ.
template <int Dim, int N>
struct NeoHookeTangent {
  Eigen::Matrix<double, Dim, N> m;             // G⁻ᵀ D
  Eigen::Matrix<double, Dim, N> volumetric_m;  // weighted volumetric · m
  Eigen::Matrix<double, Dim, N> rotational_m;  // weighted (growth + α b) · m

  Matrix<Dim> block(int i, int j) const {
    return volumetric_m.col(i) * m.col(j).transpose() - rotational_m.col(j) * m.col(i).transpose();
  }
};

template <int Dim>
struct NeoHooke {
  const double lambda, mu, kappa;

  // The interface of a law for CellKernel (cell_kernels.hpp).
  using Point = Deformation<Dim>;
  static constexpr bool barrier = true;  // W = +∞ where det G ≤ 0
  static Point point(const Matrix<Dim>& G) { return Point(G); }
  // The same for energy(Point) alone (no G⁻ᵀ).
  static Point energy_point(const Matrix<Dim>& G) { return Point(G, typename Point::EnergyOnly{}); }
  static bool admissible(const Point& d) { return d.admissible(); }

  NeoHooke(double lambda_, double mu_, double kappa_)
      : lambda(lambda_), mu(mu_), kappa(kappa_), growth_limit_(std::exp(mu / lambda + 1.0)) {}

  // c = e^(μ/λ+1): the κ-term only acts on cells grown more than c times their desired volume.
  double growth_limit() const { return growth_limit_; }

  // Energy density W(G); +∞ when det G ≤ 0.
  double energy(const Deformation<Dim>& d) const {
    if (!d.admissible()) return std::numeric_limits<double>::infinity();
    const double excess = std::max(d.det - growth_limit(), 0.0);  // (det G − c)₊
    // λ/2 (log J)² + μ/2 (tr GᵀG − d) − μ log J + κ (J − c)₊²
    return 0.5 * lambda * d.log_det * d.log_det + 0.5 * mu * (d.G.squaredNorm() - Dim) -
           mu * d.log_det + kappa * excess * excess;
  }
  double energy(const Matrix<Dim>& G) const { return energy(Deformation<Dim>(G)); }

  // First Piola stress P = ∂W/∂G (requires det G > 0):
  // P = λ log J G⁻ᵀ − μ G⁻ᵀ + μ G + 2κ (J − c)₊ J G⁻ᵀ
  Matrix<Dim> stress(const Deformation<Dim>& d) const {
    const double excess = std::max(d.det - growth_limit(), 0.0);
    return (lambda * d.log_det - mu + 2.0 * kappa * excess * d.det) * d.inv_t + mu * d.G;
  }
  Matrix<Dim> stress(const Matrix<Dim>& G) const { return stress(Deformation<Dim>(G)); }

  // Coefficients of B1, B2, B3 at G (requires det G > 0). The κ-term's second derivative
  // is d/dt [2κ (J−c)₊ J M] = 2κ (J² [J>c] + (J−c)₊ J)(M:H) M − 2κ (J−c)₊ J M Hᵀ M,
  // using dJ = J (M:H) and dM = −M Hᵀ M.
  TangentSplit split(const Deformation<Dim>& d) const {
    const double excess = std::max(d.det - growth_limit(), 0.0);
    const double beyond = d.det > growth_limit() ? 1.0 : 0.0;
    return TangentSplit{
        .volumetric = lambda + 2.0 * kappa * (d.det * d.det * beyond + excess * d.det),
        .growth = 2.0 * kappa * excess * d.det,
        .b = lambda * d.log_det - mu,
        .mu = mu,
    };
  }

  // (B1 + α B2 + B3)[H] at G = volumetric (M:H) M − (growth + α b) M Hᵀ M + μ H.
  Matrix<Dim> tangent(const Deformation<Dim>& d, const Matrix<Dim>& H, double alpha) const {
    const TangentSplit s = split(d);
    const Matrix<Dim>& M = d.inv_t;
    return s.volumetric * (M.cwiseProduct(H).sum()) * M -
           s.rotational(alpha) * M * H.transpose() * M + s.mu * H;
  }
  Matrix<Dim> tangent(const Matrix<Dim>& G, const Matrix<Dim>& H, double alpha) const {
    return tangent(Deformation<Dim>(G), H, alpha);
  }
  // B1 + α B2 contracted with basis gradients D, times `weight` (NeoHookeTangent).
  template <int N>
  NeoHookeTangent<Dim, N> tangent(const Deformation<Dim>& d, double alpha, double weight,
                                  const Eigen::Matrix<double, Dim, N>& D) const {
    const TangentSplit s = split(d);
    NeoHookeTangent<Dim, N> t;
    t.m.noalias() = d.inv_t * D;
    t.volumetric_m = (weight * s.volumetric) * t.m;
    t.rotational_m = (weight * s.rotational(alpha)) * t.m;
    return t;
  }

 private:
  double growth_limit_;  // computed once: W and P are evaluated per quadrature point
};

}  // namespace neomesh
