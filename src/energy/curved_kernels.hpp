// energy/curved_kernels.hpp — the energy of one second-order (curved) cell and its derivatives
// (docs/method.md §12), with the skeleton of cell_kernels.hpp: only the sample points differ.
//
// A curved cell is given by its nodes X (Dim × nodes, Gmsh's node order, curved_cell.hpp) and
// the target of a straight cell (CellTarget): the optimal straight cell of the desired volume v
// (the equilateral triangle, regular tetrahedron, square or cube), mapped by the target's
// shape S. With x(ξ) the curved map of the reference cell and x_opt(ξ) the map of the
// reference cell onto the optimal straight cell, γ = x ∘ x_opt⁻¹ maps the target cell onto the
// curved cell and
//   G(ξ) = ∇x(ξ) · ∇x_opt(ξ)⁻¹ = X D(ξ)ᵀ,   D(ξ) = ∇x_opt⁻ᵀ ∇_ξ N(ξ),
// column i of ∇_ξ N being the gradient of node i's basis function. x_opt is affine (the
// optimal straight cell is a simplex or a box), so ∇x_opt = J_opt is constant: E_opt on the
// unit simplex, (1/2) I on [−1,1]^d for the unit cube. ∫_{target} W(G) is then
// Σ_q w_q det J_opt W(G(ξ_q)) over a rule (ξ_q, w_q) of the reference cell, and everything the
// skeleton needs — D̂_q and ŵ_q on the unit optimal cell — is computed once per type.
#pragma once

#include <array>

#include "energy/cell_kernels.hpp"
#include "geometry/curved_cell.hpp"

namespace neomesh {

// Gauss points per direction of the curved energy. The smallest rules that integrate the
// polynomial parts of W(G(ξ)) exactly (tr GᵀG has degree 2(p − 1) = 2 on simplices, 4 per
// direction on tensor cells, and 4 in the wedge's triangle and along its axis: 2 points on
// triangles, 3 on tetrahedra, tensor cells and wedges) do not
// resolve the logarithmic parts; 4 is the least for which the energy of a moderately curved cell
// changes by less than 1e-6 (relative) with one more, for every type (docs/method.md §12,
// `CurvedKernelTest.DefaultRuleIsConverged` measures it).
inline constexpr int kCurvedGaussPoints = 4;

// The sample points of a curved cell on the optimal straight cell of unit volume: per point,
// D̂_q (Dim × nodes) and ŵ_q (Σ ŵ_q = 1), and the unit cell's Laplacian (the Rule of
// SampleKernel, cell_kernels.hpp).
// - Tensor cells: the tensor Gauss–Legendre rule with n points per direction on [−1,1]^d,
//   exact for degree 2n − 1 per direction.
// - Wedges: the triangle's collapsed rule (below) times n Gauss–Legendre points along the axis,
//   n³ points, exact for total degree 2n − 2 in the triangle and 2n − 1 along the axis.
// - Simplices: the collapsed (Duffy) product of n-point Gauss–Legendre rules,
//   ξ = (a, b(1 − a)) on the triangle and (a, b(1 − a), c(1 − a)(1 − b)) on the tetrahedron,
//   weights w_a w_b (1 − a) and w_a w_b w_c (1 − a)²(1 − b): positive, n^d points, exact for
//   total degree 2n − 2 (triangle) and 2n − 3 (tetrahedron). It is not symmetric under a
//   renumbering of the corners, so a curved simplex's energy depends on the node order by the
//   rule's error (below 1e-6 relative at the default n).
// Corner samples (`corner_weight` ω > 0): G at the corners of the reference cell, ω / corners
// each, the Gauss points sharing 1 − ω — for untangling, where a curved cell folds first.
template <CurvedType Type>
struct CurvedCellQuadrature {
  using Traits = CurvedTraits<Type>;
  static constexpr int dim = Traits::dim;
  static constexpr int vertices = Traits::nodes;
  static constexpr int max_points = Traits::corners + TensorGaussRule<dim>::max_points;
  using Gradients = typename Traits::Nodes;

  int size = 0;
  std::array<Gradients, max_points> unit_gradients;
  std::array<double, max_points> unit_weights{};
  Eigen::Matrix<double, vertices, vertices> unit_laplacian;

  // `points` per direction, 1–5.
  explicit CurvedCellQuadrature(int points, double corner_weight = 0.0) {
    if (corner_weight > 0.0)
      for (int k = 0; k < Traits::corners; ++k)
        add(reference_node<Type>(k), corner_weight / Traits::corners / optimal_det());
    if (corner_weight < 1.0) add_gauss_points(points, 1.0 - corner_weight);
    unit_laplacian.setZero();
    for (int q = 0; q < size; ++q)
      unit_laplacian.noalias() +=
          unit_weights[q] * unit_gradients[q].transpose() * unit_gradients[q];
  }

