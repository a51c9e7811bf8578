// The whole mesh on rank 0, for the writers: coordinates, cells and physical groups in input
// numbering (so a parallel run writes the same file as a serial one), with the fields.
#pragma once

#include "mesh/input_mesh.hpp"
#include "mesh/mesh_io.hpp"

namespace neomesh {

struct GatheredMesh {
  InputMesh mesh;        // cells by input number; facets and points in physical groups
  MeshFields fields;     // cell fields by input cell number, vertex fields by input vertex
  bool has_cell_groups;  // cells carry physical tags (written as the cell field "physical")
};

// Collective; the result is complete on rank 0 and empty elsewhere. Throws Error if a
// field's size does not match the mesh.
GatheredMesh gather_mesh(const PlexMesh& mesh, const MeshFields& fields);

}  // namespace neomesh
