#include "boundary/discrete_geometry.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Geometry>

#include "boundary/features.hpp"

namespace neomesh {

namespace {

// A simplex registered in more grid cells than this is checked on every query instead.
constexpr long long kMaxCellsPerSimplex = 4096;

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

void SimplexSet::visit(const Cell& c, const Point& p, Hit& best) const {
  const auto it = grid_.find(key(c));
  if (it == grid_.end()) return;
  for (int s : it->second) {
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
          if (ring == r) visit({i, j, k}, p, best);
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
