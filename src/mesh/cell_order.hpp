// Local vertex orders of the file formats and of DMPlex, relative to neomesh's canonical
// order (cell_type.hpp). `kPlexFromCanonical[t][i]` is the canonical index of the vertex
// DMPlex lists at position i (cone and closure order); `kGmshFromCanonical` likewise for
// Gmsh and VTK, which agree for the four cell types.
//
// Found by reading cells whose geometry is known: DMPlex lists quadrilaterals counter-
// clockwise, tetrahedra negatively oriented and hexahedra with the bottom face clockwise
// seen from the top face; Gmsh/VTK list quadrilaterals and both hexahedron faces
// counter-clockwise and tetrahedra positively oriented.
#pragma once

#include <array>

#include <petscdmplex.h>

#include "mesh/cell_type.hpp"

namespace neomesh {

using VertexOrder = std::array<int, 8>;

constexpr VertexOrder kPlexFromCanonical[4] = {{0, 1, 2},                  // triangle
                                               {0, 1, 3, 2},               // quadrilateral
                                               {1, 0, 2, 3},               // tetrahedron
                                               {0, 2, 3, 1, 4, 5, 7, 6}};  // hexahedron
constexpr VertexOrder kCanonicalFromPlex[4] = {
    {0, 1, 2}, {0, 1, 3, 2}, {1, 0, 2, 3}, {0, 3, 1, 2, 4, 5, 7, 6}};
constexpr VertexOrder kGmshFromCanonical[4] = {
    {0, 1, 2}, {0, 1, 3, 2}, {0, 1, 2, 3}, {0, 1, 3, 2, 4, 5, 7, 6}};

constexpr const VertexOrder& plex_from_canonical(CellType t) {
  return kPlexFromCanonical[static_cast<int>(t)];
}
constexpr const VertexOrder& canonical_from_plex(CellType t) {
  return kCanonicalFromPlex[static_cast<int>(t)];
}
constexpr const VertexOrder& gmsh_from_canonical(CellType t) {
  return kGmshFromCanonical[static_cast<int>(t)];
}

// The facets of a cell as DMPlexInterpolate makes them (DMPlexGetRawFaces_Internal): positions
// in the DMPlex cone. A facet keeps the vertex order of the first cell that has it, and its
// closure lists its vertices in that order.
struct FacetShape {
  int count;  // facets per cell
  int size;   // vertices per facet
  std::array<std::array<int, 4>, 6> vertices;
};
constexpr FacetShape kPlexFacets[4] = {
    {3, 2, {{{0, 1}, {1, 2}, {2, 0}}}},                      // triangle
    {4, 2, {{{0, 1}, {1, 2}, {2, 3}, {3, 0}}}},              // quadrilateral
    {4, 3, {{{0, 1, 2}, {0, 3, 1}, {0, 2, 3}, {2, 1, 3}}}},  // tetrahedron
    {6,
     4,  // hexahedron
     {{{0, 1, 2, 3}, {4, 5, 6, 7}, {0, 3, 5, 4}, {2, 1, 7, 6}, {3, 2, 6, 5}, {0, 4, 7, 1}}}}};

constexpr const FacetShape& plex_facets(CellType t) {
  return kPlexFacets[static_cast<int>(t)];
}

constexpr DMPolytopeType plex_polytope(CellType t) {
  switch (t) {
    case CellType::Triangle:
      return DM_POLYTOPE_TRIANGLE;
    case CellType::Quadrilateral:
      return DM_POLYTOPE_QUADRILATERAL;
    case CellType::Tetrahedron:
      return DM_POLYTOPE_TETRAHEDRON;
    case CellType::Hexahedron:
      return DM_POLYTOPE_HEXAHEDRON;
  }
  return DM_POLYTOPE_UNKNOWN;
}

}  // namespace neomesh
