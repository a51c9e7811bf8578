// Which coordinates of which vertices the optimization may change (MATH.md §7, thesis §3.2
// and outlook).
//
// Fixed (the thesis' H¹₀ setting): every boundary vertex stays where it is.
// Slide: a boundary vertex may move within the boundary. Every boundary facet (edge in 2D,
// face in 3D) that lies in an axis-aligned plane x_j = const fixes component j of its
// vertices; so a vertex inside a flat face of a box slides within the face, one on an edge
// of the box slides along the edge, and a corner stays put. Keeping a coordinate fixed keeps
// the vertex *exactly* on such a plane, so no projection is needed. A boundary facet that is
// not axis-aligned (curved or oblique boundaries) fixes its vertices completely: sliding
// there would need a projection back onto the boundary, which neomesh does not do yet.
#pragma once

#include <cstdint>
#include <string_view>
#include <vector>

#include "mesh/dof_map.hpp"
#include "mesh/mesh_view.hpp"

namespace neomesh {

enum class BoundaryMode { Fixed, Slide };

// "fixed" or "slide"; throws Error for anything else.
BoundaryMode parse_boundary_mode(std::string_view name);
std::string_view name(BoundaryMode mode);

// Per local dof (dim * vertex + component, MeshView order): 1 if that coordinate does not
// move. Collective: ranks agree on vertices they share (a rank may see only some of a
// vertex's boundary facets).
std::vector<std::uint8_t> fixed_dofs(const MeshView& view, const DofMap& dofs, BoundaryMode mode);

}  // namespace neomesh
