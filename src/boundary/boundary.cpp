#include "boundary/boundary.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <span>

#include <Eigen/Geometry>

#include "boundary/boundary_distance.hpp"
#include "boundary/chart_surface.hpp"
#include "boundary/discrete_geometry.hpp"
#include "boundary/features.hpp"
#include "boundary/shape.hpp"
#include "core/error.hpp"
#include "mesh/boundary_surface.hpp"

namespace neomesh {

namespace {

// How far (relative to the local mesh size) a vertex of a part may lie from the shape the user
// says the part lies on (--shape).
constexpr double kShapeTolerance = 1e-6;
// FEAT3 projects the vertices of a part with a chart onto it when it loads a mesh (coarse
// meshes are off their curved charts by up to a fifth of a cell; coordinates have 6 digits),
// and so does neomesh. A vertex farther than this many local mesh sizes from its chart is not
// meant to lie on it (a wrong chart file): the part is refused.
constexpr double kChartReach = 4.0;
// Alternating projections onto the charts of a vertex on several (a corner between two
// charts) stop after this many rounds or when a round moves it by less than 1e-15 of its size.
constexpr int kChartRounds = 100;
// A patch is flat if its vertices lie within this (relative to its size) of one plane; a
// plane's normal this close to an axis is taken as that axis, exactly.
constexpr double kFlatTolerance = 1e-12;

// ±e_j exactly if n is that close to an axis; n otherwise.
Point snap_to_axis(const Point& n) {
  for (int j = 0; j < 3; ++j)
    if (std::abs(n[j]) > 1.0 - kFlatTolerance) {
      Point e = Point::Zero();
      e[j] = n[j] > 0 ? 1.0 : -1.0;
      return e;
    }
  return n;
}

// The axis j if v is exactly ±e_j, else -1.
int axis_of(const Point& v) {
  for (int j = 0; j < 3; ++j)
    if (std::abs(v[j]) == 1.0) return j;
  return -1;
}

// Exact charts are analytic: their ridges follow the exact intersection. A SurfaceMesh is a
// triangulation (exact as given, but with kinks Newton's method cannot cross).
bool is_analytic(const Chart& chart) {
  return chart.kind != Chart::Kind::SurfaceMesh;
}

// Circles, spheres and their extrusions have no kinks: a part on one is one patch.
bool is_smooth(const Chart& chart) {
  return chart.kind == Chart::Kind::Circle || chart.kind == Chart::Kind::Sphere;
}

}  // namespace

struct Boundary::Impl {
  const MeshView& view;
  const DofMap& dofs;
  BoundaryOptions options;
  // What the vertices slide on: the view's when the Boundary was built, kept alive here when a
  // surface mesh moves its surface (PlexMesh::move_surface_to_coordinates).
  std::shared_ptr<const BoundarySurface> surface_owner;
  const BoundarySurface& surface;
  BoundaryFeatures features;
  std::vector<std::unique_ptr<Surface>> patch_surface;
  std::vector<std::uint8_t> patch_analytic;  // shape, exact chart or plane
  std::vector<const Chart*> patch_chart;     // the chart the patch lies on, or null
  // Per boundary vertex of a part with a chart: where it is moved before the first step.
  std::vector<std::uint8_t> on_chart;
  std::vector<Point> chart_position;
  std::vector<std::unique_ptr<Curve>> ridge_curve;
  std::vector<std::uint8_t> fixed;  // per local dof
  // The vertices that slide in tangent spaces, with what they slide on (one of the two).
  std::vector<PetscInt> sliding;
  std::vector<const Surface*> sliding_surface;
  std::vector<const Curve*> sliding_curve;
  BoundarySummary summary;
  mutable std::unique_ptr<DistanceToBoundary> input_boundary;  // built when first asked

  Impl(const MeshView& v, const DofMap& d, const BoundaryOptions& o, bool sub_facets)
      : view(v), dofs(d), options(o), surface_owner(v.boundary), surface(*surface_owner) {
    fixed.assign(static_cast<std::size_t>(view.num_vertices) * view.dim, 0);
    if (options.mode == BoundaryMode::Fixed) {
      for (PetscInt u = 0; u < view.num_vertices; ++u)
        if (view.on_boundary[u]) std::fill_n(fixed.begin() + u * view.dim, view.dim, 1);
      return;
    }
    features = find_features(surface, options.feature_angle, smooth_parts(),
                             view.surface || (sub_facets && view.dim == 3));
    build_patches();
    place_on_charts();
    build_ridges();
    assign_vertices();
    summary.corners = features.count(VertexFeature::Corner);
    summary.ridge_vertices = features.count(VertexFeature::Ridge);
    summary.surface_vertices = features.count(VertexFeature::Surface);
    summary.patches = features.num_patches;
    summary.ridges = static_cast<int>(features.ridge_edges.size());
  }

