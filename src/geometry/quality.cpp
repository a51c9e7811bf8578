#include "geometry/quality.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <utility>

#include <fmt/format.h>

#include "core/error.hpp"
#include "geometry/reference_cell.hpp"
#include "geometry/surface_frame.hpp"
#include "geometry/surface_orientation.hpp"

namespace neomesh {

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();
constexpr double kDegrees = 180.0 / std::numbers::pi;
// |volume| below this fraction of the mean cell volume counts as degenerate.
constexpr double kDegenerateVolume = 1e-14;

template <int Dim>
double cosine_between(const Vector<Dim>& a, const Vector<Dim>& b) {
  return std::clamp(a.dot(b) / (a.norm() * b.norm()), -1.0, 1.0);
}

double degrees(double cosine) {
  return std::acos(cosine) * kDegrees;
}

// How a Jacobian J (its columns a cell's edge vectors or derivatives) gives a signed volume:
// for a cell of its space's dimension, det J.
struct Determinant {
  template <typename Jacobian>
  double operator()(const Jacobian& j) const {
    return j.determinant();
  }
};

// For a surface cell, J is 3 × 2: the area of the parallelogram of its columns, signed by the
// cell's reference normal n, (j0 × j1) · n — the determinant of J in a frame (t1, t2, n). Its
// sign says whether the cell is folded against n; a cell lying in the plane normal to n gets
// the determinant of its 2D image, a cell tilted by θ against that plane cos θ times it.
struct NormalArea {
  Vector<3> normal;
  template <typename Jacobian>
  double operator()(const Jacobian& j) const {
    return Vector<3>(j.col(0)).cross(Vector<3>(j.col(1))).dot(normal);
  }
};

// A d × D Jacobian of a cell whose coordinates `X` have X::RowsAtCompileTime rows.
template <typename X, int D>
using Jacobian = Eigen::Matrix<double, X::RowsAtCompileTime, D>;

struct Measures {
  double volume, min_corner_det, min_gauss_det, scaled_jacobian, min_angle, max_angle, edge_ratio;
  double inverse_mean_ratio;

  void record_angle(double angle) {
    min_angle = std::min(min_angle, angle);
    max_angle = std::max(max_angle, angle);
  }
  // The angle between a and b: acos decreases, so only the extreme cosines need one, not each
  // of a hexahedron's 24 angles (finish_angles).
  template <int Dim>
  void record_angle_between(const Vector<Dim>& a, const Vector<Dim>& b) {
    record_cosine(cosine_between<Dim>(a, b));
  }
  void record_cosine(double c) {
    max_cosine = std::max(max_cosine, c);
    min_cosine = std::min(min_cosine, c);
  }
  void finish_angles() {
    if (!(max_cosine >= min_cosine)) return;  // none recorded (or NaN)
    record_angle(degrees(max_cosine));
    record_angle(degrees(min_cosine));
  }

