#include "geometry/curved_cell.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace neomesh {

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// Gmsh's edges and quadrilateral faces of each reference cell, by corner (see the header).
constexpr int kTriangleEdges[3][2] = {{0, 1}, {1, 2}, {2, 0}};
constexpr int kQuadrilateralEdges[4][2] = {{0, 1}, {1, 2}, {2, 3}, {3, 0}};
constexpr int kTetrahedronEdges[6][2] = {{0, 1}, {1, 2}, {2, 0}, {3, 0}, {3, 2}, {3, 1}};
constexpr int kHexahedronEdges[12][2] = {{0, 1}, {0, 3}, {0, 4}, {1, 2}, {1, 5}, {2, 3},
                                         {2, 6}, {3, 7}, {4, 5}, {4, 7}, {5, 6}, {6, 7}};
constexpr int kHexahedronFaces[6][4] = {{0, 3, 2, 1}, {0, 1, 5, 4}, {0, 4, 7, 3},
                                        {1, 2, 6, 5}, {2, 3, 7, 6}, {4, 5, 6, 7}};

// The corners of edge e of the type, or {-1, -1} past its last edge.
template <CurvedType Type>
std::pair<int, int> edge_corners(int e) {
  constexpr int dim = CurvedTraits<Type>::dim;
  if constexpr (CurvedTraits<Type>::simplex) {
    const auto& edges = dim == 2 ? kTriangleEdges : kTetrahedronEdges;
    if (e < (dim == 2 ? 3 : 6)) return {edges[e][0], edges[e][1]};
  } else if constexpr (CurvedTraits<Type>::wedge) {
    if (e < static_cast<int>(kWedgeEdges.size())) return {kWedgeEdges[e][0], kWedgeEdges[e][1]};
  } else if constexpr (dim == 2) {
    if (e < 4) return {kQuadrilateralEdges[e][0], kQuadrilateralEdges[e][1]};
  } else {
    if (e < 12) return {kHexahedronEdges[e][0], kHexahedronEdges[e][1]};
  }
  return {-1, -1};
}

// Corner i of the reference cell in Gmsh's order.
template <CurvedType Type>
Vector<CurvedTraits<Type>::dim> reference_corner(int i) {
  constexpr int dim = CurvedTraits<Type>::dim;
  Vector<dim> xi = Vector<dim>::Zero();
  if constexpr (CurvedTraits<Type>::simplex) {
    if (i > 0) xi[i - 1] = 1.0;
  } else if constexpr (CurvedTraits<Type>::wedge) {
    // The triangle's corners (0,0) (1,0) (0,1) at ζ = −1, then at ζ = +1.
    if (i % 3 > 0) xi[i % 3 - 1] = 1.0;
    xi[2] = i >= 3 ? 1.0 : -1.0;
  } else {
    // Counter-clockwise in the plane z = −1, then the same in z = +1.
    const int in_plane = i % 4;
    xi[0] = (in_plane == 1 || in_plane == 2) ? 1.0 : -1.0;
    xi[1] = in_plane >= 2 ? 1.0 : -1.0;
    if constexpr (dim == 3) xi[2] = i >= 4 ? 1.0 : -1.0;
  }
  return xi;
}

template <CurvedType Type>
Vector<CurvedTraits<Type>::dim> reference_node_uncached(int i) {
  using Traits = CurvedTraits<Type>;
  if (i < Traits::corners) return reference_corner<Type>(i);
  const int first_edge_node = Traits::corners;
  if (const auto [a, b] = edge_corners<Type>(i - first_edge_node); a >= 0)
    return 0.5 * (reference_corner<Type>(a) + reference_corner<Type>(b));
  // Wedge18's quadrilateral faces.
  if constexpr (Traits::wedge) {
    Vector<3> centre = Vector<3>::Zero();
    for (int corner : kWedgeFaces[i - first_edge_node - static_cast<int>(kWedgeEdges.size())])
      centre += 0.25 * reference_corner<Type>(corner);
    return centre;
  }
  // Tensor cells only: hexahedron27's faces, then the centre (quadrilateral9's node 8).
  if constexpr (Traits::dim == 3 && !Traits::simplex) {
    const int face = i - first_edge_node - 12;
    if (face < 6) {
      Vector<3> centre = Vector<3>::Zero();
      for (int corner : kHexahedronFaces[face]) centre += 0.25 * reference_corner<Type>(corner);
      return centre;
    }
  }
  return Vector<Traits::dim>::Zero();
}

template <CurvedType Type>
const std::array<Vector<CurvedTraits<Type>::dim>, CurvedTraits<Type>::nodes>& reference_nodes() {
  static const auto nodes = [] {
    std::array<Vector<CurvedTraits<Type>::dim>, CurvedTraits<Type>::nodes> p;
    for (int i = 0; i < CurvedTraits<Type>::nodes; ++i) p[i] = reference_node_uncached<Type>(i);
    return p;
  }();
  return nodes;
}

constexpr bool is_serendipity(CurvedType type) {
  return type == CurvedType::Quadrilateral8 || type == CurvedType::Hexahedron20 ||
         type == CurvedType::Wedge15;
}

