// Turning an InputMesh into a DMPlex of cells and vertices (not interpolated: the mesh layer
// needs no edges or faces, see input_topology.hpp), every cell on rank 0, with cell types and
// coordinates and no labels.
#pragma once

#include <mpi.h>

#include <span>

#include "core/petsc.hpp"
#include "mesh/facet_table.hpp"
#include "mesh/input_mesh.hpp"

namespace neomesh {

// Collective; `mesh` is read on rank 0 only.
OwnedDM build_plex(MPI_Comm comm, const InputMesh& mesh);

// Collective: `dm` (every cell on rank 0, as build_plex makes it) distributed over its
// communicator without overlap, split as METIS splits `graph` (rank 0's cells, empty
// elsewhere), the same way in every run: PT-Scotch, PETSc's default here, seeds its random
// generator anew each time, so two runs on the same ranks got different partitions and, through
// the AMG hierarchies, results that differed beyond round-off. A partitioner the user names
// (-petscpartitioner_type) is used instead. On a mesh without faces PETSc would build another
// graph; this one is the graph of the interpolated mesh. The DM is DMPlexDistribute's, point for
// point, but the migration is made from the parts directly instead of through a partition label
// (square-midpoint 1024² on 2 processes: docs/benchmarks.md, "Processes").
struct Distributed {
  OwnedDM dm;
  // Leaves: the new DM's points; roots: rank 0's points of `dm`.
  OwnedSF migration;
};
Distributed distribute_plex(DM dm, CellGraph& graph, std::span<const PetscInt> groups = {});

}  // namespace neomesh