  double max_cosine = -kInfinity, min_cosine = kInfinity;
};

// The edges of `Type`, each once, as pairs of vertex numbers: every edge lies on a facet (2D: is
// one), so the facets' cycles visit them all, a 3D cell's twice.
template <CellType Type>
constexpr auto cell_edges() {
  struct {
    std::array<std::array<int, 2>, 24> edge{};
    int size = 0;
  } edges;
  for (int f = 0; f < facts(Type).num_facets; ++f) {
    const FacetVertices& facet = facts(Type).facets[f];
    for (int i = 0; i < facet.size; ++i) {
      const int a = facet.vertices[i], b = facet.vertices[(i + 1) % facet.size];
      bool seen = false;
      for (int e = 0; e < edges.size; ++e)
        seen = seen || (edges.edge[e][0] == std::min(a, b) && edges.edge[e][1] == std::max(a, b));
      if (!seen) edges.edge[edges.size++] = {std::min(a, b), std::max(a, b)};
    }
  }
  return edges;
}

// Longest over shortest edge; each edge's length once (a facet's cycle takes an edge the other
// way round than its neighbour's: the same length, bit for bit, as x_a - x_b = -(x_b - x_a)).
template <CellType Type, typename X>
double edge_ratio(const X& x) {
  static constexpr auto edges = cell_edges<Type>();
  double shortest = kInfinity, longest = 0.0;
  for (int e = 0; e < edges.size; ++e) {
    const double length = (x.col(edges.edge[e][1]) - x.col(edges.edge[e][0])).norm();
    shortest = std::min(shortest, length);
    longest = std::max(longest, length);
  }
  return shortest > 0.0 ? longest / shortest : kInfinity;
}

// The signed volume: det J integrated exactly (Q1: 2 Gauss points per direction, degree ≤ 1 in
// 2D and ≤ 2 per axis in 3D; wedges and pyramids: the reference map's rule, see below).
template <CellType Type, typename X, typename Det = Determinant>
double signed_volume(const X& x, Det det = {}) {
  using Traits = CellTraits<Type>;
  constexpr int d = Traits::dim;
  if constexpr (Traits::shape == CellShape::Simplex) {
    Jacobian<X, d> edges;
    for (int j = 0; j < d; ++j) edges.col(j) = x.col(j + 1) - x.col(0);
    return det(edges) / (d == 2 ? 2.0 : 6.0);
  } else if constexpr (Traits::shape == CellShape::Tensor) {
    // The rule's weights and ∇N at its points, computed once (they were per cell: half of the
    // volume's cost).
    static const auto rule = [] {
      const TensorGaussRule<d> gauss(2);
      constexpr int n = 1 << d;  // 2^d points
      std::array<std::pair<double, typename Traits::Coordinates>, n> points;
      for (int q = 0; q < n; ++q) points[q] = {gauss.weights[q], q1_gradients<d>(gauss.points[q])};
      return points;
    }();
    double volume = 0.0;
    for (const auto& [weight, gradients] : rule)
      volume += weight * det(Jacobian<X, d>(x * gradients.transpose()));
    return volume;
  } else {
    // The wedge over the unit right triangle with height 1 (ζ = 2t − 1 halves it), the pyramid
    // over the unit square with apex height 1.
    static const ReferenceRule<Type> rule(2);
    double volume = 0.0;
    for (int q = 0; q < rule.size; ++q)
      volume +=
          rule.weights[q] * (x * shape_gradients<Type>(rule.points[q]).transpose()).determinant();
    return volume;
  }
}

// det / (product of the edge lengths) at corner frame K (corner_jacobian), 0 where an edge has
// length zero.
template <CellType Type, int K, typename X, typename Det>
double corner_sine(const X& x, Det det) {
  constexpr int d = CellTraits<Type>::dim;
  constexpr CornerFrame frame = facts(Type).corners[K];
  Jacobian<X, d> edges;
  for (int j = 0; j < d; ++j) {
    const double sign = ((frame.flip >> j) & 1) ? -1.0 : 1.0;
    edges.col(j) = sign * (x.col(frame.ends[j]) - x.col(frame.vertex));
  }
  double product = 1.0;
  for (int j = 0; j < d; ++j) product *= edges.col(j).norm();
  return product > 0.0 ? det(edges) / product : 0.0;
}

// The minimum over the corners of det / (product of the corner's edge lengths), over its value
// on the optimal cell (see quality.hpp); 0 at a corner with a zero-length edge. With a `bar`, it
// stops at the first corner that takes the value to `bar` or below and returns that value (at
// most `bar`, not the cell's): the worst-cell repair's trial points mostly fail at one corner.
// Above the bar the value is the same: the minimum ignores NaN corners in any order, and the
// division by a positive constant keeps the order of the values — which also makes the minimum
// of the values over two sets of `corners` (bit K: corner K; a simplex's corner K is at its
// vertex K) the value over all.
template <CellType Type, typename X, typename Det = Determinant>
double scaled_jacobian(const X& x, Det det = {}, double bar = -kInfinity,
                       std::uint32_t corners = kAllCorners) {
  using Traits = CellTraits<Type>;
  constexpr int d = Traits::dim;
  constexpr double ideal = facts(Type).ideal_corner_sine;
  double lowest = kInfinity;
  // Without a bar, no division per corner (an exit there would return the value anyway).
  const bool early_exit = bar > -kInfinity;
  if constexpr (Traits::shape == CellShape::Simplex) {
    if ((corners & ((1u << (d + 1)) - 1)) == 0) return lowest / ideal;  // no corner asked for
    Jacobian<X, d> edges;
    for (int j = 0; j < d; ++j) edges.col(j) = x.col(j + 1) - x.col(0);
    const double volume = det(edges);
    for (int i = 0; i <= d; ++i) {
      if (!((corners >> i) & 1)) continue;
      double product = 1.0;
      for (int j = 0; j <= d; ++j)
        if (j != i) product *= (x.col(j) - x.col(i)).norm();
      lowest = std::min(lowest, product > 0.0 ? volume / product : 0.0);
      if (early_exit && lowest / ideal <= bar) break;
    }
  } else {
    // The corners unrolled, their frames known at compile time: the worst-cell repair evaluates
    // many cells (quarter annulus of 8,000 hexahedra: half a million), and the loop over
    // frames read at run time cost twice the arithmetic. The same operations in the same order.
    [&]<int... K>(std::integer_sequence<int, K...>) {
      (void)((((corners >> K) & 1) && ((lowest = std::min(lowest, corner_sine<Type, K>(x, det))),
                                       early_exit && lowest / ideal <= bar)) ||
             ...);
    }
    (std::make_integer_sequence<int, facts(Type).num_corners>{});
  }
  return lowest / ideal;
}

// Each corner's value of scaled_jacobian (corners as there), to out[K]; returns their count.
template <CellType Type, typename X, typename Det = Determinant>
int scaled_jacobian_corners(const X& x, Det det, double* out) {
  constexpr int n =
      facts(Type).shape == CellShape::Simplex ? CellTraits<Type>::dim + 1 : facts(Type).num_corners;
  [&]<int... K>(std::integer_sequence<int, K...>) {
    ((out[K] = scaled_jacobian<Type>(x, det, -kInfinity, 1u << K)), ...);
  }
  (std::make_integer_sequence<int, n>{});
  return n;
}

// W⁻¹ at each corner frame of the optimal cell of `Type` (quality.hpp, inverse mean ratio),
// and whether every one is the identity (Q1 cells: the unit square's and cube's frames), where
// T = J W⁻¹ is J itself.
template <CellType Type>
struct IdealCornerInverses {
  std::array<Matrix<CellTraits<Type>::dim>, 8> inverse;
  bool identity = true;
};
template <CellType Type>
const IdealCornerInverses<Type>& ideal_corner_inverses() {
  static const IdealCornerInverses<Type> ideal = [] {
    IdealCornerInverses<Type> w;
    const auto optimal = unit_optimal_cell<Type>();
    for (int k = 0; k < facts(Type).num_corners; ++k) {
      w.inverse[k] = corner_jacobian<Type>(optimal, k).inverse();
      w.identity = w.identity && w.inverse[k] == Matrix<CellTraits<Type>::dim>::Identity();
    }
    return w;
  }();
  return ideal;
}

// Inverse mean ratio, the shape metric of Mesquite and of MFEM's TMOP (Knupp 2001): at each
// corner frame T = J W⁻¹, J the corner's Jacobian and W the optimal cell's at that corner,
// and |T|²_F / (d det(T)^(2/d)) ≥ 1, with 1 only where T is a scaled rotation; the mean over
// the cell's corner frames (a simplex has one). +∞ where det T ≤ 0.
template <CellType Type, typename X, typename Det = Determinant>
double inverse_mean_ratio(const X& x, Det det = {}) {
  constexpr int d = CellTraits<Type>::dim;
  const auto& ideal_inverse = ideal_corner_inverses<Type>().inverse;
  const int corners = facts(Type).num_corners;
  double sum = 0.0;
  for (int k = 0; k < corners; ++k) {
    const Jacobian<X, d> t = corner_jacobian<Type>(x, k) * ideal_inverse[k];
    const double det_t = det(t);
    if (!(det_t > 0.0)) return kInfinity;
    sum += t.squaredNorm() / (d * std::pow(det_t, 2.0 / d));
  }
  return sum / corners;
}

template <CellType Type, typename X, typename Det = Determinant>
Measures measure_simplex(const X& x, Det det = {}) {
  constexpr int d = CellTraits<Type>::dim, rows = X::RowsAtCompileTime;
  Jacobian<X, d> edges;
  for (int j = 0; j < d; ++j) edges.col(j) = x.col(j + 1) - x.col(0);

  Measures m{};
  m.volume = signed_volume<Type>(x, det);
  m.min_corner_det = m.min_gauss_det = det(edges);
  m.scaled_jacobian = scaled_jacobian<Type>(x, det);
  m.min_angle = kInfinity;
  m.max_angle = 0.0;
  if constexpr (d == 2) {
    for (int i = 0; i < 3; ++i)
      m.record_angle_between<rows>(x.col((i + 1) % 3) - x.col(i), x.col((i + 2) % 3) - x.col(i));
  } else {
    // Dihedral angle at edge (a, b): between the normals of its faces towards c and d.
    for (int a = 0; a < 4; ++a)
      for (int b = a + 1; b < 4; ++b) {
        int others[2], k = 0;
        for (int c = 0; c < 4; ++c)
          if (c != a && c != b) others[k++] = c;
        const Vector<3> e = x.col(b) - x.col(a);
        m.record_angle_between<3>(e.cross(Vector<3>(x.col(others[0]) - x.col(a))),
                                  e.cross(Vector<3>(x.col(others[1]) - x.col(a))));
      }
  }
  m.finish_angles();
  m.edge_ratio = edge_ratio<Type>(x);
  m.inverse_mean_ratio = inverse_mean_ratio<Type>(x, det);
  return m;
}

template <CellType Type, typename X, typename Det = Determinant>
Measures measure_q1(const X& x, Det det = {}) {
  constexpr int d = CellTraits<Type>::dim, n = CellTraits<Type>::vertices;
  constexpr int rows = X::RowsAtCompileTime;
  static_assert(facts(Type).num_corners == n && [] {
    for (int c = 0; c < n; ++c) {
      if (facts(Type).corners[c].vertex != c) return false;
      for (int j = 0; j < d; ++j)
        if (facts(Type).corners[c].ends[j] != (c ^ (1 << j))) return false;
    }
    return true;
  }());
  Measures m{};
  m.min_corner_det = m.min_gauss_det = m.min_angle = kInfinity;
  m.max_angle = 0.0;
  m.volume = signed_volume<Type>(x, det);
  // Each corner's Jacobian, determinant and edge lengths once, for the scaled Jacobian, the
  // corner determinants, the angles, the edge ratio and the inverse mean ratio: the operations
  // each of them did on its own, in the same order, so the same bits. Corner frame c is at
  // vertex c, its edge j towards vertex c ^ 2^j (the cell-type table), with a sign.
  const bool unit_frames = ideal_corner_inverses<Type>().identity;
  double lowest_sine = kInfinity, shortest = kInfinity, longest = 0.0, imr_sum = 0.0;
  for (int c = 0; c < n; ++c) {
    const Jacobian<X, d> jacobian = corner_jacobian<Type>(x, c);
    const double corner_det = det(jacobian);
    m.min_corner_det = std::min(m.min_corner_det, corner_det);
    std::array<double, d> length;
    double product = 1.0;
    for (int j = 0; j < d; ++j) {
      length[j] = jacobian.col(j).norm();
      product *= length[j];
      shortest = std::min(shortest, length[j]);
      longest = std::max(longest, length[j]);
    }
    lowest_sine = std::min(lowest_sine, product > 0.0 ? corner_det / product : 0.0);
    for (int j = 0; j < d; ++j)
      for (int k = j + 1; k < d; ++k) {
        // The actual edges leave the corner; the angle between them is the one inside the
        // cell unless the corner is reflex (2D) or inverted.
        const Vector<rows> a = x.col(c ^ (1 << j)) - x.col(c), b = x.col(c ^ (1 << k)) - x.col(c);
        const double cosine = std::clamp(a.dot(b) / (length[j] * length[k]), -1.0, 1.0);
        if (d == 2 && corner_det <= 0.0)
          m.record_angle(360.0 - degrees(cosine));
        else
          m.record_cosine(cosine);
      }
    if (unit_frames && imr_sum < kInfinity) {
      // T = J W⁻¹ is J itself.
      if (!(corner_det > 0.0))
        imr_sum = kInfinity;
      else
        imr_sum += jacobian.squaredNorm() / (d * std::pow(corner_det, 2.0 / d));
    }
  }
  m.scaled_jacobian = lowest_sine / facts(Type).ideal_corner_sine;
  m.inverse_mean_ratio = !unit_frames          ? inverse_mean_ratio<Type>(x, det)
                         : imr_sum < kInfinity ? imr_sum / n
                                               : kInfinity;
  m.finish_angles();
  // 2 ∇N at the 3 Gauss points per direction, computed once.
  static const auto det_gradients = [] {
    const TensorGaussRule<d> rule(3);
    std::array<typename CellTraits<Type>::Coordinates, TensorGaussRule<d>::max_points> g;
    for (int q = 0; q < rule.size; ++q) g[q] = 2.0 * q1_gradients<d>(rule.points[q]);
    return std::pair{rule.size, g};
  }();
  for (int q = 0; q < det_gradients.first; ++q) {
    const Jacobian<X, d> jacobian = x * det_gradients.second[q].transpose();
    m.min_gauss_det = std::min(m.min_gauss_det, det(jacobian));
  }
  // Every edge is an edge of two corners.
  m.edge_ratio = shortest > 0.0 ? longest / shortest : kInfinity;
  return m;
}

// Wedges and pyramids: corner frames of the cell-type table, the reference map's det J at the
// quadrature points, and the interior angles of the faces.
template <CellType Type>
Measures measure_wedge_or_pyramid(const typename CellTraits<Type>::Coordinates& x) {
  const CellFacts& cell = facts(Type);
  Measures m{};
  m.min_corner_det = m.min_gauss_det = m.min_angle = kInfinity;
  m.max_angle = 0.0;
  m.scaled_jacobian = scaled_jacobian<Type>(x);
  m.volume = signed_volume<Type>(x);
  for (int k = 0; k < cell.num_corners; ++k)
    m.min_corner_det = std::min(m.min_corner_det, corner_jacobian<Type>(x, k).determinant());
  for (int f = 0; f < cell.num_facets; ++f) {
    const FacetVertices& facet = cell.facets[f];
    for (int i = 0; i < facet.size; ++i) {
      const auto corner = x.col(facet.vertices[i]);
      m.record_angle_between<3>(x.col(facet.vertices[(i + 1) % facet.size]) - corner,
                                x.col(facet.vertices[(i + facet.size - 1) % facet.size]) - corner);
    }
  }
  m.finish_angles();
  // det J relative to the unit reference cell (see signed_volume): the pyramid's det J =
  // (1 − ξ2)²/32 det[∂B/∂u, ∂B/∂v, apex − B] with u, v ∈ [0, 1].
  static const ReferenceRule<Type> det_rule(3);
  for (int q = 0; q < det_rule.size; ++q) {
    const Vector<3>& xi = det_rule.points[q];
    const double scale = Type == CellType::Wedge ? 2.0 : 32.0 / ((1.0 - xi[2]) * (1.0 - xi[2]));
    const double det = (x * shape_gradients<Type>(xi).transpose()).determinant();
    m.min_gauss_det = std::min(m.min_gauss_det, scale * det);
  }
  m.edge_ratio = edge_ratio<Type>(x);
  m.inverse_mean_ratio = inverse_mean_ratio<Type>(x);
  return m;
}

// The reference normals of a surface mesh's cells (surface_orientation.hpp); none for others.
std::vector<double> reference_normals(const MeshView& view, std::span<const double> coords,
                                      const DofMap* dofs) {
  return view.surface ? surface_reference_normals(view, coords, dofs) : std::vector<double>{};
}

// Calls per_cell.template operator()<Type>(i, x, det) with the coordinates x of every cell i (the
// view's cell order) and how its determinants are taken (a surface cell's: seen along its
// reference normal in `normals`, 3 per cell, or a zero normal where `normals` is empty, for
// measures that need none), in parallel: cells are independent, and a run takes their quality
// several times (before, for the guard, after).
template <typename PerCell>
void for_each_cell(const MeshView& view, std::span<const double> coords,
                   std::span<const double> normals, PerCell&& per_cell) {
  if (coords.size() != static_cast<std::size_t>(view.num_vertices) * view.dim)
    fail("cell quality: {} coordinates given for {} vertices in {}D", coords.size(),
         view.num_vertices, view.dim);
  for (const CellBlock& block : view.blocks)
    visit_cell_type(block.type, [&]<CellType Type>(CellTag<Type>) {
      using Traits = CellTraits<Type>;
      if constexpr (Traits::dim == 2) {
        if (view.surface) {
#pragma omp parallel for schedule(static)
          for (PetscInt c = 0; c < block.size(); ++c) {
            Eigen::Matrix<double, 3, Traits::vertices> x;
            const PetscInt* cell = block.cell(c);
            for (int i = 0; i < Traits::vertices; ++i)
              x.col(i) = Eigen::Map<const Vector<3>>(coords.data() + 3 * cell[i]);
            const std::size_t i = static_cast<std::size_t>(block.first_cell + c);
            const NormalArea area{normals.empty()
                                      ? Vector<3>::Zero()
                                      : Vector<3>(Eigen::Map<const Vector<3>>(&normals[3 * i]))};
            per_cell.template operator()<Type>(i, x, area);
          }
          return;
        }
      }
#pragma omp parallel for schedule(static)
      for (PetscInt c = 0; c < block.size(); ++c) {
        typename Traits::Coordinates x;
        const PetscInt* cell = block.cell(c);
        for (int i = 0; i < Traits::vertices; ++i)
          for (int k = 0; k < Traits::dim; ++k) x(k, i) = coords[Traits::dim * cell[i] + k];
        per_cell.template operator()<Type>(static_cast<std::size_t>(block.first_cell + c), x,
                                           Determinant{});
      }
    });
}

template <CellType Type, typename X, typename Det = Determinant>
Measures measure(const X& x, Det det = {}) {
  using Traits = CellTraits<Type>;
  if constexpr (Traits::shape == CellShape::Simplex)
    return measure_simplex<Type>(x, det);
  else if constexpr (Traits::shape == CellShape::Tensor)
    return measure_q1<Type>(x, det);
  else
    return measure_wedge_or_pyramid<Type>(x);
}

MetricStats reduce(const std::vector<double>& values, std::int64_t global_count, MPI_Comm comm) {
  double low = kInfinity, high = -kInfinity, sum = 0.0;
  for (double v : values) {
    low = std::min(low, v);
    high = std::max(high, v);
    sum += v;
  }
  MPI_Allreduce(MPI_IN_PLACE, &low, 1, MPI_DOUBLE, MPI_MIN, comm);
  MPI_Allreduce(MPI_IN_PLACE, &high, 1, MPI_DOUBLE, MPI_MAX, comm);
  MPI_Allreduce(MPI_IN_PLACE, &sum, 1, MPI_DOUBLE, MPI_SUM, comm);
  return {low, global_count > 0 ? sum / global_count : 0.0, high};
}

// metric.template operator()<Type>(x) of one cell of `type` at `coords` (dim values per vertex).
// One metric of every cell: metric.template operator()<Type>(x, det) per cell, in the view's
// cell order, along the reference normals where the mesh is a surface.
template <typename Metric>
std::vector<double> each_cell(const MeshView& view, std::span<const double> coords,
                              const DofMap* dofs, Metric metric) {
  std::vector<double> values(view.num_cells);
  for_each_cell(view, coords, reference_normals(view, coords, dofs),
                [&values, &metric]<CellType Type>(std::size_t i, const auto& x, auto det) {
                  values[i] = metric.template operator()<Type>(x, det);
                });
  return values;
}

template <class Metric>
double of_one_cell(CellType type, const double* coords, Metric metric) {
  double value = 0.0;
  visit_cell_type(type, [&]<CellType Type>(CellTag<Type>) {
    using Traits = CellTraits<Type>;
    value = metric.template operator()<Type>(
        Eigen::Map<const typename Traits::Coordinates>(coords, Traits::dim, Traits::vertices));
  });
  return value;
}

// metric.template operator()<Type>(x, area) of one surface cell (a triangle or quadrilateral)
// at `coords` (3 values per vertex), with `area` the NormalArea of `normal`.
template <class Result, class Metric>
Result of_one_surface_cell(CellType type, const double* coords, const double* normal,
                           Metric metric) {
  Result value{};
  visit_cell_type(type, [&]<CellType Type>(CellTag<Type>) {
    if constexpr (CellTraits<Type>::dim == 2) {
      using Coordinates = Eigen::Matrix<double, 3, CellTraits<Type>::vertices>;
      value =
          metric.template operator()<Type>(Eigen::Map<const Coordinates>(coords),
                                           NormalArea{Vector<3>(normal[0], normal[1], normal[2])});
    } else {
      fail("a surface cell is a triangle or a quadrilateral, not a {}", name(Type));
    }
  });
  return value;
}

}  // namespace

