// Chart: an exact description of part of the domain's boundary, as FEAT3 mesh files give it
// in <Chart> blocks and attach it to mesh parts (<MeshPart ... chart="name">). Boundary
// vertices of a part with a chart stay exactly on it when they slide (boundary/).
//
// Only the data lives here (the mesh layer reads it); projection onto a chart is in
// boundary/shape.hpp.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace neomesh {

struct Chart {
  enum class Kind {
    Circle,       // 2D: |x − centre| = radius
    Sphere,       // 3D: |x − centre| = radius
    Polyline,     // 2D: a Bezier chart's points joined by straight segments (`points`)
    SurfaceMesh,  // 3D: a triangulated surface (`points`, `triangles`)
  };
  std::string name;
  Kind kind = Kind::Circle;
  std::array<double, 3> centre{};       // Circle, Sphere (z = 0 in 2D)
  double radius = 0.0;                  // Circle, Sphere
  std::vector<double> points;           // Polyline: 2 values per point; SurfaceMesh: 3 per point
  bool closed = false;                  // Polyline: the last point joins the first
  std::vector<std::int64_t> triangles;  // SurfaceMesh: 3 point indices (0-based) per triangle
};

}  // namespace neomesh
