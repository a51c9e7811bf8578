// The input's own boundary as geometry to slide on (docs/boundary.md): a patch of boundary
// facets is a DiscreteSurface (a polyline in 2D, triangles in 3D — quadrilateral facets split
// in two), a ridge a DiscreteCurve (a polyline in 3D). Closest points are exact on these
// piecewise-linear shapes, so a vertex that slides stays within the facets' sagitta of the
// true (curved) boundary; normals and tangents are interpolated from vertex normals, so that
// the tangent space a vertex moves in turns smoothly as it slides past the input's vertices.
#pragma once

#include <array>
#include <memory>
#include <span>
#include <unordered_map>
#include <vector>

#include "boundary/shape.hpp"
#include "mesh/boundary_surface.hpp"

namespace neomesh {

// Segments or triangles in 3D, with closest-point queries through a uniform grid.
class SimplexSet {
 public:
  // `corners` = 2 (segments) or 3 (triangles) point indices per simplex in `simplices`.
  SimplexSet(std::vector<Point> points, std::vector<std::array<int, 3>> simplices, int corners);

  struct Hit {
    int simplex = -1;
    Point point = Point::Zero();
    std::array<double, 3> weights{};  // barycentric: point = Σ weights[i] · corner i
    double distance = 0.0;
  };
  Hit closest(const Point& p) const;

  const std::vector<Point>& points() const { return points_; }
  const std::vector<std::array<int, 3>>& simplices() const { return simplices_; }
  int corners() const { return corners_; }

 private:
  using Cell = std::array<long long, 3>;
  Cell cell_of(const Point& p) const;
  static long long key(const Cell& c);
  double cell_distance(const Cell& c, const Point& p) const;
  void visit(const Cell& c, const Point& p, Hit& best) const;
  Hit closest_on(int simplex, const Point& p) const;

  std::vector<Point> points_;
  std::vector<std::array<int, 3>> simplices_;
  int corners_;
  Point origin_ = Point::Zero();
  double spacing_ = 1.0;
  Cell cells_{};  // grid extent per axis
  std::unordered_map<long long, std::vector<int>> grid_;
  std::vector<int> large_;                   // simplices too large for the grid, checked always
  std::vector<std::array<Point, 2>> boxes_;  // per simplex: its bounding box, lowest and highest
};

// Segments (2D) or triangles (3D, polygons split in a fan) of some facets of a boundary
// surface, on their own points: what a DiscreteSurface or SimplexSet is built from.
struct FacetSimplices {
  std::vector<Point> points;
  std::vector<std::array<int, 3>> simplices;
  int corners = 2;  // 2 or 3 per simplex
};
FacetSimplices facet_simplices(const BoundarySurface& s, std::span<const PetscInt> facets);

// A polyline (2D) or triangulated surface (3D) with per-point normals.
class DiscreteSurface final : public Surface {
 public:
  DiscreteSurface(std::vector<Point> points, std::vector<std::array<int, 3>> simplices, int dim);
  Point closest_point(const Point& p) const override;
  Point normal(const Point& on_surface) const override;
  Matrix3 shape_operator(const Point&) const override { return Matrix3::Zero(); }
  std::string describe() const override { return "the input's boundary"; }

 private:
  Point simplex_normal(int s) const;
  SimplexSet set_;
  int dim_;
  std::vector<Point> point_normal_;
};

// A smooth reconstruction of a triangulated patch through its points: Phong tessellation
// (Boubekeur & Alexa, "Phong Tessellation", 2008). On triangle (x₀, x₁, x₂) with barycentric
// weights b, the flat point p = Σ bᵢ xᵢ moves to
//   q(b) = p − Σᵢ αᵢ bᵢ ((p − xᵢ)·nᵢ) nᵢ,
// a quadratic patch through the three points, tangent there to the planes ⟂ nᵢ. With αᵢ = 1/2
// it matches a smooth surface whose normals the nᵢ are to second order (the flat cell's error
// is half of what the full projection adds; at αᵢ = 1, Boubekeur & Alexa's shape factor, it
// would overshoot by as much as the flat cell undershoots). The vertex normals nᵢ are Max's
// ("Weights for computing vertex normals from facet normals", 1999): exact for points on a
// sphere. An edge's curve depends on its two ends only, so the patches meet without gaps (C0);
// their normals differ across an edge and at a vertex (not C1). normal() is therefore the
// vertex normals interpolated (Phong shading's), which turns smoothly, and shape_operator() its
// derivative along the patch: with the patches' own normals the iteration keeps stepping across
// the kinks (measured on a Gmsh sphere: 200 iterations instead of 12). Where a patch could fold
// (noisy input: normals tilting along a thin triangle), its points get α = 0: a triangle whose
// patch's area element falls below min_area_ratio times the flat triangle's somewhere (checked
// at sample points) has its three points flat, and so on until no triangle does.
class PhongSurface final : public Surface {
 public:
  // The least area element a patch may have, relative to its flat triangle's: below it the
  // patch nearly folds, and its Newton steps turn ill-conditioned.
  static constexpr double kMinAreaRatio = 0.5;
  PhongSurface(std::vector<Point> points, std::vector<std::array<int, 3>> triangles,
               double min_area_ratio = kMinAreaRatio);
  Point closest_point(const Point& p) const override;
  Point normal(const Point& on_surface) const override;
  Matrix3 shape_operator(const Point& on_surface) const override;
  std::string describe() const override;
  // Points that keep their triangles flat (α = 0).
  int flat_points() const;

  // A point of a triangle: q(b) with b = (1 − u − v, u, v), and its derivatives.
  struct Patch {
    int triangle = -1;
    double u = 0, v = 0;
    Point q, qu, qv, quu, quv, qvv;
  };
  Patch evaluate(int triangle, double u, double v) const;
  // The point of the reconstruction closest to p, by Newton's method in the parameters of a
  // triangle, from the closest flat triangle, crossing into a neighbour where they leave it.
  Patch locate(const Point& p) const;
  // The unit normal normal() gives at a point of a patch.
  Point normal_at(const Patch& at) const;
  // The least ratio of the patch's area element to the flat triangle's, at sample points.
  double area_ratio(int triangle) const;

 private:
  SimplexSet set_;
  std::vector<Point> normal_;                  // per point, Max's weights
  std::vector<double> alpha_;                  // per point: 1/2, or 0 where it could fold
  std::vector<std::array<int, 3>> neighbour_;  // per triangle, across the edge opposite corner k
};

// A polyline in 3D with per-point tangents.
class DiscreteCurve final : public Curve {
 public:
  DiscreteCurve(std::vector<Point> points, std::vector<std::array<int, 3>> segments);
  Point closest_point(const Point& p) const override;
  Point tangent(const Point& on_curve) const override;
  Point curvature(const Point&) const override { return Point::Zero(); }

 private:
  Point segment_tangent(int s) const;
  SimplexSet set_;
  std::vector<Point> point_tangent_;
};

}  // namespace neomesh
