// How many OpenMP threads a front end (the command line, the Python package) gives a run on a
// mesh: the library itself sets no thread count.
#pragma once

#include <neomesh/mesh.hpp>

namespace neomesh {

// Unless OMP_NUM_THREADS says otherwise, the ranks on a node share its cores: P ranks times
// T threads must not oversubscribe them (each rank would start one thread per core). A mesh
// too small for threads to pay runs on one per rank. The count depends on the mesh and the
// machine only, never on its load: another thread count gives other last bits (sums over cells
// run per thread, and PETSc's norms and dot products go through OpenBLAS's OpenMP threads),
// and the same command must give the same mesh. 0 where OMP_NUM_THREADS is set (then keep
// OpenMP's count). Collective.
int run_thread_count(const Mesh& mesh);

}  // namespace neomesh
