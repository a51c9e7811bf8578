#include "boundary/discrete_geometry.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include <fmt/format.h>
#include <Eigen/Geometry>

#include "boundary/features.hpp"

namespace neomesh {

namespace {

// A simplex registered in more grid cells than this is checked on every query instead.
constexpr long long kMaxCellsPerSimplex = 4096;
// Relative: how much farther than the best a simplex's box must be for it to be skipped.
constexpr double kBoxMargin = 1e-9;

// The closest point of triangle abc to p, with its barycentric weights (Ericson, "Real-Time
// Collision Detection", §5.1.5: by the Voronoi regions of the vertices, edges and face).
SimplexSet::Hit closest_on_triangle(const Point& p, const Point& a, const Point& b,
                                    const Point& c) {
  SimplexSet::Hit h;
  auto at = [&](double u, double v, double w) {
    h.weights = {u, v, w};
    h.point = u * a + v * b + w * c;
    return h;
  };
  const Point ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return at(1, 0, 0);
  const Point bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return at(0, 1, 0);
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    const double v = d1 / (d1 - d3);
    return at(1 - v, v, 0);
  }
  const Point cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return at(0, 0, 1);
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    const double w = d2 / (d2 - d6);
    return at(1 - w, 0, w);
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return at(0, 1 - w, w);
  }
  const double denom = 1.0 / (va + vb + vc);
  const double v = vb * denom, w = vc * denom;
  return at(1 - v - w, v, w);
}

SimplexSet::Hit closest_on_segment(const Point& p, const Point& a, const Point& b) {
  const Point ab = b - a;
  const double len2 = ab.squaredNorm();
  const double t = len2 > 0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  SimplexSet::Hit h;
  h.weights = {1 - t, t, 0};
  h.point = a + t * ab;
  return h;
}

// Σ weights[i] · vectors[i], each vector's sign turned to agree with `reference` (normals and
// tangents of a discrete shape have no consistent orientation), normalized; `reference` if
// the sum vanishes.
Point blend(const std::array<double, 3>& weights, const std::array<Point, 3>& vectors, int n,
            const Point& reference) {
  Point sum = Point::Zero();
  for (int i = 0; i < n; ++i)
    sum += weights[i] * (vectors[i].dot(reference) < 0 ? -vectors[i] : vectors[i]);
  const double norm = sum.norm();
  return norm > 0 ? Point(sum / norm) : reference;
}

// Per point: the sum of the given per-simplex vectors (area/length-weighted, unnormalized),
// signs aligned with the first one, normalized.
std::vector<Point> point_average(const SimplexSet& set, const std::vector<Point>& per_simplex) {
  std::vector<Point> sum(set.points().size(), Point::Zero());
  for (std::size_t s = 0; s < set.simplices().size(); ++s)
    for (int i = 0; i < set.corners(); ++i) {
      Point& at = sum[set.simplices()[s][i]];
      at += at.dot(per_simplex[s]) < 0 ? -per_simplex[s] : per_simplex[s];
    }
  for (Point& v : sum)
    if (v.norm() > 0) v.normalize();
  return sum;
}

}  // namespace

FacetSimplices facet_simplices(const BoundarySurface& s, std::span<const PetscInt> facets) {
  FacetSimplices out;
  out.corners = s.dim == 2 ? 2 : 3;
  std::unordered_map<PetscInt, int> index;  // boundary vertex → point
  auto point_index = [&](PetscInt b) {
    const auto [it, added] = index.emplace(b, static_cast<int>(out.points.size()));
    if (added) out.points.push_back(surface_point(s, b));
    return it->second;
  };
  for (PetscInt f : facets) {
    const auto v = s.facet(f);
    if (v.size() == 2)
      out.simplices.push_back({point_index(v[0]), point_index(v[1]), 0});
    else
      for (std::size_t k = 1; k + 1 < v.size(); ++k)
        out.simplices.push_back({point_index(v[0]), point_index(v[k]), point_index(v[k + 1])});
  }
  return out;
}