// Π_j f_j and its gradient, ∂_k = f'_k Π_{j≠k} f_j.
template <int Dim>
std::pair<double, Vector<Dim>> product_rule(const Vector<Dim>& f, const Vector<Dim>& df) {
  Vector<Dim> grad;
  for (int k = 0; k < Dim; ++k) {
    grad[k] = df[k];
    for (int j = 0; j < Dim; ++j)
      if (j != k) grad[k] *= f[j];
  }
  return {f.prod(), grad};
}

// Basis function of the node at reference position p, and its gradient, on a tensor cell.
// Lagrange: Π_j L_{p_j}(ξ_j) with the quadratic Lagrange polynomials on {−1, 0, 1}.
// Serendipity: Π_j (1 + p_j ξ_j)/2 · (Σ_j p_j ξ_j − (d − 1)) at a corner, and (1 − ξ_m²)
// Π_{j≠m} (1 + p_j ξ_j)/2 at the midpoint of an edge along axis m.
template <CurvedType Type>
std::pair<double, Vector<CurvedTraits<Type>::dim>> tensor_basis(
    const Vector<CurvedTraits<Type>::dim>& p, const Vector<CurvedTraits<Type>::dim>& xi) {
  constexpr int dim = CurvedTraits<Type>::dim;
  Vector<dim> f, df;
  if constexpr (!is_serendipity(Type)) {
    for (int j = 0; j < dim; ++j) {
      const double t = xi[j];
      if (p[j] == 0.0) {
        f[j] = 1.0 - t * t;
        df[j] = -2.0 * t;
      } else {
        f[j] = 0.5 * t * (t + p[j]);
        df[j] = t + 0.5 * p[j];
      }
    }
    return product_rule<dim>(f, df);
  } else {
    bool corner = true;
    for (int j = 0; j < dim; ++j) {
      if (p[j] == 0.0) {
        corner = false;
        f[j] = 1.0 - xi[j] * xi[j];
        df[j] = -2.0 * xi[j];
      } else {
        f[j] = 0.5 * (1.0 + p[j] * xi[j]);
        df[j] = 0.5 * p[j];
      }
    }
    auto [value, grad] = product_rule<dim>(f, df);
    if (!corner) return {value, grad};
    const double sum = p.dot(xi) - (dim - 1);
    return {value * sum, grad * sum + value * p};
  }
}

// On a simplex, with the barycentric coordinates λ_0 = 1 − Σ ξ, λ_k = ξ_{k−1}: λ_a (2λ_a − 1) at
// corner a and 4 λ_a λ_b at the midpoint of edge (a, b).
template <CurvedType Type>
std::pair<double, Vector<CurvedTraits<Type>::dim>> simplex_basis(
    int node, const Vector<CurvedTraits<Type>::dim>& xi) {
  constexpr int dim = CurvedTraits<Type>::dim;
  const auto lambda = [&](int a) { return a == 0 ? 1.0 - xi.sum() : xi[a - 1]; };
  const auto grad_lambda = [](int a) {
    return a == 0 ? Vector<dim>(Vector<dim>::Constant(-1.0))
                  : Vector<dim>(Vector<dim>::Unit(a - 1));
  };
  if (node <= dim) {
    const double l = lambda(node);
    return {l * (2.0 * l - 1.0), (4.0 * l - 1.0) * grad_lambda(node)};
  }
  const auto [a, b] = edge_corners<Type>(node - dim - 1);
  return {4.0 * lambda(a) * lambda(b),
          4.0 * (lambda(b) * grad_lambda(a) + lambda(a) * grad_lambda(b))};
}

