// The cell types neomesh reads and optimizes. Vertex order within a cell: see
// docs/cell-types.md (Gmsh's order for files and for Mesh::from_arrays).
#pragma once

#include <cstdint>
#include <string_view>

namespace neomesh {

enum class CellType : std::uint8_t {
  Triangle,
  Quadrilateral,
  Tetrahedron,
  Hexahedron,
  Wedge,
  Pyramid
};
constexpr int kNumCellTypes = 6;

// "triangles", "quadrilaterals", "hexahedra", ...: for counts in messages.
std::string_view plural_name(CellType type);

}  // namespace neomesh