SimplexSet::SimplexSet(std::vector<Point> points, std::vector<std::array<int, 3>> simplices,
                       int corners)
    : points_(std::move(points)), simplices_(std::move(simplices)), corners_(corners) {
  Point lo = Point::Constant(std::numeric_limits<double>::max()), hi = -lo;
  for (const Point& p : points_) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  if (points_.empty()) lo = hi = Point::Zero();
  // Grid spacing: the median extent of the simplices, so that a typical one spans 1-2 cells.
  std::vector<double> extent;
  for (const auto& s : simplices_) {
    Point a = points_[s[0]], b = a;
    for (int i = 1; i < corners_; ++i) {
      a = a.cwiseMin(points_[s[i]]);
      b = b.cwiseMax(points_[s[i]]);
    }
    extent.push_back((b - a).maxCoeff());
  }
  if (!extent.empty()) {
    std::nth_element(extent.begin(), extent.begin() + extent.size() / 2, extent.end());
    spacing_ = extent[extent.size() / 2];
  }
  if (!(spacing_ > 0)) spacing_ = std::max((hi - lo).maxCoeff(), 1.0);
  origin_ = lo;
  const Cell top = cell_of(hi);
  for (int a = 0; a < 3; ++a) cells_[a] = top[a] + 1;

  for (int s = 0; s < static_cast<int>(simplices_.size()); ++s) {
    Point a = points_[simplices_[s][0]], b = a;
    for (int i = 1; i < corners_; ++i) {
      a = a.cwiseMin(points_[simplices_[s][i]]);
      b = b.cwiseMax(points_[simplices_[s][i]]);
    }
    boxes_.push_back({a, b});
    const Cell first = cell_of(a), last = cell_of(b);
    long long count = 1;
    for (int k = 0; k < 3; ++k) count *= last[k] - first[k] + 1;
    if (count > kMaxCellsPerSimplex) {
      large_.push_back(s);
      continue;
    }
    for (long long i = first[0]; i <= last[0]; ++i)
      for (long long j = first[1]; j <= last[1]; ++j)
        for (long long k = first[2]; k <= last[2]; ++k) grid_[key({i, j, k})].push_back(s);
  }
}

SimplexSet::Cell SimplexSet::cell_of(const Point& p) const {
  Cell c;
  for (int a = 0; a < 3; ++a)
    c[a] =
        static_cast<long long>(std::floor(std::clamp((p[a] - origin_[a]) / spacing_, -1e15, 1e15)));
  return c;
}

long long SimplexSet::key(const Cell& c) {
  // Cells outside the grid are never looked up, so 21 bits per axis suffice.
  return (c[0] << 42) ^ (c[1] << 21) ^ c[2];
}

SimplexSet::Hit SimplexSet::closest_on(int s, const Point& p) const {
  const auto& v = simplices_[s];
  Hit h = corners_ == 2 ? closest_on_segment(p, points_[v[0]], points_[v[1]])
                        : closest_on_triangle(p, points_[v[0]], points_[v[1]], points_[v[2]]);
  h.simplex = s;
  h.distance = (h.point - p).norm();
  return h;
}

// A simplex closer to p than some distance has its closest point in a cell no farther than that,
// and is listed in that cell: a cell farther than the best needs no visit (with a margin of
// kBoxMargin of the best and of the spacing for the cells' bounds computed with round-off).
double SimplexSet::cell_distance(const Cell& c, const Point& p) const {
  double sum = 0.0;
  for (int a = 0; a < 3; ++a) {
    const double lo = origin_[a] + static_cast<double>(c[a]) * spacing_;
    const double outside = std::max({lo - p[a], p[a] - (lo + spacing_), 0.0});
    sum += outside * outside;
  }
  return std::sqrt(sum);
}

void SimplexSet::visit(const Cell& c, const Point& p, Hit& best) const {
  const auto it = grid_.find(key(c));
  if (it == grid_.end()) return;
  for (int s : it->second) {
    // A simplex whose box is farther than the best cannot be closer: skipped without its
    // closest point (the worst-cell repair's trial points on a surface spent most of their
    // time here). The margin keeps a simplex whose computed distance could round below its
    // box's.
    const Point outside = (boxes_[s][0] - p).cwiseMax(p - boxes_[s][1]).cwiseMax(0.0);
    if (outside.norm() > best.distance * (1 + kBoxMargin)) continue;
    const Hit h = closest_on(s, p);
    if (h.distance < best.distance || (h.distance == best.distance && s < best.simplex)) best = h;
  }
}

