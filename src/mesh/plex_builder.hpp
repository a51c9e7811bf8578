// Turning an InputMesh into a DMPlex of cells and vertices (not interpolated: the mesh layer
// needs no edges or faces, see input_topology.hpp), every cell on rank 0, with cell types and
// coordinates and no labels.
#pragma once

#include <mpi.h>

#include "core/petsc.hpp"
#include "mesh/facet_table.hpp"
#include "mesh/input_mesh.hpp"

namespace neomesh {

// Collective; `mesh` is read on rank 0 only.
OwnedDM build_plex(MPI_Comm comm, const InputMesh& mesh);

// Collective: makes DMPlexDistribute split `dm` as METIS splits `graph` (rank 0's cells, empty
// elsewhere), the same way in every run: PT-Scotch, PETSc's default here, seeds its random
// generator anew each time, so two runs on the same ranks got different partitions and, through
// the AMG hierarchies, results that differed beyond round-off. A partitioner the user names
// (-petscpartitioner_type) is used instead. On a mesh without faces PETSc would build another
// graph; this one is the graph of the interpolated mesh.
void set_partition(DM dm, CellGraph& graph);

}  // namespace neomesh
