// energy/cell_kernels.hpp — the energy of one cell and its derivatives (docs/method.md §1–3),
// for any material law: one skeleton (the loop over sample points, the weights, the block fill
// and its symmetry) with the law plugged in — the Neo-Hookean law of the thesis
// (NeoHookeKernel) or the regularized one of untangling (UntanglingKernel).
//
// A cell K is given by its vertex coordinates X (Dim × vertices, one column per vertex, in
// canonical local order) and its target (CellTarget): the optimal cell of the desired volume v,
// mapped by the target's shape S (identity: the thesis' ideal cell). γ_K maps the target cell
// onto K, G = ∇γ_K. For the ideal cell:
// - simplex: G = E_K · E_opt⁻¹ (constant), one quadrature point of weight v;
// - Q1 cell: G(ξ) = ∇τ(ξ) · (2/h), h = v^(1/d), Gauss points ξ_q with weights w_q (h/2)^d;
// - wedge, pyramid: G(ξ) = ∇τ(ξ) · ∇τ_opt(ξ)⁻¹ with τ, τ_opt the maps of the reference cell
//   onto K and onto the optimal cell (ReferenceRule's points, weights w_q det ∇τ_opt(ξ_q)).
// In every case G = X · D_qᵀ where column i of D_q is ∇φ̂_i, the gradient of basis function
// i with respect to the optimal cell's coordinates at point q (the same chain rule as G).
// A shaped target T = v^(1/d) S maps the unit optimal cell onto the target cell, so
// D_q = T⁻ᵀ D̂_q with D̂_q the unit cell's gradients, and the weights are v ŵ_q as before.
//
// Local dofs are numbered vertex-major, dof = Dim · vertex + component (the DofMap's order);
// a cell gradient is a Dim × vertices matrix whose column-major storage is in that order.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <type_traits>
#include <utility>

#include "energy/neo_hooke.hpp"
#include "energy/regularized_neo_hooke.hpp"
#include "geometry/reference_cell.hpp"

namespace neomesh {

// Points of the largest rule OptimalCellQuadrature may use for the type.
template <CellType Type>
constexpr int max_quadrature_points() {
  if constexpr (CellTraits<Type>::shape == CellShape::Simplex) {
    return 1;
  } else if constexpr (CellTraits<Type>::shape == CellShape::Tensor) {
    return TensorGaussRule<CellTraits<Type>::dim>::max_points;
  } else {
    return ReferenceRule<Type>::max_points;
  }
}

// The quadrature rule on the optimal cell of unit volume: per point, the basis gradients
// D̂_q (Dim × vertices) and the weight ŵ_q (Σ ŵ_q = 1). For desired volume v the optimal
// cell is scaled by s = v^(1/d): D_q = D̂_q / s and the weights become v ŵ_q.
//
// Corner samples (not for simplices, whose G is constant): with `corner_weight` ω > 0 the
// corner frames of the cell-type table come first, ω / corners each, and the Gauss points
// share 1 − ω. At frame k, G = J_k J_k,opt⁻¹ (the frame's edges against the optimal cell's),
// so the law's barrier acts at the corners too, where det J of a Q1 cell, wedge or pyramid
// is smallest; Gauss points alone let a corner flatten (docs/untangling.md, docs/method.md).
template <CellType Type>
struct OptimalCellQuadrature {
  static constexpr int dim = CellTraits<Type>::dim;
  static constexpr int vertices = CellTraits<Type>::vertices;
  static constexpr int max_corners = CellTraits<Type>::simplex ? 0 : 8;
  static constexpr int max_points = max_corners + max_quadrature_points<Type>();
  using Gradients = typename CellTraits<Type>::Coordinates;

  int size = 0;
  std::array<Gradients, max_points> unit_gradients;
  std::array<double, max_points> unit_weights{};
  // Σ_q ŵ_q D̂_qᵀ D̂_q: the scalar Laplacian of the unit optimal cell, ∫ ∇φ̂_i·∇φ̂_j.
  Eigen::Matrix<double, vertices, vertices> unit_laplacian;