SurfaceCellMeasures surface_cell_measures(CellType type, const double* coords,
                                          const double* normal) {
  return of_one_surface_cell<SurfaceCellMeasures>(
      type, coords, normal, []<CellType Type>(const auto& x, const NormalArea& area) {
        const Measures m = measure<Type>(x, area);
        return SurfaceCellMeasures{.area = m.volume,
                                   .min_corner_det = m.min_corner_det,
                                   .min_gauss_det = m.min_gauss_det,
                                   .scaled_jacobian = m.scaled_jacobian,
                                   .min_angle = m.min_angle,
                                   .max_angle = m.max_angle,
                                   .edge_ratio = m.edge_ratio,
                                   .inverse_mean_ratio = m.inverse_mean_ratio};
      });
}

double surface_cell_scaled_jacobian(CellType type, const double* coords, const double* normal) {
  return of_one_surface_cell<double>(type, coords, normal,
                                     []<CellType Type>(const auto& x, const NormalArea& area) {
                                       return scaled_jacobian<Type>(x, area);
                                     });
}

double surface_cell_scaled_jacobian_above(CellType type, const double* coords, const double* normal,
                                          double bar, std::uint32_t corners) {
  return of_one_surface_cell<double>(
      type, coords, normal, [bar, corners]<CellType Type>(const auto& x, const NormalArea& area) {
        return scaled_jacobian<Type>(x, area, bar, corners);
      });
}

