// The geometry boundary vertices slide on, as closest-point maps (docs/boundary.md):
// - Surface: codimension 1 — a curve in 2D (z = 0), a surface in 3D. Boundary vertices inside
//   a boundary patch stay on it.
// - Curve: codimension 2 in 3D — a ridge where two patches meet. Its vertices stay on it.
// Analytic shapes (plane, circle/sphere, cylinder, level set) are exact; the input's own
// boundary is represented by DiscreteSurface and DiscreteCurve (discrete_geometry.hpp).
//
// Points are 3D (z = 0 in 2D) so that one implementation serves both dimensions.
#pragma once

#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

namespace neomesh {

using Point = Eigen::Vector3d;
using Matrix3 = Eigen::Matrix3d;

class Surface {
 public:
  virtual ~Surface() = default;
  // The point of the surface closest to p (p lies near the surface: within a step).
  virtual Point closest_point(const Point& p) const = 0;
  // Unit normal at a point of the surface (any orientation).
  virtual Point normal(const Point& on_surface) const = 0;
  // The shape operator S = ∇n (tangent × tangent, for the orientation normal() returns): the
  // closest-point map bends a tangent step u by −(uᵀ S u) n to second order. Zero for planes
  // and for piecewise-flat discrete surfaces (their curvature sits in the kinks).
  virtual Matrix3 shape_operator(const Point& on_surface) const = 0;
  // True for a plane or straight line: its tangent space is the same everywhere.
  virtual bool is_flat() const { return false; }
  // For messages: "circle:0,0,0.5", "the input's boundary".
  virtual std::string describe() const = 0;
};

class Curve {
 public:
  virtual ~Curve() = default;
  virtual Point closest_point(const Point& p) const = 0;
  // Unit tangent at a point of the curve (any orientation).
  virtual Point tangent(const Point& on_curve) const = 0;
  // The curvature vector dt/ds: the closest-point map bends a step ε t by ε²/2 times it.
  // Zero for lines and polylines.
  virtual Point curvature(const Point& on_curve) const = 0;
  virtual bool is_straight() const { return false; }
};

// φ(x, y, z) — and the time t, if asked for — from a muparser expression (z = 0 in 2D), with
// its derivatives by central differences. Its zero set is the level-set shape; `adapt --fit`
// pulls vertices onto it through the levels φ = c (boundary/interface.hpp).
class LevelSetFunction {
 public:
  // Throws Error naming the expression if it does not parse or uses other variables.
  LevelSetFunction(const std::string& expression, int dim, bool with_time = false);
  ~LevelSetFunction();
  LevelSetFunction(LevelSetFunction&&) noexcept;

  void set_time(double t);
  double value(const Point& p) const;
  Point gradient(const Point& p) const;
  // The point of {φ = level} that Newton steps along ∇φ reach from p: the closest point to
  // first order.
  Point to_level(const Point& p, double level = 0.0) const;
  // The shape operator of the level set through q: P ∇²φ P / |∇φ| with P = I − n nᵀ.
  Matrix3 shape_operator(const Point& q) const;
  const std::string& expression() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// x·n = n·point.
std::unique_ptr<Surface> make_plane(const Point& point, const Point& normal);
// |x − centre| = radius: a circle in 2D (z = 0), a sphere in 3D.
std::unique_ptr<Surface> make_sphere(const Point& centre, double radius, int dim);
// Distance radius from the line through `point` along `axis` (3D).
std::unique_ptr<Surface> make_cylinder(const Point& point, const Point& axis, double radius);
// The zero level set of a muparser expression in x, y (and z); throws Error if it does not
// parse or uses other variables.
std::unique_ptr<Surface> make_level_set(const std::string& expression, int dim);

// A composite Bezier curve in the plane (z = 0), FEAT3's Bezier chart: segment i has the
// control points controls[starts[i]] .. controls[starts[i + 1]] (degree 1 to 5). Closest
// points are exact (Newton's method on each segment, from the best of a few samples), not
// those of a sampled polyline. Throws Error for fewer than two points or a degree above 5.
std::unique_ptr<Surface> make_bezier(std::vector<Point> controls, std::vector<int> starts);
// A 2D curve (circle, Bezier) extended along z, then placed by world = R (local − origin) +
// offset (R a rotation): a surface in 3D (FEAT3's Extrude chart).
std::unique_ptr<Surface> make_extrusion(std::unique_ptr<Surface> curve,
                                        const Matrix3& rotation = Matrix3::Identity(),
                                        const Point& origin = Point::Zero(),
                                        const Point& offset = Point::Zero());

// The straight line through `point` along `direction`.
std::unique_ptr<Curve> make_line(const Point& point, const Point& direction);
// The curve where two surfaces meet (a ridge between two analytic patches). Keeps references.
std::unique_ptr<Curve> make_intersection(const Surface& a, const Surface& b);

// A shape as the command line gives it (`--shape part=SPEC`), for a mesh of dimension `dim`:
//   circle:cx,cy,r (2D)   sphere:cx,cy,cz,r (3D)   line:px,py,nx,ny (2D, point and normal)
//   plane:px,py,pz,nx,ny,nz (3D)   cylinder:px,py,pz,ax,ay,az,r (3D, axis point and direction)
//   levelset:EXPRESSION   (zero set of a muparser expression in x, y, z)
// Throws Error with a one-line message naming `spec` for anything else.
std::unique_ptr<Surface> parse_shape(std::string_view spec, int dim);

}  // namespace neomesh
