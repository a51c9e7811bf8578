// Raising a straight mesh to second order (`neomesh curve`): every cell gets the nodes of its
// second-order twin (triangle6, quadrilateral9, tetrahedron10, hexahedron27) at the image of
// their reference positions under the straight map, so that the curved cells are the straight
// ones until something moves the nodes (boundary/curve_boundary.hpp puts the boundary's on
// its geometry).
#pragma once

#include "mesh/input_mesh.hpp"

namespace neomesh {

// The second-order type a straight cell is raised to (the Lagrange cells: quadrilateral9,
// hexahedron27, wedge18), or none (pyramids: no curved type yet).
std::optional<CurvedType> raised_type(CellType linear);

// Fills mesh.high_order: one node per edge, per quadrilateral face (of hexahedra and wedges) and
// per quadrilateral or hexahedron centre, an edge's or face's node shared by its cells and created
// once (in the order the cells first reach it). The vertices and their numbering stay as they are;
// the group facets find their nodes by their corners (CurvedFacets). Throws Error, in one line
// naming the cell type, for a mesh already curved, a surface mesh, or pyramids.
void raise_to_second_order(InputMesh& mesh);

}  // namespace neomesh