// On the wedge, with the triangle's barycentric coordinates λ (as above) and μ those of the node
// at reference position p (each 0, 1/2 or 1), and t = ζ, z = p_ζ:
// - wedge18: the triangle's P2 function of the node, Π_{μ_a > 0} (μ_a = 1 ? λ_a (2λ_a − 1) :
//   2λ_a), times the quadratic Lagrange polynomial of z on {−1, 0, 1};
// - wedge15 (serendipity): at a corner ½ λ_a (2λ_a − 1)(1 + z t) − ½ λ_a (1 − t²), at the
//   midpoint of a triangle's edge 2 λ_a λ_b (1 + z t), at that of a vertical edge λ_a (1 − t²).
template <CurvedType Type>
std::pair<double, Vector<3>> wedge_basis(const Vector<3>& p, const Vector<3>& xi) {
  const std::array<double, 3> lambda = {1.0 - xi[0] - xi[1], xi[0], xi[1]};
  const std::array<double, 3> mu = {1.0 - p[0] - p[1], p[0], p[1]};
  const std::array<Vector<3>, 3> grad_lambda = {Vector<3>(-1.0, -1.0, 0.0), Vector<3>::UnitX(),
                                                Vector<3>::UnitY()};
  const double t = xi[2], z = p[2];
  if constexpr (!is_serendipity(Type)) {
    double f = 1.0;  // the triangle's factor
    Vector<3> df = Vector<3>::Zero();
    for (int a = 0; a < 3; ++a) {
      if (mu[a] == 0.0) continue;
      const bool corner = mu[a] == 1.0;
      const double g = corner ? lambda[a] * (2.0 * lambda[a] - 1.0) : 2.0 * lambda[a];
      const Vector<3> dg = (corner ? 4.0 * lambda[a] - 1.0 : 2.0) * grad_lambda[a];
      df = df * g + f * dg;
      f *= g;
    }
    const double l = z == 0.0 ? 1.0 - t * t : 0.5 * t * (t + z);
    const double dl = z == 0.0 ? -2.0 * t : t + 0.5 * z;
    return {f * l, df * l + f * dl * Vector<3>::UnitZ()};
  } else {
    int a = 0, b = -1;  // the node's corners of the triangle
    while (mu[a] == 0.0) ++a;
    if (mu[a] != 1.0)
      for (b = a + 1; mu[b] == 0.0;) ++b;
    const double la = lambda[a];
    if (z == 0.0)  // a vertical edge
      return {la * (1.0 - t * t),
              (1.0 - t * t) * grad_lambda[a] - 2.0 * t * la * Vector<3>::UnitZ()};
    if (b >= 0) {
      const double lb = lambda[b], s = 1.0 + z * t;
      return {2.0 * la * lb * s, 2.0 * s * (lb * grad_lambda[a] + la * grad_lambda[b]) +
                                     2.0 * la * lb * z * Vector<3>::UnitZ()};
    }
    const double c = la * (2.0 * la - 1.0), s = 1.0 + z * t;
    return {0.5 * c * s - 0.5 * la * (1.0 - t * t),
            (0.5 * (4.0 * la - 1.0) * s - 0.5 * (1.0 - t * t)) * grad_lambda[a] +
                (0.5 * c * z + la * t) * Vector<3>::UnitZ()};
  }
}

template <CurvedType Type>
std::pair<double, Vector<CurvedTraits<Type>::dim>> basis_function(
    int node, const Vector<CurvedTraits<Type>::dim>& xi) {
  if constexpr (CurvedTraits<Type>::simplex)
    return simplex_basis<Type>(node, xi);
  else if constexpr (CurvedTraits<Type>::wedge)
    return wedge_basis<Type>(reference_nodes<Type>()[node], xi);
  else
    return tensor_basis<Type>(reference_nodes<Type>()[node], xi);
}

// --- Bernstein polynomials ----------------------------------------------------------------------
//
// On the unit domain — the unit simplex, [0,1]^d, or the unit triangle × [0,1] — in coordinates
// t; a sub-cell is the image ξ = origin + M t of the unit domain in reference coordinates (the
// whole tensor cell: origin (−1, ..., −1), M = 2I; the whole simplex: origin 0, M = I; the whole
// wedge: origin (0, 0, −1), M = diag(1, 1, 2)).

double binomial(int n, int k) {
  double b = 1.0;
  for (int i = 1; i <= k; ++i) b = b * (n - k + i) / i;
  return b;
}

// With λ = (1 − Σ t, t) and α = (n − Σ a, a): n!/Π α_k! Π λ_k^α_k, the Bernstein polynomial
// of degree n on the unit simplex.
template <int Dim>
double simplex_bernstein(int n, const Eigen::Array<int, Dim, 1>& a, const Vector<Dim>& t) {
  const int a0 = n - a.sum();
  double value = std::pow(1.0 - t.sum(), a0) * binomial(n, a0);
  int left = n - a0;
  for (int j = 0; j < Dim; ++j) {
    value *= binomial(left, a[j]) * std::pow(t[j], a[j]);
    left -= a[j];
  }
  return value;
}

template <CurvedType Type>
struct Bezier {
  static constexpr int dim = CurvedTraits<Type>::dim;
  static constexpr int degree = CurvedTraits<Type>::det_degree;
  static constexpr int axis_degree = CurvedTraits<Type>::det_axis_degree;  // the wedge's
  // Simplices and wedges invert the whole matrix T; tensor cells T's factor of one direction.
  static constexpr bool whole_matrix = CurvedTraits<Type>::simplex || CurvedTraits<Type>::wedge;
  std::vector<Eigen::Array<int, dim, 1>> indices;  // multi-index a of B_a
  std::vector<Vector<dim>> points;                 // the Lagrange points a/n
  // T⁻¹: simplices and wedges the whole matrix; tensor cells that of one direction, since T is
  // the Kronecker product of d copies of it (points and basis both first index fastest).
  Eigen::MatrixXd to_bezier;

  // Tensor: Π_j C(n, a_j) t_j^a_j (1 − t_j)^(n − a_j); simplex: simplex_bernstein; wedge: the
  // triangle's of degree n in (t_0, t_1) times the axis' of degree n_axis in t_2.
  static double basis(const Eigen::Array<int, dim, 1>& a, const Vector<dim>& t) {
    if constexpr (CurvedTraits<Type>::simplex) {
      return simplex_bernstein<dim>(degree, a, t);
    } else if constexpr (CurvedTraits<Type>::wedge) {
      return simplex_bernstein<2>(degree, a.template head<2>(), t.template head<2>()) *
             binomial(axis_degree, a[2]) * std::pow(t[2], a[2]) *
             std::pow(1.0 - t[2], axis_degree - a[2]);
    } else {
      double value = 1.0;
      for (int j = 0; j < dim; ++j)
        value *=
            binomial(degree, a[j]) * std::pow(t[j], a[j]) * std::pow(1.0 - t[j], degree - a[j]);
      return value;
    }
  }