int surface_cell_scaled_jacobian_corners(CellType type, const double* coords, const double* normal,
                                         double* out) {
  return of_one_surface_cell<int>(type, coords, normal,
                                  [out]<CellType Type>(const auto& x, const NormalArea& area) {
                                    return scaled_jacobian_corners<Type>(x, area, out);
                                  });
}

double surface_cell_inverse_mean_ratio(CellType type, const double* coords, const double* normal) {
  return of_one_surface_cell<double>(type, coords, normal,
                                     []<CellType Type>(const auto& x, const NormalArea& area) {
                                       return inverse_mean_ratio<Type>(x, area);
                                     });
}

double surface_cell_edge_ratio(CellType type, const double* coords) {
  const double any_normal[3] = {0.0, 0.0, 1.0};  // edge lengths do not depend on it
  return of_one_surface_cell<double>(
      type, coords, any_normal,
      []<CellType Type>(const auto& x, const NormalArea&) { return edge_ratio<Type>(x); });
}

CellQuality cell_quality(const MeshView& view, std::span<const double> coords, const DofMap* dofs) {
  CellQuality q;
  for (auto* field : {&q.volume, &q.min_corner_det, &q.min_gauss_det, &q.scaled_jacobian,
                      &q.min_angle, &q.max_angle, &q.edge_ratio, &q.inverse_mean_ratio})
    field->resize(view.num_cells);
  q.type.resize(view.num_cells);
  for_each_cell(view, coords, reference_normals(view, coords, dofs),
                [&q]<CellType Type>(std::size_t i, const auto& x, auto det) {
                  const Measures m = measure<Type>(x, det);
                  q.type[i] = Type;
                  q.volume[i] = m.volume;
                  q.min_corner_det[i] = m.min_corner_det;
                  q.min_gauss_det[i] = m.min_gauss_det;
                  q.scaled_jacobian[i] = m.scaled_jacobian;
                  q.min_angle[i] = m.min_angle;
                  q.max_angle[i] = m.max_angle;
                  q.edge_ratio[i] = m.edge_ratio;
                  q.inverse_mean_ratio[i] = m.inverse_mean_ratio;
                });
  return q;
}

