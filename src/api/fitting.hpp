// What fitting to a LevelSet (Mesh::interface, Optimizer::adapt with a LevelSet) needs from the
// layers below: φ as a function of the mesh's dimension, and the one-process restriction.
#pragma once

#include <mpi.h>

#include <neomesh/level_set.hpp>

#include "boundary/shape.hpp"

namespace neomesh {

// φ for a mesh of dimension `dim`, at the level set's time.
LevelSetFunction level_set_function(const LevelSet& phi, int dim);

// Throws Error unless `comm` has one process: the interface is found within each process'
// cells, so one that crosses a partition would not be closed.
void require_one_process(MPI_Comm comm);

}  // namespace neomesh