  // `gauss_points` per direction for Q1 cells, wedges and pyramids (ReferenceRule); simplices
  // need one point (G is constant). `corner_weight` in [0, 1]: see above (1: corners only).
  explicit OptimalCellQuadrature(int gauss_points, double corner_weight = 0.0) {
    if constexpr (CellTraits<Type>::simplex) {
      corner_weight = 0.0;
    } else {
      if (corner_weight > 0.0) add_corners(corner_weight);
    }
    const int first = size;
    if (corner_weight < 1.0) add_gauss_points(gauss_points);
    for (int q = first; q < size; ++q) unit_weights[q] *= 1.0 - corner_weight;
    unit_laplacian.setZero();
    for (int q = 0; q < size; ++q)
      unit_laplacian.noalias() +=
          unit_weights[q] * unit_gradients[q].transpose() * unit_gradients[q];
  }

  // Whether the map is orientation-preserving at every corner frame of the cell-type table
  // (simplices: always true here; their single det G is checked at the quadrature point).
  // Gauss points alone miss a non-convex quad: with vertex 3 of the unit square at
  // (0.45, 0.45), det J > 0 at all 3×3 Gauss points but < 0 at that corner. In 2D det J is
  // bilinear, so positive corners mean positive everywhere; in 3D they are necessary, and the
  // Gauss points add to them. A pyramid's det J is (1 − ξ2)² f(ξ0, ξ1): its base corners
  // check f at the corners of the base, and so the whole edge up to the apex.
  static bool corners_admissible(const Gradients& x) {
    if constexpr (CellTraits<Type>::simplex) {
      return true;
    } else {
      for (int k = 0; k < facts(Type).num_corners; ++k)
        if (!(corner_jacobian<Type>(x, k).determinant() > 0.0)) return false;
      return true;
    }
  }

 private:
  void add_corners(double weight) {
    const Gradients optimal = unit_optimal_cell<Type>();
    const int corners = facts(Type).num_corners;
    for (int k = 0; k < corners; ++k) {
      // J_k = X C_kᵀ; G = J_k J_k,opt⁻¹ = X (J_k,opt⁻ᵀ C_k)ᵀ.
      const Gradients frame = corner_frame_map<Type>(k);
      const Matrix<dim> optimal_jacobian = optimal * frame.transpose();
      unit_gradients[size] = optimal_jacobian.inverse().transpose() * frame;
      unit_weights[size++] = weight / corners;
    }
  }

  void add_gauss_points(int gauss_points) {
    if constexpr (CellTraits<Type>::simplex) {
      // Barycentric gradients on the reference simplex: ∇φ_0 = −Σ e_j, ∇φ_j = e_j; pulled back
      // to the optimal cell x = a0 + E_opt ξ: ∇φ̂ = E_opt⁻ᵀ ∇_ξ φ.
      Gradients reference = Gradients::Zero();
      reference.col(0).setConstant(-1.0);
      reference.template rightCols<dim>().setIdentity();
      unit_gradients[size] = unit_optimal_simplex_edges<dim>().inverse().transpose() * reference;
      unit_weights[size++] = 1.0;
    } else if constexpr (CellTraits<Type>::shape != CellShape::Tensor) {
      // The reference cell maps affinely onto neither, so pull back point by point:
      // ∇φ̂ = ∇τ_opt⁻ᵀ ∇_ξ N at ξ_q, weight w_q det ∇τ_opt (they sum to the volume, 1).
      const ReferenceRule<Type> rule(gauss_points);
      const Gradients optimal = unit_optimal_cell<Type>();
      for (int q = 0; q < rule.size; ++q) {
        const Gradients reference = shape_gradients<Type>(rule.points[q]);
        const Matrix<dim> jacobian = optimal * reference.transpose();
        unit_gradients[size] = jacobian.inverse().transpose() * reference;
        unit_weights[size++] = rule.weights[q] * jacobian.determinant();
      }
    } else {
      // Unit cube [-1/2,1/2]^d (h = 1): ∇φ̂ = (2/h) ∇_ξ N, weight w_q (h/2)^d.
      const TensorGaussRule<dim> rule(gauss_points);
      for (int q = 0; q < rule.size; ++q) {
        unit_gradients[size] = 2.0 * q1_gradients<dim>(rule.points[q]);
        unit_weights[size++] = rule.weights[q] / double(1 << dim);
      }
    }
  }
};

// The target of one cell: its desired volume v and its shape S (det S = 1), given as S⁻ᵀ
// (column-major Dim × Dim, where the basis gradients need it); null: S = I, the thesis' ideal
// cell. Only SᵀS counts (docs/method.md, "Target cells"): W is isotropic, so S and Q S give
// the same energy for every rotation Q. `stiffness` k weighs the cell's energy, k ∫ W: a
// stretched cell kept from the input is as small as its shortest edge, and without k its
// neighbours would squash it (targets/input_targets.hpp).
template <int Dim>
struct CellTarget {
  double volume;
  const double* shape_inverse_t = nullptr;
  double stiffness = 1.0;
  // 1/s = v^(−1/d): the optimal cell's edge scale, which every evaluation needs (a Functional
  // computes it once per desired volume, not per call: pow costs as much as a tetrahedron's
  // energy).
  double inverse_edge;

