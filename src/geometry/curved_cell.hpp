// Second-order (curved) cells: their geometry and the validity certificate of their Jacobian
// determinant (docs/method.md, "Curved cells: validity certificate").
//
// Conventions:
// - Nodes are numbered as Gmsh numbers them: the corners first (quadrilaterals and hexahedra
//   counter-clockwise, as in the files, not in neomesh's tensor order), then one node per edge
//   in Gmsh's edge order, then one per quadrilateral face, then the centre. The triangle6 and
//   tetrahedron10 edges are (0,1) (1,2) (2,0) and (0,1) (1,2) (2,0) (3,0) (3,2) (3,1); the
//   hexahedron's edges (0,1) (0,3) (0,4) (1,2) (1,5) (2,3) (2,6) (3,7) (4,5) (4,7) (5,6) (6,7),
//   its faces z = −1, y = −1, x = −1, x = +1, y = +1, z = +1. The wedge's (Gmsh's prism) edges
//   (0,1) (0,2) (0,3) (1,2) (1,4) (2,5) (3,4) (3,5) (4,5), its quadrilateral faces (0,1,4,3)
//   (0,2,5,3) (1,2,5,4).
// - Reference cells are Gmsh's: the unit simplex (corner 0 at the origin, corner k at the k-th
//   unit vector), [−1,1]^d for quadrilaterals and hexahedra, and the unit triangle × [−1,1] for
//   the wedge (corners 0 1 2 at ζ = −1, 3 4 5 above them). The higher-order nodes sit at the
//   midpoints of their edges, the centres of their faces and of the cell.
// - Quadrilateral9, hexahedron27 and wedge18 are the Lagrange cells (tensor products);
//   quadrilateral8, hexahedron20 and wedge15 the serendipity cells (no face or centre nodes).
// - J(ξ) = ∂x/∂ξ is the Jacobian of the map from the reference cell; det J > 0 everywhere on a
//   valid, positively oriented cell.
#pragma once

#include <array>
#include <limits>
#include <string_view>
#include <vector>

#include <Eigen/Dense>

#include "geometry/reference_cell.hpp"
#include "mesh/cell_type.hpp"
#include "mesh/curved_type.hpp"