  Bezier() {
    constexpr int largest = std::max(degree, axis_degree);
    Eigen::Array<int, dim, 1> a = Eigen::Array<int, dim, 1>::Zero();
    for (;;) {
      bool in = true;
      if constexpr (CurvedTraits<Type>::simplex) in = a.sum() <= degree;
      if constexpr (CurvedTraits<Type>::wedge) in = a[0] + a[1] <= degree;
      if constexpr (!whole_matrix) in = a.maxCoeff() <= degree;
      if (in) {
        indices.push_back(a);
        Vector<dim> p = a.template cast<double>().matrix() / degree;
        if constexpr (CurvedTraits<Type>::wedge) p[2] = double(a[2]) / axis_degree;
        points.push_back(p);
      }
      int j = 0;  // next multi-index in [0, largest]^d, first index fastest
      while (j < dim && a[j] == largest) a[j++] = 0;
      if (j == dim) break;
      ++a[j];
    }
    if constexpr (whole_matrix) {
      const int n = static_cast<int>(points.size());
      Eigen::MatrixXd t(n, n);
      for (int p = 0; p < n; ++p)
        for (int k = 0; k < n; ++k) t(p, k) = basis(indices[k], points[p]);
      to_bezier = t.fullPivLu().inverse();
    } else {
      Eigen::MatrixXd t(degree + 1, degree + 1);
      for (int p = 0; p <= degree; ++p)
        for (int k = 0; k <= degree; ++k)
          t(p, k) = binomial(degree, k) * std::pow(double(p) / degree, k) *
                    std::pow(1.0 - double(p) / degree, degree - k);
      to_bezier = t.fullPivLu().inverse();
    }
  }

  // The Bézier coefficients of the polynomial with `values` at the points.
  Eigen::VectorXd coefficients(const Eigen::VectorXd& values) const {
    if constexpr (whole_matrix) {
      return to_bezier * values;
    } else {
      // T⁻¹ applied along each direction in turn: (n + 1) d multiplications per value instead of
      // (n + 1)^d (hexahedron: 18 instead of 216).
      constexpr int m = degree + 1;
      Eigen::VectorXd c = values;
      Eigen::Matrix<double, m, 1> line;
      for (int j = 0, stride = 1; j < dim; ++j, stride *= m)
        for (int first = 0; first < c.size(); ++first) {
          if ((first / stride) % m != 0) continue;  // not the start of a line along j
          for (int i = 0; i < m; ++i) line[i] = c[first + i * stride];
          line = to_bezier * line;
          for (int i = 0; i < m; ++i) c[first + i * stride] = line[i];
        }
      return c;
    }
  }
};

template <CurvedType Type>
const Bezier<Type>& bezier() {
  static const Bezier<Type> data;
  return data;
}

template <int Dim>
struct SubCell {
  Vector<Dim> origin;
  Matrix<Dim> m;
  int depth;
  double parent_lower;  // the parent's least Bézier coefficient: a bound until this is examined
};

template <CurvedType Type>
SubCell<CurvedTraits<Type>::dim> whole_cell() {
  constexpr int dim = CurvedTraits<Type>::dim;
  if constexpr (CurvedTraits<Type>::simplex)
    return {Vector<dim>::Zero(), Matrix<dim>::Identity(), 0, -kInfinity};
  else if constexpr (CurvedTraits<Type>::wedge)
    return {Vector<3>(0.0, 0.0, -1.0), Matrix<3>(Vector<3>(1.0, 1.0, 2.0).asDiagonal()), 0,
            -kInfinity};
  else
    return {Vector<dim>::Constant(-1.0), 2.0 * Matrix<dim>::Identity(), 0, -kInfinity};
}

