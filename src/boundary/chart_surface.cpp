#include "boundary/chart_surface.hpp"

#include <array>
#include <cmath>
#include <vector>

#include <Eigen/Geometry>

#include "boundary/discrete_geometry.hpp"
#include "core/error.hpp"

namespace neomesh {

namespace {

std::unique_ptr<Surface> chart_curve(const Chart& chart) {
  if (chart.kind == Chart::Kind::Circle)
    return make_sphere({chart.centre[0], chart.centre[1], 0.0}, chart.radius, 2);
  std::vector<Point> controls;
  for (std::size_t i = 0; i + 1 < chart.points.size(); i += 2)
    controls.emplace_back(chart.points[i], chart.points[i + 1], 0.0);
  return make_bezier(std::move(controls),
                     std::vector<int>(chart.vertices.begin(), chart.vertices.end()));
}

}  // namespace

std::unique_ptr<Surface> chart_surface(const Chart& chart, int dim, const std::string& part) {
  const auto need_dim = [&](int d, const char* what) {
    if (dim != d)
      fail("chart '{}' of part '{}' is {}, but the mesh is {}D", chart.name, part, what, dim);
  };
  if (chart.extruded) {
    need_dim(3, "a 2D curve extruded along z (3D)");
    // FEAT3's angles are yaw, pitch and roll in revolutions.
    const auto turn = [&](int i, const Point& axis) {
      return Eigen::AngleAxisd(2 * M_PI * chart.angles[i], axis).toRotationMatrix();
    };
    const Matrix3 rotation =
        turn(0, Point::UnitZ()) * turn(1, Point::UnitY()) * turn(2, Point::UnitX());
    return make_extrusion(chart_curve(chart), rotation,
                          {chart.origin[0], chart.origin[1], chart.origin[2]},
                          {chart.offset[0], chart.offset[1], chart.offset[2]});
  }
  switch (chart.kind) {
    case Chart::Kind::Circle:
      need_dim(2, "a circle");
      return chart_curve(chart);
    case Chart::Kind::Bezier:
      need_dim(2, "a 2D curve");
      return chart_curve(chart);
    case Chart::Kind::Sphere:
      need_dim(3, "a sphere");
      return make_sphere({chart.centre[0], chart.centre[1], chart.centre[2]}, chart.radius, 3);
    case Chart::Kind::SurfaceMesh: {
      need_dim(3, "a surface");
      std::vector<Point> points;
      for (std::size_t i = 0; i + 2 < chart.points.size(); i += 3)
        points.emplace_back(chart.points[i], chart.points[i + 1], chart.points[i + 2]);
      std::vector<std::array<int, 3>> triangles;
      for (std::size_t i = 0; i + 2 < chart.triangles.size(); i += 3) {
        std::array<int, 3> t;
        for (int k = 0; k < 3; ++k) {
          const std::int64_t v = chart.triangles[i + k];
          if (v < 0 || v >= static_cast<std::int64_t>(points.size()))
            fail("chart '{}': triangle {} refers to point {} of {}", chart.name, i / 3, v,
                 points.size());
          t[k] = static_cast<int>(v);
        }
        triangles.push_back(t);
      }
      if (triangles.empty()) fail("chart '{}' of part '{}' has no triangles", chart.name, part);
      return std::make_unique<DiscreteSurface>(std::move(points), std::move(triangles), 3);
    }
  }
  fail("chart '{}': unknown kind", chart.name);
}

}  // namespace neomesh
