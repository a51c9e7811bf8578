// energy/regularized_neo_hooke.hpp — the untangling law: the Neo-Hookean energy with det G
// replaced by a regularized determinant that stays positive on inverted cells (Garanzha et
// al., "Foldover-free maps in 50 lines of code", 2021; docs/untangling.md):
//
//   χ_ε(D) = (D + √(ε² + D²)) / 2,   D = det G,  ε > 0
//   W_ε(G) = λ/2 (log χ)² − μ log χ + μ/2 (tr GᵀG − d)
//
// χ_ε > 0 for every D, χ_ε(D) → D for D ≫ ε and → ε²/(4|D|) for D ≪ −ε: W_ε is finite and
// smooth everywhere, large on inverted cells, and tends to the Neo-Hookean W (without its
// κ-term) as ε → 0 on valid ones. The argument G is ∇γ_K (optimal → actual), as in
// neo_hooke.hpp.
//
// The derivatives are written with the cofactor C = ∂D/∂G (C = D G⁻ᵀ where G is
// invertible), which, unlike G⁻ᵀ, exists at D ≤ 0. With φ(D) = W_ε − μ/2 (tr GᵀG − d):
//   P = φ′(D) C + μ G
//   ∂²W_ε/∂G²[H] = φ″(D) (C:H) C + φ′(D) ∂C/∂G[H] + μ H
// The quasi-Newton split (as in thesis §4.4, B1 + α B2 + B3 with H(1) the exact Hessian):
//   B1 = φ″₊ (C:H) C,  B2 = φ″₋ (C:H) C + φ′ ∂C/∂G[H],  B3 = μ H.
#pragma once

#include <algorithm>
#include <cmath>

#include "geometry/reference_cell.hpp"

namespace neomesh {

// The cofactor matrix C = ∂ det G / ∂G: in 2D [[g11, −g10], [−g01, g00]], in 3D the
// columns g1 × g2, g2 × g0, g0 × g1 of G's columns g0, g1, g2.
template <int Dim>
Matrix<Dim> cofactor(const Matrix<Dim>& G) {
  Matrix<Dim> C;
  if constexpr (Dim == 2) {
    C << G(1, 1), -G(1, 0), -G(0, 1), G(0, 0);
  } else {
    C.col(0) = G.col(1).cross(G.col(2));
    C.col(1) = G.col(2).cross(G.col(0));
    C.col(2) = G.col(0).cross(G.col(1));
  }
  return C;
}

// χ_ε(D) = (D + √(ε² + D²)) / 2. For D < 0, D + √(…) cancels: the equal ε² / (2 (√(…) − D)).
inline double regularized_det(double D, double epsilon) {
  const double r = std::hypot(epsilon, D);
  return D >= 0.0 ? 0.5 * (D + r) : 0.5 * epsilon * epsilon / (r - D);
}

// φ and its derivatives at one D: what the kernel needs per sample point.
struct RegularizedDeterminant {
  double phi;    // λ/2 (log χ)² − μ log χ
  double dphi;   // φ′(D)
  double d2phi;  // φ″(D)
};

// B1 + α B2 at one point contracted with the basis gradients D (columns ∇φ̂_i), times the
// point's weight (B3 = μ H the kernel adds once per cell). With c_i = C ∇φ̂_i, block (i,j) is
//   (φ″₊ + α φ″₋) c_i c_jᵀ + α φ′ S_ij,
// where S_ij = ∂²D/∂G² on (e_a ∇φ̂_iᵀ, e_b ∇φ̂_jᵀ) is skew: (S_ij)_ab = ε_ab (∇φ̂_i × ∇φ̂_j)
// in 2D and ε_abc (G (∇φ̂_i × ∇φ̂_j))_c in 3D.
template <int Dim, int N>
struct RegularizedTangent {
  double volumetric, twist;  // weighted
  Matrix<Dim> G;
  Eigen::Matrix<double, Dim, N> c;  // C D
  Eigen::Matrix<double, Dim, N> D;

  Matrix<Dim> block(int i, int j) const {
    return volumetric * c.col(i) * c.col(j).transpose() + twist * skew(D.col(i), D.col(j));
  }

 private:
  // ∂²D/∂G² on (e_a uᵀ, e_b vᵀ) as a Dim × Dim matrix over (a, b).
  Matrix<Dim> skew(const Vector<Dim>& u, const Vector<Dim>& v) const {
    Matrix<Dim> S;
    if constexpr (Dim == 2) {
      const double s = u[0] * v[1] - u[1] * v[0];
      S << 0.0, s, -s, 0.0;
    } else {
      const Vector<3> w = G * u.cross(v);
      S << 0.0, w[2], -w[1], -w[2], 0.0, w[0], w[1], -w[0], 0.0;
    }
    return S;
  }
};

template <int Dim>
struct RegularizedNeoHooke {
  double lambda, mu, epsilon;

  // The interface of a law for CellKernel (cell_kernels.hpp): finite for every G.
  struct Point {
    Matrix<Dim> G;
    RegularizedDeterminant r;
  };
  static constexpr bool barrier = false;
  Point point(const Matrix<Dim>& G) const { return {G, at(G.determinant())}; }
  Point energy_point(const Matrix<Dim>& G) const { return point(G); }
  static bool admissible(const Point&) { return true; }
  double energy(const Point& p) const { return p.r.phi + 0.5 * mu * (p.G.squaredNorm() - Dim); }
  Matrix<Dim> stress(const Point& p) const { return p.r.dphi * cofactor(p.G) + mu * p.G; }
  template <int N>
  RegularizedTangent<Dim, N> tangent(const Point& p, double alpha, double weight,
                                     const Eigen::Matrix<double, Dim, N>& D) const {
    return {.volumetric = weight * (std::max(p.r.d2phi, 0.0) + alpha * std::min(p.r.d2phi, 0.0)),
            .twist = weight * alpha * p.r.dphi,
            .G = p.G,
            .c = cofactor(p.G) * D,
            .D = D};
  }

  // φ, φ′, φ″ at D. With r = √(ε² + D²): χ′ = χ / r, χ″ = χ (r − D) / r³, and
  // φ′ = (λ log χ − μ) / r, φ″ = (λ + μ − λ log χ) / r² + (λ log χ − μ)(r − D) / r³.
  RegularizedDeterminant at(double D) const {
    const double r = std::hypot(epsilon, D);
    const double log_chi = std::log(regularized_det(D, epsilon));
    const double b = lambda * log_chi - mu;
    return RegularizedDeterminant{
        .phi = 0.5 * lambda * log_chi * log_chi - mu * log_chi,
        .dphi = b / r,
        .d2phi = (lambda - b) / (r * r) + b * (r - D) / (r * r * r),
    };
  }

  // W_ε(G).
  double energy(const Matrix<Dim>& G) const { return energy(point(G)); }
  // P = ∂W_ε/∂G.
  Matrix<Dim> stress(const Matrix<Dim>& G) const { return stress(point(G)); }
};

}  // namespace neomesh
