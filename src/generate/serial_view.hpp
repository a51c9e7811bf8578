// A MeshView of a whole MeshData on one process, without DMPlex: for unit tests of the
// numerics and for serial tools that build their mesh in memory.
#pragma once

#include "mesh/mesh_data.hpp"
#include "mesh/mesh_view.hpp"

namespace neomesh {

// One cell block, every vertex owned, on_boundary from boundary_vertices(), the boundary
// parts from mesh.boundary_parts, global_cell and input_vertex = 0..n-1, the boundary surface.
MeshView serial_view(const MeshData& mesh);

}  // namespace neomesh