  // The ideal cell of `volume` (implicit: a volume is the thesis' target).
  CellTarget(double v, const double* s = nullptr, double k = 1.0)
      : CellTarget(v, std::pow(v, -1.0 / Dim), s, k) {}
  // The same with v^(−1/d) given.
  CellTarget(double v, double inverse_edge_, const double* s, double k)
      : volume(v), shape_inverse_t(s), stiffness(k), inverse_edge(inverse_edge_) {}
  // The weight of the cell's integrals: k v (v, exactly, for k = 1).
  double weight() const { return stiffness == 1.0 ? volume : volume * stiffness; }

  // D = T⁻ᵀ D̂ for the unit cell's gradients D̂, given 1/s = v^(−1/d).
  template <int N>
  Eigen::Matrix<double, Dim, N> pull_back(const Eigen::Matrix<double, Dim, N>& unit,
                                          double inverse_edge) const {
    if (!shape_inverse_t) return inverse_edge * unit;
    return inverse_edge * (Eigen::Map<const Matrix<Dim>>(shape_inverse_t) * unit);
  }
};

// Actual volume of a cell and the smallest det G over its quadrature points.
struct CellMeasure {
  double volume;
  double min_det;
};

// The skeleton: the energy and its derivatives as sums over the sample points of a `Rule`, for
// straight cells (OptimalCellQuadrature) and second-order ones (CurvedCellQuadrature,
// curved_kernels.hpp) alike. `Rule` gives
//   dim, vertices, Gradients                the cell's nodes: X is Dim × vertices
//   size, unit_gradients[q], unit_weights[q]   D̂_q and ŵ_q on the optimal cell of unit volume
//   unit_laplacian                          Σ_q ŵ_q D̂_qᵀ D̂_q
//   static corners_admissible(X)            the orientation checks beyond the sample points
// `Law` gives, per sample point (neo_hooke.hpp, regularized_neo_hooke.hpp):
//   Point point(G)                          the quantities of W at G, computed once
//   static bool admissible(Point)           whether W is finite there
//   double energy(Point), Matrix stress(Point)    W and P = ∂W/∂G
//   tangent(Point, α, weight, D)            B1 + α B2 of ∂²W/∂G² contracted with the basis
//                                           gradients D: .block(i, j) is the (i, j) block
//   mu                                      B3 = μ H, the same for every G
//   static constexpr bool barrier           W = +∞ where det G ≤ 0 (checked at the corners too)
template <typename Rule, typename Law>
class SampleKernel {
 public:
  static constexpr int dim = Rule::dim;
  static constexpr int vertices = Rule::vertices;
  static constexpr int dofs = dim * vertices;
  using Coordinates = typename Rule::Gradients;     // X, one column per node
  using Gradient = Coordinates;                     // ∂(cell energy)/∂X
  using Block = Eigen::Matrix<double, dofs, dofs>;  // (dof, dof) in local order
  using Target = CellTarget<dim>;

  SampleKernel(const Law& law, const Rule& rule) : law_(law), rule_(rule) {}

  // The rule's orientation checks (OptimalCellQuadrature::corners_admissible).
  static bool corners_admissible(const Coordinates& x) { return Rule::corners_admissible(x); }

  // ∫_{target cell} W(G) dx = Σ_q v ŵ_q W(G_q); for a barrier law +∞ if det G ≤ 0 at some
  // point or corner.
  double energy(const Coordinates& x, const Target& target) const {
    if (!barrier_holds(x)) return std::numeric_limits<double>::infinity();
    const double scale = target.inverse_edge;
    double sum = 0.0;
    for (int q = 0; q < rule_.size; ++q) {
      const auto p =
          law_.energy_point(x * target.pull_back(rule_.unit_gradients[q], scale).transpose());
      if (!Law::admissible(p)) return std::numeric_limits<double>::infinity();
      sum += target.weight() * rule_.unit_weights[q] * law_.energy(p);
    }
    return sum;
  }