std::vector<double> cell_volumes(const MeshView& view, std::span<const double> coords,
                                 const DofMap* dofs) {
  return each_cell(view, coords, dofs, []<CellType Type>(const auto& x, auto det) {
    return signed_volume<Type>(x, det);
  });
}

std::vector<double> cell_scaled_jacobians(const MeshView& view, std::span<const double> coords,
                                          const DofMap* dofs) {
  return each_cell(view, coords, dofs, []<CellType Type>(const auto& x, auto det) {
    return scaled_jacobian<Type>(x, det);
  });
}

std::vector<double> cell_inverse_mean_ratios(const MeshView& view, std::span<const double> coords,
                                             const DofMap* dofs) {
  return each_cell(view, coords, dofs, []<CellType Type>(const auto& x, auto det) {
    return inverse_mean_ratio<Type>(x, det);
  });
}

double cell_scaled_jacobian(CellType type, const double* coords) {
  return of_one_cell(type, coords,
                     []<CellType Type>(const auto& x) { return scaled_jacobian<Type>(x); });
}

double cell_scaled_jacobian_above(CellType type, const double* coords, double bar,
                                  std::uint32_t corners) {
  return of_one_cell(type, coords, [bar, corners]<CellType Type>(const auto& x) {
    return scaled_jacobian<Type>(x, Determinant{}, bar, corners);
  });
}