// Rings of cells around p's cell, nearest first. After ring r every simplex with a point inside
// the box of cells c ± r has been seen, so the search ends once the best distance is below p's
// distance to the box's faces that have grid cells beyond them: a closer (or equally close)
// simplex would have a point inside. A point on or near the surface usually ends after ring 0.
SimplexSet::Hit SimplexSet::closest(const Point& p) const {
  Hit best;
  best.distance = std::numeric_limits<double>::infinity();
  for (int s : large_) {
    const Hit h = closest_on(s, p);
    if (h.distance < best.distance) best = h;
  }
  const Cell c = cell_of(p);
  Point offset;  // p's position in its cell
  for (int a = 0; a < 3; ++a)
    offset[a] = p[a] - (origin_[a] + static_cast<double>(c[a]) * spacing_);
  long long reach = 0;  // rings beyond this hold no grid cell
  for (int a = 0; a < 3; ++a) reach = std::max({reach, c[a], cells_[a] - 1 - c[a]});
  for (long long r = 0; r <= reach; ++r) {
    Cell lo, hi;
    double unseen = std::numeric_limits<double>::infinity();  // distance to the unseen cells
    for (int a = 0; a < 3; ++a) {
      lo[a] = std::max(c[a] - r, 0LL);
      hi[a] = std::min(c[a] + r, cells_[a] - 1);
      const double ring_width = static_cast<double>(r) * spacing_;
      if (c[a] - r > 0) unseen = std::min(unseen, offset[a] + ring_width);
      if (c[a] + r < cells_[a] - 1) unseen = std::min(unseen, spacing_ - offset[a] + ring_width);
    }
    for (long long i = lo[0]; i <= hi[0]; ++i)
      for (long long j = lo[1]; j <= hi[1]; ++j)
        for (long long k = lo[2]; k <= hi[2]; ++k) {
          const long long ring =
              std::max({std::abs(i - c[0]), std::abs(j - c[1]), std::abs(k - c[2])});
          if (ring == r && !(cell_distance({i, j, k}, p) >
                             best.distance * (1 + kBoxMargin) + kBoxMargin * spacing_))
            visit({i, j, k}, p, best);
        }
    if (best.distance < unseen) break;
  }
  return best;
}

DiscreteSurface::DiscreteSurface(std::vector<Point> points,
                                 std::vector<std::array<int, 3>> simplices, int dim)
    : set_(std::move(points), std::move(simplices), dim == 2 ? 2 : 3), dim_(dim) {
  std::vector<Point> weighted;  // normals scaled by length (2D) or twice the area (3D)
  for (int s = 0; s < static_cast<int>(set_.simplices().size()); ++s) {
    const auto& v = set_.simplices()[s];
    const Point e = set_.points()[v[1]] - set_.points()[v[0]];
    weighted.push_back(dim_ == 2 ? Point(-e.y(), e.x(), 0.0)
                                 : Point(e.cross(set_.points()[v[2]] - set_.points()[v[0]])));
  }
  point_normal_ = point_average(set_, weighted);
}

Point DiscreteSurface::simplex_normal(int s) const {
  const auto& v = set_.simplices()[s];
  const Point e = set_.points()[v[1]] - set_.points()[v[0]];
  const Point n = dim_ == 2 ? Point(-e.y(), e.x(), 0.0)
                            : Point(e.cross(set_.points()[v[2]] - set_.points()[v[0]]));
  return n.normalized();
}

Point DiscreteSurface::closest_point(const Point& p) const {
  return set_.closest(p).point;
}

Point DiscreteSurface::normal(const Point& q) const {
  const SimplexSet::Hit h = set_.closest(q);
  const auto& v = set_.simplices()[h.simplex];
  return blend(h.weights, {point_normal_[v[0]], point_normal_[v[1]], point_normal_[v[2]]},
               set_.corners(), simplex_normal(h.simplex));
}

DiscreteCurve::DiscreteCurve(std::vector<Point> points, std::vector<std::array<int, 3>> segments)
    : set_(std::move(points), std::move(segments), 2) {
  std::vector<Point> weighted;
  for (int s = 0; s < static_cast<int>(set_.simplices().size()); ++s)
    weighted.push_back(set_.points()[set_.simplices()[s][1]] -
                       set_.points()[set_.simplices()[s][0]]);
  point_tangent_ = point_average(set_, weighted);
}

Point DiscreteCurve::segment_tangent(int s) const {
  return (set_.points()[set_.simplices()[s][1]] - set_.points()[set_.simplices()[s][0]])
      .normalized();
}

Point DiscreteCurve::closest_point(const Point& p) const {
  return set_.closest(p).point;
}