  // The cell energy and its gradient: ∂/∂X_ai = Σ_q v ŵ_q (P(G_q) D_q)_ai, i.e.
  // F′[φ] = ∫ P(G) : ∇φ̂ for φ = e_a φ_i. Returns +∞ (gradient unspecified) if inadmissible.
  double energy_and_gradient(const Coordinates& x, const Target& target, Gradient& gradient) const {
    gradient.setZero();
    if (!barrier_holds(x)) return std::numeric_limits<double>::infinity();
    const double scale = target.inverse_edge;
    double sum = 0.0;
    for (int q = 0; q < rule_.size; ++q) {
      const Gradient basis = target.pull_back(rule_.unit_gradients[q], scale);
      const auto p = law_.point(x * basis.transpose());
      if (!Law::admissible(p)) return std::numeric_limits<double>::infinity();
      const double weight = target.weight() * rule_.unit_weights[q];
      sum += weight * law_.energy(p);
      gradient.noalias() += weight * law_.stress(p) * basis;
    }
    return sum;
  }

  // H(α) = B1 + α B2 + B3 on the cell: per point, block (i, j) is the law's second derivative
  // on (e_a ∇φ̂_iᵀ, e_b ∇φ̂_jᵀ). Only the lower triangle is computed; make_exactly_symmetric
  // mirrors it. B3 = μ H is μ times the target cell's Laplacian, added once, not per point.
  // Returns false (block unspecified) if the law is infinite at some point.
  bool hessian(const Coordinates& x, const Target& target, double alpha,
               Eigen::Ref<Block> block) const {
    const double scale = target.inverse_edge;
    block.setZero();
    for (int q = 0; q < rule_.size; ++q) {
      const Gradient basis = target.pull_back(rule_.unit_gradients[q], scale);
      const auto p = law_.point(x * basis.transpose());
      if (!Law::admissible(p)) return false;
      const auto tangent = law_.tangent(p, alpha, target.weight() * rule_.unit_weights[q], basis);
      for (int j = 0; j < vertices; ++j)
        for (int i = j; i < vertices; ++i)  // lower blocks; the upper ones are their transposes
          block.template block<dim, dim>(dim * i, dim * j) += tangent.block(i, j);
    }
    add_scalar_laplacian(law_.mu * scalar_laplacian(target, scale), block);
    make_exactly_symmetric(block);
    return true;
  }

  // Vector Laplacian on the target cell: ∫ ∇φ̂_i·∇φ̂_j δ_ab (= B3/μ); independent of X.
  void optimal_laplacian(const Target& target, Eigen::Ref<Block> block) const {
    block.setZero();
    add_scalar_laplacian(scalar_laplacian(target, target.inverse_edge), block);
    make_exactly_symmetric(block);
  }

  // Vector Laplacian on the actual cell K: ∫_K ∇φ_i·∇φ_j dx = ∫_{target} det G (G⁻ᵀ∇φ̂_i)·
  // (G⁻ᵀ∇φ̂_j). Returns false (block unspecified) if det G ≤ 0 at some point.
  bool current_laplacian(const Coordinates& x, const Target& target,
                         Eigen::Ref<Block> block) const {
    const double scale = target.inverse_edge;
    block.setZero();
    for (int q = 0; q < rule_.size; ++q) {
      const Gradient basis = target.pull_back(rule_.unit_gradients[q], scale);
      const Deformation<dim> d(x * basis.transpose());
      if (!d.admissible()) return false;
      const Gradient m = d.inv_t * basis;
      add_scalar_laplacian(target.weight() * rule_.unit_weights[q] * d.det * m.transpose() * m,
                           block);
    }
    make_exactly_symmetric(block);
    return true;
  }

  // energy(x, target) and measure(x, target) bit for bit, each point's G formed once (the
  // output's cell fields).
  std::pair<double, CellMeasure> energy_and_measure(const Coordinates& x,
                                                    const Target& target) const {
    constexpr double infinity = std::numeric_limits<double>::infinity();
    const double scale = target.inverse_edge;
    double energy = barrier_holds(x) ? 0.0 : infinity;
    CellMeasure m{0.0, infinity};
    for (int q = 0; q < rule_.size; ++q) {
      const auto p =
          law_.energy_point(x * target.pull_back(rule_.unit_gradients[q], scale).transpose());
      const double det = p.G.determinant();
      m.volume += target.volume * rule_.unit_weights[q] * det;
      m.min_det = std::min(m.min_det, det);
      if (!Law::admissible(p))
        energy = infinity;
      else if (energy < infinity)
        energy += target.weight() * rule_.unit_weights[q] * law_.energy(p);
    }
    return {energy, m};
  }

