#include "boundary/features.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <span>
#include <tuple>

#include <Eigen/Geometry>

#include "boundary/shape.hpp"
#include "core/union_find.hpp"
#include "geometry/surface_orientation.hpp"

namespace neomesh {

namespace {

// The angle by which a polyline turns at b coming from a and going on to c, in degrees.
double turning_angle(const Point& a, const Point& b, const Point& c) {
  const Point d1 = b - a, d2 = c - b;
  const double cosine = d1.dot(d2) / (d1.norm() * d2.norm());
  return std::acos(std::clamp(cosine, -1.0, 1.0)) * 180.0 / M_PI;
}

// Per boundary vertex, its facets (CSR).
struct Incidence {
  std::vector<PetscInt> offsets, facets;
  std::span<const PetscInt> of(PetscInt v) const {
    return {facets.data() + offsets[v], static_cast<std::size_t>(offsets[v + 1] - offsets[v])};
  }
};

Incidence incidence(const BoundarySurface& s) {
  Incidence in;
  in.offsets.assign(s.num_vertices() + 1, 0);
  for (PetscInt f = 0; f < s.num_facets(); ++f)
    for (PetscInt v : s.facet(f)) ++in.offsets[v + 1];
  std::partial_sum(in.offsets.begin(), in.offsets.end(), in.offsets.begin());
  in.facets.resize(in.offsets.back());
  std::vector<PetscInt> next(in.offsets.begin(), in.offsets.end() - 1);
  for (PetscInt f = 0; f < s.num_facets(); ++f)
    for (PetscInt v : s.facet(f)) in.facets[next[v]++] = f;
  return in;
}

// True if facets f and g lie in one part that is one smooth shape: no feature between them.
struct SmoothParts {
  const BoundarySurface& s;
  std::span<const std::uint8_t> smooth;
  bool same_smooth(PetscInt f, PetscInt g) const {
    const int p = s.facet_part[f];
    return p >= 0 && p == s.facet_part[g] && static_cast<std::size_t>(p) < smooth.size() &&
           smooth[p];
  }
};

void features_2d(const BoundarySurface& s, double angle, const SmoothParts& parts,
                 BoundaryFeatures& out) {
  const Incidence in = incidence(s);
  const PetscInt nv = s.num_vertices();
  auto other_end = [&](PetscInt f, PetscInt v) {
    const auto e = s.facet(f);
    return e[0] == v ? e[1] : e[0];
  };
  std::vector<std::uint8_t> corner(nv, 0);
  for (PetscInt v = 0; v < nv; ++v) {
    const auto edges = in.of(v);
    corner[v] = edges.size() != 2 || s.facet_part[edges[0]] != s.facet_part[edges[1]] ||
                (!parts.same_smooth(edges[0], edges[1]) &&
                 turning_angle(surface_point(s, other_end(edges[0], v)), surface_point(s, v),
                               surface_point(s, other_end(edges[1], v))) > angle);
  }
  UnionFind patches(s.num_facets());
  for (PetscInt v = 0; v < nv; ++v)
    if (!corner[v]) patches.join(in.of(v)[0], in.of(v)[1]);
  out.facet_patch = patches.labels(out.num_patches);
  for (PetscInt v = 0; v < nv; ++v) {
    out.kind[v] = corner[v] ? VertexFeature::Corner : VertexFeature::Surface;
    if (!corner[v]) out.patch[v] = out.facet_patch[in.of(v)[0]];
  }
}

void features_3d(const BoundarySurface& s, double angle, const SmoothParts& parts, bool folds,
                 BoundaryFeatures& out) {
  const PetscInt nv = s.num_vertices();
  // Every facet's edges as (smaller vertex, larger vertex, facet, 1 if the facet runs from the
  // larger to the smaller), sorted so that the facets of an edge are neighbours.
  struct EdgeUse {
    PetscInt a, b, facet;
    bool reversed;
  };
  std::vector<EdgeUse> uses;
  for (PetscInt f = 0; f < s.num_facets(); ++f) {
    const auto v = s.facet(f);
    for (std::size_t i = 0; i < v.size(); ++i) {
      const PetscInt p = v[i], q = v[(i + 1) % v.size()];
      uses.push_back({std::min(p, q), std::max(p, q), f, p > q});
    }
  }
  std::sort(uses.begin(), uses.end(), [](const EdgeUse& x, const EdgeUse& y) {
    return std::tie(x.a, x.b, x.facet) < std::tie(y.a, y.b, y.facet);
  });
  std::vector<Point> normal(s.num_facets());
  for (PetscInt f = 0; f < s.num_facets(); ++f) normal[f] = facet_area_normal(s, f).normalized();
  if (folds) {
    const std::vector<std::uint8_t> folded =
        folded_polygons(s.facet_offsets, s.facet_vertices, s.coords, nullptr);
    for (PetscInt f = 0; f < s.num_facets(); ++f)
      if (folded[f]) normal[f] = -normal[f];
  }

  struct Edge {
    PetscInt a, b, first, last;  // uses[first, last)
    bool ridge;
  };
  std::vector<Edge> edges;
  UnionFind patches(s.num_facets());
  for (std::size_t i = 0; i < uses.size();) {
    std::size_t j = i + 1;
    while (j < uses.size() && uses[j].a == uses[i].a && uses[j].b == uses[i].b) ++j;
    bool ridge = j - i != 2;
    if (!ridge) {
      const EdgeUse &x = uses[i], &y = uses[i + 1];
      // Consistently oriented neighbours run along their common edge in opposite directions.
      const Point ny = x.reversed != y.reversed ? normal[y.facet] : Point(-normal[y.facet]);
      const double between =
          std::acos(std::clamp(normal[x.facet].dot(ny), -1.0, 1.0)) * 180.0 / M_PI;
      ridge = s.facet_part[x.facet] != s.facet_part[y.facet] ||
              (between > angle && !parts.same_smooth(x.facet, y.facet));
      if (!ridge) patches.join(x.facet, y.facet);
    }
    edges.push_back(
        {uses[i].a, uses[i].b, static_cast<PetscInt>(i), static_cast<PetscInt>(j), ridge});
    i = j;
  }
  out.facet_patch = patches.labels(out.num_patches);

  // The two patches a ridge edge separates (sorted), or (-1, -1).
  auto sides = [&](const Edge& e) -> std::array<int, 2> {
    if (e.last - e.first != 2) return {-1, -1};
    const int p = out.facet_patch[uses[e.first].facet],
              q = out.facet_patch[uses[e.first + 1].facet];
    return {std::min(p, q), std::max(p, q)};
  };
  std::vector<std::vector<PetscInt>> ridge_edges_at(nv);
  for (std::size_t e = 0; e < edges.size(); ++e)
    if (edges[e].ridge) {
      ridge_edges_at[edges[e].a].push_back(static_cast<PetscInt>(e));
      ridge_edges_at[edges[e].b].push_back(static_cast<PetscInt>(e));
    }
  const Incidence in = incidence(s);
  UnionFind ridges(edges.size());
  for (PetscInt v = 0; v < nv; ++v) {
    const auto& at = ridge_edges_at[v];
    if (at.empty()) {
      out.kind[v] = VertexFeature::Surface;
      out.patch[v] = out.facet_patch[in.of(v)[0]];
      continue;
    }
    out.kind[v] = VertexFeature::Corner;
    if (at.size() != 2) continue;
    const Edge &e1 = edges[at[0]], &e2 = edges[at[1]];
    const PetscInt a = e1.a == v ? e1.b : e1.a, c = e2.a == v ? e2.b : e2.a;
    if (sides(e1) != sides(e2) ||
        turning_angle(surface_point(s, a), surface_point(s, v), surface_point(s, c)) > angle)
      continue;
    out.kind[v] = VertexFeature::Ridge;
    ridges.join(at[0], at[1]);
  }
  // Number the ridges by their edges; vertices take their edges' ridge.
  std::vector<int> ridge_of_edge(edges.size(), -1);
  std::vector<int> label(edges.size(), -1);
  for (std::size_t e = 0; e < edges.size(); ++e) {
    if (!edges[e].ridge) continue;
    const std::size_t root = ridges.find(e);
    if (label[root] < 0) {
      label[root] = static_cast<int>(out.ridge_edges.size());
      out.ridge_edges.emplace_back();
      out.ridge_patches.push_back(sides(edges[e]));
    }
    ridge_of_edge[e] = label[root];
    out.ridge_edges[label[root]].push_back({edges[e].a, edges[e].b});
  }
  for (PetscInt v = 0; v < nv; ++v)
    if (out.kind[v] == VertexFeature::Ridge) out.ridge[v] = ridge_of_edge[ridge_edges_at[v][0]];
}

}  // namespace

Point facet_area_normal(const BoundarySurface& s, PetscInt f) {
  const auto v = s.facet(f);
  if (v.size() == 2) {
    const Point e = surface_point(s, v[1]) - surface_point(s, v[0]);
    return {-e.y(), e.x(), 0.0};
  }
  Point n = Point::Zero();
  for (std::size_t i = 0; i < v.size(); ++i)
    n += surface_point(s, v[i]).cross(surface_point(s, v[(i + 1) % v.size()]));
  return n;
}

PetscInt BoundaryFeatures::count(VertexFeature k) const {
  return static_cast<PetscInt>(std::count(kind.begin(), kind.end(), k));
}

BoundaryFeatures find_features(const BoundarySurface& surface, double feature_angle_degrees,
                               std::span<const std::uint8_t> smooth_part, bool folds) {
  const SmoothParts parts{surface, smooth_part};
  BoundaryFeatures out;
  const PetscInt nv = surface.num_vertices();
  out.kind.assign(nv, VertexFeature::Corner);
  out.patch.assign(nv, -1);
  out.ridge.assign(nv, -1);
  if (surface.dim == 2)
    features_2d(surface, feature_angle_degrees, parts, out);
  else
    features_3d(surface, feature_angle_degrees, parts, folds, out);
  out.patch_part.assign(out.num_patches, -1);
  for (PetscInt f = 0; f < surface.num_facets(); ++f)
    out.patch_part[out.facet_patch[f]] = surface.facet_part[f];
  return out;
}

}  // namespace neomesh