// The children of the unit domain as affine maps t ↦ o + M t: 2^d half boxes; the triangle's
// 4 and the tetrahedron's 8 sub-simplices of its edge midpoints (the tetrahedron: its 4 corner
// tetrahedra and the inner octahedron cut along the diagonal from mid(0,2) to mid(1,3)); the
// wedge's 8, the triangle's 4 times the axis' 2 halves.
template <CurvedType Type>
std::vector<std::pair<Vector<CurvedTraits<Type>::dim>, Matrix<CurvedTraits<Type>::dim>>>
unit_children() {
  constexpr int dim = CurvedTraits<Type>::dim;
  std::vector<std::pair<Vector<dim>, Matrix<dim>>> children;
  if constexpr (CurvedTraits<Type>::wedge) {
    for (const auto& [o, m] : unit_children<CurvedType::Triangle6>())
      for (int half = 0; half < 2; ++half) {
        Matrix<3> m3 = Matrix<3>::Zero();
        m3.topLeftCorner<2, 2>() = m;
        m3(2, 2) = 0.5;
        children.emplace_back(Vector<3>(o[0], o[1], 0.5 * half), m3);
      }
  } else if constexpr (!CurvedTraits<Type>::simplex) {
    for (int c = 0; c < (1 << dim); ++c) {
      Vector<dim> o;
      for (int j = 0; j < dim; ++j) o[j] = ((c >> j) & 1) ? 0.5 : 0.0;
      children.emplace_back(o, 0.5 * Matrix<dim>::Identity());
    }
  } else {
    std::array<Vector<dim>, dim + 1> v;
    for (int k = 0; k <= dim; ++k) v[k] = reference_corner<Type>(k);
    const auto mid = [&](int a, int b) { return Vector<dim>(0.5 * (v[a] + v[b])); };
    const auto add = [&](const std::array<Vector<dim>, dim + 1>& w) {
      Matrix<dim> m;
      for (int j = 0; j < dim; ++j) m.col(j) = w[j + 1] - w[0];
      children.emplace_back(w[0], m);
    };
    if constexpr (dim == 2) {
      add({v[0], mid(0, 1), mid(0, 2)});
      add({mid(0, 1), v[1], mid(1, 2)});
      add({mid(0, 2), mid(1, 2), v[2]});
      add({mid(1, 2), mid(0, 2), mid(0, 1)});
    } else {
      for (int k = 0; k < 4; ++k) {
        std::array<Vector<3>, 4> w;
        for (int j = 0; j < 4; ++j) w[j] = j == k ? v[k] : mid(k, j);
        add(w);
      }
      const std::array<Vector<3>, 4> ring = {mid(0, 1), mid(1, 2), mid(2, 3), mid(3, 0)};
      for (int k = 0; k < 4; ++k) add({mid(0, 2), mid(1, 3), ring[k], ring[(k + 1) % 4]});
    }
  }
  return children;
}

// The corner frames A_k (docs above curved_scaled_jacobian): the edges leaving each reference
// corner of a simplex; the axes for tensor cells, one frame for all corners.
template <CurvedType Type>
const std::vector<Matrix<CurvedTraits<Type>::dim>>& corner_frames() {
  constexpr int dim = CurvedTraits<Type>::dim;
  static const auto frames = [] {
    std::vector<Matrix<dim>> a;
    if constexpr (CurvedTraits<Type>::simplex) {
      for (int k = 0; k <= dim; ++k) {
        Matrix<dim> frame;
        for (int j = 0, col = 0; j <= dim; ++j)
          if (j != k) frame.col(col++) = reference_corner<Type>(j) - reference_corner<Type>(k);
        a.push_back(frame);
      }
    } else if constexpr (CurvedTraits<Type>::wedge) {
      // Corner k: the edges to the next two corners of its triangle, and the axis upwards (the
      // cell-type table's frames; det A_k = 1).
      for (int k = 0; k < 6; ++k) {
        const int base = k - k % 3;
        Matrix<3> frame;
        for (int j = 1; j <= 2; ++j)
          frame.col(j - 1) = reference_corner<Type>(base + (k + j) % 3) - reference_corner<Type>(k);
        frame.col(2) = Vector<3>::UnitZ();
        a.push_back(frame);
      }
    } else {
      a.push_back(Matrix<dim>::Identity());
    }
    return a;
  }();
  return frames;
}

// q_k(J) = det J / Π_j |J A_k e_j| (0 where a column vanishes), over the optimal cell's value.
// det J rather than det(J A_k): |det A_k| = 1 and quality.hpp signs every corner of a simplex
// by its volume.
template <CurvedType Type>
double frame_sine(const Matrix<CurvedTraits<Type>::dim>& j, int k) {
  const Matrix<CurvedTraits<Type>::dim> columns = j * corner_frames<Type>()[k];
  const double product = columns.colwise().norm().prod();
  return (product > 0.0 ? j.determinant() / product : 0.0) /
         facts(CurvedTraits<Type>::linear).ideal_corner_sine;
}

template <CurvedType Type>
double pointwise_sine(const Matrix<CurvedTraits<Type>::dim>& j) {
  double q = kInfinity;
  for (int k = 0; k < static_cast<int>(corner_frames<Type>().size()); ++k)
    q = std::min(q, frame_sine<Type>(j, k));
  return q;
}

// The least q can be: −1 before the division by the optimal cell's value (Hadamard's
// inequality, |det(J A_k)| ≤ Π_j |J A_k e_j|, and |det A_k| = 1).
template <CurvedType Type>
double least_sine() {
  return -1.0 / facts(CurvedTraits<Type>::linear).ideal_corner_sine;
}