  // Actual volume Σ_q v ŵ_q det G_q (exact for ≥ 2 Gauss points per direction) and min det G.
  CellMeasure measure(const Coordinates& x, const Target& target) const {
    const double scale = target.inverse_edge;
    CellMeasure m{0.0, std::numeric_limits<double>::infinity()};
    for (int q = 0; q < rule_.size; ++q) {
      const double det =
          (x * target.pull_back(rule_.unit_gradients[q], scale).transpose()).determinant();
      m.volume += target.volume * rule_.unit_weights[q] * det;
      m.min_det = std::min(m.min_det, det);
    }
    return m;
  }

 private:
  static bool barrier_holds(const Coordinates& x) {
    if constexpr (Law::barrier) return corners_admissible(x);
    return true;
  }

  // Copies the lower triangle onto the upper one: the block is symmetric in exact arithmetic,
  // and this makes it so in floating point (PETSc may then rely on MAT_SYMMETRIC).
  static void make_exactly_symmetric(Eigen::Ref<Block> block) {
    block.template triangularView<Eigen::StrictlyUpper>() = block.transpose().eval();
  }

  // k Σ_q v ŵ_q D_qᵀ D_q (D_q = T⁻ᵀ D̂_q / s, 1/s = `scale`): for the ideal cell the unit
  // cell's Laplacian scaled, v s⁻² L̂; for a shaped target summed point by point.
  Eigen::Matrix<double, vertices, vertices> scalar_laplacian(const Target& target,
                                                             double scale) const {
    if (!target.shape_inverse_t) return (target.weight() * scale * scale) * rule_.unit_laplacian;
    Eigen::Matrix<double, vertices, vertices> sum =
        Eigen::Matrix<double, vertices, vertices>::Zero();
    for (int q = 0; q < rule_.size; ++q) {
      const Gradient basis = target.pull_back(rule_.unit_gradients[q], scale);
      sum.noalias() += target.weight() * rule_.unit_weights[q] * basis.transpose() * basis;
    }
    return sum;
  }

  // block((i,a),(j,b)) += scalar(i,j) δ_ab
  static void add_scalar_laplacian(const Eigen::Matrix<double, vertices, vertices>& scalar,
                                   Eigen::Ref<Block> block) {
    for (int j = 0; j < vertices; ++j)
      for (int i = 0; i < vertices; ++i)
        block.template block<dim, dim>(dim * i, dim * j).diagonal().array() += scalar(i, j);
  }

  Law law_;
  Rule rule_;
};

// The kernel of a straight cell: the skeleton on the optimal cell's Gauss points (and corner
// samples).
template <CellType Type, typename Law>
class CellKernel : public SampleKernel<OptimalCellQuadrature<Type>, Law> {
 public:
  static constexpr CellType type = Type;

  // `corner_weight`: the share of the corner samples (OptimalCellQuadrature; 0: the thesis').
  CellKernel(const Law& law, int gauss_points, double corner_weight = 0.0)
      : SampleKernel<OptimalCellQuadrature<Type>, Law>(
            law, OptimalCellQuadrature<Type>(gauss_points, corner_weight)) {}
};

// The thesis' energy: the Neo-Hookean law at the Gauss points (and, in the worst-cell phase,
// corner samples).
template <CellType Type>
using NeoHookeKernel = CellKernel<Type, NeoHooke<CellTraits<Type>::dim>>;

// The untangling energy (docs/untangling.md): the regularized law, finite for every X, at the
// sample points where the Neo-Hookean phase looks for det G > 0 — simplices: their one point;
// quadrilaterals: the four corners (det G is bilinear: positive corners make it positive
// everywhere); hexahedra, wedges, pyramids: the corner frames and the Gauss points, half the
// weight each (positive corners are necessary in 3D, not sufficient).
template <CellType Type>
using UntanglingKernel = CellKernel<Type, RegularizedNeoHooke<CellTraits<Type>::dim>>;

template <CellType Type>
constexpr double untangling_corner_weight() {
  return CellTraits<Type>::simplex ? 0.0 : CellTraits<Type>::dim == 2 ? 1.0 : 0.5;
}

template <CellType Type>
UntanglingKernel<Type> make_untangling_kernel(const RegularizedNeoHooke<CellTraits<Type>::dim>& law,
                                              int gauss_points) {
  return UntanglingKernel<Type>(law, gauss_points, untangling_corner_weight<Type>());
}

}  // namespace neomesh