  std::string part_name(int part) const {
    return part >= 0 ? view.parts[part].name : std::string();
  }

  // The shape specs of BoundaryOptions::shapes by part index; fails for names that are no facet
  // group.
  std::map<int, std::string> shapes_by_part() const {
    std::vector<std::uint8_t> has_facets(view.parts.size(), 0);
    for (int part : surface.facet_part)
      if (part >= 0) has_facets[part] = 1;
    std::map<int, std::string> out;
    for (const auto& [name, spec] : options.shapes) {
      int found = -1;
      for (std::size_t p = 0; p < view.parts.size(); ++p)
        if (view.parts[p].name == name && has_facets[p]) found = static_cast<int>(p);
      if (found < 0) {
        std::string names;
        for (std::size_t p = 0; p < view.parts.size(); ++p)
          if (has_facets[p] && !view.parts[p].name.empty())
            names += (names.empty() ? "" : ", ") + view.parts[p].name;
        fail("boundary.shapes: {}={}: the mesh has no boundary part named '{}' ({})", name, spec,
             name, names.empty() ? "it has no named boundary parts" : "its parts: " + names);
      }
      out[found] = spec;
    }
    return out;
  }

  // The chart part `part` lies on, or null; fails for a chart the mesh does not define.
  const Chart* chart_of(int part) const {
    if (part < 0 || surface.part_chart[part].empty()) return nullptr;
    const std::string& name = surface.part_chart[part];
    const auto c = std::find_if(surface.charts.begin(), surface.charts.end(),
                                [&](const Chart& x) { return x.name == name; });
    if (c == surface.charts.end())
      fail("part '{}' is attached to chart '{}', which the mesh file does not define",
           part_name(part), name);
    return &*c;
  }

  // Per part: 1 if it lies on one smooth shape or chart (features.hpp).
  std::vector<std::uint8_t> smooth_parts() const {
    std::vector<std::uint8_t> smooth(view.parts.size(), 0);
    for (std::size_t p = 0; p < smooth.size(); ++p)
      if (const Chart* c = chart_of(static_cast<int>(p))) smooth[p] = is_smooth(*c);
    for (const auto& [part, spec] : shapes_by_part()) smooth[part] = !spec.starts_with("levelset:");
    return smooth;
  }

  // The plane the facets lie in, or null.
  std::unique_ptr<Surface> plane_through(const std::vector<PetscInt>& facets) const {
    Point n = Point::Zero(), lo = Point::Constant(1e300), hi = -lo;
    PetscInt first = surface.facet(facets[0])[0];
    for (PetscInt f : facets) {
      const auto v = surface.facet(f);
      for (std::size_t i = 0; i < v.size(); ++i) {
        const Point p = surface_point(surface, v[i]);
        lo = lo.cwiseMin(p);
        hi = hi.cwiseMax(p);
      }
      const Point m = facet_area_normal(surface, f);
      n += n.dot(m) < 0 ? -m : m;
    }
    if (!(n.norm() > 0)) return nullptr;
    n = snap_to_axis(n.normalized());
    const Point origin = surface_point(surface, first);
    const double size = (hi - lo).norm();
    for (PetscInt f : facets)
      for (PetscInt b : surface.facet(f))
        if (std::abs(n.dot(surface_point(surface, b) - origin)) > kFlatTolerance * size)
          return nullptr;
    return make_plane(origin, n);
  }

  // Largest length of a boundary edge at each boundary vertex: the local mesh size.
  std::vector<double> vertex_sizes() const {
    std::vector<double> size(surface.num_vertices(), 0.0);
    for (PetscInt f = 0; f < surface.num_facets(); ++f) {
      const auto v = surface.facet(f);
      for (std::size_t i = 0; i < v.size(); ++i) {
        const PetscInt a = v[i], b = v[(i + 1) % v.size()];
        const double l = (surface_point(surface, a) - surface_point(surface, b)).norm();
        size[a] = std::max(size[a], l);
        size[b] = std::max(size[b], l);
      }
    }
    return size;
  }

