// The four cell types neomesh optimizes and their canonical local vertex orders.
//
// Canonical local order (used by every array of cell→vertex indices in neomesh):
// - triangle, tetrahedron: positively oriented (det[x1-x0, x2-x0(, x3-x0)] > 0);
// - quadrilateral, hexahedron: tensor order: local vertex i sits at reference point
//   ξ_j = ((i >> j) & 1) ? +1 : -1, so a unit square is (0,0),(1,0),(0,1),(1,1) — the
//   FEAT3 convention. (Gmsh, VTK and DMPlex use counter-clockwise order; the mesh layer
//   converts at its boundary.)
#pragma once

#include <cstdint>
#include <string_view>

namespace neomesh {

enum class CellType : std::uint8_t { Triangle, Quadrilateral, Tetrahedron, Hexahedron };

constexpr int dimension(CellType t) {
  return (t == CellType::Triangle || t == CellType::Quadrilateral) ? 2 : 3;
}

constexpr int num_vertices(CellType t) {
  switch (t) {
    case CellType::Triangle:
      return 3;
    case CellType::Quadrilateral:
      return 4;
    case CellType::Tetrahedron:
      return 4;
    case CellType::Hexahedron:
      return 8;
  }
  return 0;
}

constexpr bool is_simplex(CellType t) {
  return t == CellType::Triangle || t == CellType::Tetrahedron;
}

constexpr std::string_view name(CellType t) {
  switch (t) {
    case CellType::Triangle:
      return "triangle";
    case CellType::Quadrilateral:
      return "quadrilateral";
    case CellType::Tetrahedron:
      return "tetrahedron";
    case CellType::Hexahedron:
      return "hexahedron";
  }
  return "?";
}

}  // namespace neomesh
