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
//
// On several processes the node mesh is distributed with each curved cell's sub-cells kept on
// one process (PlexMesh::from_input's cell_groups = NodeMesh::subcells): METIS splits the graph
// of the curved cells, so that every curved cell's energy and certificate are one process' alone,
// its nodes owned there or ghosts, as a straight cell's vertices are. Splitting the sub-cells
// instead would cut curved cells, whose energy couples all their nodes.
#pragma once

#include <span>
#include <string>
#include <vector>

#include <mpi.h>
#include <petscsys.h>

#include "mesh/input_mesh.hpp"
#include "mesh/mesh_view.hpp"
#include "mesh/plex_mesh.hpp"

namespace neomesh {

struct NodeMesh {
  // Vertices: the curved mesh's points (input_mesh.hpp: its vertices, then its high-order
  // nodes), then the virtual ones; cells: the sub-cells, with their curved cell's tag; facets in
  // physical groups subdivided alike, so that boundary parts keep their names.
  InputMesh mesh;
  PetscInt points = 0;  // vertices below this are the curved mesh's points
  // Curved cell c's sub-cells are cells [subcells[c], subcells[c + 1]) of `mesh`.
  std::vector<PetscInt> subcells = {0};
};

// Throws Error for a mesh without second-order cells.
NodeMesh node_mesh(const InputMesh& curved);

// A process' part of a curved mesh's node mesh, as smoothing optimizes it.
struct DistributedNodeMesh {
  PlexMesh nodes;  // node_mesh's, each curved cell's sub-cells on one process
  // Its view's vertices with blocks of the curved cells (CellBlock::curved, every node in Gmsh's
  // order) or of their straight corner cells (canonical order), by type; global_cell is the
  // curved cell's number.
  MeshView cells, corners;
  PetscInt points = 0;  // NodeMesh::points, on every process
};

// Collective: the node mesh of `curved` (the whole curved mesh on rank 0, empty elsewhere, as
// gather_mesh gives it), distributed over `comm`; `name` for messages. Its sub-cells may be
// inverted: they give the topology only.
DistributedNodeMesh distribute_node_mesh(const InputMesh& curved, const std::string& name,
                                         MPI_Comm comm);

// Collective: the curved mesh's points (`points` of them, node_mesh's first vertices) at
// `coords` (nodes.dim values per local vertex of `nodes`) on rank 0, in input numbering, each
// from the process that owns it; empty elsewhere.
std::vector<double> gather_points(const MeshView& nodes, std::span<const double> coords,
                                  PetscInt points, MPI_Comm comm);

// The volume of each cell of a view of curved cells at `coords` (view.dim per vertex), exactly
// (curved_volume).
std::vector<double> curved_cell_volumes(const MeshView& cells, std::span<const double> coords);

}  // namespace neomesh
