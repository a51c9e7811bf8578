// Putting a raised mesh's boundary on its geometry (`neomesh curve`, docs/user-guide.md "Curved
// meshes"): the boundary vertices and the second-order nodes of the boundary's edges and faces
// go to the closest point of the exact shape of their boundary part — a `--shape part=SPEC`
// (shape.hpp) or the FEAT3 chart the part is attached to. Where a part has neither, its nodes
// stay where raising put them, on the straight facets: the boundary is then as the input gives
// it, no smoother.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "mesh/input_mesh.hpp"

namespace neomesh {

struct CurvedBoundarySummary {
  PetscInt vertices_on_geometry = 0;  // boundary vertices put on a shape or chart
  PetscInt nodes_on_geometry = 0;     // second-order boundary nodes put on one
  PetscInt nodes_straight = 0;        // second-order boundary nodes of parts without geometry
  double max_vertex_move = 0.0;       // how far the farthest vertex moved onto its geometry
  // The largest distance of a node (vertex or second-order) from the geometry it was put on,
  // measured again after placing: what "on the shape" means in floating point.
  double max_off_geometry = 0.0;
};

// Moves the boundary vertices and second-order boundary nodes of a mesh raised by
// raise_to_second_order onto their parts' geometry: `shapes` as (part, spec) pairs, then the
// FEAT3 charts of the parts no shape names. A node whose corners all lie on one geometry goes
// to its closest point; on two (3D: a ridge between two parts), to their intersection's;
// otherwise (a corner of three parts) it stays. Throws Error in one line for a shape naming no
// boundary part, a 2D mesh off z = 0, or a vertex farther from its part's geometry than a
// quarter of its shortest boundary edge (the geometry does not describe the part).
CurvedBoundarySummary place_boundary_nodes(
    InputMesh& mesh, const std::vector<std::pair<std::string, std::string>>& shapes);

}  // namespace neomesh
