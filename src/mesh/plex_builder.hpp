// Turning an InputMesh into a DMPlex: every cell on rank 0, interpolated (edges and faces
// exist), with the labels the rest of the mesh layer relies on:
//   "Cell Sets"   cell → physical tag;
//   "Face Sets"   facet → physical tag (also derived from InputMesh::vertex_sets);
//   "Vertex Sets" vertex → physical tag;
//   "boundary"    value 1 on boundary facets and their edges and vertices.
// The boundary is marked here, before distribution, so partition interfaces never count.
#pragma once

#include <mpi.h>

#include "core/petsc.hpp"
#include "mesh/input_mesh.hpp"

namespace neomesh {

inline constexpr const char* kBoundaryLabel = "boundary";

// Collective; `mesh` is read on rank 0 only. Adds a point group (dim 0) to mesh.groups for
// each vertex set with vertices on no boundary facet of the set.
OwnedDM build_plex(MPI_Comm comm, InputMesh& mesh);

}  // namespace neomesh