  // Every vertex of the facets must lie on the given geometry; `what` names it in the error.
  void check_on_surface(const Surface& s, const std::vector<PetscInt>& facets,
                        const std::vector<double>& size, const std::string& what) const {
    for (PetscInt f : facets)
      for (PetscInt b : surface.facet(f)) {
        const Point p = surface_point(surface, b);
        const double distance = (s.closest_point(p) - p).norm();
        if (!(distance <= kShapeTolerance * size[b]))
          fail(
              "{}: the vertex at ({:g}, {:g}{}) (number {} in input order) is {:.3g} from it, "
              "more than {:g} of the local mesh size {:.3g}",
              what, p[0], p[1], surface.dim == 3 ? fmt::format(", {:g}", p[2]) : "",
              surface.input_vertex[b] + 1, distance, kShapeTolerance, size[b]);
      }
  }

  void build_patches() {
    const int np = features.num_patches;
    std::vector<std::vector<PetscInt>> facets(np);
    for (PetscInt f = 0; f < surface.num_facets(); ++f)
      facets[features.facet_patch[f]].push_back(f);
    const std::map<int, std::string> shapes = shapes_by_part();
    const std::vector<double> size = vertex_sizes();
    patch_surface.resize(np);
    patch_analytic.assign(np, 0);
    patch_chart.assign(np, nullptr);
    for (int p = 0; p < np; ++p) {
      const int part = features.patch_part[p];
      const std::string name = part_name(part);
      const std::string chart = part >= 0 ? surface.part_chart[part] : std::string();
      const std::string label = part >= 0 ? fmt::format("part '{}'", name) : "unnamed part";
      if (const auto it = shapes.find(part); part >= 0 && it != shapes.end()) {
        patch_surface[p] = parse_shape(it->second, surface.dim);
        patch_analytic[p] = 1;
        check_on_surface(*patch_surface[p], facets[p], size,
                         fmt::format("boundary.shapes: {}={}", name, it->second));
      } else if (!chart.empty()) {
        const Chart* c = chart_of(part);
        patch_surface[p] = chart_surface(*c, surface.dim, name);
        patch_analytic[p] = is_analytic(*c);
        patch_chart[p] = c;
      } else if (auto plane = plane_through(facets[p])) {
        patch_surface[p] = std::move(plane);
        patch_analytic[p] = 1;
      } else {
        FacetSimplices s = facet_simplices(surface, facets[p]);
        if (view.surface && options.surface_geometry == SurfaceGeometry::Phong)
          patch_surface[p] =
              std::make_unique<PhongSurface>(std::move(s.points), std::move(s.simplices));
        else
          patch_surface[p] = std::make_unique<DiscreteSurface>(std::move(s.points),
                                                               std::move(s.simplices), surface.dim);
      }
      summary.patch_geometry.push_back(fmt::format("{}: {}", label, patch_surface[p]->describe()));
    }
  }

  // FEAT3's adapt(): every vertex of a part with a chart onto the chart (a corner between two
  // charts onto both, by alternating projections). Fails for a vertex too far from its chart
  // to be meant to lie on it (kChartReach).
  void place_on_charts() {
    const PetscInt nv = surface.num_vertices();
    std::vector<std::vector<int>> patches_at(nv);  // the chart patches of each vertex's facets
    for (PetscInt f = 0; f < surface.num_facets(); ++f) {
      const int p = features.facet_patch[f];
      if (!patch_chart[p]) continue;
      for (PetscInt b : surface.facet(f))
        if (std::find(patches_at[b].begin(), patches_at[b].end(), p) == patches_at[b].end())
          patches_at[b].push_back(p);
    }
    const std::vector<double> size = vertex_sizes();
    on_chart.assign(nv, 0);
    chart_position.assign(nv, Point::Zero());
    for (PetscInt b = 0; b < nv; ++b) {
      if (patches_at[b].empty()) continue;
      const Point p = surface_point(surface, b);
      Point q = p;
      for (int round = 0; round < kChartRounds; ++round) {
        const Point before = q;
        for (int patch : patches_at[b]) q = patch_surface[patch]->closest_point(q);
        if (patches_at[b].size() == 1 || (q - before).norm() <= 1e-15 * size[b]) break;
      }
      const double distance = (q - p).norm();
      if (!(distance <= kChartReach * size[b])) {
        const int part = features.patch_part[patches_at[b][0]];
        fail(
            "chart '{}' of part '{}': the vertex at ({:g}, {:g}{}) (number {} in input order) is "
            "{:.3g} from it, {:.3g} times the local mesh size {:.3g} (at most {:g}); is it the "
            "right chart for this mesh?",
            patch_chart[patches_at[b][0]]->name, part_name(part), p[0], p[1],
            surface.dim == 3 ? fmt::format(", {:g}", p[2]) : "", surface.input_vertex[b] + 1,
            distance, distance / size[b], size[b], kChartReach);
      }
      on_chart[b] = 1;
      chart_position[b] = q;
      if (distance > 0) {
        ++summary.moved_onto_charts;
        summary.max_move_onto_charts = std::max(summary.max_move_onto_charts, distance);
      }
    }
  }

