// geometry/surface_frame.hpp — the reference normal and tangent frame of a surface cell, a
// triangle or quadrilateral whose vertices are points in space (docs/method.md, "Surface
// cells"). The surface kernel (energy/surface_kernels.hpp) maps the cell into its frame; the
// quality measures (quality.hpp) sign its determinants by its normal.
#pragma once

#include <optional>

#include "geometry/reference_cell.hpp"

namespace neomesh {

// A surface cell's tangent frame Q = [t1 t2]: orthonormal columns with t1 × t2 = n.
using SurfaceFrame = Eigen::Matrix<double, 3, 2>;

// The frame with unit normal n whose t1 is `edge` projected into the plane normal to n and
// normalized; t2 = n × t1. None if `edge` has no part in that plane.
inline std::optional<SurfaceFrame> tangent_frame(const Vector<3>& normal, const Vector<3>& edge) {
  const Vector<3> in_plane = edge - edge.dot(normal) * normal;
  const double length = in_plane.norm();
  if (!(length > 0.0)) return std::nullopt;
  SurfaceFrame frame;
  frame.col(0) = in_plane / length;
  frame.col(1) = normal.cross(frame.col(0));
  return frame;
}

// The reference unit normal of a triangle or quadrilateral from its vertex coordinates (one
// column per vertex, canonical order): a triangle's (x1 − x0) × (x2 − x0), normalized; a
// quadrilateral's Newell normal, which for four vertices is the cross product of the
// diagonals, (x3 − x0) × (x2 − x1) in tensor order. Both point to the side from which the
// cell runs counter-clockwise, the +z side of a valid 2D cell. None for a cell without area.
template <CellType Type>
std::optional<Vector<3>> surface_cell_normal(
    const Eigen::Matrix<double, 3, CellTraits<Type>::vertices>& x) {
  static_assert(Type == CellType::Triangle || Type == CellType::Quadrilateral,
                "a surface cell is a triangle or a quadrilateral");
  Vector<3> normal;
  if constexpr (Type == CellType::Triangle)
    normal = (x.col(1) - x.col(0)).cross(x.col(2) - x.col(0));
  else
    normal = (x.col(3) - x.col(0)).cross(x.col(2) - x.col(1));
  const double length = normal.norm();
  if (!(length > 0.0)) return std::nullopt;
  return Vector<3>(normal / length);
}

// The frame of a cell from its vertex coordinates: its reference normal (surface_cell_normal)
// and t1 along its first edge, x1 − x0. None for a cell without area.
template <CellType Type>
std::optional<SurfaceFrame> surface_cell_frame(
    const Eigen::Matrix<double, 3, CellTraits<Type>::vertices>& x) {
  const std::optional<Vector<3>> normal = surface_cell_normal<Type>(x);
  if (!normal) return std::nullopt;
  return tangent_frame(*normal, x.col(1) - x.col(0));
}

}  // namespace neomesh