  // det J > 0 at every corner of the reference cell, where a bent edge or face first folds the
  // map (the law's barrier then acts there as for straight cells). It does not certify the
  // cell (certify_jacobian does): det J can vanish between the corners and the Gauss points.
  static bool corners_admissible(const Gradients& x) {
    static const std::array<Gradients, Traits::corners> corners = [] {
      std::array<Gradients, Traits::corners> g;
      for (int k = 0; k < Traits::corners; ++k)
        g[k] = curved_gradients<Type>(reference_node<Type>(k));
      return g;
    }();
    for (const Gradients& g : corners)
      if (!((x * g.transpose()).determinant() > 0.0)) return false;
    return true;
  }

 private:
  // J_opt: the reference cell onto the optimal straight cell of unit volume.
  static Matrix<dim> optimal_jacobian() {
    if constexpr (Traits::simplex) {
      return unit_optimal_simplex_edges<dim>();
    } else if constexpr (Traits::wedge) {
      // The optimal prism's triangle edges, and half its height (ζ spans 2).
      const auto y = unit_optimal_cell<CellType::Wedge>();
      Matrix<3> j;
      j << y.col(1) - y.col(0), y.col(2) - y.col(0), 0.5 * (y.col(3) - y.col(0));
      return j;
    } else {
      return 0.5 * Matrix<dim>::Identity();
    }
  }
  static double optimal_det() { return optimal_jacobian().determinant(); }

  // A point ξ of the reference cell with reference weight w: D̂ = J_opt⁻ᵀ ∇_ξ N(ξ), ŵ = w det J_opt.
  void add(const Vector<dim>& xi, double weight) {
    unit_gradients[size] = optimal_jacobian().inverse().transpose() * curved_gradients<Type>(xi);
    unit_weights[size++] = weight * optimal_det();
  }

  void add_gauss_points(int n, double share) {
    if constexpr (Traits::wedge) {
      // The triangle's collapsed rule times n Gauss points along the axis.
      const GaussRule1D g = gauss_legendre(n);
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
          const double a = 0.5 * (1.0 + g.points[i]), b = 0.5 * (1.0 + g.points[j]);
          const double w = 0.25 * g.weights[i] * g.weights[j] * (1.0 - a);
          for (int k = 0; k < n; ++k)
            add(Vector<3>(a, b * (1.0 - a), g.points[k]), share * w * g.weights[k]);
        }
    } else if constexpr (!Traits::simplex) {
      const TensorGaussRule<dim> rule(n);
      for (int q = 0; q < rule.size; ++q) add(rule.points[q], share * rule.weights[q]);
    } else {
      // Gauss–Legendre on [0, 1]: t = (1 + s)/2, weight w/2.
      const GaussRule1D g = gauss_legendre(n);
      std::array<double, 5> t{}, w{};
      for (int i = 0; i < n; ++i) {
        t[i] = 0.5 * (1.0 + g.points[i]);
        w[i] = 0.5 * g.weights[i];
      }
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
          const double a = t[i], b = t[j];
          if constexpr (dim == 2) {
            add(Vector<2>(a, b * (1.0 - a)), share * w[i] * w[j] * (1.0 - a));
          } else {
            for (int k = 0; k < n; ++k) {
              const double c = t[k];
              add(Vector<3>(a, b * (1.0 - a), c * (1.0 - a) * (1.0 - b)),
                  share * w[i] * w[j] * w[k] * (1.0 - a) * (1.0 - a) * (1.0 - b));
            }
          }
        }
    }
  }
};

// The kernel of a curved cell: the skeleton on CurvedCellQuadrature's points.
template <CurvedType Type, typename Law>
class CurvedCellKernel : public SampleKernel<CurvedCellQuadrature<Type>, Law> {
 public:
  static constexpr CurvedType type = Type;

  // `points` per direction (kCurvedGaussPoints); `corner_weight`: the corner samples' share.
  CurvedCellKernel(const Law& law, int points = kCurvedGaussPoints, double corner_weight = 0.0)
      : SampleKernel<CurvedCellQuadrature<Type>, Law>(
            law, CurvedCellQuadrature<Type>(points, corner_weight)) {}
};

template <CurvedType Type>
using CurvedNeoHookeKernel = CurvedCellKernel<Type, NeoHooke<CurvedTraits<Type>::dim>>;
template <CurvedType Type>
using CurvedUntanglingKernel = CurvedCellKernel<Type, RegularizedNeoHooke<CurvedTraits<Type>::dim>>;

// The untangling energy of a curved cell: the regularized law at the corners and the Gauss
// points, half the weight each, for every type. Unlike a straight simplex, a curved one's
// det J varies, and unlike a straight quadrilateral's it is not bilinear, so neither one point
// nor the corners alone see where it folds.
inline constexpr double kCurvedUntanglingCornerWeight = 0.5;

template <CurvedType Type>
CurvedUntanglingKernel<Type> make_curved_untangling_kernel(
    const RegularizedNeoHooke<CurvedTraits<Type>::dim>& law, int points = kCurvedGaussPoints) {
  return CurvedUntanglingKernel<Type>(law, points, kCurvedUntanglingCornerWeight);
}

}  // namespace neomesh