  // Moves the owned boundary vertices of parts with charts (global Vec x) onto them.
  void place_on_charts(Vec x) const {
    if (on_chart.empty()) return;
    const int d = view.dim;
    PetscInt first = 0;
    NM_PETSC(VecGetOwnershipRange(x, &first, nullptr));
    double* a = nullptr;
    NM_PETSC(VecGetArray(x, &a));
    for (PetscInt u = 0; u < view.num_vertices; ++u) {
      if (!view.on_boundary[u] || !view.owned[u]) continue;
      const PetscInt b = surface.find(view.input_vertex[u]);
      if (b < 0 || !on_chart[b]) continue;
      double* at = a + dofs.global_dof()[u * d] - first;
      for (int j = 0; j < d; ++j) at[j] = chart_position[b][j];
    }
    NM_PETSC(VecRestoreArray(x, &a));
  }

  void build_ridges() {
    for (std::size_t r = 0; r < features.ridge_edges.size(); ++r) {
      const auto [a, b] = features.ridge_patches[r];
      const auto& edges = features.ridge_edges[r];
      if (a >= 0 && a != b && patch_analytic[a] && patch_analytic[b]) {
        const Surface &sa = *patch_surface[a], &sb = *patch_surface[b];
        const Point on = surface_point(surface, edges[0][0]);
        if (sa.is_flat() && sb.is_flat()) {
          const Point direction = sa.normal(on).cross(sb.normal(on));
          ridge_curve.push_back(make_line(on, snap_to_axis(direction.normalized())));
        } else {
          ridge_curve.push_back(make_intersection(sa, sb));
        }
        continue;
      }
      std::map<PetscInt, int> index;
      std::vector<Point> points;
      std::vector<std::array<int, 3>> segments;
      auto point_index = [&](PetscInt v) {
        const auto [it, added] = index.emplace(v, static_cast<int>(points.size()));
        if (added) points.push_back(surface_point(surface, v));
        return it->second;
      };
      for (const auto& e : edges) segments.push_back({point_index(e[0]), point_index(e[1]), 0});
      ridge_curve.push_back(
          std::make_unique<DiscreteCurve>(std::move(points), std::move(segments)));
    }
  }

  void assign_vertices() {
    const int d = view.dim;
    for (PetscInt u = 0; u < view.num_vertices; ++u) {
      if (!view.on_boundary[u]) continue;
      const PetscInt b = surface.find(view.input_vertex[u]);
      std::uint8_t* f = fixed.data() + u * d;
      if (b < 0 || features.kind[b] == VertexFeature::Corner) {
        std::fill_n(f, d, 1);
        continue;
      }
      const Point at = surface_point(surface, b);
      if (features.kind[b] == VertexFeature::Surface) {
        const Surface& s = *patch_surface[features.patch[b]];
        const int axis = s.is_flat() ? axis_of(s.normal(at)) : -1;
        if (axis >= 0) {
          f[axis] = 1;  // stays exactly in its plane x_axis = const
          continue;
        }
        sliding.push_back(u);
        sliding_surface.push_back(&s);
        sliding_curve.push_back(nullptr);
      } else {
        const Curve& c = *ridge_curve[features.ridge[b]];
        const int axis = c.is_straight() ? axis_of(c.tangent(at)) : -1;
        if (axis >= 0) {
          for (int j = 0; j < d; ++j) f[j] = j != axis;  // stays exactly on its line
          continue;
        }
        sliding.push_back(u);
        sliding_surface.push_back(nullptr);
        sliding_curve.push_back(&c);
      }
    }
  }

  Point local_point(std::span<const double> x, PetscInt u) const {
    Point p = Point::Zero();
    for (int j = 0; j < view.dim; ++j) p[j] = x[u * view.dim + j];
    return p;
  }