// A lower bound of min q over a sub-cell whose least Bézier coefficient of det J is `lower` > 0,
// from the Bézier control points of J's entries (sampled at the same points as det J).
template <CurvedType Type>
double sine_lower_bound(const std::vector<Matrix<CurvedTraits<Type>::dim>>& jacobians,
                        double lower) {
  constexpr int dim = CurvedTraits<Type>::dim;
  const int n = static_cast<int>(jacobians.size());
  // Control points of J: entry (r, c) of control point m is control[r + dim * c](m).
  std::array<Eigen::VectorXd, dim * dim> control;
  for (int e = 0; e < dim * dim; ++e) {
    Eigen::VectorXd values(n);
    for (int p = 0; p < n; ++p) values[p] = jacobians[p](e % dim, e / dim);
    control[e] = bezier<Type>().coefficients(values);
  }
  double bound = kInfinity;
  for (int k = 0; k < static_cast<int>(corner_frames<Type>().size()); ++k) {
    double product = 1.0;  // Π_j max over control points of |J A_k e_j|
    for (int j = 0; j < dim; ++j) {
      const Vector<dim> a = corner_frames<Type>()[k].col(j);
      double largest = 0.0;
      for (int m = 0; m < n; ++m) {
        Matrix<dim> jm;
        for (int e = 0; e < dim * dim; ++e) jm(e % dim, e / dim) = control[e][m];
        largest = std::max(largest, (jm * a).norm());
      }
      product *= largest;
    }
    bound = std::min(bound, lower / product / facts(CurvedTraits<Type>::linear).ideal_corner_sine);
  }
  return bound;
}

// What a visitor of subdivide() does with the sub-cell it was shown.
enum class Step { Done, Split, Stop };

// Sub-cells as subdivide() shows them: J and det J at the Lagrange points, and the least Bézier
// coefficient of det J.
template <CurvedType Type>
struct Sample {
  const SubCell<CurvedTraits<Type>::dim>& cell;
  const std::vector<Matrix<CurvedTraits<Type>::dim>>& jacobians;
  const Eigen::VectorXd& values;
  double lower;
  const std::vector<SubCell<CurvedTraits<Type>::dim>>& pending;  // not yet shown
};

// Shows `visit` the whole cell, then, depth first, the children of every sub-cell it splits
// (Step::Split), until none is left or it says Step::Stop.
template <CurvedType Type, typename Visit>
void subdivide(const typename CurvedTraits<Type>::Nodes& x, Visit&& visit) {
  constexpr int dim = CurvedTraits<Type>::dim;
  const Bezier<Type>& b = bezier<Type>();
  static const auto children = unit_children<Type>();
  const int n = static_cast<int>(b.points.size());
  std::vector<SubCell<dim>> pending = {whole_cell<Type>()};
  std::vector<Matrix<dim>> jacobians(n);
  Eigen::VectorXd values(n);
  while (!pending.empty()) {
    const SubCell<dim> cell = pending.back();
    pending.pop_back();
    for (int p = 0; p < n; ++p) {
      jacobians[p] = curved_jacobian<Type>(x, cell.origin + cell.m * b.points[p]);
      values[p] = jacobians[p].determinant();
    }
    const double lower = b.coefficients(values).minCoeff();
    const Step step = visit(Sample<Type>{cell, jacobians, values, lower, pending});
    if (step == Step::Stop) return;
    if (step == Step::Split)
      for (const auto& [o, m] : children)
        pending.push_back({cell.origin + cell.m * o, cell.m * m, cell.depth + 1, lower});
  }
}

template <CurvedType Type>
JacobianCertificate certificate(const typename CurvedTraits<Type>::Nodes& x, int max_depth) {
  JacobianCertificate cert{Validity::Valid, kInfinity, kInfinity, 0, 0};
  subdivide<Type>(x, [&](const Sample<Type>& s) {
    ++cert.subcells;
    cert.depth = std::max(cert.depth, s.cell.depth);
    const double lowest_value = s.values.minCoeff();
    cert.min_det_upper = std::min(cert.min_det_upper, lowest_value);
    if (lowest_value <= 0.0) {
      // What is left unexamined is bounded by its parents' coefficients.
      cert.validity = Validity::Invalid;
      cert.min_det_lower = std::min(cert.min_det_lower, s.lower);
      for (const auto& rest : s.pending)
        cert.min_det_lower = std::min(cert.min_det_lower, rest.parent_lower);
      return Step::Stop;
    }
    if (s.lower <= 0.0 && s.cell.depth < max_depth) return Step::Split;
    cert.min_det_lower = std::min(cert.min_det_lower, s.lower);
    if (s.lower > 0.0) return Step::Done;
    cert.validity = Validity::Undecided;
    return Step::Done;
  });
  return cert;
}

// Bounds of min q over the cell: the least sampled q above; below, on each sub-cell with
// positive coefficients of det J, sine_lower_bound, split further while that is more than
// `tolerance` below the least sampled q; least_sine where det J is not shown positive.
template <CurvedType Type>
std::pair<double, double> sine_bounds(const typename CurvedTraits<Type>::Nodes& x, int max_depth,
                                      double tolerance) {
  double lower = kInfinity, upper = kInfinity;
  subdivide<Type>(x, [&](const Sample<Type>& s) {
    for (const auto& j : s.jacobians) upper = std::min(upper, pointwise_sine<Type>(j));
    const bool deepest = s.cell.depth >= max_depth;
    if (s.values.minCoeff() <= 0.0) {
      lower = least_sine<Type>();
      return Step::Stop;
    }
    if (s.lower <= 0.0) {
      if (deepest) lower = least_sine<Type>();
      return deepest ? Step::Done : Step::Split;
    }
    const double bound = sine_lower_bound<Type>(s.jacobians, s.lower);
    if (bound < upper - tolerance && !deepest) return Step::Split;
    lower = std::min(lower, bound);
    return Step::Done;
  });
  return {lower, upper};
}

}  // namespace

