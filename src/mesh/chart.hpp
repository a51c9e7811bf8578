// Chart: an exact description of part of the domain's boundary, as FEAT3 mesh files give it
// in <Chart> blocks and attach it to mesh parts (<MeshPart ... chart="name">). Boundary
// vertices of a part with a chart are moved onto it before the first step and stay exactly
// on it when they slide (boundary/, docs/boundary.md).
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
    Bezier,       // 2D: a composite Bezier curve (FEAT3 Bezier; a Polyline is one of degree 1)
    SurfaceMesh,  // 3D: a triangulated surface (`points`, `triangles`)
  };
  std::string name;
  Kind kind = Kind::Circle;
  // FEAT3 <Extrude>: the 2D chart (Circle or Bezier) extended along z, for a 3D mesh.
  // Its placement (attributes of <Extrude>): world = R (local − origin) + offset, R the
  // rotations by `angles` (in revolutions) about z, y and x.
  bool extruded = false;
  std::array<double, 3> origin{}, offset{}, angles{};
  std::array<double, 3> centre{};  // Circle, Sphere (z = 0 in 2D)
  double radius = 0.0;             // Circle, Sphere
  // Bezier: 2 values per point, the curve's vertices with the inner control points of the
  // segment ending at each vertex before it; SurfaceMesh: 3 values per point.
  std::vector<double> points;
  // Bezier: the index (into points) of each vertex the curve passes through, ascending, the
  // first 0; segment i has the control polygon points vertices[i] .. vertices[i + 1].
  std::vector<std::int64_t> vertices;
  std::vector<std::int64_t> triangles;  // SurfaceMesh: 3 point indices (0-based) per triangle
};

}  // namespace neomesh