  // P, w, M of each sliding vertex (sliding_vertices.hpp).
  void tangent_spaces(std::span<const double> x, std::span<double> out) const {
    const int d = view.dim;
    for (std::size_t i = 0; i < sliding.size(); ++i) {
      const Point p = local_point(x, sliding[i]);
      double* P = out.data() + i * tangent_space_size(d);
      double* w = P + d * d;
      double* M = w + d;
      Point bend;
      Matrix3 shape;
      if (sliding_surface[i]) {
        const Point n = sliding_surface[i]->normal(p);
        bend = -n;
        shape = sliding_surface[i]->shape_operator(p);
        for (int a = 0; a < d; ++a)
          for (int c = 0; c < d; ++c) P[a * d + c] = (a == c ? 1.0 : 0.0) - n[a] * n[c];
      } else {
        const Point t = sliding_curve[i]->tangent(p);
        bend = sliding_curve[i]->curvature(p);
        shape = t * t.transpose();
        for (int a = 0; a < d; ++a)
          for (int c = 0; c < d; ++c) P[a * d + c] = t[a] * t[c];
      }
      for (int a = 0; a < d; ++a) {
        w[a] = bend[a];
        for (int c = 0; c < d; ++c) M[a * d + c] = shape(a, c);
      }
    }
  }

  void project(Vec x) const {
    if (sliding.empty()) return;
    const int d = view.dim;
    PetscInt first = 0;
    NM_PETSC(VecGetOwnershipRange(x, &first, nullptr));
    double* a = nullptr;
    NM_PETSC(VecGetArray(x, &a));
    for (std::size_t i = 0; i < sliding.size(); ++i) {
      const PetscInt u = sliding[i];
      if (!view.owned[u]) continue;
      double* at = a + dofs.global_dof()[u * d] - first;
      Point p = Point::Zero();
      for (int j = 0; j < d; ++j) p[j] = at[j];
      const Point q = sliding_surface[i] ? sliding_surface[i]->closest_point(p)
                                         : sliding_curve[i]->closest_point(p);
      for (int j = 0; j < d; ++j) at[j] = q[j];
    }
    NM_PETSC(VecRestoreArray(x, &a));
  }

  double max_distance_from_input(Vec x) const {
    if (!input_boundary) input_boundary = std::make_unique<DistanceToBoundary>(surface);
    std::vector<double> local(static_cast<std::size_t>(dofs.num_local_dofs()));
    dofs.global_to_local(x, local);
    return max_boundary_distance(view, local, *input_boundary, dofs.comm());
  }
};

Boundary::Boundary(const MeshView& view, const DofMap& dofs, const BoundaryOptions& options,
                   bool sub_facets)
    : impl_(std::make_unique<Impl>(view, dofs, options, sub_facets)) {}
Boundary::~Boundary() = default;

bool Boundary::slides_on_surface_of(const MeshView& view) const {
  return view.boundary == impl_->surface_owner;
}

FixedDofs Boundary::fixed_dofs() const {
  return FixedDofs{impl_->fixed};
}

SlidingVertices Boundary::sliding_vertices() const {
  const Impl* impl = impl_.get();
  SlidingVertices s;
  s.vertices = impl->sliding;
  s.tangent_spaces = [impl](std::span<const double> x, std::span<double> out) {
    impl->tangent_spaces(x, out);
  };
  s.project = [impl](Vec x) { impl->project(x); };
  return s;
}

void Boundary::project(Vec x) const {
  impl_->project(x);
}

std::vector<int> Boundary::sliding_geometry() const {
  const Impl& b = *impl_;
  // Patches first, then ridges.
  std::map<const void*, int> index;
  for (const auto& s : b.patch_surface) index.emplace(s.get(), static_cast<int>(index.size()));
  for (const auto& c : b.ridge_curve) index.emplace(c.get(), static_cast<int>(index.size()));
  std::vector<int> geometry(static_cast<std::size_t>(b.view.num_vertices), -1);
  for (std::size_t i = 0; i < b.sliding.size(); ++i)
    geometry[b.sliding[i]] =
        b.sliding_surface[i] ? index.at(b.sliding_surface[i]) : index.at(b.sliding_curve[i]);
  return geometry;
}

Point Boundary::closest_point(int g, const Point& p) const {
  const auto patches = static_cast<int>(impl_->patch_surface.size());
  return g < patches ? impl_->patch_surface[g]->closest_point(p)
                     : impl_->ridge_curve[g - patches]->closest_point(p);
}

void Boundary::place_on_charts(Vec x) const {
  impl_->place_on_charts(x);
}

const BoundarySummary& Boundary::summary() const {
  return impl_->summary;
}

double Boundary::max_distance_from_input(Vec x) const {
  return impl_->max_distance_from_input(x);
}

}  // namespace neomesh