int cell_scaled_jacobian_corners(CellType type, const double* coords, double* out) {
  int n = 0;
  visit_cell_type(type, [&]<CellType Type>(CellTag<Type>) {
    using Traits = CellTraits<Type>;
    n = scaled_jacobian_corners<Type>(
        Eigen::Map<const typename Traits::Coordinates>(coords, Traits::dim, Traits::vertices),
        Determinant{}, out);
  });
  return n;
}

std::uint32_t scaled_jacobian_corners_at(CellType type, int vertex) {
  const CellFacts& cell = facts(type);
  if (cell.shape == CellShape::Simplex) return kAllCorners;  // every edge ends at every corner
  std::uint32_t corners = 0;
  for (int k = 0; k < cell.num_corners; ++k) {
    const CornerFrame& frame = cell.corners[k];
    bool at = frame.vertex == vertex;
    for (int j = 0; j < cell.dim; ++j) at = at || frame.ends[j] == vertex;
    if (at) corners |= 1u << k;
  }
  return corners;
}

double cell_inverse_mean_ratio(CellType type, const double* coords) {
  return of_one_cell(type, coords,
                     []<CellType Type>(const auto& x) { return inverse_mean_ratio<Type>(x); });
}

double cell_edge_ratio(CellType type, const double* coords) {
  return of_one_cell(type, coords,
                     []<CellType Type>(const auto& x) { return edge_ratio<Type>(x); });
}

