// A mesh of second-order cells as the optimizer sees it (docs/method.md §12, "The solver"):
// every node is a vertex, so that what works per vertex — dof maps, boundary detection and
// sliding, the matrices' pattern — carries over, and the cells whose energy is summed are the
// curved cells, over all their nodes.
//
// The DMPlex of such a mesh is built from the straight sub-cells through the nodes: a
// triangle6 gives 4 triangles, a tetrahedron10 8 tetrahedra (its inner octahedron cut along one
// diagonal), a quadrilateral9 4 quadrilaterals, a hexahedron27 8 hexahedra and a wedge18 8
// wedges (the triangle's 4 sub-triangles between its 3 levels). The serendipity cells lack the
// face and centre nodes of that lattice: a quadrilateral8 gets a virtual centre, a hexahedron20
// virtual face centres (shared with the neighbour across the face) and a centre, a wedge15
// virtual centres of its quadrilateral faces, at the curved map's image of those reference
// points. Virtual vertices belong to no curved
// cell: they have no energy, stay where they are, and are not written. The sub-cells only give
// the topology (the boundary's facets, who neighbours whom); their shape plays no part.
#pragma once

#include <span>
#include <vector>

#include <petscsys.h>

#include "mesh/input_mesh.hpp"
#include "mesh/mesh_view.hpp"

namespace neomesh {

struct NodeMesh {
  // Vertices: the curved mesh's points (input_mesh.hpp: its vertices, then its high-order
  // nodes), then the virtual ones; cells: the sub-cells, with their curved cell's tag; facets in
  // physical groups subdivided alike, so that boundary parts keep their names.
  InputMesh mesh;
  PetscInt points = 0;  // vertices below this are the curved mesh's points
};

// Throws Error for a mesh without second-order cells.
NodeMesh node_mesh(const InputMesh& curved);

// The views the optimizer uses beside `nodes` (the view of node_mesh's PlexMesh, one process):
// the same vertices, with blocks of the curved cells (CellBlock::curved, every node in Gmsh's
// order) or of their straight corner cells (canonical order), cells grouped by type, and
// global_cell the curved cell's number in `curved`.
MeshView curved_cells_view(const MeshView& nodes, const InputMesh& curved);
MeshView corner_cells_view(const MeshView& nodes, const InputMesh& curved);

// The volume of each cell of a view of curved cells at `coords` (view.dim per vertex), exactly
// (curved_volume).
std::vector<double> curved_cell_volumes(const MeshView& cells, std::span<const double> coords);

}  // namespace neomesh
