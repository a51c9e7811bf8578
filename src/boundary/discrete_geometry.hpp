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
  void visit(const Cell& c, const Point& p, Hit& best) const;
  Hit closest_on(int simplex, const Point& p) const;

  std::vector<Point> points_;
  std::vector<std::array<int, 3>> simplices_;
  int corners_;
  Point origin_ = Point::Zero();
  double spacing_ = 1.0;
  Cell cells_{};  // grid extent per axis
  std::unordered_map<long long, std::vector<int>> grid_;
  std::vector<int> large_;  // simplices too large for the grid, checked always
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