std::vector<double> cell_edge_ratios(const MeshView& view, std::span<const double> coords) {
  std::vector<double> ratio(view.num_cells);
  for_each_cell(view, coords, {}, [&ratio]<CellType Type>(std::size_t i, const auto& x, auto) {
    ratio[i] = edge_ratio<Type>(x);
  });
  return ratio;
}

std::vector<std::pair<std::string_view, MetricStats>> QualitySummary::metrics() const {
  return {{"volume", volume},
          {"min_det_corners", min_corner_det},
          {"min_det_gauss", min_gauss_det},
          {"scaled_jacobian", scaled_jacobian},
          {"min_angle", min_angle},
          {"max_angle", max_angle},
          {"edge_ratio", edge_ratio},
          {"inverse_mean_ratio", inverse_mean_ratio}};
}

std::vector<Field> quality_fields(const CellQuality& q) {
  return {{"volume", q.volume},         {"scaled_jacobian", q.scaled_jacobian},
          {"min_angle", q.min_angle},   {"max_angle", q.max_angle},
          {"edge_ratio", q.edge_ratio}, {"inverse_mean_ratio", q.inverse_mean_ratio}};
}

QualitySummary summarize(const CellQuality& quality, MPI_Comm comm) {
  QualitySummary s;
  for (CellType t : quality.type) ++s.cells_by_type[static_cast<int>(t)];
  MPI_Allreduce(MPI_IN_PLACE, s.cells_by_type.data(), kNumCellTypes, MPI_INT64_T, MPI_SUM, comm);
  for (std::int64_t n : s.cells_by_type) s.cells += n;

  s.volume = reduce(quality.volume, s.cells, comm);
  s.min_corner_det = reduce(quality.min_corner_det, s.cells, comm);
  s.min_gauss_det = reduce(quality.min_gauss_det, s.cells, comm);
  s.scaled_jacobian = reduce(quality.scaled_jacobian, s.cells, comm);
  s.min_angle = reduce(quality.min_angle, s.cells, comm);
  s.max_angle = reduce(quality.max_angle, s.cells, comm);
  s.edge_ratio = reduce(quality.edge_ratio, s.cells, comm);
  s.inverse_mean_ratio = reduce(quality.inverse_mean_ratio, s.cells, comm);

  double abs_volume = 0.0;
  for (double v : quality.volume) abs_volume += std::abs(v);
  MPI_Allreduce(MPI_IN_PLACE, &abs_volume, 1, MPI_DOUBLE, MPI_SUM, comm);
  const double tiny = kDegenerateVolume * (s.cells > 0 ? abs_volume / s.cells : 0.0);
  std::array<std::int64_t, 2> counts{};  // inverted, degenerate
  for (std::size_t c = 0; c < quality.size(); ++c) {
    counts[0] += std::min(quality.min_corner_det[c], quality.min_gauss_det[c]) <= 0.0;
    counts[1] += std::abs(quality.volume[c]) <= tiny || std::isinf(quality.edge_ratio[c]);
  }
  MPI_Allreduce(MPI_IN_PLACE, counts.data(), 2, MPI_INT64_T, MPI_SUM, comm);
  s.inverted = counts[0];
  s.degenerate = counts[1];
  return s;
}

}  // namespace neomesh