std::string_view name(Validity validity) {
  static constexpr std::array<std::string_view, 3> names = {"valid", "invalid", "undecided"};
  return names[static_cast<int>(validity)];
}

template <CurvedType Type>
Vector<CurvedTraits<Type>::dim> reference_node(int i) {
  return reference_nodes<Type>()[i];
}

template <CurvedType Type>
Eigen::Matrix<double, CurvedTraits<Type>::nodes, 1> curved_basis(
    const Vector<CurvedTraits<Type>::dim>& xi) {
  Eigen::Matrix<double, CurvedTraits<Type>::nodes, 1> values;
  for (int i = 0; i < CurvedTraits<Type>::nodes; ++i) values[i] = basis_function<Type>(i, xi).first;
  return values;
}

template <CurvedType Type>
Eigen::Matrix<double, CurvedTraits<Type>::dim, CurvedTraits<Type>::nodes> curved_gradients(
    const Vector<CurvedTraits<Type>::dim>& xi) {
  Eigen::Matrix<double, CurvedTraits<Type>::dim, CurvedTraits<Type>::nodes> grad;
  for (int i = 0; i < CurvedTraits<Type>::nodes; ++i)
    grad.col(i) = basis_function<Type>(i, xi).second;
  return grad;
}

template <CurvedType Type>
Vector<CurvedTraits<Type>::dim> curved_map(const typename CurvedTraits<Type>::Nodes& x,
                                           const Vector<CurvedTraits<Type>::dim>& xi) {
  return x * curved_basis<Type>(xi);
}

template <CurvedType Type>
Matrix<CurvedTraits<Type>::dim> curved_jacobian(const typename CurvedTraits<Type>::Nodes& x,
                                                const Vector<CurvedTraits<Type>::dim>& xi) {
  return x * curved_gradients<Type>(xi).transpose();
}

template <CurvedType Type>
double curved_det(const typename CurvedTraits<Type>::Nodes& x,
                  const Vector<CurvedTraits<Type>::dim>& xi) {
  return curved_jacobian<Type>(x, xi).determinant();
}

template <CurvedType Type>
std::array<int, CurvedTraits<Type>::corners> linear_corners() {
  if constexpr (CurvedTraits<Type>::simplex || CurvedTraits<Type>::wedge) {
    std::array<int, CurvedTraits<Type>::corners> c;
    for (int i = 0; i < CurvedTraits<Type>::corners; ++i) c[i] = i;
    return c;
  } else if constexpr (CurvedTraits<Type>::dim == 2) {
    return {0, 1, 3, 2};
  } else {
    return {0, 1, 3, 2, 4, 5, 7, 6};
  }
}

template <CurvedType Type>
typename CurvedTraits<Type>::Nodes straight_curved_cell(
    const Eigen::Matrix<double, CurvedTraits<Type>::dim, CurvedTraits<Type>::corners>& corners) {
  using Traits = CurvedTraits<Type>;
  typename Traits::Nodes x;
  for (int i = 0; i < Traits::nodes; ++i) {
    const Vector<Traits::dim> p = reference_node<Type>(i);
    if constexpr (Traits::simplex) {
      x.col(i) = corners.col(0);
      for (int k = 0; k < Traits::dim; ++k)
        x.col(i) += p[k] * (corners.col(k + 1) - corners.col(0));
    } else if constexpr (Traits::wedge) {
      // λ_a (1 ∓ ζ)/2 (reference_cell.hpp's wedge).
      const double lambda[3] = {1.0 - p[0] - p[1], p[0], p[1]};
      x.col(i).setZero();
      for (int a = 0; a < 3; ++a)
        x.col(i) += lambda[a] *
                    (0.5 * (1.0 - p[2]) * corners.col(a) + 0.5 * (1.0 + p[2]) * corners.col(a + 3));
    } else {
      // Q1 in tensor order: N_v(ξ) = Π_j (1 + s_vj ξ_j)/2.
      x.col(i).setZero();
      for (int v = 0; v < Traits::corners; ++v)
        x.col(i) +=
            corners.col(v) *
            (0.5 * (Vector<Traits::dim>::Ones() + q1_vertex<Traits::dim>(v).cwiseProduct(p)))
                .prod();
    }
  }
  return x;
}

template <CurvedType Type>
Eigen::VectorXd jacobian_bezier_coefficients(const typename CurvedTraits<Type>::Nodes& x) {
  const Bezier<Type>& b = bezier<Type>();
  const auto whole = whole_cell<Type>();
  Eigen::VectorXd values(b.points.size());
  for (std::size_t p = 0; p < b.points.size(); ++p)
    values[p] = curved_det<Type>(x, whole.origin + whole.m * b.points[p]);
  return b.coefficients(values);
}

