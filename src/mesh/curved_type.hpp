// The second-order (curved) cell types and how files number their nodes: one table of facts.
// Their geometry (basis, Jacobian, validity certificate) is geometry/curved_cell.hpp's.
//
// Node order: Gmsh's (curved_cell.hpp states it): the corners as Gmsh lists them, then one node
// per edge, per quadrilateral face and the centre. VTK lists the same nodes in another order
// for the tetrahedron (the last three edges) and the hexahedra (edges and faces); its quadratic
// cells (types 22-29) and its Lagrange cells of order 2 (types 69-72) agree with each other.
// Exodus II (Ioss' element topologies) and CGNS (SIDS "Unstructured Grid Element Numbering
// Conventions") list the tetrahedron's edges as VTK does and the hexahedron's as the bottom
// face's cycle, the vertical edges, the top face's cycle; their hexahedron27 faces differ.
// Medit's TrianglesP2 and TetrahedraP2, as Gmsh reads and writes them, are VTK's order.
#pragma once

#include <array>
#include <cstdint>
#include <initializer_list>
#include <optional>
#include <span>
#include <string_view>
#include <type_traits>

#include "mesh/cell_type.hpp"

namespace neomesh {

enum class CurvedType : std::uint8_t {
  Triangle6,
  Quadrilateral8,
  Quadrilateral9,
  Tetrahedron10,
  Hexahedron20,
  Hexahedron27,
  Wedge15,
  Wedge18
};

inline constexpr std::array<CurvedType, 8> kCurvedTypes = {
    CurvedType::Triangle6,     CurvedType::Quadrilateral8, CurvedType::Quadrilateral9,
    CurvedType::Tetrahedron10, CurvedType::Hexahedron20,   CurvedType::Hexahedron27,
    CurvedType::Wedge15,       CurvedType::Wedge18};

inline constexpr int kMaxCurvedNodes = 27;

// Gmsh's edges and (for the hexahedron and the wedge) quadrilateral faces of each shape, by their
// corners: a cell's edge nodes follow its corners in this order, its face nodes its edge nodes.
using CurvedEdge = std::array<std::uint8_t, 2>;
using CurvedFace = std::array<std::uint8_t, 4>;
inline constexpr std::array<CurvedEdge, 3> kTriangleEdges = {{{0, 1}, {1, 2}, {2, 0}}};
inline constexpr std::array<CurvedEdge, 4> kQuadrilateralEdges = {{{0, 1}, {1, 2}, {2, 3}, {3, 0}}};
inline constexpr std::array<CurvedEdge, 6> kTetrahedronEdges = {
    {{0, 1}, {1, 2}, {2, 0}, {3, 0}, {3, 2}, {3, 1}}};
inline constexpr std::array<CurvedEdge, 12> kHexahedronEdges = {{{0, 1},
                                                                 {0, 3},
                                                                 {0, 4},
                                                                 {1, 2},
                                                                 {1, 5},
                                                                 {2, 3},
                                                                 {2, 6},
                                                                 {3, 7},
                                                                 {4, 5},
                                                                 {4, 7},
                                                                 {5, 6},
                                                                 {6, 7}}};
// z = −1, y = −1, x = −1, x = +1, y = +1, z = +1.
inline constexpr std::array<CurvedFace, 6> kHexahedronFaces = {
    {{0, 3, 2, 1}, {0, 1, 5, 4}, {0, 3, 7, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {4, 5, 6, 7}}};
// The wedge (Gmsh's prism): its edges by their lower corner, then its quadrilateral faces
// y = 0, x = 0 and x + y = 1 of the reference prism.
inline constexpr std::array<CurvedEdge, 9> kWedgeEdges = {
    {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 4}, {2, 5}, {3, 4}, {3, 5}, {4, 5}}};
inline constexpr std::array<CurvedFace, 3> kWedgeFaces = {
    {{0, 1, 4, 3}, {0, 2, 5, 3}, {1, 2, 5, 4}}};

struct CurvedFacts {
  std::string_view name;  // "hexahedron27"
  CellType linear;        // the straight cell of the same shape: its corners are the vertices
  int nodes;              // corners included
  int gmsh;               // Gmsh element type (.msh 2.2 and 4.1)
  int vtk;                // VTK's quadratic cell type
  int vtk_lagrange;       // VTK's Lagrange cell type (order 2 with `nodes` points)
  // Position i of VTK's list holds Gmsh node vtk_order[i] (the corners agree but for the
  // wedge's, whose triangles VTK's quadratic wedges list the other way round); that of VTK's
  // Lagrange cell lagrange_order[i]; likewise Exodus II's and CGNS's.
  std::array<std::uint8_t, kMaxCurvedNodes> vtk_order;
  std::array<std::uint8_t, kMaxCurvedNodes> lagrange_order;
  std::array<std::uint8_t, kMaxCurvedNodes> exodus_order;
  std::array<std::uint8_t, kMaxCurvedNodes> cgns_order;
  std::span<const CurvedEdge> edges;  // the edges that carry a node
  std::span<const CurvedFace> faces;  // the faces that carry one (of a 3D cell)
};

// Exodus' and CGNS' hexahedron: the corners, the edges (the bottom cycle, the vertical edges,
// the top cycle), then the Gmsh nodes `after`.
constexpr std::array<std::uint8_t, kMaxCurvedNodes> bottom_vertical_top(
    std::initializer_list<std::uint8_t> after) {
  std::array<std::uint8_t, kMaxCurvedNodes> order = {0,  1, 2,  3,  4,  5,  6,  7,  8,  11,
                                                     13, 9, 10, 12, 14, 15, 16, 18, 19, 17};
  int i = 20;
  for (std::uint8_t n : after) order[i++] = n;
  return order;
}

inline constexpr std::array<CurvedFacts, kCurvedTypes.size()> kCurvedFacts = {{
    {"triangle6",
     CellType::Triangle,
     6,
     9,
     22,
     69,
     {0, 1, 2, 3, 4, 5},
     {0, 1, 2, 3, 4, 5},
     {0, 1, 2, 3, 4, 5},
     {0, 1, 2, 3, 4, 5},
     kTriangleEdges,
     {}},
    {"quadrilateral8",
     CellType::Quadrilateral,
     8,
     16,
     23,
     -1,
     {0, 1, 2, 3, 4, 5, 6, 7},
     {0, 1, 2, 3, 4, 5, 6, 7},
     {0, 1, 2, 3, 4, 5, 6, 7},
     {0, 1, 2, 3, 4, 5, 6, 7},
     kQuadrilateralEdges,
     {}},
    {"quadrilateral9",
     CellType::Quadrilateral,
     9,
     10,
     28,
     70,
     {0, 1, 2, 3, 4, 5, 6, 7, 8},
     {0, 1, 2, 3, 4, 5, 6, 7, 8},
     {0, 1, 2, 3, 4, 5, 6, 7, 8},
     {0, 1, 2, 3, 4, 5, 6, 7, 8},
     kQuadrilateralEdges,
     {}},
    // VTK's edges (0,1) (1,2) (2,0) (0,3) (1,3) (2,3); Gmsh's end (3,0) (3,2) (3,1).
    {"tetrahedron10",
     CellType::Tetrahedron,
     10,
     11,
     24,
     71,
     {0, 1, 2, 3, 4, 5, 6, 7, 9, 8},
     {0, 1, 2, 3, 4, 5, 6, 7, 9, 8},
     {0, 1, 2, 3, 4, 5, 6, 7, 9, 8},
     {0, 1, 2, 3, 4, 5, 6, 7, 9, 8},
     kTetrahedronEdges,
     {}},
    // VTK's edges: the bottom and the top face's cycles, then the vertical ones.
    {"hexahedron20",
     CellType::Hexahedron,
     20,
     17,
     25,
     -1,
     {0, 1, 2, 3, 4, 5, 6, 7, 8, 11, 13, 9, 16, 18, 19, 17, 10, 12, 14, 15},
     {0, 1, 2, 3, 4, 5, 6, 7, 8, 11, 13, 9, 16, 18, 19, 17, 10, 12, 14, 15},
     bottom_vertical_top({}),
     bottom_vertical_top({}),
     kHexahedronEdges,
     {}},
    // As hexahedron20, then VTK's faces x = −1, x = +1, y = −1, y = +1, z = −1, z = +1;
    // Exodus' centre, then z = −1, z = +1, x = −1, x = +1, y = −1, y = +1; CGNS' z = −1,
    // y = −1, x = +1, y = +1, x = −1, z = +1, then the centre.
    {"hexahedron27",
     CellType::Hexahedron,
     27,
     12,
     29,
     72,
     {0,  1,  2,  3,  4,  5,  6,  7,  8,  11, 13, 9,  16, 18,
      19, 17, 10, 12, 14, 15, 22, 23, 21, 24, 20, 25, 26},
     {0,  1,  2,  3,  4,  5,  6,  7,  8,  11, 13, 9,  16, 18,
      19, 17, 10, 12, 14, 15, 22, 23, 21, 24, 20, 25, 26},
     bottom_vertical_top({26, 20, 25, 22, 23, 21, 24}),
     bottom_vertical_top({20, 21, 23, 24, 22, 25, 26}),
     kHexahedronEdges,
     kHexahedronFaces},
    // Gmsh's prism15 and prism18. VTK's quadratic wedges (26, 32) list the corners as its linear
    // wedge (cell_order.hpp: both triangles the other way round), then the edges of the bottom
    // and the top triangle's cycles, the vertical edges, and (32) the faces (0,1,4,3) (1,2,5,4)
    // (2,0,3,5) in its own numbering; its Lagrange wedge (73) keeps Gmsh's corners, then the
    // same cycles of edges and the faces y = 0, x + y = 1, x = 0 (vtkHigherOrderWedge::
    // PointIndexFromIJK). Exodus (Ioss' Wedge18) and CGNS (PENTA_18): the bottom cycle, the
    // vertical edges, the top cycle, then the faces (0,1,4,3) (1,2,5,4) (0,3,5,2).
    {"wedge15",
     CellType::Wedge,
     15,
     18,
     26,
     -1,
     {0, 2, 1, 3, 5, 4, 7, 9, 6, 13, 14, 12, 8, 11, 10},
     {0, 2, 1, 3, 5, 4, 7, 9, 6, 13, 14, 12, 8, 11, 10},
     {0, 1, 2, 3, 4, 5, 6, 9, 7, 8, 10, 11, 12, 14, 13},
     {0, 1, 2, 3, 4, 5, 6, 9, 7, 8, 10, 11, 12, 14, 13},
     kWedgeEdges,
     {}},
    {"wedge18",
     CellType::Wedge,
     18,
     13,
     32,
     73,
     {0, 2, 1, 3, 5, 4, 7, 9, 6, 13, 14, 12, 8, 11, 10, 16, 17, 15},
     {0, 1, 2, 3, 4, 5, 6, 9, 7, 12, 14, 13, 8, 10, 11, 15, 17, 16},
     {0, 1, 2, 3, 4, 5, 6, 9, 7, 8, 10, 11, 12, 14, 13, 15, 17, 16},
     {0, 1, 2, 3, 4, 5, 6, 9, 7, 8, 10, 11, 12, 14, 13, 15, 17, 16},
     kWedgeEdges,
     kWedgeFaces},
}};

constexpr const CurvedFacts& facts(CurvedType t) {
  return kCurvedFacts[static_cast<int>(t)];
}
constexpr std::string_view name(CurvedType t) {
  return facts(t).name;
}

// A curved type as a type, for dispatching once per block or cell to code compiled per type.
template <CurvedType Type>
using CurvedTag = std::integral_constant<CurvedType, Type>;

// Calls f(CurvedTag<type>{}) with the type as a compile-time constant: the one switch over
// curved types.
template <typename F>
decltype(auto) visit_curved_type(CurvedType type, F&& f) {
  switch (type) {
    case CurvedType::Triangle6:
      return f(CurvedTag<CurvedType::Triangle6>{});
    case CurvedType::Quadrilateral8:
      return f(CurvedTag<CurvedType::Quadrilateral8>{});
    case CurvedType::Quadrilateral9:
      return f(CurvedTag<CurvedType::Quadrilateral9>{});
    case CurvedType::Tetrahedron10:
      return f(CurvedTag<CurvedType::Tetrahedron10>{});
    case CurvedType::Hexahedron20:
      return f(CurvedTag<CurvedType::Hexahedron20>{});
    case CurvedType::Hexahedron27:
      return f(CurvedTag<CurvedType::Hexahedron27>{});
    case CurvedType::Wedge15:
      return f(CurvedTag<CurvedType::Wedge15>{});
    case CurvedType::Wedge18:
      break;
  }
  return f(CurvedTag<CurvedType::Wedge18>{});
}

// VTK before 9.1 numbered the quadratic Lagrange hexahedron's (type 72) vertical edges at y = 1
// the other way round: positions 18 and 19 swapped. VTK converts files of older versions on
// reading (XML before 2.2, legacy before 5.1), so such files hold the old order.
constexpr int old_lagrange_hexahedron_position(int i) {
  return i == 18 ? 19 : i == 19 ? 18 : i;
}

// Position i of VTK's list of a cell of `type` holds Gmsh node vtk_order(type, lagrange)[i]:
// for its Lagrange cell (`lagrange`) or its quadratic one.
constexpr const std::array<std::uint8_t, kMaxCurvedNodes>& vtk_order(CurvedType type,
                                                                     bool lagrange) {
  return lagrange ? facts(type).lagrange_order : facts(type).vtk_order;
}

// The type with `nodes` nodes whose straight cell is `linear`, or none.
constexpr std::optional<CurvedType> curved_type(CellType linear, int nodes) {
  for (CurvedType t : kCurvedTypes)
    if (facts(t).linear == linear && facts(t).nodes == nodes) return t;
  return std::nullopt;
}

}  // namespace neomesh
