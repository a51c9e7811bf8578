// The cell types neomesh optimizes: one table of their facts, and one dispatch to code
// compiled per cell type.
//
// Canonical local order (used by every array of cell→vertex indices in neomesh):
// - triangle, tetrahedron: positively oriented (det[x1-x0, x2-x0(, x3-x0)] > 0);
// - quadrilateral, hexahedron: tensor order: local vertex i sits at reference point
//   ξ_j = ((i >> j) & 1) ? +1 : -1, so a unit square is (0,0),(1,0),(0,1),(1,1) — the
//   FEAT3 convention. (Gmsh, VTK and DMPlex use counter-clockwise order; the mesh layer
//   converts at its boundary.)
// - wedge (triangular prism): a positively oriented bottom triangle 0 1 2 (counter-clockwise
//   seen from the top), then the top triangle 3 4 5 with vertex i + 3 joined to vertex i —
//   the Gmsh order (VTK lists both triangles the other way round);
// - pyramid: the base quadrilateral 0 1 2 3 in tensor order, counter-clockwise seen from the
//   apex 4 when read 0 1 3 2 (the hexahedron's bottom face with its top face collapsed).
#pragma once

#include <array>
#include <cstdint>
#include <string_view>
#include <type_traits>
#include <utility>

#include <neomesh/cell_type.hpp>