Point DiscreteCurve::tangent(const Point& q) const {
  const SimplexSet::Hit h = set_.closest(q);
  const auto& v = set_.simplices()[h.simplex];
  return blend(h.weights, {point_tangent_[v[0]], point_tangent_[v[1]], Point::Zero()}, 2,
               segment_tangent(h.simplex));
}

}  // namespace neomesh

namespace neomesh {

namespace {

// Phong tessellation's shape factor that makes a patch through points of a smooth surface, with
// its normals, agree with it to second order (discrete_geometry.hpp).
constexpr double kPhongAlpha = 0.5;
// Sample points per edge of a triangle at which its patch's area element is checked.
constexpr int kPhongFoldSamples = 8;
// Newton's method for the closest point: at most this many steps, crossings into a neighbouring
// triangle before an edge is held (a closest point on an edge, the patches on both sides
// pointing across it), and the parameter step (barycentric, relative to 1) that ends it.
constexpr int kPhongNewtonSteps = 60;
constexpr int kPhongCrossings = 8;
constexpr double kPhongStepTolerance = 1e-15;

// Per point, Max's normal: Σ over its triangles of e₁ × e₂ / (|e₁|² |e₂|²), the two edges from
// the point, signs aligned with the sum so far; exact for points on a sphere whose triangles
// close around the point.
std::vector<Point> max_normals(const SimplexSet& set) {
  std::vector<Point> sum(set.points().size(), Point::Zero());
  for (const auto& t : set.simplices())
    for (int k = 0; k < 3; ++k) {
      const Point& x = set.points()[t[k]];
      const Point e1 = set.points()[t[(k + 1) % 3]] - x, e2 = set.points()[t[(k + 2) % 3]] - x;
      const Point term = e1.cross(e2) / (e1.squaredNorm() * e2.squaredNorm());
      Point& at = sum[t[k]];
      at += at.dot(term) < 0 ? -term : term;
    }
  for (Point& n : sum)
    if (n.norm() > 0) n.normalize();
  return sum;
}

// Per triangle, the triangle across the edge opposite each corner (-1: none, or more than one).
std::vector<std::array<int, 3>> triangle_neighbours(const SimplexSet& set) {
  const auto& t = set.simplices();
  std::map<std::pair<int, int>, std::vector<std::pair<int, int>>> by_edge;  // (triangle, corner)
  for (int s = 0; s < static_cast<int>(t.size()); ++s)
    for (int k = 0; k < 3; ++k) {
      const int a = t[s][(k + 1) % 3], b = t[s][(k + 2) % 3];
      by_edge[{std::min(a, b), std::max(a, b)}].emplace_back(s, k);
    }
  std::vector<std::array<int, 3>> out(t.size(), {-1, -1, -1});
  for (const auto& [edge, sides] : by_edge)
    if (sides.size() == 2) {
      out[sides[0].first][sides[0].second] = sides[1].first;
      out[sides[1].first][sides[1].second] = sides[0].first;
    }
  return out;
}

// d(b)/du, d(b)/dv for b = (1 − u − v, u, v); and the direction in (u, v) along the edge
// opposite corner k.
constexpr std::array<double, 3> kBu{-1, 1, 0}, kBv{-1, 0, 1};
constexpr std::array<std::array<double, 2>, 3> kEdgeDirection{{{1, -1}, {0, 1}, {1, 0}}};

std::array<double, 3> barycentric(double u, double v) {
  return {1 - u - v, u, v};
}

}  // namespace

PhongSurface::PhongSurface(std::vector<Point> points, std::vector<std::array<int, 3>> triangles,
                           double min_area_ratio)
    : set_(std::move(points), std::move(triangles), 3),
      normal_(max_normals(set_)),
      alpha_(set_.points().size(), kPhongAlpha),
      neighbour_(triangle_neighbours(set_)) {
  for (std::size_t i = 0; i < normal_.size(); ++i)
    if (normal_[i].norm() == 0) alpha_[i] = 0;
  // Flattening a triangle's points can shrink a neighbour's area element: again until none is
  // below the bound (each round flattens a point, or ends).
  for (bool changed = true; changed;) {
    changed = false;
    for (int s = 0; s < static_cast<int>(set_.simplices().size()); ++s) {
      const auto& t = set_.simplices()[s];
      if (alpha_[t[0]] == 0 && alpha_[t[1]] == 0 && alpha_[t[2]] == 0) continue;
      if (area_ratio(s) >= min_area_ratio) continue;
      for (int k = 0; k < 3; ++k) alpha_[t[k]] = 0;
      changed = true;
    }
  }
}

double PhongSurface::area_ratio(int triangle) const {
  const auto& t = set_.simplices()[triangle];
  const Point& x = set_.points()[t[0]];
  const Point flat = (set_.points()[t[1]] - x).cross(set_.points()[t[2]] - x);
  double least = std::numeric_limits<double>::infinity();
  for (int i = 0; i <= kPhongFoldSamples; ++i)
    for (int j = 0; i + j <= kPhongFoldSamples; ++j) {
      const Patch at =
          evaluate(triangle, double(i) / kPhongFoldSamples, double(j) / kPhongFoldSamples);
      least = std::min(least, at.qu.cross(at.qv).dot(flat) / flat.squaredNorm());
    }
  return least;
}

std::string PhongSurface::describe() const {
  const int flat = flat_points();
  return flat == 0 ? std::string("Phong tessellation of the input's boundary")
                   : fmt::format(
                         "Phong tessellation of the input's boundary, flat at {} of its {} "
                         "points (where it could fold)",
                         flat, alpha_.size());
}

int PhongSurface::flat_points() const {
  return static_cast<int>(std::count(alpha_.begin(), alpha_.end(), 0.0));
}

PhongSurface::Patch PhongSurface::evaluate(int triangle, double u, double v) const {
  const auto& t = set_.simplices()[triangle];
  const Point &x0 = set_.points()[t[0]], &x1 = set_.points()[t[1]], &x2 = set_.points()[t[2]];
  const Point e1 = x1 - x0, e2 = x2 - x0;
  const std::array<double, 3> b = barycentric(u, v);
  const Point p = x0 + u * e1 + v * e2;
  Patch out{triangle, u, v, p, e1, e2, Point::Zero(), Point::Zero(), Point::Zero()};
  for (int i = 0; i < 3; ++i) {
    const double a = alpha_[t[i]];
    if (a == 0) continue;
    // f = bᵢ ((p − xᵢ)·nᵢ) and its derivatives; q = p − Σ αᵢ f nᵢ.
    const Point& n = normal_[t[i]];
    const double h = (p - set_.points()[t[i]]).dot(n), hu = e1.dot(n), hv = e2.dot(n);
    out.q -= a * b[i] * h * n;
    out.qu -= a * (kBu[i] * h + b[i] * hu) * n;
    out.qv -= a * (kBv[i] * h + b[i] * hv) * n;
    out.quu -= a * 2 * kBu[i] * hu * n;
    out.quv -= a * (kBu[i] * hv + kBv[i] * hu) * n;
    out.qvv -= a * 2 * kBv[i] * hv * n;
  }
  return out;
}

// Newton's method on ½|q(u, v) − p|² in the parameters of one triangle at a time (Gauss-Newton
// where the Hessian is not positive definite). A step leaving the triangle stops at its edge and
// goes on in the neighbour there (the edge's curve is the same on both sides); at a border, or
// after kPhongCrossings crossings, the edge is held and the step taken along it.
PhongSurface::Patch PhongSurface::locate(const Point& p) const {
  const SimplexSet::Hit hit = set_.closest(p);
  int t = hit.simplex, crossings = 0, held = -1;
  double u = hit.weights[1], v = hit.weights[2];
  for (int step = 0; step < kPhongNewtonSteps; ++step) {
    const Patch at = evaluate(t, u, v);
    const Point r = at.q - p;
    const Eigen::Vector2d g(at.qu.dot(r), at.qv.dot(r));
    Eigen::Matrix2d H;
    H << at.qu.dot(at.qu) + at.quu.dot(r), at.qu.dot(at.qv) + at.quv.dot(r),
        at.qu.dot(at.qv) + at.quv.dot(r), at.qv.dot(at.qv) + at.qvv.dot(r);
    if (!(H(0, 0) > 0 && H.determinant() > 0))
      H << at.qu.dot(at.qu), at.qu.dot(at.qv), at.qu.dot(at.qv), at.qv.dot(at.qv);
    Eigen::Vector2d d = -H.ldlt().solve(g);
    if (held >= 0 && kBu[held] * d[0] + kBv[held] * d[1] < 0) {  // would leave across `held`
      const Eigen::Vector2d e(kEdgeDirection[held][0], kEdgeDirection[held][1]);
      const double curvature = e.dot(H * e);
      d = curvature > 0 ? Eigen::Vector2d(-e.dot(g) / curvature * e) : Eigen::Vector2d::Zero();
    } else {
      held = -1;
    }
    // The largest fraction of the step that keeps every weight ≥ 0, and the weight that ends it.
    const std::array<double, 3> b = barycentric(u, v);
    double fraction = 1;
    int leaves = -1;
    for (int k = 0; k < 3; ++k) {
      const double db = kBu[k] * d[0] + kBv[k] * d[1];
      if (k != held && db < 0 && b[k] + db < 0 && -b[k] / db < fraction) {
        fraction = std::max(0.0, -b[k] / db);
        leaves = k;
      }
    }
    u += fraction * d[0];
    v += fraction * d[1];
    if (held >= 0 || leaves >= 0) {  // onto the edge exactly
      std::array<double, 3> w = barycentric(u, v);
      for (double& x : w) x = std::max(x, 0.0);
      if (leaves >= 0) w[leaves] = 0;
      if (held >= 0) w[held] = 0;
      const double sum = w[0] + w[1] + w[2];
      u = w[1] / sum;
      v = w[2] / sum;
    }
    if (leaves < 0) {
      if (fraction * d.norm() <= kPhongStepTolerance) break;
      continue;
    }
    const int next = neighbour_[t][leaves];
    if (next < 0 || crossings >= kPhongCrossings) {
      held = leaves;
      continue;
    }
    // The same point in the neighbour's weights: by vertex, 0 for the corner across the edge.
    const std::array<double, 3> w = barycentric(u, v);
    std::array<double, 3> to{0, 0, 0};
    for (int k = 0; k < 3; ++k)
      for (int j = 0; j < 3; ++j)
        if (set_.simplices()[next][j] == set_.simplices()[t][k]) to[j] = w[k];
    t = next;
    u = to[1];
    v = to[2];
    held = -1;
    ++crossings;
  }
  return evaluate(t, u, v);
}

Point PhongSurface::closest_point(const Point& p) const {
  return locate(p).q;
}

// The vertex normals interpolated, Phong shading's normal, signed as the patch's: continuous
// across edges and vertices, where the patches' own normals turn (C0, discrete_geometry.hpp). A
// vertex moving in the plane it gives leaves the patch by the angle between the two normals, to
// first order; the projection takes it back.
Point PhongSurface::normal_at(const Patch& at) const {
  const auto& t = set_.simplices()[at.triangle];
  return blend(barycentric(at.u, at.v), {normal_[t[0]], normal_[t[1]], normal_[t[2]]}, 3,
               at.qu.cross(at.qv).normalized());
}

Point PhongSurface::normal(const Point& q) const {
  return normal_at(locate(q));
}

// ∇n of normal() on the tangent plane, symmetrized (only uᵀ S u bends a step): with
// m = Σ bᵢ nᵢ and n = m/|m|, n_u = (I − n nᵀ) m_u / |m|; a tangent vector e has parameters
// I⁻¹ Jᵀ e (J = [q_u q_v], I = JᵀJ), so ∇n = [n_u n_v] I⁻¹ Jᵀ.
Matrix3 PhongSurface::shape_operator(const Point& q) const {
  const Patch at = locate(q);
  const auto& t = set_.simplices()[at.triangle];
  const Point n = normal_at(at);
  const std::array<double, 3> b = barycentric(at.u, at.v);
  Point m = Point::Zero(), mu = Point::Zero(), mv = Point::Zero();
  for (int i = 0; i < 3; ++i) {
    const Point ni = normal_[t[i]].dot(n) < 0 ? Point(-normal_[t[i]]) : normal_[t[i]];
    m += b[i] * ni;
    mu += kBu[i] * ni;
    mv += kBv[i] * ni;
  }
  const Matrix3 P = Matrix3::Identity() - n * n.transpose();
  Eigen::Matrix<double, 3, 2> J, dn;
  J << at.qu, at.qv;
  dn << P * mu / m.norm(), P * mv / m.norm();
  const Matrix3 gradient = dn * (J.transpose() * J).inverse() * J.transpose();
  return P * (0.5 * (gradient + gradient.transpose())) * P;
}

}  // namespace neomesh
