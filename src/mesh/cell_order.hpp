// Local vertex orders of the file formats and of DMPlex, relative to neomesh's canonical
// order, read from the cell-type table (cell_type.hpp), and DMPlex's polytope of each type.
//
// Found by reading cells whose geometry is known, and for the wedge and pyramid from
// DMPlexInvertCell and DMPlexGetRawFaces_Internal: DMPlex lists quadrilaterals counter-
// clockwise, tetrahedra negatively oriented, hexahedra with the bottom face clockwise seen
// from the top face, wedges with the bottom triangle clockwise seen from the top (the top
// vertex above bottom position i at cone position 3, 5, 4 for i = 0, 1, 2) and pyramids with
// the base clockwise seen from the apex; Gmsh/VTK list quadrilaterals and both hexahedron
// faces counter-clockwise, tetrahedra positively oriented and pyramid bases counter-clockwise
// seen from the apex. Gmsh lists wedge bottoms counter-clockwise seen from the top, VTK
// clockwise (vtkWedge: the normal of 0 1 2 points away from 3 4 5; Mesquite's wedges agree).
#pragma once

#include <array>

#include <petscdmplex.h>

#include "mesh/cell_type.hpp"

namespace neomesh {

using VertexOrder = std::array<std::uint8_t, 8>;

constexpr const VertexOrder& plex_from_canonical(CellType t) {
  return facts(t).plex_order;
}
constexpr const VertexOrder& gmsh_from_canonical(CellType t) {
  return facts(t).gmsh_order;
}

// VTK's linear orders are Gmsh's but for the wedge, whose triangles VTK lists the other way round.
inline constexpr VertexOrder kVtkWedgeOrder = {0, 2, 1, 3, 5, 4};
constexpr const VertexOrder& vtk_from_canonical(CellType t) {
  return t == CellType::Wedge ? kVtkWedgeOrder : gmsh_from_canonical(t);
}

namespace detail {
constexpr std::array<VertexOrder, kNumCellTypes> inverse_plex_orders() {
  std::array<VertexOrder, kNumCellTypes> out{};
  for (int t = 0; t < kNumCellTypes; ++t)
    for (int i = 0; i < kCellFacts[t].vertices; ++i)
      out[t][kCellFacts[t].plex_order[i]] = static_cast<std::uint8_t>(i);
  return out;
}
inline constexpr std::array<VertexOrder, kNumCellTypes> kCanonicalFromPlex = inverse_plex_orders();
}  // namespace detail

// Position in the DMPlex cone of canonical vertex i.
constexpr const VertexOrder& canonical_from_plex(CellType t) {
  return detail::kCanonicalFromPlex[static_cast<int>(t)];
}

inline constexpr std::array<DMPolytopeType, kNumCellTypes> kPlexPolytope = {
    DM_POLYTOPE_TRIANGLE,   DM_POLYTOPE_QUADRILATERAL, DM_POLYTOPE_TETRAHEDRON,
    DM_POLYTOPE_HEXAHEDRON, DM_POLYTOPE_TRI_PRISM,     DM_POLYTOPE_PYRAMID};

constexpr DMPolytopeType plex_polytope(CellType t) {
  return kPlexPolytope[static_cast<int>(t)];
}

}  // namespace neomesh