namespace neomesh {

// How a cell is mapped from its reference cell (reference_cell.hpp): affinely (simplex),
// multilinearly from [-1,1]^d (tensor), as triangle × interval (wedge) or as the cube with
// its top face collapsed onto the apex (pyramid).
enum class CellShape : std::uint8_t { Simplex, Tensor, Wedge, Pyramid };

// A corner Jacobian: the edges from `vertex` to `ends` (d of them), each negated where
// `flip` has its bit set, so that the determinant is positive on a valid cell. It equals the
// Jacobian of the reference map at that corner up to a positive factor.
struct CornerFrame {
  std::uint8_t vertex;
  std::array<std::uint8_t, 3> ends;
  std::uint8_t flip;  // bit j: column j is vertex − end instead of end − vertex
};

// A facet: its local vertices (canonical indices) in DMPlex's order — a cycle running
// counter-clockwise seen from outside the cell (2D: the edge's two ends), starting where
// DMPlexInterpolate starts it.
struct FacetVertices {
  std::uint8_t size;
  std::array<std::uint8_t, 4> vertices;
};

// A facet's (or edge's) vertex numbers as a key that two cells sharing it build alike: the first
// `size` entries sorted ascending (the rest left as they are, e.g. -1). By insertion: GCC 12
// warns wrongly about std::sort on part of an array.
template <typename T, std::size_t N>
void sort_facet_key(std::array<T, N>& key, int size) {
  for (int k = 1; k < size; ++k)
    for (int i = k; i > 0 && key[i - 1] > key[i]; --i) std::swap(key[i - 1], key[i]);
}

struct CellFacts {
  std::string_view name, plural;
  int dim, vertices;
  CellShape shape;
  int gmsh;  // Gmsh element type (.msh 2.2 and 4.1)
  int vtk;   // VTK cell type
  // Gmsh (and VTK: they agree for these types) vertex order: position i of a Gmsh element
  // holds canonical vertex gmsh_order[i].
  std::array<std::uint8_t, 8> gmsh_order;
  // DMPlex cone order: position i of the cone holds canonical vertex plex_order[i].
  std::array<std::uint8_t, 8> plex_order;
  // A renumbering that mirrors the cell (reflects it, negating every corner Jacobian).
  std::array<std::uint8_t, 8> mirror;
  int num_facets;
  std::array<FacetVertices, 6> facets;
  int num_corners;
  std::array<CornerFrame, 8> corners;
  // The scaled corner Jacobian det J / (product of the corner's edge lengths) at every corner
  // of the optimal cell: what quality metrics divide by so that the optimal cell scores 1.
  double ideal_corner_sine;
};

// The facts of each type, indexed by CellType.
inline constexpr std::array<CellFacts, kNumCellTypes> kCellFacts = {{
    {.name = "triangle",
     .plural = "triangles",
     .dim = 2,
     .vertices = 3,
     .shape = CellShape::Simplex,
     .gmsh = 2,
     .vtk = 5,
     .gmsh_order = {0, 1, 2},
     .plex_order = {0, 1, 2},
     .mirror = {0, 2, 1},
     .num_facets = 3,
     .facets = {{{2, {0, 1}}, {2, {1, 2}}, {2, {2, 0}}}},
     .num_corners = 1,  // one Jacobian: G is constant
     .corners = {{{0, {1, 2}, 0}}},
     .ideal_corner_sine = 0.86602540378443864676},  // √3/2
    {.name = "quadrilateral",
     .plural = "quadrilaterals",
     .dim = 2,
     .vertices = 4,
     .shape = CellShape::Tensor,
     .gmsh = 3,
     .vtk = 9,
     .gmsh_order = {0, 1, 3, 2},
     .plex_order = {0, 1, 3, 2},
     .mirror = {1, 0, 3, 2},
     .num_facets = 4,
     .facets = {{{2, {0, 1}}, {2, {1, 3}}, {2, {3, 2}}, {2, {2, 0}}}},
     .num_corners =
         4,  // tensor order: corner i's edges go to i ^ 1, i ^ 2, flipped where i has the bit
     .corners = {{{0, {1, 2}, 0}, {1, {0, 3}, 1}, {2, {3, 0}, 2}, {3, {2, 1}, 3}}},
     .ideal_corner_sine = 1.0},
    {.name = "tetrahedron",
     .plural = "tetrahedra",
     .dim = 3,
     .vertices = 4,
     .shape = CellShape::Simplex,
     .gmsh = 4,
     .vtk = 10,
     .gmsh_order = {0, 1, 2, 3},
     .plex_order = {1, 0, 2, 3},
     .mirror = {0, 2, 1, 3},
     .num_facets = 4,
     .facets = {{{3, {1, 0, 2}}, {3, {1, 3, 0}}, {3, {1, 2, 3}}, {3, {2, 0, 3}}}},
     .num_corners = 1,
     .corners = {{{0, {1, 2, 3}, 0}}},
     .ideal_corner_sine = 0.70710678118654752440},  // √2/2
    {.name = "hexahedron",
     .plural = "hexahedra",
     .dim = 3,
     .vertices = 8,
     .shape = CellShape::Tensor,
     .gmsh = 5,
     .vtk = 12,
     .gmsh_order = {0, 1, 3, 2, 4, 5, 7, 6},
     .plex_order = {0, 2, 3, 1, 4, 5, 7, 6},
     .mirror = {1, 0, 3, 2, 5, 4, 7, 6},
     .num_facets = 6,
     .facets = {{{4, {0, 2, 3, 1}},
                 {4, {4, 5, 7, 6}},
                 {4, {0, 1, 5, 4}},
                 {4, {3, 2, 6, 7}},
                 {4, {1, 3, 7, 5}},
                 {4, {0, 4, 6, 2}}}},
     .num_corners = 8,  // as the quadrilateral's, with i ^ 4 third
     .corners = {{{0, {1, 2, 4}, 0},
                  {1, {0, 3, 5}, 1},
                  {2, {3, 0, 6}, 2},
                  {3, {2, 1, 7}, 3},
                  {4, {5, 6, 0}, 4},
                  {5, {4, 7, 1}, 5},
                  {6, {7, 4, 2}, 6},
                  {7, {6, 5, 3}, 7}}},
     .ideal_corner_sine = 1.0},
    {.name = "wedge",
     .plural = "wedges",
     .dim = 3,
     .vertices = 6,
     .shape = CellShape::Wedge,
     .gmsh = 6,
     .vtk = 13,
     .gmsh_order = {0, 1, 2, 3, 4, 5},
     .plex_order = {0, 2, 1, 3, 4, 5},
     .mirror = {0, 2, 1, 3, 5, 4},
     .num_facets = 5,
     .facets = {{{3, {0, 2, 1}},
                 {3, {3, 4, 5}},
                 {4, {0, 1, 4, 3}},
                 {4, {1, 2, 5, 4}},
                 {4, {2, 0, 3, 5}}}},
     .num_corners = 6,  // the next two vertices of its triangle, then the one above/below
     .corners = {{{0, {1, 2, 3}, 0},
                  {1, {2, 0, 4}, 0},
                  {2, {0, 1, 5}, 0},
                  {3, {4, 5, 0}, 4},
                  {4, {5, 3, 1}, 4},
                  {5, {3, 4, 2}, 4}}},
     // √3/2: two edges at 60°, the third orthogonal to both.
     .ideal_corner_sine = 0.86602540378443864676},
    {.name = "pyramid",
     .plural = "pyramids",
     .dim = 3,
     .vertices = 5,
     .shape = CellShape::Pyramid,
     .gmsh = 7,
     .vtk = 14,
     .gmsh_order = {0, 1, 3, 2, 4},
     .plex_order = {0, 2, 3, 1, 4},
     .mirror = {1, 0, 3, 2, 4},
     .num_facets = 5,
     .facets =
         {{{4, {0, 2, 3, 1}}, {3, {0, 1, 4}}, {3, {1, 3, 4}}, {3, {3, 2, 4}}, {3, {2, 0, 4}}}},
     // The base corners (as the quadrilateral's, with the apex third), then the apex with
     // each three consecutive base vertices: the same four tetrahedra seen from the apex.
     .num_corners = 8,
     .corners = {{{0, {1, 2, 4}, 0},
                  {1, {0, 3, 4}, 1},
                  {2, {3, 0, 4}, 2},
                  {3, {2, 1, 4}, 3},
                  {4, {2, 3, 1}, 0},
                  {4, {3, 1, 0}, 0},
                  {4, {1, 0, 2}, 0},
                  {4, {0, 2, 3}, 0}}},
     // √2/2: equilateral side faces on a square base, at a base corner and at the apex.
     .ideal_corner_sine = 0.70710678118654752440},
}};

constexpr const CellFacts& facts(CellType t) {
  return kCellFacts[static_cast<int>(t)];
}
constexpr int dimension(CellType t) {
  return facts(t).dim;
}
constexpr int num_vertices(CellType t) {
  return facts(t).vertices;
}
constexpr bool is_simplex(CellType t) {
  return facts(t).shape == CellShape::Simplex;
}
constexpr std::string_view name(CellType t) {
  return facts(t).name;
}

// Every cell type, in the order of the enum (the order of a MeshView's blocks).
inline constexpr std::array<CellType, kNumCellTypes> kAllCellTypes = {
    CellType::Triangle,   CellType::Quadrilateral, CellType::Tetrahedron,
    CellType::Hexahedron, CellType::Wedge,         CellType::Pyramid};

// A cell type as a type, for dispatching once per block to code compiled per cell type.
template <CellType Type>
using CellTag = std::integral_constant<CellType, Type>;

// Calls f(CellTag<type>{}) with the type as a compile-time constant: the one switch over
// cell types; everything else reads the table or is templated on the type.
template <typename F>
decltype(auto) visit_cell_type(CellType type, F&& f) {
  switch (type) {
    case CellType::Triangle:
      return f(CellTag<CellType::Triangle>{});
    case CellType::Quadrilateral:
      return f(CellTag<CellType::Quadrilateral>{});
    case CellType::Tetrahedron:
      return f(CellTag<CellType::Tetrahedron>{});
    case CellType::Hexahedron:
      return f(CellTag<CellType::Hexahedron>{});
    case CellType::Wedge:
      return f(CellTag<CellType::Wedge>{});
    case CellType::Pyramid:
      break;
  }
  return f(CellTag<CellType::Pyramid>{});
}

// The cell type of `dim` with `vertices` vertices (3D: 4 tetrahedron, 5 pyramid, 6 wedge,
// 8 hexahedron), or -1.
constexpr int cell_type_index(int dim, int vertices) {
  for (int t = 0; t < kNumCellTypes; ++t)
    if (kCellFacts[t].dim == dim && kCellFacts[t].vertices == vertices) return t;
  return -1;
}

}  // namespace neomesh