template <CurvedType Type>
double bezier_value(const Eigen::VectorXd& coefficients,
                    const Vector<CurvedTraits<Type>::dim>& xi) {
  const Bezier<Type>& b = bezier<Type>();
  const auto whole = whole_cell<Type>();
  const Vector<CurvedTraits<Type>::dim> t = whole.m.inverse() * (xi - whole.origin);
  double value = 0.0;
  for (std::size_t k = 0; k < b.indices.size(); ++k)
    value += coefficients[k] * Bezier<Type>::basis(b.indices[k], t);
  return value;
}

template <CurvedType Type>
JacobianCertificate certify_jacobian(const typename CurvedTraits<Type>::Nodes& x, int max_depth) {
  return certificate<Type>(x, max_depth);
}

template <CurvedType Type>
CurvedScaledJacobian curved_scaled_jacobian(const typename CurvedTraits<Type>::Nodes& x,
                                            int max_depth, double tolerance) {
  const JacobianCertificate cert = certificate<Type>(x, max_depth);
  const auto [lower, upper] = sine_bounds<Type>(x, max_depth, tolerance);
  // Frame k at corner k (tensor cells: the one frame at every corner).
  double corner = kInfinity;
  const int frames = static_cast<int>(corner_frames<Type>().size());
  for (int k = 0; k < CurvedTraits<Type>::corners; ++k)
    corner = std::min(corner, frame_sine<Type>(curved_jacobian<Type>(x, reference_corner<Type>(k)),
                                               frames == 1 ? 0 : k));
  const bool valid = cert.validity == Validity::Valid;
  return {.certificate = cert,
          .scaled_jacobian = valid ? corner : std::min({corner, upper, 0.0}),
          .lower = valid ? lower : least_sine<Type>(),
          .upper = upper};
}

template <CurvedType Type>
double curved_volume(const typename CurvedTraits<Type>::Nodes& x) {
  using Traits = CurvedTraits<Type>;
  // The unit simplex: 1/d!; [−1,1]^d: 2^d; the unit triangle × [−1,1]: 1.
  const double reference = Traits::simplex ? (Traits::dim == 2 ? 0.5 : 1.0 / 6.0)
                           : Traits::wedge ? 1.0
                                           : 1 << Traits::dim;
  return reference * jacobian_bezier_coefficients<Type>(x).mean();
}

#define NEOMESH_CURVED_INSTANTIATE(T)                                                            \
  template Vector<CurvedTraits<T>::dim> reference_node<T>(int);                                  \
  template Eigen::Matrix<double, CurvedTraits<T>::nodes, 1> curved_basis<T>(                     \
      const Vector<CurvedTraits<T>::dim>&);                                                      \
  template Eigen::Matrix<double, CurvedTraits<T>::dim, CurvedTraits<T>::nodes>                   \
  curved_gradients<T>(const Vector<CurvedTraits<T>::dim>&);                                      \
  template Vector<CurvedTraits<T>::dim> curved_map<T>(const CurvedTraits<T>::Nodes&,             \
                                                      const Vector<CurvedTraits<T>::dim>&);      \
  template Matrix<CurvedTraits<T>::dim> curved_jacobian<T>(const CurvedTraits<T>::Nodes&,        \
                                                           const Vector<CurvedTraits<T>::dim>&); \
  template double curved_det<T>(const CurvedTraits<T>::Nodes&,                                   \
                                const Vector<CurvedTraits<T>::dim>&);                            \
  template std::array<int, CurvedTraits<T>::corners> linear_corners<T>();                        \
  template CurvedTraits<T>::Nodes straight_curved_cell<T>(                                       \
      const Eigen::Matrix<double, CurvedTraits<T>::dim, CurvedTraits<T>::corners>&);             \
  template Eigen::VectorXd jacobian_bezier_coefficients<T>(const CurvedTraits<T>::Nodes&);       \
  template double bezier_value<T>(const Eigen::VectorXd&, const Vector<CurvedTraits<T>::dim>&);  \
  template double curved_volume<T>(const CurvedTraits<T>::Nodes&);                               \
  template JacobianCertificate certify_jacobian<T>(const CurvedTraits<T>::Nodes&, int);          \
  template CurvedScaledJacobian curved_scaled_jacobian<T>(const CurvedTraits<T>::Nodes&, int,    \
                                                          double);

NEOMESH_CURVED_INSTANTIATE(CurvedType::Triangle6)
NEOMESH_CURVED_INSTANTIATE(CurvedType::Quadrilateral8)
NEOMESH_CURVED_INSTANTIATE(CurvedType::Quadrilateral9)
NEOMESH_CURVED_INSTANTIATE(CurvedType::Tetrahedron10)
NEOMESH_CURVED_INSTANTIATE(CurvedType::Hexahedron20)
NEOMESH_CURVED_INSTANTIATE(CurvedType::Hexahedron27)
NEOMESH_CURVED_INSTANTIATE(CurvedType::Wedge15)
NEOMESH_CURVED_INSTANTIATE(CurvedType::Wedge18)

#undef NEOMESH_CURVED_INSTANTIATE

}  // namespace neomesh