namespace neomesh {

// Compile-time facts of a second-order type. `det_degree` is the degree of det J as a
// polynomial: total degree d(p − 1) = 2 (triangle) or 3 (tetrahedron) for simplices, degree per
// direction dp − 1 = 3 (quadrilateral) or 5 (hexahedron) for tensor cells. The wedge's map lies
// in P2(triangle) ⊗ P2(axis), so ∂x/∂r, ∂x/∂s lie in P1 ⊗ P2 and ∂x/∂ζ in P2 ⊗ P1: det J is in
// P4 ⊗ P5, total degree `det_degree` = 4 in the triangle's coordinates and `det_axis_degree` = 5
// along the axis. The serendipity cells share their Lagrange sibling's bound (their maps lie in
// its space).
template <CurvedType Type>
struct CurvedTraits {
  static constexpr CellType linear = facts(Type).linear;  // the straight cell
  static constexpr int dim = dimension(linear);
  static constexpr bool simplex = is_simplex(linear);
  static constexpr bool wedge = facts(linear).shape == CellShape::Wedge;
  static constexpr int nodes = facts(Type).nodes;
  static constexpr int corners = simplex ? dim + 1 : wedge ? 6 : (1 << dim);
  static constexpr int det_degree = simplex ? dim : wedge ? 4 : 2 * dim - 1;
  static constexpr int det_axis_degree = wedge ? 5 : det_degree;
  using Nodes = Eigen::Matrix<double, dim, nodes>;  // one column per node
  using Point = Vector<dim>;
};

// Reference position of node i.
template <CurvedType Type>
Vector<CurvedTraits<Type>::dim> reference_node(int i);

// The basis functions N_i(ξ), one per node, and their gradients (one column per node).
template <CurvedType Type>
Eigen::Matrix<double, CurvedTraits<Type>::nodes, 1> curved_basis(
    const Vector<CurvedTraits<Type>::dim>& xi);
template <CurvedType Type>
Eigen::Matrix<double, CurvedTraits<Type>::dim, CurvedTraits<Type>::nodes> curved_gradients(
    const Vector<CurvedTraits<Type>::dim>& xi);

// x(ξ) = Σ_i x_i N_i(ξ), J(ξ) = Σ_i x_i ∇N_i(ξ)ᵀ and det J(ξ) of the cell with nodes `x`.
template <CurvedType Type>
Vector<CurvedTraits<Type>::dim> curved_map(const typename CurvedTraits<Type>::Nodes& x,
                                           const Vector<CurvedTraits<Type>::dim>& xi);
template <CurvedType Type>
Matrix<CurvedTraits<Type>::dim> curved_jacobian(const typename CurvedTraits<Type>::Nodes& x,
                                                const Vector<CurvedTraits<Type>::dim>& xi);
template <CurvedType Type>
double curved_det(const typename CurvedTraits<Type>::Nodes& x,
                  const Vector<CurvedTraits<Type>::dim>& xi);

// Node indices of the corners in neomesh's canonical order (cell_type.hpp: tensor order for
// quadrilaterals and hexahedra), so that x(:, linear_corners()) is the straight cell.
template <CurvedType Type>
std::array<int, CurvedTraits<Type>::corners> linear_corners();

// The second-order cell whose map is the straight cell's: every node at the image of its
// reference position under the linear (simplex) or multilinear (Q1) map of `corners`, given in
// canonical order. Its det J equals the straight cell's everywhere.
template <CurvedType Type>
typename CurvedTraits<Type>::Nodes straight_curved_cell(
    const Eigen::Matrix<double, CurvedTraits<Type>::dim, CurvedTraits<Type>::corners>& corners);

// --- The Bézier (Bernstein) expansion of det J ------------------------------------------------
//
// det J is a polynomial of degree n = det_degree (total degree on simplices, per direction on
// tensor cells; on the wedge total degree 4 in the triangle times degree 5 along the axis). On a
// (sub)domain D it is Σ_k c_k B_k, with B_k the Bernstein polynomials of that degree on D:
// nonnegative and summing to 1, so min_k c_k ≤ min_D det J ≤ the value at any point of D. The
// coefficients are found by sampling det J at the Lagrange points of degree n on D (equispaced) and
// applying the inverse of the fixed matrix T_pk = B_k(point p), computed once per type.

// The coefficients of det J on the whole reference cell, in the order of bezier_value's basis.
template <CurvedType Type>
Eigen::VectorXd jacobian_bezier_coefficients(const typename CurvedTraits<Type>::Nodes& x);
// Σ_k c_k B_k(ξ) on the whole reference cell.
template <CurvedType Type>
double bezier_value(const Eigen::VectorXd& coefficients, const Vector<CurvedTraits<Type>::dim>& xi);

// ∫ det J over the reference cell, exactly: the cell's (signed) volume. Every Bernstein polynomial
// of one degree has the same integral over its domain, so it is the mean of the coefficients
// times the reference cell's volume.
template <CurvedType Type>
double curved_volume(const typename CurvedTraits<Type>::Nodes& x);

// --- The validity certificate ----------------------------------------------------------------

enum class Validity {
  Valid,      // det J > 0 everywhere (every Bézier coefficient of some subdivision > 0)
  Invalid,    // det J ≤ 0 at a sample point
  Undecided,  // the bounds did not decide at the depth limit: treat as invalid
};
std::string_view name(Validity validity);

// Subdivision levels of the certificate by default: each level halves the sub-cells' edges
// (2^d children), and the gap between the bounds shrinks by about 4 per level.
inline constexpr int kCertificateDepth = 6;

struct JacobianCertificate {
  Validity validity;
  double min_det_lower;  // ≤ min over the cell of det J (a Bézier coefficient)
  double min_det_upper;  // ≥ min over the cell of det J (a sampled value)
  int depth;             // deepest subdivision level examined (0: the whole cell decided)
  int subcells;          // sub-cells examined, the whole cell included
};

// Decides the sign of det J over the cell: on each sub-cell, a sampled det J ≤ 0 makes the cell
// invalid; all Bézier coefficients > 0 make the sub-cell valid; otherwise the sub-cell is split
// (tensor cells into 2^d halves, triangles into 4 and tetrahedra into 8 by their edge
// midpoints, wedges into 8: the triangle's 4 times the axis' 2 halves) until `max_depth`, where it
// stays undecided. On Invalid the search stops at once.
template <CurvedType Type>
JacobianCertificate certify_jacobian(const typename CurvedTraits<Type>::Nodes& x,
                                     int max_depth = kCertificateDepth);

// The scaled Jacobian of a curved cell.
//
// At a reference point ξ and for corner frame k, q_k(ξ) = det J(ξ) / Π_j |J(ξ) A_k e_j|, where
// the columns of A_k are the reference edges leaving corner k (|det A_k| = 1; the wedge's: the
// edges of its triangle and the unit axis, as the cell-type table's corner frames), divided like
// quality.hpp's measure by its value on the optimal cell (√3/2 for triangles and wedges, √2/2
// for tetrahedra, 1 otherwise). Quadrilaterals and hexahedra have one frame, the reference axes:
// q = det J / Π_j |∂x/∂ξ_j|. At corner k, J A_k holds the tangents of the cell's edges there, so
// q_k(corner k) is quality.hpp's corner sine of the curved cell. Pointwise, q(ξ) = min_k q_k(ξ).
struct CurvedScaledJacobian {
  JacobianCertificate certificate;
  // min_k q_k(corner k), with the certificate's sign: an Invalid cell gets min(that, the least
  // sampled q) ≤ 0, an Undecided one at most 0. For a straight cell given as second order
  // (higher-order nodes where straight_curved_cell puts them) this is exactly quality.hpp's
  // scaled Jacobian of the straight cell.
  double scaled_jacobian;
  // Bounds of the minimum of q over the cell, found by subdividing as the certificate does:
  // `upper` is the least q at the sample points of the sub-cells (corners included); `lower` is,
  // over the final sub-cells, min_k (least Bézier coefficient of det J) / (bound of
  // Π_j |J A_k e_j| by the largest norm of each column's Bézier control points); a sub-cell is
  // split while that is more than `tolerance` below `upper` (see below), so upper − lower ≤
  // tolerance unless the depth limit came first. A cell the certificate does not find Valid gets
  // the least value q can take, −1/(the optimal cell's value) by Hadamard's inequality. upper ≤
  // scaled_jacobian: q can dip inside the cell below its corners' values (a bent edge, or a twisted
  // straight hexahedron; not a valid straight quadrilateral, whose q is least at a corner). For a
  // straight simplex lower = upper = scaled_jacobian.
  double lower, upper;
};

// `tolerance`: how far apart the bounds of the minimum of q may stay; sub-cells are split further
// (up to max_depth) while their lower bound is more than that below the least sampled q. By
// default the bounds are those of the certificate's own sub-cells, which costs about as much as
// the certificate; tight bounds cost more where q varies over the cell: a straight hexahedron27
// jittered by a quarter of its edge takes up to 40 ms for 0.1 and 0.7 s for 0.01, a
// quadrilateral 2 ms for 0.01.
template <CurvedType Type>
CurvedScaledJacobian curved_scaled_jacobian(
    const typename CurvedTraits<Type>::Nodes& x, int max_depth = kCertificateDepth,
    double tolerance = std::numeric_limits<double>::infinity());

}  // namespace neomesh
