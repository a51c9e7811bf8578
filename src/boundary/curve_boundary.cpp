#include "boundary/curve_boundary.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <set>

#include "boundary/chart_surface.hpp"
#include "boundary/shape.hpp"
#include "core/error.hpp"

namespace neomesh {

namespace {

struct Geometry {
  std::string part;
  std::unique_ptr<Surface> surface;
  std::vector<char> holds;  // per vertex: 1 if the part has it
};

// The boundary facets (sides of one cell only) by their vertices, as a cycle.
std::vector<std::vector<PetscInt>> boundary_facets(const InputMesh& mesh) {
  std::map<std::array<PetscInt, 4>, std::pair<int, std::vector<PetscInt>>> sides;
  for (PetscInt c = 0; c < mesh.num_cells(); ++c) {
    const CellFacts& f = facts(mesh.cell_types[c]);
    const PetscInt* v = mesh.cell_vertices.data() + mesh.cell_offsets[c];
    for (int k = 0; k < f.num_facets; ++k) {
      const FacetVertices& side = f.facets[k];
      std::array<PetscInt, 4> key = {-1, -1, -1, -1};
      std::vector<PetscInt> cycle;
      for (int i = 0; i < side.size; ++i) cycle.push_back(key[i] = v[side.vertices[i]]);
      sort_facet_key(key, side.size);
      auto& entry = sides[key];
      if (entry.first++ == 0) entry.second = std::move(cycle);
    }
  }
  std::vector<std::vector<PetscInt>> out;
  for (auto& [key, entry] : sides)
    if (entry.first == 1) out.push_back(std::move(entry.second));
  return out;
}

std::vector<Geometry> geometries(const InputMesh& mesh,
                                 const std::vector<std::pair<std::string, std::string>>& shapes) {
  std::vector<Geometry> out;
  const auto part_vertices = [&](const std::string& part) {
    std::vector<char> holds(mesh.num_vertices(), 0);
    bool found = false;
    for (const PhysicalGroup& g : mesh.groups) {
      if (g.dim != mesh.dim - 1 || g.name != part) continue;
      found = true;
      for (PetscInt k = 0; k < mesh.facets.size(); ++k)
        if (mesh.facets.tags[k] == g.tag)
          for (PetscInt i = mesh.facets.offsets[k]; i < mesh.facets.offsets[k + 1]; ++i)
            holds[mesh.facets.vertices[i]] = 1;
    }
    for (const VertexSet& set : mesh.vertex_sets)
      if (set.name == part) {
        found = true;
        for (std::int64_t v : set.vertices) holds[v] = 1;
      }
    return found ? holds : std::vector<char>{};
  };
  for (const auto& [part, spec] : shapes) {
    std::vector<char> holds = part_vertices(part);
    if (holds.empty()) fail("--shape {}={}: the mesh has no boundary part '{}'", part, spec, part);
    out.push_back({part, parse_shape(spec, mesh.dim), std::move(holds)});
  }
  for (const VertexSet& set : mesh.vertex_sets) {
    if (set.chart.empty()) continue;
    if (std::any_of(shapes.begin(), shapes.end(),
                    [&](const auto& s) { return s.first == set.name; }))
      continue;  // an explicit shape wins over the chart
    const auto chart = std::find_if(mesh.charts.begin(), mesh.charts.end(),
                                    [&](const Chart& c) { return c.name == set.chart; });
    if (chart == mesh.charts.end())
      fail("part '{}' is attached to chart '{}', which the input does not give", set.name,
           set.chart);
    out.push_back({set.name, chart_surface(*chart, mesh.dim, set.name), part_vertices(set.name)});
  }
  return out;
}

}  // namespace

namespace {

// Carries the boundary's move onto its geometry (`before` → the points now, on the points
// flagged in `boundary`) into the interior: each other high-order node (the vertices inside are
// the mesher's design, and the targets' corners, and stay) moves by the inverse-distance
// weighted mean (weights 1/r⁴) of the boundary points' moves, faded out by (1 − t)² with t its
// distance from the nearest boundary point over twice that point's spacing (its distance to the
// nearest other boundary point, doubled: about a boundary edge). Bending a boundary edge by its
// sagitta folds the thin cells of a boundary layer behind it, whose thickness is a fraction of
// that; carried so, each layer bends with the boundary as a whole and the cells away from it,
// as large as the boundary edges, take up the difference.
void carry_into_interior(InputMesh& mesh, const std::vector<double>& before,
                         const std::vector<char>& boundary) {
  const int d = mesh.coord_dim();
  std::vector<double> x = curved_point_coordinates(mesh);
  const auto n = static_cast<PetscInt>(boundary.size());
  const PetscInt nv = mesh.num_vertices();
  std::vector<PetscInt> on;
  bool moved = false;
  for (PetscInt i = 0; i < n; ++i)
    if (boundary[i]) {
      on.push_back(i);
      for (int j = 0; j < d; ++j) moved = moved || x[d * i + j] != before[d * i + j];
    }
  if (!moved || on.empty()) return;
  const auto distance2 = [&](PetscInt a, PetscInt b) {
    double r2 = 0.0;
    for (int j = 0; j < d; ++j)
      r2 += (before[d * a + j] - before[d * b + j]) * (before[d * a + j] - before[d * b + j]);
    return r2;
  };
  std::vector<double> spacing(on.size(), std::numeric_limits<double>::infinity());
#pragma omp parallel for schedule(static)
  for (std::size_t k = 0; k < on.size(); ++k)
    for (std::size_t l = 0; l < on.size(); ++l)
      if (l != k) spacing[k] = std::min(spacing[k], 2.0 * std::sqrt(distance2(on[k], on[l])));
#pragma omp parallel for schedule(dynamic, 64)
  for (PetscInt i = 0; i < n; ++i) {
    if (boundary[i] || i < nv) continue;
    std::array<double, 3> sum{};
    double weights = 0.0, nearest = std::numeric_limits<double>::infinity();
    std::size_t closest = 0;
    for (std::size_t k = 0; k < on.size(); ++k) {
      const double r2 = distance2(i, on[k]);
      if (r2 < nearest) nearest = r2, closest = k;
      const double w = 1.0 / (r2 * r2);
      weights += w;
      for (int j = 0; j < d; ++j) sum[j] += w * (x[d * on[k] + j] - before[d * on[k] + j]);
    }
    const double t = std::sqrt(nearest) / (2.0 * spacing[closest]);
    if (!(t < 1.0) || !(weights > 0.0) || !std::isfinite(weights)) continue;
    const double fade = (1.0 - t) * (1.0 - t);
    for (int j = 0; j < d; ++j) x[d * i + j] = before[d * i + j] + fade * sum[j] / weights;
  }
  set_curved_point_coordinates(mesh, x);
}

}  // namespace

CurvedBoundarySummary place_boundary_nodes(
    InputMesh& mesh, const std::vector<std::pair<std::string, std::string>>& shapes) {
  if (!mesh.curved()) fail("place_boundary_nodes: the mesh has no second-order nodes");
  if (mesh.plane) fail("curving a 2D mesh that lies off the plane z = 0 is not supported");
  const std::vector<Geometry> geometry = geometries(mesh, shapes);
  const std::vector<double> before = curved_point_coordinates(mesh);
  const int cd = mesh.coord_dim();
  const auto vertex = [&](PetscInt v) {
    Point p = Point::Zero();
    for (int j = 0; j < cd; ++j) p[j] = mesh.coords[cd * v + j];
    return p;
  };
  const auto node = [&](PetscInt n) {
    return Point(mesh.high_order.xyz[3 * n], mesh.high_order.xyz[3 * n + 1],
                 mesh.high_order.xyz[3 * n + 2]);
  };
  // The geometries holding all of `corners`, and the point of theirs closest to p: on one, its
  // closest point; on two, that of their intersection (3D); else none.
  const auto on_geometry = [&](const std::vector<PetscInt>& corners, const Point& p,
                               Point& q) -> std::vector<const Surface*> {
    std::vector<const Surface*> on;
    // Parts given the same shape (the six sides of a cube mapped onto a sphere) are one.
    for (const Geometry& g : geometry)
      if (std::all_of(corners.begin(), corners.end(), [&](PetscInt v) { return g.holds[v]; }) &&
          std::none_of(on.begin(), on.end(),
                       [&](const Surface* s) { return s->describe() == g.surface->describe(); }))
        on.push_back(g.surface.get());
    if (on.size() == 1) q = on[0]->closest_point(p);
    if (on.size() == 2 && mesh.dim == 3) q = make_intersection(*on[0], *on[1])->closest_point(p);
    if (on.size() > 2 || (on.size() == 2 && mesh.dim != 3)) on.clear();
    return on;
  };
  const auto distance_after = [](const std::vector<const Surface*>& on, const Point& q) {
    double d = 0.0;
    for (const Surface* s : on) d = std::max(d, (s->closest_point(q) - q).norm());
    return d;
  };

  const std::vector<std::vector<PetscInt>> facets = boundary_facets(mesh);
  std::vector<double> shortest(mesh.num_vertices(), std::numeric_limits<double>::infinity());
  for (const auto& f : facets)
    for (std::size_t i = 0; i < f.size(); ++i) {
      const PetscInt a = f[i], b = f[(i + 1) % f.size()];
      const double length = (vertex(a) - vertex(b)).norm();
      shortest[a] = std::min(shortest[a], length);
      shortest[b] = std::min(shortest[b], length);
    }

  CurvedBoundarySummary summary;
  std::vector<char> moved(mesh.num_vertices(), 0);
  for (const auto& f : facets)
    for (PetscInt v : f) {
      if (moved[v]) continue;
      moved[v] = 1;
      Point q;
      const auto on = on_geometry({v}, vertex(v), q);
      if (on.empty()) continue;
      const double move = (q - vertex(v)).norm();
      if (move > 0.25 * shortest[v])
        fail(
            "boundary vertex {} (0-based) is {:.3g} off {}, more than a quarter of its shortest "
            "boundary edge: that geometry does not describe its part",
            v, move, on[0]->describe());
      for (int j = 0; j < cd; ++j) mesh.coords[cd * v + j] = q[j];
      summary.max_vertex_move = std::max(summary.max_vertex_move, move);
      summary.max_off_geometry = std::max(summary.max_off_geometry, distance_after(on, q));
      ++summary.vertices_on_geometry;
    }

  // The second-order nodes of the boundary's edges and (hexahedron27) faces, by their corners.
  std::map<std::array<PetscInt, 2>, PetscInt> edge_node;
  std::map<std::array<PetscInt, 4>, PetscInt> face_node;
  std::array<PetscInt, kMaxCurvedNodes> p{};
  const PetscInt nv = mesh.num_vertices();
  for (PetscInt c = 0; c < mesh.num_cells(); ++c) {
    curved_cell_points(mesh, c, p.data());
    const CurvedFacts& f = facts(mesh.high_order.types[c]);
    const int corners = num_vertices(f.linear);
    for (std::size_t e = 0; e < f.edges.size(); ++e) {
      std::array<PetscInt, 2> key = {p[f.edges[e][0]], p[f.edges[e][1]]};
      std::sort(key.begin(), key.end());
      edge_node.emplace(key, p[corners + e] - nv);
    }
    for (std::size_t k = 0; k < f.faces.size(); ++k) {
      std::array<PetscInt, 4> key;
      for (int i = 0; i < 4; ++i) key[i] = p[f.faces[k][i]];
      std::sort(key.begin(), key.end());
      face_node.emplace(key, p[corners + f.edges.size() + k] - nv);
    }
  }
  std::set<PetscInt> placed;
  const auto place = [&](PetscInt n, const std::vector<PetscInt>& corners) {
    if (!placed.insert(n).second) return;
    Point q;
    const auto on = on_geometry(corners, node(n), q);
    if (on.empty()) {
      ++summary.nodes_straight;
      return;
    }
    for (int j = 0; j < 3; ++j) mesh.high_order.xyz[3 * n + j] = q[j];
    summary.max_off_geometry = std::max(summary.max_off_geometry, distance_after(on, q));
    ++summary.nodes_on_geometry;
  };
  for (const auto& f : facets) {
    const int n = static_cast<int>(f.size());
    for (int i = 0; i < (n == 2 ? 1 : n); ++i) {
      const PetscInt a = f[i], b = f[(i + 1) % n];
      place(edge_node.at({std::min(a, b), std::max(a, b)}), {a, b});
    }
    if (n == 4) {
      std::array<PetscInt, 4> key = {f[0], f[1], f[2], f[3]};
      std::sort(key.begin(), key.end());
      place(face_node.at(key), f);
    }
  }
  std::vector<char> boundary(mesh.num_points(), 0);
  for (PetscInt v = 0; v < nv; ++v) boundary[v] = moved[v];
  for (PetscInt node : placed) boundary[nv + node] = 1;
  carry_into_interior(mesh, before, boundary);
  return summary;
}

}  // namespace neomesh
